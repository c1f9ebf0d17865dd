//! Criterion benchmarks of the explicit solver (one core, release).
//!
//! * `explicit/table1_loading_point`: the Table 1 surface (about 400 summits), tilt free, DMT:
//!   one load step of a 0-10 uN loading curve from the previous equilibrium (floor 20 us).
//! * `explicit/load_point/N`: one step of the loading curve from pull-off to L* = 0.1 for N summits.
//! * `explicit/table1_md_lognormal_point`: the Table 1 surface with lognormal radii (R = 0.5 +/-
//!   0.3 um), tilt free, Maugis-Dugdale (per-summit tables): one step of a pull-off to 10 uN
//!   loading curve.
//! * `explicit/table1_md_lognormal_new`: building that solver (sorting check and the tables).
//! * `explicit/curve_1e6_tilt_free`: 1e6 summits, tilt free, DMT: pull-off search plus a 100-point
//!   loading curve from pull-off to L* = 0.1 (floor 0.5 s in all).
//! * `explicit/curve_1e6_flat`: the same curve for a flat shoe (the GW situation; `contact --sweep
//!   --mode flat`).
//!
//! * `explicit/wet/...`: the same with a meniscus at every wetted summit (water, RH 35 %, 25 C,
//!   contact angles 0: `Meniscus::from_capillarity`), for the cost of capillarity against dry.
//!
//! `cargo bench -p stiction-contact --bench explicit`

use std::hint::black_box;

use criterion::{Criterion, criterion_main};
use stiction_contact::capillary::{Capillarity, Liquid};
use stiction_contact::explicit::{Detail, ExplicitSolver, Meniscus, ShoeMode, SolverConfig};
use stiction_contact::single::{AdhesionLaw, AsperityParams, Branch};
use stiction_surface::{FaceParams, Layout, Placement, RadiusDistribution, Surface, generate};

fn surface(summits: f64, seed: u64) -> Surface {
    let (eta, sigma, r) = (4e12, 0.04e-6, 0.5e-6);
    let width = (summits / eta / 4.0).sqrt();
    let layout =
        Layout { apparent_length_m: 4.0 * width, apparent_width_m: width, placement: Placement::Poisson, seed };
    generate(&layout, &FaceParams::gaussian_fixed(eta, sigma, r)).expect("surface")
}

/// Load at L* = 0.1 (eq. 5c) for `m` summits of the Table 1 statistics \[N\].
fn load_star_01(m: usize) -> f64 {
    0.1 * m as f64 * 0.5e-6f64.sqrt() * 0.04e-6f64.powf(1.5) / 9.1e-12
}

fn solver(s: Surface, detail: Detail) -> ExplicitSolver {
    solver_mode(s, detail, ShoeMode::TiltFree)
}

fn solver_mode(s: Surface, detail: Detail, mode: ShoeMode) -> ExplicitSolver {
    let cfg = SolverConfig { detail, mode, ..Default::default() };
    ExplicitSolver::new(s, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver")
}

/// Water at 25 C, RH 35 %, both contact angles 0.
fn meniscus() -> Meniscus {
    let t = 298.15;
    let cap = Capillarity::new(Liquid::water(t), t, 0.35, 0.0, 0.0).expect("capillarity").expect("wet");
    Meniscus::from_capillarity(&cap)
}

fn loads(from: f64, to: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| from + (to - from) * k as f64 / (n - 1) as f64).collect()
}

pub(crate) fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("explicit");
    let layout = Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed: 1 };
    let t1 = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).expect("surface");
    let mut s1 = solver(t1, Detail::Full);
    let steps = loads(0.0, 10e-6, 100);
    let mut k = 0usize;
    g.bench_function("table1_loading_point", |b| {
        b.iter(|| {
            if k == 0 {
                s1.reset();
            }
            let e = s1.solve(black_box(steps[k])).expect("solve");
            k = (k + 1) % steps.len();
            e
        })
    });
    let face_ln = FaceParams {
        radius_sd_m: 0.3e-6,
        radius_distribution: RadiusDistribution::Lognormal,
        ..FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)
    };
    let t1_ln = generate(&layout, &face_ln).expect("surface");
    let md = |s: Surface| {
        ExplicitSolver::new(s, AdhesionLaw::MaugisDugdale, AsperityParams::table1(), SolverConfig::default())
            .expect("solver")
    };
    g.bench_function("table1_md_lognormal_new", |b| b.iter(|| md(black_box(t1_ln.clone()))));
    let mut s_md = md(t1_ln);
    let po = s_md.pull_off(0.0, 1e-6).expect("pull-off").load_n;
    let steps_md = loads(po, 10e-6, 100);
    let mut k = 0usize;
    g.bench_function("table1_md_lognormal_point", |b| {
        b.iter(|| {
            if k == 0 {
                s_md.reset();
                s_md.pull_off(0.0, 1e-6).expect("pull-off");
            }
            let e = s_md.solve(black_box(steps_md[k])).expect("solve");
            k = (k + 1) % steps_md.len();
            e
        })
    });
    let t1w = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).expect("surface");
    let mut s1w = solver(t1w, Detail::Full);
    s1w.set_meniscus(Some(meniscus())).expect("meniscus");
    let mut k = 0usize;
    g.bench_function("wet/table1_loading_point", |b| {
        b.iter(|| {
            if k == 0 {
                s1w.reset();
            }
            let e = s1w.solve(black_box(steps[k])).expect("solve");
            k = (k + 1) % steps.len();
            e
        })
    });
    for &(n, wet) in &[(1e4, false), (1e5, false), (1e6, false), (1e4, true), (1e5, true), (1e6, true)] {
        let mut s = solver(surface(n, 1), Detail::Summary);
        if wet {
            s.set_meniscus(Some(meniscus())).expect("meniscus");
        }
        let m = s.len();
        let po = s.pull_off(0.0, 1e-6).expect("pull-off").load_n;
        let curve = loads(po, load_star_01(m), 100);
        let mut k = 0usize;
        let name = if wet { format!("wet/load_point/{n:.0e}") } else { format!("load_point/{n:.0e}") };
        g.bench_function(name, |b| {
            b.iter(|| {
                if k == 0 {
                    s.reset();
                    s.pull_off(0.0, 1e-6).expect("pull-off");
                }
                let e = s.solve(black_box(curve[k])).expect("solve");
                k = (k + 1) % curve.len();
                e
            })
        });
    }
    g.sample_size(10);
    let s6 = surface(1e6, 1);
    let m6 = s6.len();
    let mut big = solver(s6, Detail::Summary);
    g.bench_function("curve_1e6_tilt_free", |b| {
        b.iter(|| {
            big.reset();
            let po = big.pull_off(0.0, 1e-6).expect("pull-off").load_n;
            big.sweep(&loads(po, load_star_01(m6), 100), Branch::Loading).expect("sweep")
        })
    });
    let mut big_wet = solver(surface(1e6, 1), Detail::Summary);
    big_wet.set_meniscus(Some(meniscus())).expect("meniscus");
    g.bench_function("wet/curve_1e6_tilt_free", |b| {
        b.iter(|| {
            big_wet.reset();
            let po = big_wet.pull_off(0.0, 1e-6).expect("pull-off").load_n;
            big_wet.sweep(&loads(po, load_star_01(m6), 100), Branch::Loading).expect("sweep")
        })
    });
    let mut flat = solver_mode(surface(1e6, 1), Detail::Summary, ShoeMode::Flat);
    g.bench_function("curve_1e6_flat", |b| {
        b.iter(|| {
            flat.reset();
            let po = flat.pull_off(0.0, 1e-6).expect("pull-off").load_n;
            flat.sweep(&loads(po, load_star_01(m6), 100), Branch::Loading).expect("sweep")
        })
    });
    g.finish();
}

// criterion_group! expands to an undocumented function.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench);
}
use group::benches;
criterion_main!(benches);
