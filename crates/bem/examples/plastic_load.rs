//! Elastic-perfectly-plastic contact under load control on the self-affine surface of
//! `adhesive_path` (the case of `scripts/tamaas-plastic.py`):
//!
//! `cargo run --release -p stiction-bem --example plastic_load -- N SLOPE HARDNESS_PA TOL [HEIGHTS.bin] P1 P2 ...`
//!
//! (cell 100 um, E* 1 GPa; mean pressures in Pa, each solved cold). One line of JSON per load.

use std::time::Instant;
use stiction_bem::{BemSolver, Grid, SolverOptions, synth};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let n: usize = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(128);
    let slope: f64 = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(0.1);
    let hardness: f64 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(5e7);
    let tol: f64 = a.get(4).and_then(|s| s.parse().ok()).unwrap_or(1e-6);
    let cell = 100e-6;
    let g = Grid::new(n, n, cell / n as f64, cell / n as f64).expect("grid");
    let mut h = synth::self_affine(g, 0.8, cell / 4.0, 4.0 * cell / n as f64, 1e-6, 1).expect("surface");
    let f = slope / synth::rms_slope(&h, g);
    h.iter_mut().for_each(|v| *v *= f);
    let mut rest = 5;
    if let Some(path) = a.get(5).filter(|s| s.ends_with(".bin")) {
        let bytes: Vec<u8> = h.iter().flat_map(|v| v.to_le_bytes()).collect();
        std::fs::write(path, bytes).expect("write heights");
        rest = 6;
    }
    let mut s = BemSolver::new(n, n, g.dx_m, g.dy_m, &h, 1e9).expect("solver");
    let opts = SolverOptions { tolerance: tol, ..Default::default() };
    for p in a.iter().skip(rest).filter_map(|s| s.parse::<f64>().ok()) {
        let t0 = Instant::now();
        let st = s.solve_load_plastic(p, hardness, &opts, None).expect("solve");
        println!(
            "{{\"mean_pressure_pa\":{:e},\"contact_fraction\":{:e},\"plastic_fraction\":{:e},\"mean_gap_m\":{:e},\"iterations\":{},\"residual\":{:e},\"seconds\":{:.3}}}",
            st.solution.mean_pressure_pa,
            st.solution.contact_fraction,
            st.plastic_fraction,
            st.solution.mean_gap_m,
            st.solution.iterations,
            st.solution.residual,
            t0.elapsed().as_secs_f64()
        );
    }
}
