//! An adhesive approach and retraction under mean-gap control on a self-affine surface (the case
//! of `scripts/tamaas-adhesion.py`), timed, with a checksum of every state's bytes:
//!
//! `cargo run --release -p stiction-bem --example adhesive_path -- N SLOPE POINTS [TOL] [W] [HEIGHTS.bin] [RANGE] [solve|path|approach|approach-path]`
//!
//! `N` grid points a side (cell 100 um), `SLOPE` the spectral rms slope, `POINTS` mean gaps each
//! way, `TOL` the tolerance (1e-6), `W` the work of adhesion (12 J/m^2; E* 1 GPa), `RANGE` the
//! Dugdale range (0.3e-6 m). With `HEIGHTS.bin` (`-` for none) the heights are written there
//! (f64 little-endian, row-major) for the Tamaas side. One line of JSON per state on stdout; the
//! time and checksum on stderr. `path`: only the imposed mean gaps, one line each, no solve.
//! `approach` and `approach-path`: the same for the loading branch alone (no retraction).

use std::io::Write;
use std::time::Instant;
use stiction_bem::{BemSolver, ContactSolution, Dugdale, Grid, SolverOptions, synth};

/// The cell side, m.
const CELL_M: f64 = 100e-6;
/// Composite modulus, Pa.
const E_STAR_PA: f64 = 1e9;
/// Default Dugdale range, m.
const RANGE_M: f64 = 0.3e-6;

/// The self-affine surface of the comparison: H = 0.8, roll-off L/4, short cut-off 4 dx, seed 1,
/// scaled to the spectral rms slope `slope`.
fn surface(n: usize, slope: f64) -> (Grid, Vec<f64>) {
    let g = Grid::new(n, n, CELL_M / n as f64, CELL_M / n as f64).expect("grid");
    let mut h = synth::self_affine(g, 0.8, CELL_M / 4.0, 4.0 * CELL_M / n as f64, 1e-6, 1).expect("surface");
    let f = slope / synth::rms_slope(&h, g);
    h.iter_mut().for_each(|v| *v *= f);
    (g, h)
}

fn fnv(hash: &mut u64, v: &[f64]) {
    for x in v {
        for b in x.to_bits().to_le_bytes() {
            *hash = (*hash ^ b as u64).wrapping_mul(0x100000001b3);
        }
    }
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let arg = |i: usize, d: f64| a.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let n = arg(1, 256.0) as usize;
    let slope = arg(2, 0.1);
    let points = arg(3, 12.0) as usize;
    let tol = arg(4, 1e-6);
    let w = arg(5, 12.0);
    let (g, h) = surface(n, slope);
    let range_m = arg(7, RANGE_M);
    let mode = a.get(8).map(String::as_str).unwrap_or("solve");
    let only_path = mode.ends_with("path");
    let with_retraction = !mode.starts_with("approach");
    if let Some(path) = a.get(6).filter(|p| p.as_str() != "-") {
        let bytes: Vec<u8> = h.iter().flat_map(|v| v.to_le_bytes()).collect();
        std::fs::write(path, bytes).expect("write heights");
    }
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let top = h.iter().copied().fold(f64::NEG_INFINITY, f64::max) - mean;
    // Mean gaps from just within reach of the highest point (top + 0.9 range) down to a tenth
    // of the top, and back.
    let (hi, lo) = (top + 0.9 * range_m, 0.1 * top);
    let gaps: Vec<f64> = (0..points).map(|i| hi + (lo - hi) * i as f64 / (points - 1) as f64).collect();
    let law = Dugdale::from_work_and_range(w, range_m).expect("law");
    let opts = SolverOptions { tolerance: tol, ..Default::default() };
    let t0 = Instant::now();
    let mut s = BemSolver::new(n, n, g.dx_m, g.dy_m, &h, E_STAR_PA).expect("solver");
    let mut state: Option<ContactSolution> = None;
    let mut hash = 0xcbf29ce484222325u64;
    let mut iterations = 0;
    let out = std::io::stdout();
    let mut out = out.lock();
    let back = if with_retraction { points.saturating_sub(1) } else { 0 };
    let path =
        gaps.iter().map(|&g| ("approach", g)).chain(gaps.iter().rev().skip(1).take(back).map(|&g| ("retraction", g)));
    if only_path {
        for (branch, gap) in path {
            writeln!(out, "{{\"branch\":\"{branch}\",\"mean_gap_m\":{gap:e}}}").expect("stdout");
        }
        return;
    }
    for (branch, gap) in path {
        let st = s.solve_adhesive_mean_gap(gap, &law, &opts, state.as_ref()).expect("solve");
        fnv(&mut hash, &st.pressure_pa);
        fnv(&mut hash, &st.gap_m);
        iterations += st.iterations;
        // The Dugdale potential phi(g) = -(w/rho) max(rho - g, 0), averaged.
        let adhesive =
            -law.stress_pa * st.gap_m.iter().map(|g| (range_m - g).max(0.0)).sum::<f64>() / n as f64 / n as f64;
        writeln!(
            out,
            "{{\"branch\":\"{branch}\",\"mean_gap_m\":{:e},\"mean_pressure_pa\":{:e},\"repulsive_fraction\":{:e},\"cohesive_fraction\":{:e},\"iterations\":{},\"zone_updates\":{},\"elastic_energy_j_per_m2\":{:e},\"adhesive_energy_j_per_m2\":{:e}}}",
            st.mean_gap_m,
            st.mean_pressure_pa,
            st.contact_fraction,
            st.cohesive_fraction,
            st.iterations,
            st.zone_updates,
            st.elastic_energy_j_per_m2,
            adhesive
        )
        .expect("stdout");
        state = Some(st);
    }
    eprintln!(
        "{n}x{n} slope {slope} points {points} tol {tol:e}: {:.3} s, {iterations} iterations, checksum {hash:016x}, threads {}",
        t0.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
}
