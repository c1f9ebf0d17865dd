//! One timed cold solve per grid size (the bench's case), with iterations and contact fraction:
//! `cargo run --release -p stiction-bem --example bem_timing -- 1024`.

use std::time::Instant;
use stiction_bem::{BemSolver, Grid, SolverOptions, synth};

fn main() {
    let n: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(1024);
    let l = 100e-6;
    let g = Grid::new(n, n, l / n as f64, l / n as f64).expect("grid");
    let h = synth::self_affine(g, 0.8, l / 4.0, 4.0 * l / n as f64, 0.5e-6, 1).expect("surface");
    let t0 = Instant::now();
    let mut s = BemSolver::new(n, n, g.dx_m, g.dy_m, &h, 1e11).expect("solver");
    let p = 0.05 * 1e11 * s.slope_rms();
    let setup = t0.elapsed();
    let t1 = Instant::now();
    let sol = s.solve_load(p, &SolverOptions { tolerance: 1e-6, ..Default::default() }, None).expect("solve");
    println!(
        "{n}x{n}: setup {:.3} s, solve {:.3} s, {} iterations, residual {:.2e}, A/A0 {:.5}, patches {}, threads {}",
        setup.as_secs_f64(),
        t1.elapsed().as_secs_f64(),
        sol.iterations,
        sol.residual,
        sol.contact_fraction,
        sol.patches,
        rayon::current_num_threads()
    );
}
