//! The least-squares problem of a fit: residuals from simulations, forward
//! difference Jacobians in parallel, and the Levenberg–Marquardt starts.

use super::{FitError, FitSetup, SimulatedChannels, StartReport, rms, simulate_channels};
use lagrangian_runtime::LagrangianSystem;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra034::{DMatrix, DVector, Dyn, Owned};
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Step of the forward differences in the fit variables (for logarithmic
/// variables a 0.1 % change of the parameter).
const STEP: f64 = 1e-3;

/// Residual of a run that failed: large, so the optimizer steps back.
const FAILED: f64 = 1e3;

pub(super) struct Problem<'a, S> {
    prototype: Mutex<S>,
    setup: &'a FitSetup,
    progress: &'a (dyn Fn(usize, f64) + Sync),
    simulations: AtomicUsize,
    best: Mutex<f64>,
    /// `rms(target) · √(points · channels)` per channel.
    scales: Vec<f64>,
    /// The unconstrained variables at the scenario's values.
    u0: Vec<f64>,
    /// The entries that change the simulated target (the others are held).
    pub free: Vec<usize>,
}

pub(super) struct Outcome {
    pub values: Vec<f64>,
    /// Free variables at the optimum.
    pub u: Vec<f64>,
    pub cost: f64,
    pub cost_initial: f64,
    pub starts: Vec<StartReport>,
}

impl<'a, S: Clone + Send> Problem<'a, S> {
    pub fn new<const N: usize>(
        system: &S,
        setup: &'a FitSetup,
        progress: &'a (dyn Fn(usize, f64) + Sync),
    ) -> Result<Self, FitError>
    where
        S: LagrangianSystem<N>,
    {
        let channels = setup.target.channels.len() as f64;
        let scales = setup
            .target
            .channels
            .iter()
            .map(|c| rms(c.values.iter().copied()) * (c.values.len() as f64 * channels).sqrt())
            .collect();
        let u0 = setup
            .parameters
            .to_unconstrained(&setup.parameters.base_values());
        let mut problem = Problem {
            prototype: Mutex::new(system.clone()),
            setup,
            progress,
            simulations: AtomicUsize::new(0),
            best: Mutex::new(f64::INFINITY),
            scales,
            free: (0..u0.len()).collect(),
            u0,
        };
        // Which entries move the target at all: the columns of the full
        // Jacobian at the start that are not exactly zero.
        let start = problem.u0.clone();
        let r0 = problem
            .residuals(&start)
            .map_err(|e| FitError::StartFails(Box::new(e)))?;
        let all: Vec<usize> = (0..start.len()).collect();
        let columns = problem.columns::<N>(&start, &all, &r0);
        let norms: Vec<f64> = columns
            .iter()
            .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
            .collect();
        let largest = norms.iter().copied().fold(0.0, f64::max);
        problem.free = (0..norms.len())
            .filter(|&i| norms[i] > 1e-12 * largest && norms[i] > 0.0)
            .collect();
        if problem.free.is_empty() {
            return Err(FitError::NoInfluence);
        }
        Ok(problem)
    }

    /// A copy of the model for one thread (models keep scratch space).
    fn system(&self) -> S {
        self.prototype
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
    }

    pub fn parameters(&self) -> &super::Parameters {
        &self.setup.parameters
    }

    pub fn simulations(&self) -> usize {
        self.simulations.load(Ordering::Relaxed)
    }

    /// Full unconstrained vector from the free variables `u`.
    fn full(&self, u: &[f64]) -> Vec<f64> {
        let mut full = self.u0.clone();
        for (&i, &x) in self.free.iter().zip(u) {
            full[i] = x;
        }
        full
    }

    /// The simulated channels for physical `values`, at the run's own
    /// output times.
    pub fn run_of<const N: usize>(&self, values: &[f64]) -> Result<SimulatedChannels, FitError>
    where
        S: LagrangianSystem<N>,
    {
        let system = self.system();
        self.run_with::<N>(&system, values)
    }

    fn run_with<const N: usize>(
        &self,
        system: &S,
        values: &[f64],
    ) -> Result<SimulatedChannels, FitError>
    where
        S: LagrangianSystem<N>,
    {
        self.simulations.fetch_add(1, Ordering::Relaxed);
        let settings = self.setup.parameters.overrides(values);
        simulate_channels(system, &self.setup.base, &settings, &self.setup.target)
    }

    /// Residuals for the full unconstrained vector.
    fn residuals_with<const N: usize>(&self, system: &S, full: &[f64]) -> Result<Vec<f64>, FitError>
    where
        S: LagrangianSystem<N>,
    {
        let values = self.setup.parameters.to_physical(full);
        let sim = self
            .run_with::<N>(system, &values)?
            .at(&self.setup.target.t);
        let mut r = Vec::new();
        for ((c, s), scale) in self
            .setup
            .target
            .channels
            .iter()
            .zip(&sim)
            .zip(&self.scales)
        {
            r.extend(s.iter().zip(&c.values).map(|(s, y)| (s - y) / scale));
        }
        if r.iter().any(|x| !x.is_finite()) {
            return Err(FitError::NotFinite);
        }
        let cost = 0.5 * r.iter().map(|x| x * x).sum::<f64>();
        let mut best = self.best.lock().unwrap_or_else(|e| e.into_inner());
        if cost < *best {
            *best = cost;
        }
        (self.progress)(self.simulations(), *best);
        Ok(r)
    }

    fn residuals<const N: usize>(&self, full: &[f64]) -> Result<Vec<f64>, FitError>
    where
        S: LagrangianSystem<N>,
    {
        let system = self.system();
        self.residuals_with::<N>(&system, full)
    }

    /// `∂r/∂u_i` for the entries `indices` of the full vector `full`, by
    /// forward differences, the columns simulated in parallel.
    fn columns<const N: usize>(&self, full: &[f64], indices: &[usize], r: &[f64]) -> Vec<Vec<f64>>
    where
        S: LagrangianSystem<N>,
    {
        let copy = || self.system();
        indices
            .par_iter()
            .map_init(copy, |system, &i| {
                let mut shifted = full.to_vec();
                shifted[i] += STEP;
                match self.residuals_with::<N>(system, &shifted) {
                    Ok(s) => s.iter().zip(r).map(|(a, b)| (a - b) / STEP).collect(),
                    Err(_) => vec![0.0; r.len()],
                }
            })
            .collect()
    }

    /// The Jacobian with respect to the free variables, one column each.
    pub fn jacobian<const N: usize>(&self, u: &[f64], r: &[f64]) -> Vec<Vec<f64>>
    where
        S: LagrangianSystem<N>,
    {
        self.columns::<N>(&self.full(u), &self.free, r)
    }

    /// Residuals at free variables `u`.
    pub fn residuals_at<const N: usize>(&self, u: &[f64]) -> Result<Vec<f64>, FitError>
    where
        S: LagrangianSystem<N>,
    {
        self.residuals::<N>(&self.full(u))
    }

    /// Residuals at free variables `u` (`FAILED` everywhere if the run fails).
    pub fn residuals_free<const N: usize>(&self, u: &[f64], length: usize) -> Vec<f64>
    where
        S: LagrangianSystem<N>,
    {
        self.residuals::<N>(&self.full(u))
            .unwrap_or_else(|_| vec![FAILED; length])
    }

    /// Levenberg–Marquardt from `starts` starting points; the best result.
    pub fn minimize<const N: usize>(&self, starts: usize, seed: u64) -> Result<Outcome, FitError>
    where
        S: LagrangianSystem<N>,
    {
        let start: Vec<f64> = self.free.iter().map(|&i| self.u0[i]).collect();
        let r0 = self.residuals::<N>(&self.full(&start))?;
        let cost_initial = 0.5 * r0.iter().map(|x| x * x).sum::<f64>();
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut reports = Vec::new();
        let mut best: Option<(f64, Vec<f64>)> = None;
        for k in 0..starts.max(1) {
            let u: Vec<f64> = if k == 0 {
                start.clone()
            } else {
                start
                    .iter()
                    .zip(&self.free)
                    .map(|(&x, &i)| {
                        // A factor in [1/1.5, 1.5], log-uniform.
                        let f = 1.5f64.ln() * (2.0 * unit(&mut rng) - 1.0);
                        match self.setup.parameters.entries[i].transform {
                            super::parameters::Transform::Identity => x * f.exp(),
                            _ => x + f,
                        }
                    })
                    .collect()
            };
            let before = self.simulations();
            let adapter = Adapter::<S, N>::new(self, u, r0.len());
            let (adapter, report) = LevenbergMarquardt::new()
                .with_patience(20)
                .with_ftol(1e-10)
                .with_xtol(1e-8)
                .minimize(adapter);
            let u = adapter.u.as_slice().to_vec();
            let cost = 0.5 * adapter.r.norm_squared();
            reports.push(StartReport {
                cost,
                simulations: self.simulations() - before,
                termination: format!("{:?}", report.termination),
                converged: report.termination.was_successful(),
            });
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, u));
            }
        }
        let (cost, u) = best.ok_or(FitError::NoStart)?;
        // Held entries keep their values exactly (not through exp(ln p)).
        let base = self.setup.parameters.base_values();
        let values = self
            .setup
            .parameters
            .to_physical(&self.full(&u))
            .into_iter()
            .enumerate()
            .map(|(i, v)| if self.free.contains(&i) { v } else { base[i] })
            .collect();
        Ok(Outcome {
            values,
            u,
            cost,
            cost_initial,
            starts: reports,
        })
    }
}

fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// The problem as the `levenberg-marquardt` crate sees it.
struct Adapter<'p, 'a, S, const N: usize> {
    problem: &'p Problem<'a, S>,
    u: DVector<f64>,
    r: DVector<f64>,
    length: usize,
}

impl<'p, 'a, S: Clone + Send + LagrangianSystem<N>, const N: usize> Adapter<'p, 'a, S, N> {
    fn new(problem: &'p Problem<'a, S>, u: Vec<f64>, length: usize) -> Self {
        let r = DVector::from_vec(problem.residuals_free::<N>(&u, length));
        Adapter {
            problem,
            u: DVector::from_vec(u),
            r,
            length,
        }
    }
}

impl<S: Clone + Send + LagrangianSystem<N>, const N: usize> LeastSquaresProblem<f64, Dyn, Dyn>
    for Adapter<'_, '_, S, N>
{
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.u = x.clone();
        self.r = DVector::from_vec(self.problem.residuals_free::<N>(x.as_slice(), self.length));
    }

    fn params(&self) -> DVector<f64> {
        self.u.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        Some(self.r.clone())
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let columns = self
            .problem
            .jacobian::<N>(self.u.as_slice(), self.r.as_slice());
        Some(DMatrix::from_fn(self.length, columns.len(), |i, j| {
            columns[j][i]
        }))
    }
}
