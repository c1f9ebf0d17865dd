//! The shoe on the wall: Dugdale adhesion under load control (either Green's function) against
//! the Maugis-Dugdale curve, and the tilting rigid shoe against the explicit solver's `tilt` mode.

use std::f64::consts::PI;

use stiction_bem::{BemSolver, Boundary, Dugdale, SolverOptions};
use stiction_contact::explicit::{ExplicitSolver, ShoeMode, SolverConfig};
use stiction_contact::single::{AdhesionLaw, AsperityParams, MaugisCurve};
use stiction_surface::{Radii, Surface};

/// Pixel centres of an `nx x ny` grid of pixel `dx`, from the corner.
fn centre(i: usize, nx: usize, dx: f64) -> (f64, f64) {
    (((i % nx) as f64 + 0.5) * dx, ((i / nx) as f64 + 0.5) * dx)
}

/// Paraboloid summits `h_k - r_k^2/(2R)` (the envelope) on an `nx x ny` patch.
fn summits(nx: usize, ny: usize, dx: f64, radius: f64, tops: &[(f64, f64, f64)]) -> Vec<f64> {
    (0..nx * ny)
        .map(|i| {
            let (x, y) = centre(i, nx, dx);
            tops.iter()
                .map(|&(sx, sy, h)| h - ((x - sx).powi(2) + (y - sy).powi(2)) / (2.0 * radius))
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect()
}

/// The Dugdale sphere at lambda = 0.5, P/(pi w R) = 0.5 and 2, on the loading branch under load
/// control, with the non-periodic and the periodic Green's function: contact radius within 1.5
/// pixels of the Maugis-Dugdale curve (Maugis 1992; `MaugisCurve::state_at_load`), more than
/// Hertz's at the same load; the external load carried to 1e-9.
#[test]
fn dugdale_sphere_under_load_control() {
    let (e_star, radius, l, n): (f64, f64, f64, usize) = (1.0, 1.0, 1.0, 128);
    let (lambda, la) = (0.5, 0.1);
    let d = 0.75 / e_star;
    let w = (la * l).powi(3) / (PI * radius * radius * d);
    let sigma0 = lambda / 2.0 * (PI * w / (radius * d * d)).cbrt();
    let law = Dugdale::from_work_and_range(w, w / sigma0).unwrap();
    let dx = l / n as f64;
    let h: Vec<f64> = (0..n * n)
        .map(|i| {
            let (x, y) = centre(i, n, dx);
            -((x - 0.5 * l).powi(2) + (y - 0.5 * l).powi(2)) / (2.0 * radius)
        })
        .collect();
    let curve = MaugisCurve::new(lambda).unwrap();
    let opts = SolverOptions { tolerance: 1e-6, ..Default::default() };
    for b in [Boundary::NonPeriodic, Boundary::Periodic] {
        let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, b).unwrap();
        let mut last = None;
        for p_bar in [0.5, 2.0] {
            let load = p_bar * PI * w * radius;
            let sol = s.adhesive_at_load(load / (l * l), &law, &opts, last.as_ref()).unwrap();
            assert!((sol.load_n(&s.grid()) / load - 1.0).abs() < 1e-9, "load {}", sol.load_n(&s.grid()));
            let a = (sol.contact_area_m2 / PI).sqrt();
            let exact = curve.state_at_load(p_bar).unwrap().a_hat * la;
            eprintln!(
                "{b:?} P/(pi w R) = {p_bar}: a = {a:.5}, Maugis-Dugdale {exact:.5} ({:+.2} px), zone updates {}",
                (a - exact) / dx,
                sol.zone_updates
            );
            assert!((a - exact).abs() < 1.5 * dx, "{b:?} p_bar {p_bar}: a {a} vs {exact}");
            let hertz = (3.0 * load * radius / (4.0 * e_star)).cbrt();
            assert!(a > hertz, "adhesion should enlarge the contact: {a} vs Hertz {hertz}");
            last = Some(sol);
        }
        // The heights are the sphere's again after the solve.
        assert_eq!(s.heights_m(), &h[..]);
    }
}

/// Three summits far apart (R = 5 um, 8-9 um apart, contact radii about 0.35 um = 2.3 pixels;
/// E* = 1 GPa), the shoe loaded at the patch centre: the tilting BEM shoe against the explicit
/// solver in `tilt` mode (independent Hertz summits).
#[test]
fn tilting_shoe_on_sparse_summits_is_the_explicit_solvers() {
    let (n, dx, radius, e_star) = (128usize, 20e-6 / 128.0, 5e-6, 1e9);
    let l = n as f64 * dx;
    let tops = [(6e-6, 7e-6, 0.0), (14.5e-6, 6.5e-6, -30e-9), (10.5e-6, 15e-6, -60e-9)];
    let h = summits(n, n, dx, radius, &tops);
    let load = 3e-5;
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let opts = SolverOptions { tolerance: 1e-8, ..Default::default() };
    let shoe = s.tilting_at_load(load / (l * l), None, &opts, None).unwrap();
    let surface = Surface::new(
        l,
        l,
        tops.iter().map(|t| t.0 as f32).collect(),
        tops.iter().map(|t| t.1 as f32).collect(),
        tops.iter().map(|t| t.2).collect(),
        Radii::Uniform(radius),
    )
    .unwrap();
    let params = AsperityParams {
        radius_m: radius,
        compliance_per_pa: 0.75 / e_star,
        work_of_adhesion_j_per_m2: 0.0,
        equilibrium_spacing_m: 0.3e-9,
    };
    let cfg = SolverConfig { mode: ShoeMode::TiltFree, ..Default::default() };
    let mut ex = ExplicitSolver::new(surface, AdhesionLaw::Hertz, params, cfg).unwrap();
    let eq = ex.solve(load).unwrap();
    // Per-summit loads and areas of the BEM: pixels assigned to the nearest summit.
    let mut p_k = [0.0; 3];
    let mut a_k = [0.0; 3];
    for i in 0..n * n {
        let (x, y) = centre(i, n, dx);
        let k = (0..3)
            .min_by(|&a, &b| {
                let da = (x - tops[a].0).hypot(y - tops[a].1);
                let db = (x - tops[b].0).hypot(y - tops[b].1);
                da.total_cmp(&db)
            })
            .unwrap();
        p_k[k] += shoe.solution.pressure_pa[i] * dx * dx;
        if shoe.solution.contact[i] {
            a_k[k] += dx * dx;
        }
    }
    eprintln!(
        "BEM: tilts {:.5e} {:.5e}, solves {}, loads {p_k:?}, areas {a_k:?}, patches {}",
        shoe.tilt_x_rad, shoe.tilt_y_rad, shoe.solves, shoe.solution.patches
    );
    eprintln!("explicit: tilts {:.5e} {:.5e}, contacts {}", eq.tilt_x_rad, eq.tilt_y_rad, eq.contacts);
    for c in &eq.summits {
        eprintln!("  summit {:?}", c);
    }
}
