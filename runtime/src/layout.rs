//! What each routine of a compiled model computes, and the order of its
//! outputs: the one description the optimizer builds to, the emitters write
//! from and the interpreter unpacks by.

/// Which group of outputs a routine computes.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum RoutineKind {
    /// The upper triangle of `M` (row by row, [`mass_entries`]), then `f`.
    Dynamics,
    /// `T, V, D, Σ ∂D/∂q̇·q̇, Σ Q·q̇` (the fields of [`Energies`], in order).
    Energies,
    /// `∂f/∂q`, `∂f/∂q̇`, `∂(M a)/∂q`, each row-major `n × n`
    /// ([`JACOBIAN_BLOCKS`]).
    Jacobians,
    /// The arguments of every input-function call of the dynamics routine,
    /// concatenated in the order of the model's input sites.
    InputArguments,
    /// The outputs of [`RoutineKind::Dynamics`], then `Σ ∂D/∂q̇·q̇` and
    /// `Σ Q·q̇`: one pass for an integrator that also integrates the
    /// dissipated energy and the work of the forces, sharing the operations
    /// and input calls the two groups have in common.
    DynamicsAndPowers,
    /// The spec's `output` statements, in declaration order, at
    /// `(t, q, q̇, q̈)`: the accelerations are inputs, so the outputs are
    /// evaluated after the equations of motion are solved. Only models that
    /// declare outputs have this routine.
    Outputs,
    /// The switching functions of the dynamics: the argument of each `abs`
    /// and `sign`, `a − b` of each `min(a, b)` and `max(a, b)`, at
    /// `(t, q, q̇)`. The integrator locates each sign change as an event, so
    /// that no step straddles a kink. Only models with non-smooth functions
    /// have this routine.
    Switching,
    /// The holonomic constraints `g(q, t) = 0` at `(t, q, q̇)`: `g`, `∂g/∂t`,
    /// `G = ∂g/∂q` (row-major) and `γ` (`G q̈ = γ` along a motion that keeps
    /// them), in the order of [`ConstraintLayout`]. Only models that declare
    /// constraints have this routine.
    Constraints,
}

/// Where each term of [`RoutineKind::Constraints`] is among its outputs, for
/// `m` constraints on `n` coordinates: `g` (`m`), `g_t` (`m`), `G` (`m × n`,
/// row-major), `γ` (`m`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConstraintLayout {
    /// The number of constraints.
    pub m: usize,
    /// The number of coordinates.
    pub n: usize,
}

impl ConstraintLayout {
    /// The number of outputs, `m (n + 3)`.
    pub fn len(self) -> usize {
        self.m * (self.n + 3)
    }

    /// Whether there are no constraints.
    pub fn is_empty(self) -> bool {
        self.m == 0
    }

    /// The residuals `g`.
    pub fn residual(self) -> std::ops::Range<usize> {
        0..self.m
    }

    /// The time partials `∂g/∂t`.
    pub fn time_rate(self) -> std::ops::Range<usize> {
        self.m..2 * self.m
    }

    /// `G`, row-major `m × n`.
    pub fn jacobian(self) -> std::ops::Range<usize> {
        2 * self.m..self.m * (2 + self.n)
    }

    /// `γ`.
    pub fn acceleration(self) -> std::ops::Range<usize> {
        self.m * (2 + self.n)..self.len()
    }
}

/// `(i, j)` of the entries of `M` among the dynamics outputs, in order: the
/// upper triangle (`i ≤ j`), row by row; `M` is symmetric.
pub fn mass_entries(n: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..n).flat_map(move |i| (i..n).map(move |j| (i, j)))
}

/// Writes the dynamics outputs `out` of a model with `n` coordinates into
/// row-major `mass` (`n × n`, both triangles) and `forcing`, and returns the
/// outputs that follow them (the powers of [`RoutineKind::DynamicsAndPowers`]).
///
/// The loops visit `M` in the order of [`mass_entries`] (a test holds them
/// equal); written out so that, inlined with a constant `n`, they unroll.
#[inline]
pub fn unpack_dynamics<'a>(
    out: &'a [f64],
    n: usize,
    mass: &mut [f64],
    forcing: &mut [f64],
) -> &'a [f64] {
    let mut k = 0;
    for i in 0..n {
        for j in i..n {
            mass[i * n + j] = out[k];
            mass[j * n + i] = out[k];
            k += 1;
        }
    }
    forcing[..n].copy_from_slice(&out[k..k + n]);
    &out[k + n..]
}

/// The names of the Jacobian blocks, in output order (the fields of
/// `Jacobians`): each block is row-major `n × n`, entry `(i, k)` the
/// derivative of equation `i` by coordinate or velocity `k`.
pub const JACOBIAN_BLOCKS: [&str; 3] = ["forcing_q", "forcing_qd", "mass_times_acceleration_q"];

/// Energy bookkeeping at one state: the outputs of [`RoutineKind::Energies`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energies {
    /// Kinetic energy `T`.
    pub kinetic: f64,
    /// Potential energy `V`.
    pub potential: f64,
    /// Rayleigh dissipation function `D`.
    pub dissipation: f64,
    /// `Σ_i ∂D/∂q̇_i q̇_i`: power dissipated by `D` (= 2D when D is quadratic).
    pub damping_power: f64,
    /// `Σ_i Q_i q̇_i`: power of the generalized forces of the force statements.
    pub external_power: f64,
}

impl Energies {
    /// The field names, in output order.
    pub const FIELDS: [&'static str; 5] = [
        "kinetic",
        "potential",
        "dissipation",
        "damping_power",
        "external_power",
    ];

    /// The values in the order of [`Energies::FIELDS`].
    pub fn values(&self) -> [f64; 5] {
        [
            self.kinetic,
            self.potential,
            self.dissipation,
            self.damping_power,
            self.external_power,
        ]
    }

    /// The energies from the outputs of an energies routine, in the order of
    /// [`Energies::FIELDS`].
    pub fn from_outputs(out: &[f64; 5]) -> Energies {
        let [
            kinetic,
            potential,
            dissipation,
            damping_power,
            external_power,
        ] = *out;
        Energies {
            kinetic,
            potential,
            dissipation,
            damping_power,
            external_power,
        }
    }

    /// `T` and `V`.
    pub fn mechanical(&self) -> MechanicalEnergy {
        MechanicalEnergy {
            kinetic: self.kinetic,
            potential: self.potential,
        }
    }
}

/// The mechanical energy at one state: `T` and `V`, the fields of
/// [`Energies`] that need neither the dissipation nor the forces (those of
/// the tape's derived mechanical-energy routine, in order).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MechanicalEnergy {
    /// Kinetic energy `T`.
    pub kinetic: f64,
    /// Potential energy `V`.
    pub potential: f64,
}

/// What one output of a routine is: the place it has in the runtime's
/// types. Emitters write each output to its slot instead of re-deriving the
/// order of a routine's outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OutputSlot {
    /// Entry `(row, column)`, `row ≤ column`, of the mass matrix `M`; `M` is
    /// symmetric, so it is entry `(column, row)` too.
    Mass {
        /// The row, `≤ column`.
        row: usize,
        /// The column.
        column: usize,
    },
    /// Component `i` of the forcing `f`.
    Forcing(usize),
    /// One of the energies or powers of [`Energies`].
    Energy(Energy),
    /// Entry `(row, column)` of one of the Jacobian blocks.
    Jacobian {
        /// Which block.
        block: JacobianBlock,
        /// The equation.
        row: usize,
        /// The coordinate or velocity differentiated by.
        column: usize,
    },
    /// Value `k` of the concatenated arguments of the input calls
    /// ([`RoutineKind::InputArguments`]).
    InputArgument(usize),
    /// The value of the spec's output `k`, in declaration order
    /// ([`RoutineKind::Outputs`]).
    Output(usize),
    /// Switching function `k` ([`RoutineKind::Switching`]).
    Switching(usize),
    /// Value `k` of the constraint terms, in the order of
    /// [`ConstraintLayout`] ([`RoutineKind::Constraints`]).
    Constraint(usize),
}

/// One field of [`Energies`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Energy {
    /// Kinetic energy `T`.
    Kinetic,
    /// Potential energy `V`.
    Potential,
    /// Rayleigh dissipation function `D`.
    Dissipation,
    /// `Σ ∂D/∂q̇·q̇`.
    DampingPower,
    /// `Σ Q·q̇`.
    ExternalPower,
}

impl Energy {
    /// All of them, in the order of [`Energies::FIELDS`].
    pub const ALL: [Energy; 5] = [
        Energy::Kinetic,
        Energy::Potential,
        Energy::Dissipation,
        Energy::DampingPower,
        Energy::ExternalPower,
    ];

    /// The position in [`Energies::FIELDS`] (and among the energies outputs).
    pub fn index(self) -> usize {
        self as usize
    }

    /// The field name in [`Energies`].
    pub fn field(self) -> &'static str {
        Energies::FIELDS[self.index()]
    }
}

/// One of the Jacobian blocks, in output order ([`JACOBIAN_BLOCKS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JacobianBlock {
    /// `∂f/∂q`.
    ForcingQ,
    /// `∂f/∂q̇`.
    ForcingQd,
    /// `∂(M a)/∂q`.
    MassTimesAccelerationQ,
}

impl JacobianBlock {
    /// All of them, in output order.
    pub const ALL: [JacobianBlock; 3] = [
        JacobianBlock::ForcingQ,
        JacobianBlock::ForcingQd,
        JacobianBlock::MassTimesAccelerationQ,
    ];

    /// The position among the blocks.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The field name in `Jacobians` ([`JACOBIAN_BLOCKS`]).
    pub fn field(self) -> &'static str {
        JACOBIAN_BLOCKS[self.index()]
    }
}

impl RoutineKind {
    /// Every routine a program can have.
    pub const ALL: [RoutineKind; 8] = [
        RoutineKind::Dynamics,
        RoutineKind::Energies,
        RoutineKind::Jacobians,
        RoutineKind::InputArguments,
        RoutineKind::DynamicsAndPowers,
        RoutineKind::Outputs,
        RoutineKind::Switching,
        RoutineKind::Constraints,
    ];

    /// The routine's position in [`RoutineKind::ALL`]: a table by kind
    /// finds a routine without a search.
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The number of outputs of the routine for a model with `n`
    /// coordinates; `None` for [`RoutineKind::InputArguments`],
    /// [`RoutineKind::Outputs`], [`RoutineKind::Switching`] and
    /// [`RoutineKind::Constraints`], whose counts depend on the model's input
    /// calls, output statements, functions and constraints.
    pub fn output_count(self, n: usize) -> Option<usize> {
        let mass = n * (n + 1) / 2;
        match self {
            RoutineKind::Dynamics => Some(mass + n),
            RoutineKind::DynamicsAndPowers => Some(mass + n + 2),
            RoutineKind::Energies => Some(Energy::ALL.len()),
            RoutineKind::Jacobians => Some(JacobianBlock::ALL.len() * n * n),
            RoutineKind::InputArguments
            | RoutineKind::Outputs
            | RoutineKind::Switching
            | RoutineKind::Constraints => None,
        }
    }

    /// What output `k` of the routine is, for a model with `n` coordinates;
    /// `None` beyond [`RoutineKind::output_count`].
    pub fn output_slot(self, n: usize, k: usize) -> Option<OutputSlot> {
        if self.output_count(n).is_some_and(|count| k >= count) {
            return None;
        }
        let mass = n * (n + 1) / 2;
        Some(match self {
            RoutineKind::Dynamics | RoutineKind::DynamicsAndPowers if k < mass => {
                let (row, column) = mass_entry(n, k);
                OutputSlot::Mass { row, column }
            }
            RoutineKind::Dynamics | RoutineKind::DynamicsAndPowers if k < mass + n => {
                OutputSlot::Forcing(k - mass)
            }
            RoutineKind::Dynamics | RoutineKind::DynamicsAndPowers => {
                OutputSlot::Energy(Energy::ALL[Energy::DampingPower.index() + k - mass - n])
            }
            RoutineKind::Energies => OutputSlot::Energy(Energy::ALL[k]),
            RoutineKind::Jacobians => OutputSlot::Jacobian {
                block: JacobianBlock::ALL[k / (n * n)],
                row: k % (n * n) / n,
                column: k % n,
            },
            RoutineKind::InputArguments => OutputSlot::InputArgument(k),
            RoutineKind::Outputs => OutputSlot::Output(k),
            RoutineKind::Switching => OutputSlot::Switching(k),
            RoutineKind::Constraints => OutputSlot::Constraint(k),
        })
    }
}

/// Entry `k` of [`mass_entries`]`(n)`.
fn mass_entry(n: usize, mut k: usize) -> (usize, usize) {
    let mut row = 0;
    while k >= n - row {
        k -= n - row;
        row += 1;
    }
    (row, row + k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mass_matrix_is_its_upper_triangle_row_by_row() {
        let entries: Vec<_> = mass_entries(3).collect();
        assert_eq!(entries, [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]);
        let out = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0];
        let (mut mass, mut forcing) = ([0.0; 9], [0.0; 3]);
        let rest = unpack_dynamics(&out, 3, &mut mass, &mut forcing);
        assert_eq!(mass, [1.0, 2.0, 3.0, 2.0, 4.0, 5.0, 3.0, 5.0, 6.0]);
        for (k, (i, j)) in mass_entries(3).enumerate() {
            assert_eq!((mass[i * 3 + j], mass[j * 3 + i]), (out[k], out[k]));
        }
        assert_eq!(forcing, [7.0, 8.0, 9.0]);
        assert_eq!(rest, [10.0, 11.0]);
    }

    /// The slots name the outputs in the order the other descriptions give.
    #[test]
    fn output_slots_follow_the_layout() {
        let n = 3;
        let slots = |kind: RoutineKind| -> Vec<OutputSlot> {
            let count = kind.output_count(n).unwrap();
            assert_eq!(kind.output_slot(n, count), None);
            (0..count)
                .map(|k| kind.output_slot(n, k).unwrap())
                .collect()
        };
        let mut dynamics: Vec<OutputSlot> = mass_entries(n)
            .map(|(row, column)| OutputSlot::Mass { row, column })
            .collect();
        dynamics.extend((0..n).map(OutputSlot::Forcing));
        assert_eq!(slots(RoutineKind::Dynamics), dynamics);
        dynamics.push(OutputSlot::Energy(Energy::DampingPower));
        dynamics.push(OutputSlot::Energy(Energy::ExternalPower));
        assert_eq!(slots(RoutineKind::DynamicsAndPowers), dynamics);
        let energies: Vec<&str> = slots(RoutineKind::Energies)
            .into_iter()
            .map(|slot| match slot {
                OutputSlot::Energy(e) => e.field(),
                other => panic!("{other:?} among the energies"),
            })
            .collect();
        assert_eq!(energies, Energies::FIELDS);
        let jacobians = slots(RoutineKind::Jacobians);
        assert_eq!(jacobians.len(), 27);
        assert_eq!(
            jacobians[9 + 5],
            OutputSlot::Jacobian {
                block: JacobianBlock::ForcingQd,
                row: 1,
                column: 2
            }
        );
        let blocks = JacobianBlock::ALL.map(JacobianBlock::field);
        assert_eq!(blocks, JACOBIAN_BLOCKS);
        assert_eq!(
            RoutineKind::InputArguments.output_slot(n, 7),
            Some(OutputSlot::InputArgument(7))
        );
        assert_eq!(RoutineKind::Outputs.output_count(n), None);
        assert_eq!(
            RoutineKind::Outputs.output_slot(n, 2),
            Some(OutputSlot::Output(2))
        );
    }
}
