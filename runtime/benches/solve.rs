//! The mass-matrix solve of a chain (a banded `M`): the pattern solve
//! against the envelope solve, side by side in one run, for 50 and 200
//! coordinates, `M` diagonal and tridiagonal. `cargo bench -p
//! lagrangian-runtime --bench solve`; figures in BENCHMARKS.md.
use lagrangian_runtime::linalg::{Envelope, LdltPattern, solve_in_envelope, solve_with_pattern};
use nalgebra::{SMatrix, SVector};
use std::hint::black_box;

const fn band<const N: usize>(w: usize) -> [[bool; N]; N] {
    let mut nz = [[false; N]; N];
    let mut i = 0;
    while i < N {
        let mut j = 0;
        while j < N {
            nz[i][j] = i.abs_diff(j) <= w;
            j += 1;
        }
        i += 1;
    }
    nz
}

fn time<const N: usize>(what: &str, w: usize, pattern: &LdltPattern<N>, envelope: &Envelope<N>) {
    let m = SMatrix::<f64, N, N>::from_fn(|i, j| {
        if i == j {
            4.0
        } else if i.abs_diff(j) <= w {
            -0.5 / (1.0 + i.abs_diff(j) as f64)
        } else {
            0.0
        }
    });
    let b = SVector::<f64, N>::from_fn(|i, _| i as f64);
    let runs = 50000;
    let start = std::time::Instant::now();
    for _ in 0..runs {
        black_box(solve_with_pattern(black_box(&m), black_box(&b), pattern));
    }
    let a = start.elapsed().as_secs_f64() / runs as f64 * 1e6;
    let start = std::time::Instant::now();
    for _ in 0..runs {
        black_box(solve_in_envelope(black_box(&m), black_box(&b), envelope));
    }
    let e = start.elapsed().as_secs_f64() / runs as f64 * 1e6;
    println!(
        "{what} N={N}: pattern {a:.2} us, envelope {e:.2} us, ratio {:.2}",
        a / e
    );
}

fn main() {
    // `cargo test --benches` runs a bench binary with `--bench` absent: skip.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    const D50: LdltPattern<50> = LdltPattern::from_mass(band::<50>(0));
    const T50: LdltPattern<50> = LdltPattern::from_mass(band::<50>(1));
    const D200: LdltPattern<200> = LdltPattern::from_mass(band::<200>(0));
    const T200: LdltPattern<200> = LdltPattern::from_mass(band::<200>(1));
    time::<50>("diagonal", 0, &D50, &Envelope::of(D50));
    time::<50>("tridiagonal", 1, &T50, &Envelope::of(T50));
    time::<200>("diagonal", 0, &D200, &Envelope::of(D200));
    time::<200>("tridiagonal", 1, &T200, &Envelope::of(T200));
}
