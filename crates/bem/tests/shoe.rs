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

/// The tilted-plane wall `h = a x + b y` (a = 2e-3, b = -1e-3) on 32 x 24 pixels of 1 um:
/// `(nx, ny, dx, a, b, heights)`.
fn tilted_plane() -> (usize, usize, f64, f64, f64, Vec<f64>) {
    let (nx, ny, dx) = (32usize, 24usize, 1e-6);
    let (a, b) = (2e-3, -1e-3);
    let h = (0..nx * ny)
        .map(|i| {
            let (x, y) = centre(i, nx, dx);
            a * x + b * y
        })
        .collect();
    (nx, ny, dx, a, b, h)
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

/// Per-summit load (N) and contact area (m^2) of a BEM state: pixels assigned to the nearest top.
fn per_summit(
    sol: &stiction_bem::ContactSolution,
    n: usize,
    dx: f64,
    tops: &[(f64, f64, f64)],
) -> (Vec<f64>, Vec<f64>) {
    let mut p_k = vec![0.0; tops.len()];
    let mut a_k = vec![0.0; tops.len()];
    for i in 0..n * n {
        let (x, y) = centre(i, n, dx);
        let k = (0..tops.len())
            .min_by(|&a, &b| (x - tops[a].0).hypot(y - tops[a].1).total_cmp(&(x - tops[b].0).hypot(y - tops[b].1)))
            .unwrap();
        p_k[k] += sol.pressure_pa[i] * dx * dx;
        if sol.contact[i] {
            a_k[k] += dx * dx;
        }
    }
    (p_k, a_k)
}

/// The tilting BEM shoe and the explicit solver (tilt mode) on the same summits; returns the BEM
/// shoe, the explicit equilibrium and the BEM's per-summit loads and areas.
fn both(
    tops: &[(f64, f64, f64)],
    load: f64,
    law: AdhesionLaw,
    work: f64,
    z0: f64,
) -> (stiction_bem::TiltedShoe, stiction_contact::explicit::Equilibrium, Vec<f64>, Vec<f64>) {
    let (n, dx, radius, e_star) = (128usize, 20e-6 / 128.0, 5e-6, 1e9);
    let l = n as f64 * dx;
    let h = summits(n, n, dx, radius, tops);
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let opts = SolverOptions { tolerance: 1e-8, ..Default::default() };
    // The explicit Maugis-Dugdale law has sigma0 = 16 w/(9 sqrt 3 z0): the same Dugdale range.
    let dugdale = (work > 0.0).then(|| Dugdale::from_work_and_range(work, 9.0 * 3f64.sqrt() / 16.0 * z0).unwrap());
    let shoe = s.tilting_at_load(load / (l * l), dugdale.as_ref(), &opts, None).unwrap();
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
        work_of_adhesion_j_per_m2: work,
        equilibrium_spacing_m: z0,
    };
    let cfg = SolverConfig { mode: ShoeMode::TiltFree, ..Default::default() };
    let eq = ExplicitSolver::new(surface, law, params, cfg).unwrap().solve(load).unwrap();
    let (p_k, a_k) = per_summit(&shoe.solution, n, dx, tops);
    (shoe, eq, p_k, a_k)
}

/// Three summits far apart (R = 5 um, 8-9 um apart, contact radii about 0.35 um = 2.2 pixels of
/// 0.156 um; E* = 1 GPa, L = 30 uN at the patch centre): the tilting BEM shoe against the explicit
/// solver in `tilt` mode (independent Hertz summits). With three contacts the summit loads are
/// statically determined, so they agree to the shift of each contact point on its sphere, which
/// the summit model ignores (R t = 34 nm on lever arms of about 4 um: 1 %); the tilts add the
/// summits' elastic interaction through the wall (displacement P/(pi E* s) at a distance s against
/// the approach a^2/R: 4a/(3 pi s) = 2 %, of the same sign at all three, so it mostly cancels in
/// the tilt). Tolerances: tilts within 2 % (measured -0.3 %, -0.5 %), summit loads within 2 %
/// (measured +1.0 %, -0.02 %, -0.9 %), contact radii sqrt(A/pi) within 1.5 pixels (measured
/// +0.9 to +1.3 pixels: a 2-pixel contact counted in whole pixels), three patches. The same with
/// Maugis-Dugdale adhesion (w = 0.3 J/m^2, z0 = 20 nm: lambda = 0.44, 2 pi w R = 9.4 uN per summit
/// against 10 uN of load): tilts within 4 % (measured -2.9 %, -1.0 %: the cohesive zone spans about
/// three pixels, and the Dugdale sphere's radius converges at first order in the zone's pixels),
/// loads within 2 % (measured +0.9 %, +0.3 %, -1.0 %).
#[test]
fn tilting_shoe_on_sparse_summits_is_the_explicit_solvers() {
    let tops = [(6e-6, 7e-6, 0.0), (14.5e-6, 6.5e-6, -30e-9), (10.5e-6, 15e-6, -60e-9)];
    let dx = 20e-6 / 128.0;
    for (law, work) in [(AdhesionLaw::Hertz, 0.0), (AdhesionLaw::MaugisDugdale, 0.3)] {
        let (shoe, eq, p_k, a_k) = both(&tops, 3e-5, law, work, 20e-9);
        eprintln!(
            "{law:?}: BEM tilts {:.5e} {:.5e} ({} solves), explicit {:.5e} {:.5e}; loads {p_k:?}; areas {a_k:?}",
            shoe.tilt_x_rad, shoe.tilt_y_rad, shoe.solves, eq.tilt_x_rad, eq.tilt_y_rad
        );
        assert_eq!(eq.contacts, 3);
        assert_eq!(shoe.solution.patches, 3);
        let tol = if work > 0.0 { 0.04 } else { 0.02 };
        assert!((shoe.tilt_x_rad / eq.tilt_x_rad - 1.0).abs() < tol, "tilt x");
        assert!((shoe.tilt_y_rad / eq.tilt_y_rad - 1.0).abs() < tol, "tilt y");
        for c in &eq.summits {
            let k = c.index as usize;
            eprintln!(
                "  summit {k}: load {:e} vs {:e}, a {:e} vs {:e}",
                p_k[k],
                c.load_n,
                (a_k[k] / PI).sqrt(),
                c.contact_radius_m
            );
            assert!((p_k[k] / c.load_n - 1.0).abs() < 0.02, "summit {k}: load {} vs {}", p_k[k], c.load_n);
            assert!(((a_k[k] / PI).sqrt() - c.contact_radius_m).abs() < 1.5 * dx, "summit {k}: area {}", a_k[k]);
        }
    }
}

/// Where contacts merge: two summits 0.8 um apart (R = 5 um) beside two far ones. At low load
/// the BEM and the summit model agree; as the load rises the pair's contacts grow into one
/// patch, the wall between them is pressed down by both (the summit model lets each summit sink
/// into an undisturbed half-space), and the tilts part. Numbers in docs/bem.md ("Tilting shoe").
/// Asserted: at 10 uN (four separate contacts) the tilts agree within 3 % (measured 1.9 %, 1.2 %);
/// at 1 mN the pair is one patch (three patches against four summit contacts), the pair carries the
/// same load within 2 % (measured 1.0 %) and the tilt along the pair's axis differs by more than a
/// factor 2 (measured -2.1e-3 against -8.7e-3 rad).
#[test]
fn merging_contacts_show_what_the_summit_model_misses() {
    let tops = [(6e-6, 7e-6, 0.0), (6.8e-6, 7e-6, -5e-9), (14.5e-6, 6.5e-6, -30e-9), (10.5e-6, 15e-6, -60e-9)];
    for load in [1e-5, 3e-5, 1e-4, 3e-4, 1e-3] {
        let (shoe, eq, p_k, a_k) = both(&tops, load, AdhesionLaw::Hertz, 0.0, 0.3e-9);
        let a_bem: f64 = a_k.iter().sum();
        eprintln!(
            "L {load:e}: BEM patches {} area {a_bem:.4e} tilts {:.4e} {:.4e}; explicit contacts {} area {:.4e} tilts {:.4e} {:.4e}; pair load BEM {:.4e} explicit {:.4e}",
            shoe.solution.patches,
            shoe.tilt_x_rad,
            shoe.tilt_y_rad,
            eq.contacts,
            eq.real_area_m2,
            eq.tilt_x_rad,
            eq.tilt_y_rad,
            p_k[0] + p_k[1],
            eq.summits.iter().filter(|c| c.index < 2).map(|c| c.load_n).sum::<f64>()
        );
        let pair_explicit: f64 = eq.summits.iter().filter(|c| c.index < 2).map(|c| c.load_n).sum();
        assert!(((p_k[0] + p_k[1]) / pair_explicit - 1.0).abs() < 0.02, "pair load");
        if load == 1e-5 {
            assert_eq!((shoe.solution.patches, eq.contacts), (4, 4));
            assert!((shoe.tilt_x_rad / eq.tilt_x_rad - 1.0).abs() < 0.03);
            assert!((shoe.tilt_y_rad / eq.tilt_y_rad - 1.0).abs() < 0.03);
        }
        if load == 1e-3 {
            assert_eq!((shoe.solution.patches, eq.contacts), (3, 4));
            assert!(eq.tilt_x_rad / shoe.tilt_x_rad > 2.0, "tilts {} {}", shoe.tilt_x_rad, eq.tilt_x_rad);
        }
    }
}

/// A wall that is a tilted plane, `h = a x + b y` (a = 2e-3, b = -1e-3, a 32 x 24 patch of 1 um
/// pixels, E* = 1 GPa, 1 MPa): the face that balances its moments is the plane itself,
/// `t = (a, b)`, on which the patch is a flat rigid punch in full contact, loaded symmetrically
/// about the centre (Boussinesq's punch: zero moment). Closed form: the tilts equal (a, b); the
/// tolerance, 1e-3 of the slope, is the moment tolerance (1e-4 of F L/2) over the punch's
/// rotational stiffness, which a uniform rotation of the full contact puts at about a tenth of
/// F L/2 per tilt of the height range over the half-diagonal. The whole patch is in contact. With
/// a Dugdale law beside it the same plane is found (the zone is the whole patch, uniform tension).
#[test]
fn tilted_plane_wall_is_met_by_the_face_at_its_slope() {
    let (nx, ny, dx, a, b, h) = tilted_plane();
    let mut s = BemSolver::with_boundary(nx, ny, dx, dx, &h, 1e9, Boundary::NonPeriodic).unwrap();
    let opts = SolverOptions { tolerance: 1e-6, ..Default::default() };
    let p = 1e6;
    let law = Dugdale::from_work_and_range(0.1, 1e-9).unwrap();
    for dugdale in [None, Some(&law)] {
        let shoe = s.tilting_at_load(p, dugdale, &opts, None).unwrap();
        eprintln!(
            "adhesive {}: tilts {:e} {:e} ({} solves), contact fraction {}",
            dugdale.is_some(),
            shoe.tilt_x_rad,
            shoe.tilt_y_rad,
            shoe.solves,
            shoe.solution.contact_fraction
        );
        assert!((shoe.tilt_x_rad / a - 1.0).abs() < 1e-3, "{}", shoe.tilt_x_rad);
        assert!((shoe.tilt_y_rad / b - 1.0).abs() < 1e-3, "{}", shoe.tilt_y_rad);
        assert_eq!(shoe.solution.contact_fraction, 1.0);
        assert_eq!(s.heights_m(), &h[..]);
    }
}

/// The hardness cap on the tilting shoe, on the tilted-plane wall of
/// `tilted_plane_wall_is_met_by_the_face_at_its_slope`: the flat punch's pressure is singular at
/// its edges (Boussinesq), so a hardness of twice the mean pressure caps a rim of edge pixels; the
/// rim is symmetric about the centre, so there is still no moment and the face meets the wall at
/// its slope, closed form t = (a, b) (tolerance 1e-3, as there). The capped pose carries the load
/// (mean 1e-9 relative), no point exceeds the hardness, and the plastic area is reported, within
/// the contact; with a Dugdale law the net traction is capped the same way.
#[test]
fn capped_tilting_shoe_meets_a_tilted_plane_at_its_slope() {
    let (nx, ny, dx, a, b, h) = tilted_plane();
    let mut s = BemSolver::with_boundary(nx, ny, dx, dx, &h, 1e9, Boundary::NonPeriodic).unwrap();
    let (p, hardness) = (1e6, 2e6);
    let opts = SolverOptions { tolerance: 1e-6, hardness_pa: Some(hardness), ..Default::default() };
    let law = Dugdale::from_work_and_range(0.1, 1e-9).unwrap();
    for dugdale in [None, Some(&law)] {
        let shoe = s.tilting_at_load(p, dugdale, &opts, None).unwrap();
        let (fraction, area, _) = shoe.plastic.expect("the capped pose reports its plastic area");
        eprintln!(
            "adhesive {}: tilts {:e} {:e} ({} solves), plastic fraction {fraction}",
            dugdale.is_some(),
            shoe.tilt_x_rad,
            shoe.tilt_y_rad,
            shoe.solves
        );
        assert!((shoe.tilt_x_rad / a - 1.0).abs() < 1e-3, "{}", shoe.tilt_x_rad);
        assert!((shoe.tilt_y_rad / b - 1.0).abs() < 1e-3, "{}", shoe.tilt_y_rad);
        assert!(fraction > 0.0 && fraction < 1.0, "{fraction}");
        assert!((area / (fraction * (nx * ny) as f64 * dx * dx) - 1.0).abs() < 1e-12);
        assert!((shoe.solution.mean_pressure_pa / p - 1.0).abs() < 1e-9, "{}", shoe.solution.mean_pressure_pa);
        let top = shoe.solution.pressure_pa.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(top <= hardness * (1.0 + 1e-12), "{top}");
        assert_eq!(s.heights_m(), &h[..]);
    }
}
