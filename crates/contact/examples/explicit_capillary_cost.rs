//! Cost of capillarity in the explicit solver: pull-off search and a 100-point loading curve to
//! L* = 0.1 on a Table 1 surface of about 1e5 summits (tilt free, DMT), dry and with a meniscus
//! (water, RH 35 %, 25 C, contact angles 0), with the passes and summits scanned per point.
//! `cargo run --release -p stiction-contact --example explicit_capillary_cost -- [dry|wet]`
//! (deterministic instruction counts: run each under `valgrind --tool=callgrind
//! --toggle-collect='*ExplicitSolver*sweep*'`).

use stiction_contact::capillary::{Capillarity, Liquid};
use stiction_contact::explicit::{Detail, ExplicitSolver, Meniscus, SolverConfig};
use stiction_contact::single::{AdhesionLaw, AsperityParams, Branch};
use stiction_surface::{FaceParams, Layout, Placement, generate};

fn main() {
    let (n, eta, sigma, r) = (1e5, 4e12, 0.04e-6, 0.5e-6);
    let width = (n / eta / 4.0f64).sqrt();
    let layout =
        Layout { apparent_length_m: 4.0 * width, apparent_width_m: width, placement: Placement::Poisson, seed: 1 };
    let s = generate(&layout, &FaceParams::gaussian_fixed(eta, sigma, r)).expect("surface");
    let m = s.len();
    let l01 = 0.1 * m as f64 * r.sqrt() * sigma.powf(1.5) / 9.1e-12;
    let which: Vec<bool> = match std::env::args().nth(1).as_deref() {
        Some("dry") => vec![false],
        Some("wet") => vec![true],
        _ => vec![false, true],
    };
    for wet in which {
        let cfg = SolverConfig { detail: Detail::Summary, ..Default::default() };
        let mut sol = ExplicitSolver::new(s.clone(), AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver");
        if wet {
            let cap = Capillarity::new(Liquid::water(298.15), 298.15, 0.35, 0.0, 0.0).expect("water").expect("wet");
            sol.set_meniscus(Some(Meniscus::from_capillarity(&cap))).expect("meniscus");
        }
        let t0 = std::time::Instant::now();
        let po = sol.pull_off(0.0, 1e-6).expect("pull-off").load_n;
        let w0 = sol.work();
        let t1 = std::time::Instant::now();
        let loads: Vec<f64> = (0..100).map(|k| po + (l01 - po) * k as f64 / 99.0).collect();
        let sw = sol.sweep(&loads, Branch::Loading).expect("sweep");
        let w1 = sol.work();
        let last = sw.points.last().expect("points");
        println!(
            "wet={wet} pull_off_n={po:e} pull_off_s={:.4} curve_s={:.4} passes_per_point={:.2} scanned_per_point={:.0} contacts={} wetted={} capillary_load_n={:e}",
            (t1 - t0).as_secs_f64(),
            t1.elapsed().as_secs_f64(),
            (w1.passes - w0.passes) as f64 / 100.0,
            (w1.summits_scanned - w0.summits_scanned) as f64 / 100.0,
            last.contacts,
            last.wetted_summits,
            last.capillary_load_n
        );
    }
}
