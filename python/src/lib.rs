//! The native part of the Python package `lagrangian`: a compiled spec run
//! by the interpreter (evaluated over rows of states in Rust), its derived
//! equations, `lpm simulate`, `lpm sweep` and `lpm fit` — with failures
//! raised as the exception of their `lpm` exit status.
//!
//! The Python layer (`python/lagrangian/__init__.py`) shapes arguments and
//! results (one state or a batch, numpy and pandas).

use lagrangian_core::Compiled;
use lagrangian_core::emit::{Notation, render_equations, render_markdown};
use lagrangian_runtime::{Energies, InputFunctions, InterpretedModel};
use lagrangian_sim::scenario::Override;
use lagrangian_studies::error::StudyError;
use lagrangian_studies::files::{Cached, Files};
use lagrangian_studies::mass::State;
use lagrangian_studies::status::ExitStatus;
use numpy::{
    IntoPyArray, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyDict;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, LazyLock, Mutex, MutexGuard};

mod ensembles;

/// The exception class of each exit status, registered by the Python layer.
static ERRORS: PyOnceLock<Py<PyDict>> = PyOnceLock::new();

/// The files every call of the module reads: each table parsed once per
/// text, for as long as the interpreter runs (an edited file is read anew).
static FILES: LazyLock<Arc<dyn Files>> = LazyLock::new(|| Arc::new(Cached::default()));

/// The exception of `error`'s exit status, with its message.
fn raise(error: impl Into<StudyError>) -> PyErr {
    let error: StudyError = error.into();
    let message = error.to_string().trim_end().to_string();
    Python::attach(|py| {
        let code = error.status().code();
        let class = ERRORS
            .get(py)
            .and_then(|errors| errors.bind(py).get_item(code).ok().flatten());
        match class {
            Some(class) => match class.call1((message, code)) {
                Ok(error) => PyErr::from_value(error),
                Err(e) => e,
            },
            None => PyRuntimeError::new_err(message),
        }
    })
}

/// Every exit status of `lpm`: `(code, name, meaning)`, in order.
#[pyfunction]
fn exit_statuses() -> Vec<(u8, String, String)> {
    (ExitStatus::ALL.iter())
        .map(|s| (s.code(), s.name(), s.meaning().to_string()))
        .collect()
}

/// Registers the exception class of each exit status (`{code: class}`).
#[pyfunction]
fn register_errors(py: Python<'_>, classes: Bound<'_, PyDict>) -> PyResult<()> {
    ERRORS
        .set(py, classes.unbind())
        .map_err(|_| PyRuntimeError::new_err("the error classes are registered already"))
}

/// `q̈` (k × n) and `λ` (k × m) of a batch.
type AccelerationsAndMultipliers<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>);

/// `M` (k × n × n) and `f` (k × n) of a batch.
type MassAndForcing<'py> = (Bound<'py, PyArray3<f64>>, Bound<'py, PyArray2<f64>>);

/// A spec compiled and run by the interpreter.
#[pyclass(module = "lagrangian._lagrangian")]
struct NativeModel {
    /// Behind a lock: the interpreter keeps scratch registers.
    model: Mutex<InterpretedModel>,
    /// The spec's text and where it came from, for `derive`.
    source: String,
    file: String,
}

/// A spec's text compiled, its errors rendered against `file`.
fn compile(source: &str, file: &str) -> Result<Compiled, StudyError> {
    Compiled::from_source(source).map_err(|e| StudyError::Spec(e.render(file, source)))
}

/// The rows of a batch of states: `t` (k), `q` and `qd` (k × n).
struct Batch<'a> {
    t: &'a [f64],
    q: &'a [f64],
    qd: &'a [f64],
    n: usize,
}

impl Batch<'_> {
    fn rows(&self) -> usize {
        self.t.len()
    }

    fn row(&self, k: usize) -> (f64, &[f64], &[f64]) {
        let range = k * self.n..(k + 1) * self.n;
        (self.t[k], &self.q[range.clone()], &self.qd[range])
    }
}

impl NativeModel {
    fn model(&self) -> MutexGuard<'_, InterpretedModel> {
        // A panic while the lock is held leaves nothing half-changed.
        self.model.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The input functions' constant values (every input the dynamics calls
    /// needs one), with parameters applied as `lpm eval --set` does.
    fn inputs(
        &self,
        values: HashMap<String, f64>,
    ) -> Result<(InterpretedModel, Box<dyn InputFunctions>), StudyError> {
        let settings: Vec<Override> = (values.iter())
            .map(|(name, value)| Override::number(name, *value))
            .collect();
        let mut model = self.model().clone();
        let (inputs, _) = lagrangian_studies::eval::apply_settings(&mut model, &settings)?;
        Ok((model, inputs))
    }

    /// The values `each` gives at every row of a batch, concatenated; it
    /// gets the model with the parameters of `inputs` set and the inputs'
    /// constants.
    fn each_row(
        &self,
        (t, q, qd): (
            &PyReadonlyArray1<'_, f64>,
            &PyReadonlyArray2<'_, f64>,
            &PyReadonlyArray2<'_, f64>,
        ),
        inputs: HashMap<String, f64>,
        mut each: impl FnMut(
            &InterpretedModel,
            &dyn InputFunctions,
            State,
        ) -> Result<Vec<f64>, StudyError>,
    ) -> PyResult<Vec<f64>> {
        let batch = self.batch(t, q, qd).map_err(raise)?;
        let (model, inputs) = self.inputs(inputs).map_err(raise)?;
        let mut out = Vec::new();
        for k in 0..batch.rows() {
            out.extend(each(&model, &*inputs, batch.row(k)).map_err(raise)?);
        }
        Ok(out)
    }

    /// Checks the shapes of a batch against the model's dimension.
    fn batch<'a>(
        &self,
        t: &'a PyReadonlyArray1<'_, f64>,
        q: &'a PyReadonlyArray2<'_, f64>,
        qd: &'a PyReadonlyArray2<'_, f64>,
    ) -> Result<Batch<'a>, StudyError> {
        let model = self.model();
        let n = model.dimension();
        let shape = |a: &PyReadonlyArray2<'_, f64>| a.shape().to_vec();
        let k = t.len();
        if shape(q) != [k, n] || shape(qd) != [k, n] {
            return Err(StudyError::usage(format!(
                "the states need {n} coordinates ({}) and {n} velocities each; got q of shape {:?} and qd of shape {:?} for {k} times",
                model.coordinates().join(", "),
                shape(q),
                shape(qd)
            )));
        }
        let slice = |a: &'a PyReadonlyArray2<'_, f64>| {
            a.as_slice()
                .map_err(|_| StudyError::usage("states must be C-contiguous float64 arrays"))
        };
        Ok(Batch {
            t: t.as_slice()
                .map_err(|_| StudyError::usage("times must be a contiguous float64 array"))?,
            q: slice(q)?,
            qd: slice(qd)?,
            n,
        })
    }
}

#[pymethods]
impl NativeModel {
    /// Compiles the spec `source` (read from `file`, or `<spec>`).
    #[new]
    fn new(source: String, file: String) -> PyResult<NativeModel> {
        let model = compile(&source, &file).map_err(raise)?.interpreted();
        Ok(NativeModel {
            model: Mutex::new(model),
            source,
            file,
        })
    }

    #[getter]
    fn name(&self) -> String {
        self.model().name().to_string()
    }

    #[getter]
    fn coordinates(&self) -> Vec<String> {
        self.model().coordinates().to_vec()
    }

    #[getter]
    fn parameter_names(&self) -> Vec<String> {
        self.model().parameter_names().to_vec()
    }

    #[getter]
    fn parameter_values(&self) -> Vec<f64> {
        self.model().parameters().to_vec()
    }

    #[getter]
    fn input_names(&self) -> Vec<String> {
        self.model().input_names().to_vec()
    }

    #[getter]
    fn output_names(&self) -> Vec<String> {
        self.model().output_names().to_vec()
    }

    #[getter]
    fn constraint_names(&self) -> Vec<String> {
        self.model().constraint_names().to_vec()
    }

    #[getter]
    fn energy_names(&self) -> Vec<String> {
        Energies::FIELDS.iter().map(|s| s.to_string()).collect()
    }

    /// Sets a parameter by name.
    fn set_parameter(&mut self, name: &str, value: f64) -> PyResult<()> {
        (self.model().set_parameter(name, value))
            .map_err(|e| raise(StudyError::usage(e.to_string())))
    }

    /// `M` (k × n × n) and `f` (k × n) at each row of the batch.
    fn dynamics<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        inputs: HashMap<String, f64>,
    ) -> PyResult<MassAndForcing<'py>> {
        let n = self.model().dimension();
        let rows = self.each_row((&t, &q, &qd), inputs, |model, inputs, state| {
            let (mass, forcing) = lagrangian_studies::eval::evaluate(model, state, inputs)?;
            Ok([mass, forcing].concat())
        })?;
        let k = rows.len() / (n * n + n).max(1);
        let (mut mass, mut forcing) = (Vec::with_capacity(k * n * n), Vec::with_capacity(k * n));
        for row in rows.chunks(n * n + n) {
            mass.extend_from_slice(&row[..n * n]);
            forcing.extend_from_slice(&row[n * n..]);
        }
        let mass = mass.into_pyarray(py).reshape([k, n, n])?;
        let forcing = forcing.into_pyarray(py).reshape([k, n])?;
        Ok((mass, forcing))
    }

    /// `q̈` (k × n) and the constraints' multipliers `λ` (k × m) at each
    /// row of the batch: `M q̈ = f`, or with constraints `M q̈ = f + Gᵀλ`,
    /// `G q̈ = γ − 2α ġ − β² g` (a scenario's default stabilization), by
    /// the solve `lpm simulate` and `lpm eval` use.
    fn accelerations<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        inputs: HashMap<String, f64>,
    ) -> PyResult<AccelerationsAndMultipliers<'py>> {
        let batch = self.batch(&t, &q, &qd).map_err(raise)?;
        let (model, inputs) = self.inputs(inputs).map_err(raise)?;
        let states: Vec<State> = (0..batch.rows()).map(|k| batch.row(k)).collect();
        let stabilization = lagrangian_sim::simulate::constrained::DEFAULT_STABILIZATION;
        let solved =
            lagrangian_studies::eval::accelerations(&model, &states, &*inputs, stabilization)
                .map_err(raise)?;
        let (n, m) = (model.dimension(), model.constraint_names().len());
        let k = solved.len();
        let qdd: Vec<f64> = solved.iter().flat_map(|s| s.qdd.iter().copied()).collect();
        let lambda: Vec<f64> = (solved.iter())
            .flat_map(|s| s.multipliers.iter().copied())
            .collect();
        let qdd = qdd.into_pyarray(py).reshape([k, n])?;
        let lambda = lambda.into_pyarray(py).reshape([k, m])?;
        Ok((qdd, lambda))
    }

    /// The energies and powers (k × 5, in the order of `energy_names`).
    fn energies<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
        q: PyReadonlyArray2<'py, f64>,
        qd: PyReadonlyArray2<'py, f64>,
        inputs: HashMap<String, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows = self.each_row((&t, &q, &qd), inputs, |model, inputs, (t, q, qd)| {
            let energies = (model.evaluate_energies(t, q, qd, inputs))
                .map_err(|e| StudyError::evaluation(e.to_string()))?;
            Ok(energies.values().to_vec())
        })?;
        let k = rows.len() / Energies::FIELDS.len();
        rows.into_pyarray(py).reshape([k, Energies::FIELDS.len()])
    }

    /// The derived equations as `lpm derive` prints them: `text`, `latex`
    /// or `markdown`.
    fn derive(&self, format: &str) -> PyResult<String> {
        let mut compiled = compile(&self.source, &self.file).map_err(raise)?;
        match format {
            "text" => Ok(render_equations(&mut compiled, Notation::Text)),
            "latex" => Ok(render_equations(&mut compiled, Notation::Latex)),
            "markdown" => Ok(render_markdown(&mut compiled, &self.file)),
            other => Err(raise(StudyError::usage(format!(
                "format `{other}`: choose text, latex or markdown"
            )))),
        }
    }
}

/// summary.json, trajectory.csv and the events `(t, component, description)`.
type Simulation = (String, String, Vec<(f64, String, String)>);

/// `lpm simulate` without its files: `(summary.json, trajectory.csv,
/// events as (t, component, description))`.
#[pyfunction]
#[pyo3(signature = (spec, scenario, settings))]
fn simulate(
    py: Python<'_>,
    spec: PathBuf,
    scenario: Option<PathBuf>,
    settings: Vec<String>,
) -> PyResult<Simulation> {
    let settings = Override::parse_all(&settings).map_err(raise)?;
    let simulated = py
        .detach(|| {
            lagrangian_studies::simulate::simulate_spec(
                &**FILES,
                &spec,
                scenario.as_deref(),
                &settings,
            )
        })
        .map_err(raise)?;
    let summary = lagrangian_sim::report::summary_json(&simulated.result);
    let trajectory = simulated.trajectory_csv();
    let events = (simulated.result.events.iter())
        .map(|e| (e.t, e.component.clone(), e.description.clone()))
        .collect();
    Ok((summary, trajectory, events))
}

/// `lpm export-fmu`: writes the FMU `out`; returns its size in bytes.
#[pyfunction]
#[pyo3(signature = (spec, scenario, out, runtime))]
fn export_fmu(
    py: Python<'_>,
    spec: PathBuf,
    scenario: Option<PathBuf>,
    out: PathBuf,
    runtime: Option<PathBuf>,
) -> PyResult<u64> {
    let exported = py
        .detach(|| {
            lagrangian_fmi::exporter::export(&spec, scenario.as_deref(), &out, runtime.as_deref())
        })
        .map_err(raise)?;
    Ok(exported.bytes)
}

/// The FMU runtime's file name on this platform (`liblagrangian_fmu.so`),
/// as the package ships it.
#[pyfunction]
fn fmu_runtime_file() -> String {
    lagrangian_fmi::exporter::runtime_file()
}

/// The module `lagrangian._lagrangian`.
#[pymodule]
fn _lagrangian(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeModel>()?;
    m.add_function(wrap_pyfunction!(exit_statuses, m)?)?;
    m.add_function(wrap_pyfunction!(register_errors, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    // `lpm sweep` and `lpm fit` (ensembles.rs).
    m.add_function(wrap_pyfunction!(ensembles::sweep_table, m)?)?;
    m.add_function(wrap_pyfunction!(ensembles::sweep_merge, m)?)?;
    m.add_function(wrap_pyfunction!(ensembles::sweep_plan, m)?)?;
    m.add_function(wrap_pyfunction!(ensembles::sweep_envelope, m)?)?;
    m.add_function(wrap_pyfunction!(ensembles::fit, m)?)?;
    m.add_function(wrap_pyfunction!(export_fmu, m)?)?;
    m.add_function(wrap_pyfunction!(fmu_runtime_file, m)?)?;
    m.add_function(wrap_pyfunction!(ensembles::sweep_merge_envelope, m)?)?;
    Ok(())
}
