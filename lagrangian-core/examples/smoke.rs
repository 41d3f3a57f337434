//! A spec's mass matrix entries as text, with the derivation time on stderr:
//! `cargo run -p lagrangian-core --example smoke -- SPEC`.

fn main() {
    let path = std::env::args().nth(1).unwrap();
    let src = std::fs::read_to_string(&path).unwrap();
    let mut model = match lagrangian_core::Model::from_source(&src) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{}", e.render(&path, &src));
            std::process::exit(1)
        }
    };
    let t0 = std::time::Instant::now();
    let d = match lagrangian_core::derive::derive(&mut model) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("{}", e.render(&path, &src));
            std::process::exit(1)
        }
    };
    eprintln!("derive: {:?}", t0.elapsed());
    let n = d.dimension;
    for i in 0..n {
        for j in i..n {
            println!("M[{i}][{j}] = {}", model.store.to_text(d.mass(i, j)));
        }
    }
    for i in 0..n {
        println!("f[{i}] = {}", model.store.to_text(d.forcing[i]));
    }
    println!("T = {}", model.store.to_text(d.kinetic));
    println!("V = {}", model.store.to_text(d.potential));
    println!("nodes: {}", model.store.len());
    let compiled =
        lagrangian_core::Compiled::new(lagrangian_core::Model::from_source(&src).unwrap()).unwrap();
    for r in &compiled.program.routines {
        println!(
            "{:?}: {:?} total {}",
            r.kind,
            compiled.program.counts(r),
            compiled.program.counts(r).total()
        );
    }
    if std::env::var("EMIT").is_ok() {
        println!(
            "{}",
            lagrangian_core::emit::emit_file(compiled, &Default::default(), "// header")
        );
    }
}
#[allow(dead_code)]
fn unused() {}
