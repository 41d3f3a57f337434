//! The modes of a linearized system: the eigenvalues of `A`, one mode per
//! complex-conjugate pair or real eigenvalue, with natural frequency
//! `|λ|/2π` and damping ratio `−Re λ/|λ|`.

use nalgebra::{Complex, DMatrix, Schur};

/// What a mode does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeKind {
    /// `λ = 0`: a rigid-body motion (no restoring force), or a neutral
    /// direction of the equilibrium.
    RigidBody,
    /// A complex pair on the imaginary axis: an oscillation that neither
    /// grows nor decays.
    Undamped,
    /// A complex pair with `Re λ < 0`: a decaying oscillation.
    Underdamped,
    /// A real `λ < 0`: a decay without oscillation.
    Overdamped,
    /// `Re λ > 0`: a motion that grows (an unstable equilibrium).
    Unstable,
}

impl ModeKind {
    /// The kind in snake case, as the reports write it.
    pub fn name(self) -> &'static str {
        match self {
            ModeKind::RigidBody => "rigid_body",
            ModeKind::Undamped => "undamped",
            ModeKind::Underdamped => "underdamped",
            ModeKind::Overdamped => "overdamped",
            ModeKind::Unstable => "unstable",
        }
    }

    /// The kind in words.
    pub fn description(self) -> &'static str {
        match self {
            ModeKind::RigidBody => "rigid-body mode (zero eigenvalue: no restoring force)",
            ModeKind::Undamped => "undamped oscillation",
            ModeKind::Underdamped => "damped oscillation",
            ModeKind::Overdamped => "overdamped (real eigenvalue: decays without oscillating)",
            ModeKind::Unstable => "unstable (grows: Re λ > 0)",
        }
    }
}

/// One mode of `A`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mode {
    /// Its eigenvalue (of a complex pair, the one with `Im λ > 0`) \[1/s\].
    pub eigenvalue: Complex<f64>,
    /// `|λ| / 2π` \[Hz\] (the damped frequency is `Im λ / 2π`).
    pub frequency_hz: f64,
    /// `−Re λ / |λ|`; NaN for a rigid-body mode.
    pub damping_ratio: f64,
    /// What the mode does.
    pub kind: ModeKind,
}

/// The modes of `A` by increasing frequency; `None` when its eigenvalues
/// do not converge (or `A` is not finite).
pub fn modes(a: &DMatrix<f64>) -> Option<Vec<Mode>> {
    if a.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let eigenvalues =
        Schur::try_new(a.clone(), f64::EPSILON, 1000 * a.nrows().max(1))?.complex_eigenvalues();
    // An eigenvalue of a defective zero block (a free mass: λ = 0 twice)
    // moves by about √(ε‖A‖); below that it is zero.
    let zero = 10.0 * f64::EPSILON.sqrt() * a.amax().max(1.0);
    let mut modes: Vec<Mode> = (eigenvalues.iter())
        .filter(|λ| λ.im >= -zero) // a real one, or the upper of a pair
        .map(|&λ| mode(λ, zero))
        .collect();
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    Some(modes)
}

/// The mode of eigenvalue `λ`, with `zero` the size below which a part
/// of an eigenvalue is zero.
fn mode(λ: Complex<f64>, zero: f64) -> Mode {
    let size = λ.norm();
    let real = λ.im.abs() <= zero;
    let kind = if size <= zero {
        ModeKind::RigidBody
    } else if λ.re > zero {
        ModeKind::Unstable
    } else if real {
        ModeKind::Overdamped
    } else if λ.re.abs() <= zero {
        ModeKind::Undamped
    } else {
        ModeKind::Underdamped
    };
    let (eigenvalue, damping_ratio) = match kind {
        ModeKind::RigidBody => (Complex::new(0.0, 0.0), f64::NAN),
        ModeKind::Undamped => (Complex::new(0.0, λ.im), 0.0),
        _ if real => (Complex::new(λ.re, 0.0), -λ.re / size),
        _ => (λ, -λ.re / size),
    };
    Mode {
        eigenvalue,
        frequency_hz: eigenvalue.norm() / std::f64::consts::TAU,
        damping_ratio,
        kind,
    }
}
