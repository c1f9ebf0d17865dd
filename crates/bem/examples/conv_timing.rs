//! Time of one FFT convolution (displacement from pressure) on an n x n grid:
//! `cargo run --release -p stiction-bem --example conv_timing -- 1024`.
use std::time::Instant;
use stiction_bem::{Grid, HalfSpace};
fn main() {
    let n: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(1024);
    let g = Grid::new(n, n, 1e-7, 1e-7).expect("grid");
    let mut h = HalfSpace::new(g, 1e11).expect("half-space");
    let p: Vec<f64> = (0..n * n).map(|i| (i % 7) as f64).collect();
    let mut u = h.displacement(&p);
    let t = Instant::now();
    for _ in 0..20 {
        u = h.displacement(&u);
    }
    println!(
        "{n}x{n}: {:.2} ms per convolution ({} threads)",
        t.elapsed().as_secs_f64() / 20.0 * 1e3,
        rayon::current_num_threads()
    );
}
