//! The spec of an n-link pendulum chain on stdout:
//! `cargo run -p lagrangian-core --example chain -- 10`.

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    print!("{}", lagrangian_core::examples::pendulum_chain(n));
}
