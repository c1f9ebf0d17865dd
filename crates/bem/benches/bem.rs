//! Speed of the non-adhesive BEM solve: a Gaussian self-affine surface (H = 0.8, roll-off L/4,
//! short cut-off 4 dx, seed 1), load p = 0.05 E* h'_rms (A/A0 about 0.12), tolerance 1e-6, cold
//! start (uniform pressure). `cargo bench -p stiction-bem --bench bem`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use stiction_bem::{BemSolver, Grid, SolverOptions, synth};

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

criterion_group!(benches, bench);
criterion_main!(benches);
