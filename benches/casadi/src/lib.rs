//! The paper model (specs/yaris_double_pendulum.lpm) as CasADi's generated C,
//! for the q̈ bench: `M`, `f` and `q̈ = solve(M, f)` at `(t, q, v)` for the
//! parameters `p` in spec order. The bench's input functions are part of the
//! expressions (see benches/reference/casadi_yaris.py).

use std::ffi::c_int;
use std::ptr::null_mut;

/// The number of parameters, in the order of the spec's `parameters` block.
pub const PARAMETERS: usize = 17;

unsafe extern "C" {
    fn yaris_mass_forcing(
        arg: *const *const f64,
        res: *const *mut f64,
        iw: *mut i64,
        w: *mut f64,
        mem: c_int,
    ) -> c_int;
    fn yaris_accelerations(
        arg: *const *const f64,
        res: *const *mut f64,
        iw: *mut i64,
        w: *mut f64,
        mem: c_int,
    ) -> c_int;
}

/// `(M, f)` at a state; `M` column-major.
pub fn mass_forcing(
    t: f64,
    q: &[f64; 3],
    v: &[f64; 3],
    p: &[f64; PARAMETERS],
) -> ([f64; 9], [f64; 3]) {
    let (mut mass, mut forcing) = ([0.0; 9], [0.0; 3]);
    let arg = [&t as *const f64, q.as_ptr(), v.as_ptr(), p.as_ptr()];
    let res = [mass.as_mut_ptr(), forcing.as_mut_ptr()];
    // SAFETY: the generated function reads 1, 3, 3 and 17 values from the
    // four arguments and writes 9 and 3 values to the two results (its
    // sparsity patterns); it needs no work arrays (its `_work` sizes are 0).
    let status =
        unsafe { yaris_mass_forcing(arg.as_ptr(), res.as_ptr(), null_mut(), null_mut(), 0) };
    assert_eq!(status, 0);
    (mass, forcing)
}

/// `q̈ = M⁻¹ f` at a state.
pub fn accelerations(t: f64, q: &[f64; 3], v: &[f64; 3], p: &[f64; PARAMETERS]) -> [f64; 3] {
    let mut qdd = [0.0; 3];
    let arg = [&t as *const f64, q.as_ptr(), v.as_ptr(), p.as_ptr()];
    let res = [qdd.as_mut_ptr()];
    // SAFETY: as in `mass_forcing`, with one result of 3 values.
    let status =
        unsafe { yaris_accelerations(arg.as_ptr(), res.as_ptr(), null_mut(), null_mut(), 0) };
    assert_eq!(status, 0);
    qdd
}
