//! Compiles CasADi's generated C (committed; see
//! benches/reference/casadi_yaris.py) at -O3, as one would ship it.

fn main() {
    println!("cargo:rerun-if-changed=yaris_casadi.c");
    cc::Build::new()
        .file("yaris_casadi.c")
        .opt_level(3)
        .warnings(false)
        .compile("yaris_casadi");
}
