//! Load-controlled solves on a set of candidate points, verified on the whole grid
//! (`stiction_bem::restricted`), against the closed forms and against the whole-grid iteration
//! (`SolverOptions::restricted = false`) on the same discrete problem.
//!
//! Both iterations stop at the complementarity residual `eps < tol` (the crate docs), a gap error
//! of about `tol rms(h)` over the contact, so two converged states differ in pressure by about the
//! pressure that such a gap error takes over a contact of radius `a`: `E* tol rms(h) / a`. The
//! bound asserted is 100 times that (the residual is a weighted mean, the error is a maximum).

use std::f64::consts::PI;

use stiction_bem::{BemError, BemSolver, Boundary, ContactSolution, Dugdale, PlasticSolution, SolverOptions};
use stiction_contact::single::MaugisCurve;

/// Heights `max_k (h_k - |x - x_k|^2/(2R))` of paraboloid summits at `(x_k, y_k)` (m) on an
/// `n x n` patch of pixel `dx` (pixel centres from the corner).
fn summits(n: usize, dx: f64, radius: f64, tops: &[(f64, f64, f64)]) -> Vec<f64> {
    (0..n * n)
        .map(|i| {
            let (x, y) = (((i % n) as f64 + 0.5) * dx, ((i / n) as f64 + 0.5) * dx);
            tops.iter()
                .map(|&(sx, sy, h)| h - ((x - sx).powi(2) + (y - sy).powi(2)) / (2.0 * radius))
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .collect()
}

fn rms(v: &[f64]) -> f64 {
    let m = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// The bound of the module docs on the pressure difference of two converged states, Pa.
fn pressure_bound(e_star: f64, tol: f64, heights: &[f64], a: f64) -> f64 {
    100.0 * e_star * tol * rms(heights) / a
}

/// The same problem on the whole grid.
fn full(s: &mut BemSolver, p: f64, opts: &SolverOptions, warm: Option<&ContactSolution>) -> ContactSolution {
    s.solve_load(p, &SolverOptions { restricted: false, ..*opts }, warm).unwrap()
}

/// Hertz on the finite patch (Johnson 1985, eq. 4.22-4.23; the non-periodic case of
/// tests/nonperiodic.rs): a sphere of R = 200 um on a 128^2 patch of 24 um, E* = 100 GPa, at the
/// loads of a = 2.25 um (12 pixels; cold start) and 2.5 um (warm-started from the first). The
/// set is used (`restriction` is reported), the contact radius is Hertz's within 1.5 pixels and
/// the peak within 0.5 % (the tolerances of tests/nonperiodic.rs), and the state is the
/// whole-grid iteration's: the same contact points, the pressure within the bound of the module
/// docs (tolerance 1e-8).
#[test]
fn hertz_sphere_on_a_set_is_the_whole_grid_solution() {
    let (n, l, e_star, radius) = (128usize, 24e-6, 100e9, 200e-6);
    let dx = l / n as f64;
    let h = summits(n, dx, radius, &[(0.5 * l, 0.5 * l, 0.0)]);
    let opts = SolverOptions::default();
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let (mut warm_set, mut warm_full): (Option<ContactSolution>, Option<ContactSolution>) = (None, None);
    for a in [2.25e-6f64, 2.5e-6] {
        let load = 4.0 * e_star * a.powi(3) / (3.0 * radius);
        let p0 = 2.0 * e_star * a / (PI * radius);
        let p = load / (l * l);
        let set = s.solve_load(p, &opts, warm_set.as_ref()).unwrap();
        let whole = full(&mut s, p, &opts, warm_full.as_ref());
        let r = set.restriction.expect("solved on a set");
        assert!(whole.restriction.is_none());
        let a_num = (set.contact_area_m2 / PI).sqrt();
        let peak = set.pressure_pa.iter().copied().fold(0.0, f64::max) / p0;
        let diff = max_abs_diff(&set.pressure_pa, &whole.pressure_pa);
        let bound = pressure_bound(e_star, opts.tolerance, &h, a);
        eprintln!(
            "a = {a:e}: set of {} points ({} at first, {} checks), {} + {} iterations; radius {:+.2} px, \
             peak {:+.4} %, |p_set - p_whole| = {diff:.3e} Pa = {:.2e} p0 (bound {bound:.2e} Pa)",
            r.points,
            r.initial_points,
            r.checks,
            set.iterations,
            whole.iterations,
            (a_num - a) / dx,
            100.0 * (peak - 1.0),
            diff / p0
        );
        assert!((a_num - a).abs() < 1.5 * dx, "a {a_num:e} vs Hertz {a:e}");
        assert!((peak - 1.0).abs() < 0.005, "peak / p0 = {peak}");
        assert_eq!(set.contact, whole.contact, "contact points");
        assert!(diff < bound, "|p_set - p_whole| = {diff:e} Pa, bound {bound:e} Pa");
        assert!((set.mean_pressure_pa / p - 1.0).abs() < 1e-12, "load {}", set.mean_pressure_pa);
        let gap_diff = max_abs_diff(&set.gap_m, &whole.gap_m);
        assert!(gap_diff < 1e-6 * rms(&h), "gap fields differ by {gap_diff:e} m");
        warm_set = Some(set);
        warm_full = Some(whole);
    }
}

/// The Dugdale sphere on the loading branch under load control (the case of
/// `dugdale_sphere_under_load_control` in tests/shoe.rs and of
/// `dugdale_sphere_at_load_on_the_loading_branch` in tests/validation.rs: lambda = 0.5,
/// P/(pi w R) = 0.5 then 2 continued from the first, on the finite patch), scaled so that the
/// contact and the cohesive zone fit a set (a/L = 0.035 on 128^2): the set is
/// used, the contact radius is on the Maugis-Dugdale curve (Maugis 1992;
/// `MaugisCurve::state_at_load`) within 1.5 pixels, the external load is carried to 1e-9, and the
/// state is the whole-grid zone iteration's: the same contact points and cohesive zone, the net
/// traction within the bound of the module docs (tolerance 1e-6).
#[test]
fn dugdale_sphere_on_a_set_is_the_whole_grid_solution() {
    let (e_star, radius, l, n): (f64, f64, f64, usize) = (1.0, 1.0, 1.0, 128);
    let (lambda, la) = (0.5, 0.035);
    let d = 0.75 / e_star;
    let w = (la * l).powi(3) / (PI * radius * radius * d);
    let sigma0 = lambda / 2.0 * (PI * w / (radius * d * d)).cbrt();
    let law = Dugdale::from_work_and_range(w, w / sigma0).unwrap();
    let dx = l / n as f64;
    let h = summits(n, dx, radius, &[(0.5 * l, 0.5 * l, 0.0)]);
    let curve = MaugisCurve::new(lambda).unwrap();
    let opts = SolverOptions { tolerance: 1e-6, ..Default::default() };
    let whole_opts = SolverOptions { restricted: false, ..opts };
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let (mut last_set, mut last_whole): (Option<ContactSolution>, Option<ContactSolution>) = (None, None);
    for p_bar in [0.5, 2.0] {
        let load = p_bar * PI * w * radius;
        let set = s.adhesive_at_load(load / (l * l), &law, &opts, last_set.as_ref()).unwrap();
        let whole = s.adhesive_at_load(load / (l * l), &law, &whole_opts, last_whole.as_ref()).unwrap();
        let r = set.restriction.expect("solved on a set");
        assert!(whole.restriction.is_none());
        let a = (set.contact_area_m2 / PI).sqrt();
        let exact = curve.state_at_load(p_bar).unwrap().a_hat * la;
        let diff = max_abs_diff(&set.pressure_pa, &whole.pressure_pa);
        let bound = pressure_bound(e_star, opts.tolerance, &h, a);
        eprintln!(
            "P/(pi w R) = {p_bar}: set of {} points ({} at first, {} checks), {} zone updates; a = {a:.5}, \
             Maugis-Dugdale {exact:.5} ({:+.2} px); |p_set - p_whole| = {diff:.3e} (bound {bound:.2e}), \
             cohesive points {} and {}",
            r.points,
            r.initial_points,
            r.checks,
            set.zone_updates,
            (a - exact) / dx,
            set.cohesive_fraction * (n * n) as f64,
            whole.cohesive_fraction * (n * n) as f64,
        );
        assert!((set.load_n(&s.grid()) / load - 1.0).abs() < 1e-9, "load {}", set.load_n(&s.grid()));
        assert!((a - exact).abs() < 1.5 * dx, "p_bar {p_bar}: a {a} vs {exact}");
        assert_eq!(set.contact, whole.contact, "contact points");
        assert_eq!(set.cohesive_fraction, whole.cohesive_fraction, "cohesive zone");
        assert!(diff < bound, "|p_set - p_whole| = {diff:e}, bound {bound:e}");
        last_set = Some(set);
        last_whole = Some(whole);
    }
    assert_eq!(s.heights_m(), &h[..], "the heights are the sphere's after the solves");
}

/// A set too small at first: two summits of R = 100 um, 9.6 um apart on a 128^2 patch of 24 um,
/// the second 10 nm lower. The cold set is the highest points (all on the first summit) with a
/// ring; at the load that would give one sphere a = 1.5 um (approach 22.5 nm > 10 nm) the second
/// summit touches too, which only the whole-grid check can see. The check must grow the set (more
/// than one check, more points than at first), and the state is the whole-grid iteration's: both
/// summits in contact, the same contact points, the pressure within the bound of the module docs.
#[test]
fn the_check_grows_a_set_that_misses_a_contact() {
    let (n, l, e_star, radius) = (128usize, 24e-6, 100e9, 100e-6);
    let dx = l / n as f64;
    let tops = [(0.3 * l, 0.5 * l, 0.0), (0.7 * l, 0.5 * l, -10e-9)];
    let h = summits(n, dx, radius, &tops);
    let a: f64 = 1.5e-6;
    let p = 4.0 * e_star * a.powi(3) / (3.0 * radius) / (l * l);
    let opts = SolverOptions::default();
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let set = s.solve_load(p, &opts, None).unwrap();
    let whole = full(&mut s, p, &opts, None);
    let r = set.restriction.expect("solved on a set");
    let diff = max_abs_diff(&set.pressure_pa, &whole.pressure_pa);
    let bound = pressure_bound(e_star, opts.tolerance, &h, a);
    eprintln!(
        "set of {} points ({} at first), {} checks; {} patches; |p_set - p_whole| = {diff:.3e} Pa (bound {bound:.2e})",
        r.points, r.initial_points, r.checks, set.patches
    );
    assert!(r.checks >= 2, "the check should have found the second summit: {r:?}");
    assert!(r.points > r.initial_points, "{r:?}");
    assert_eq!(set.patches, 2, "both summits in contact");
    assert_eq!(set.contact, whole.contact, "contact points");
    assert!(diff < bound, "|p_set - p_whole| = {diff:e} Pa, bound {bound:e} Pa");
}

/// A contact too large for a set (a Hertz contact of a = 0.3 L on 64^2, 900 points, more than
/// `restricted::max_set_points` = 478 on this grid) is solved on the whole grid, as with the set
/// switched off, to the bit.
#[test]
fn a_large_contact_falls_back_to_the_whole_grid() {
    let (n, l, e_star, radius) = (64usize, 12e-6, 100e9, 200e-6);
    let dx = l / n as f64;
    let grid = stiction_bem::Grid::new(n, n, dx, dx).unwrap();
    assert_eq!(stiction_bem::restricted::max_set_points(grid), 478);
    let h = summits(n, dx, radius, &[(0.5 * l, 0.5 * l, 0.0)]);
    let a = 0.3 * l;
    let p = 4.0 * e_star * a.powi(3) / (3.0 * radius) / (l * l);
    let opts = SolverOptions::default();
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let auto = s.solve_load(p, &opts, None).unwrap();
    let whole = full(&mut s, p, &opts, None);
    assert!(auto.restriction.is_none(), "{:?}", auto.restriction);
    assert_eq!(auto.pressure_pa, whole.pressure_pa);
    assert_eq!(auto.iterations, whole.iterations);
}

/// The capped problem on the whole grid (the projected conjugate gradient).
fn full_capped(
    s: &mut BemSolver,
    p: f64,
    law: Option<&Dugdale>,
    opts: &SolverOptions,
) -> Result<PlasticSolution, BemError> {
    s.plastic_at_load(p, law, &SolverOptions { restricted: false, ..*opts }, None)
}

/// A capped Hertz sphere on a set (the exact active-set solve of the capped problem) is the
/// whole-grid capped iteration's state (the same discrete problem): the sphere of
/// `hertz_sphere_on_a_set_is_the_whole_grid_solution` at the Hertz load of a = 2.25 um
/// (p0 = 716 MPa) with the hardness at 0.7 p0, and with adhesion at that of a = 1.5 um (so that
/// the contact and its cohesive zone fit a set; the Dugdale law of w = 0.5 J/m^2, rho = 5 nm:
/// sigma0 = 100 MPa, the contact pressure capped at H + sigma0). The
/// set is used; the contact, the points at the cap and the cohesive zone are the whole grid's; the
/// traction within the bound of the module docs at the whole grid's tolerance 1e-10 (at 1e-8 the
/// whole grid's state is 2x the bound off, and the set's residual is 1e-17); the load carried to
/// 1e-12; the plastic points a core inside the contact (at least one, fewer than the contact
/// points), and the largest traction at most H (a perfectly plastic pixel). At 0.4 p0 (a = 1.5 um)
/// the whole-grid iteration does not converge in its 10,000 iterations (it stalls at a residual
/// of 0.08) and the set solves it in 16 steps. In every case the state keeps the rigid-plastic bounds: the load the contact points
/// carry (`P` plus the zone's tension outside the contact, `sigma0 (N_zone - N_contact) dx^2`)
/// over H needs at least that many contact points and allows at most that many at the cap.
#[test]
fn capped_sphere_on_a_set_is_the_whole_grid_solution() {
    let (n, l, e_star, radius) = (128usize, 24e-6, 100e9, 200e-6);
    let dx = l / n as f64;
    let h = summits(n, dx, radius, &[(0.5 * l, 0.5 * l, 0.0)]);
    let law = Dugdale::from_work_and_range(0.5, 5e-9).unwrap();
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    for (ratio, adhesive, a) in [(0.7, false, 2.25e-6f64), (0.7, true, 1.5e-6), (0.4, false, 1.5e-6)] {
        let p0 = 2.0 * e_star * a / (PI * radius);
        let p = 4.0 * e_star * a.powi(3) / (3.0 * radius) / (l * l);
        let hardness = ratio * p0;
        let law = adhesive.then_some(&law);
        let opts = SolverOptions { hardness_pa: Some(hardness), tolerance: 1e-10, ..Default::default() };
        let set = s.plastic_at_load(p, law, &opts, None).unwrap();
        let r = set.solution.restriction.expect("solved on a set");
        let contact = set.solution.contact.iter().filter(|&&c| c).count();
        let plastic = (set.plastic_fraction * (n * n) as f64).round() as usize;
        let peak = set.solution.pressure_pa.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        // The load the contact points carry: the external one plus the zone's tension outside them.
        let zone = (set.solution.cohesive_fraction * (n * n) as f64).round();
        let sigma0 = law.map_or(0.0, |l| l.stress_pa);
        let carried = p * (l * l) + sigma0 * (zone - contact as f64) * dx * dx;
        let rigid_plastic = carried / (hardness * dx * dx);
        eprintln!(
            "H = {ratio} p0, adhesive {adhesive}: set of {} points, {} steps, residual {:.1e}; contact {contact}, \
             plastic {plastic} points (P/(H dx^2) = {rigid_plastic:.1}), peak {:.6} H",
            r.points,
            set.solution.iterations,
            set.solution.residual,
            peak / hardness
        );
        assert!((set.solution.mean_pressure_pa / p - 1.0).abs() < 1e-12);
        assert!(plastic >= 1 && plastic < contact, "plastic {plastic} of {contact}");
        assert!(peak <= hardness * (1.0 + 1e-12), "peak {peak} above H {hardness}");
        assert!((plastic as f64) <= rigid_plastic, "at most P/(H dx^2) points at H");
        assert!((contact as f64) >= rigid_plastic, "at least P/(H dx^2) points in contact");
        match full_capped(&mut s, p, law, &opts) {
            Ok(whole) => {
                assert!(whole.solution.restriction.is_none());
                let diff = max_abs_diff(&set.solution.pressure_pa, &whole.solution.pressure_pa);
                let bound = pressure_bound(e_star, opts.tolerance, &h, a);
                eprintln!(
                    "  whole grid: {} iterations, |p_set - p_whole| = {diff:.3e} Pa (bound {bound:.2e})",
                    whole.solution.iterations
                );
                assert_eq!(set.solution.contact, whole.solution.contact, "contact points");
                assert_eq!(set.plastic_fraction, whole.plastic_fraction, "plastic points");
                assert_eq!(set.solution.cohesive_fraction, whole.solution.cohesive_fraction, "cohesive zone");
                assert!(diff < bound, "|p_set - p_whole| = {diff:e} Pa, bound {bound:e} Pa");
            }
            Err(e) => {
                eprintln!("  whole grid: {e}");
                assert!(ratio < 0.5, "the whole grid converges at H = {ratio} p0: {e}");
            }
        }
    }
    assert_eq!(s.heights_m(), &h[..], "the heights are the sphere's after the solves");
}

/// The rigid-plastic limit on a few pixels, where the whole-grid capped iteration stalls (E*/H =
/// 5e4, a contact of 8 pixels). A sphere of R = 10 um on a 64^2 patch of 0.1 um pixels, its top
/// off the pixel centres by (0.13, 0.31) px so that the pixels' squared distances from it are
/// 0.11, 0.49, 0.85, 1.23, 1.37, 1.73, 1.75, 2.47, 2.87, ... px^2: the 8th is 0.4 px^2 = 0.2 nm
/// of height above the 9th, against the elastic deflection of a pixel at the hardness,
/// `H dx / E*` = 4 pm. At a load of 7.3 H dx^2 the closed form of a rigid-perfectly-plastic
/// contact (the flat sinks until the pixels it meets carry the load at H: Abbott and Firestone's
/// bearing area) puts the 7 highest pixels at H and the 8th at 0.3 H, no other pixel in contact.
/// The set gives exactly that (0.3 H within 1e-9 relative). Also checked: the 7 at the cap have a
/// plastic depth, and the whole-grid iteration, where it converges, agrees.
#[test]
fn a_few_pixel_contact_far_above_the_hardness_is_rigid_plastic() {
    let (n, dx, e_star, radius, hardness) = (64usize, 0.1e-6, 100e9, 10e-6, 2e6);
    let l = n as f64 * dx;
    let top = ((32.0 + 0.5 + 0.13) * dx, (32.0 + 0.5 + 0.31) * dx, 0.0);
    let h = summits(n, dx, radius, &[top]);
    let p = 7.3 * hardness * dx * dx / (l * l);
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let opts = SolverOptions { hardness_pa: Some(hardness), ..Default::default() };
    let st = s.plastic_at_load(p, None, &opts, None).unwrap();
    assert!(st.solution.restriction.is_some(), "solved on a set");
    let mut order: Vec<usize> = (0..n * n).collect();
    order.sort_by(|&i, &j| h[j].total_cmp(&h[i]));
    let pr = &st.solution.pressure_pa;
    for (rank, &i) in order.iter().enumerate().take(12) {
        eprintln!("height rank {rank}: p/H = {:.12}", pr[i] / hardness);
    }
    for &i in &order[..7] {
        assert_eq!(pr[i], hardness, "the 7 highest pixels flow at H");
    }
    assert!((pr[order[7]] / (0.3 * hardness) - 1.0).abs() < 1e-9, "8th pixel p/H = {}", pr[order[7]] / hardness);
    assert!(order[8..].iter().all(|&i| pr[i] == 0.0), "no other pixel in contact");
    assert_eq!((st.plastic_fraction * (n * n) as f64).round(), 7.0);
    assert!(st.max_plastic_depth_m > 0.0);
    match full_capped(&mut s, p, None, &opts) {
        Ok(w) => {
            eprintln!("whole grid: converged in {} iterations", w.solution.iterations);
            assert_eq!(w.solution.contact, st.solution.contact);
        }
        Err(e) => eprintln!("whole grid: {e}"),
    }
}
