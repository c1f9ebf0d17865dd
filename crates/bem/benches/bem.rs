//! Speed of the non-adhesive BEM solve: a Gaussian self-affine surface (H = 0.8, roll-off L/4,
//! short cut-off 4 dx, seed 1), load p = 0.05 E* h'_rms (A/A0 about 0.12), tolerance 1e-6, cold
//! start (uniform pressure); and of an adhesive approach (the case of scripts/tamaas-adhesion.py:
//! 128^2, rms slope 0.1, E* 1 GPa, w 12 J/m^2, range 0.3 um, three mean gaps from the reach of the
//! highest point down, each warm-started); and of the meter's finite shoe (`shoe_at_load`: the
//! 500 x 125 patch of 40 nm pixels of scenarios/tas2000-bem.json with one paraboloid summit of
//! R = 10 um, E* = 110 GPa, Dugdale w = 0.1 J/m^2 and h0 = 0.29 nm, the seven clamp loads
//! 0.406-4.774 uN on the loading branch, each continued from the last), on a set of candidate
//! points and on the whole grid. `cargo bench -p stiction-bem --bench bem`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use stiction_bem::{BemSolver, Boundary, ContactSolution, Dugdale, Grid, SolverOptions, synth};

fn case(n: usize) -> BemSolver {
    let l = 100e-6;
    let g = Grid::new(n, n, l / n as f64, l / n as f64).expect("grid");
    let h = synth::self_affine(g, 0.8, l / 4.0, 4.0 * l / n as f64, 0.5e-6, 1).expect("surface");
    BemSolver::new(n, n, g.dx_m, g.dy_m, &h, 1e11).expect("solver")
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("bem_load_1e-6");
    group.sample_size(10);
    for n in [256usize, 1024] {
        let mut s = case(n);
        let p = 0.05 * 1e11 * s.slope_rms();
        let opts = SolverOptions { tolerance: 1e-6, ..Default::default() };
        group.measurement_time(Duration::from_secs(if n > 512 { 150 } else { 10 }));
        group.bench_function(format!("{n}x{n}"), |b| {
            b.iter(|| black_box(s.solve_load(p, &opts, None).expect("solve").contact_fraction))
        });
    }
    group.finish();
}

fn adhesive(c: &mut Criterion) {
    let (n, l) = (128usize, 100e-6);
    let g = Grid::new(n, n, l / n as f64, l / n as f64).expect("grid");
    let mut h = synth::self_affine(g, 0.8, l / 4.0, 4.0 * l / n as f64, 1e-6, 1).expect("surface");
    let f = 0.1 / synth::rms_slope(&h, g);
    h.iter_mut().for_each(|v| *v *= f);
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let top = h.iter().copied().fold(f64::NEG_INFINITY, f64::max) - mean;
    let law = Dugdale::from_work_and_range(12.0, 0.3e-6).expect("law");
    let opts = SolverOptions { tolerance: 1e-6, ..Default::default() };
    let mut s = BemSolver::new(n, n, g.dx_m, g.dy_m, &h, 1e9).expect("solver");
    let gaps = [top + 0.27e-6, top + 0.1e-6, 0.8 * top];
    let mut group = c.benchmark_group("bem_adhesive_approach_1e-6");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    group.bench_function("128x128, 3 gaps", |b| {
        b.iter(|| {
            let mut state: Option<ContactSolution> = None;
            for &gap in &gaps {
                state = Some(s.solve_adhesive_mean_gap(gap, &law, &opts, state.as_ref()).expect("solve"));
            }
            black_box(state.map(|s| s.mean_pressure_pa))
        })
    });
    group.finish();
}

fn shoe_at_load(c: &mut Criterion) {
    let (nx, ny, dx, radius) = (500usize, 125usize, 40e-9, 10e-6);
    let h: Vec<f64> = (0..nx * ny)
        .map(|i| {
            let (x, y) = (((i % nx) as f64 - 0.5 * nx as f64) * dx, ((i / nx) as f64 - 0.5 * ny as f64) * dx);
            -(x * x + y * y) / (2.0 * radius)
        })
        .collect();
    let law = Dugdale::from_work_and_range(0.1, 0.29e-9).expect("law");
    let area = nx as f64 * ny as f64 * dx * dx;
    let loads: Vec<f64> = (0..7).map(|k| (0.406e-6 + k as f64 * (4.774e-6 - 0.406e-6) / 6.0) / area).collect();
    let mut s = BemSolver::with_boundary(nx, ny, dx, dx, &h, 1.1e11, Boundary::NonPeriodic).expect("solver");
    let mut group = c.benchmark_group("bem_shoe_at_load_1e-6");
    group.sample_size(10);
    for (name, restricted) in [("on a set", true), ("whole grid", false)] {
        let opts = SolverOptions { tolerance: 1e-6, max_zone_updates: 50, restricted, ..Default::default() };
        group.measurement_time(Duration::from_secs(if restricted { 5 } else { 30 }));
        group.bench_function(format!("500x125, 7 loads, {name}"), |b| {
            b.iter(|| {
                let mut state: Option<ContactSolution> = None;
                for &p in &loads {
                    state = Some(s.adhesive_at_load(p, &law, &opts, state.as_ref()).expect("solve"));
                }
                black_box(state.map(|s| s.contact_area_m2))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench, adhesive, shoe_at_load);
criterion_main!(benches);
