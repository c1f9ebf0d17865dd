//! One timed cold solve (the bench's case), with iterations and contact fraction:
//! `cargo run --release -p stiction-bem --example bem_timing -- N [periodic|non-periodic] [HEIGHTS.bin]`.
//!
//! The surface is self-affine (H = 0.8, roll-off L/4, short cut-off 4 dx, rms 0.5 um, seed 1) on a
//! 100 um cell of `N x N` points, E* = 100 GPa, load control at p = 0.05 E* h'_rms, tolerance
//! 1e-6. `non-periodic`: the grid is a finite patch on a half-space that goes on (the Green's
//! function zero-padded to `2N x 2N`). With `HEIGHTS.bin` the heights are written there (f64
//! little-endian, row-major) and the mean pressure printed, for `scripts/tamaas-speed.py`.

use std::time::Instant;
use stiction_bem::{BemSolver, Boundary, Grid, SolverOptions, synth};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let n: usize = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(1024);
    let boundary = match a.get(2).map(String::as_str) {
        Some("non-periodic") => Boundary::NonPeriodic,
        _ => Boundary::Periodic,
    };
    let l = 100e-6;
    let g = Grid::new(n, n, l / n as f64, l / n as f64).expect("grid");
    let h = synth::self_affine(g, 0.8, l / 4.0, 4.0 * l / n as f64, 0.5e-6, 1).expect("surface");
    if let Some(path) = a.get(3) {
        let bytes: Vec<u8> = h.iter().flat_map(|v| v.to_le_bytes()).collect();
        std::fs::write(path, bytes).expect("write heights");
    }
    let t0 = Instant::now();
    let mut s = BemSolver::with_boundary(n, n, g.dx_m, g.dy_m, &h, 1e11, boundary).expect("solver");
    let p = 0.05 * 1e11 * s.slope_rms();
    let setup = t0.elapsed();
    let t1 = Instant::now();
    let sol = s.solve_load(p, &SolverOptions { tolerance: 1e-6, ..Default::default() }, None).expect("solve");
    println!(
        "{n}x{n} {boundary:?}: setup {:.3} s, solve {:.3} s, {} iterations, residual {:.2e}, A/A0 {:.5}, patches {}, threads {}, mean pressure {:e} Pa",
        setup.as_secs_f64(),
        t1.elapsed().as_secs_f64(),
        sol.iterations,
        sol.residual,
        sol.contact_fraction,
        sol.patches,
        rayon::current_num_threads(),
        p
    );
}
