//! Validation of the single-asperity laws (Hertz eq. 3, DMT eq. 4, JKR, Maugis-Dugdale) against
//! their closed forms, limits and an independent 30-digit mpmath solution of the Maugis equations.

// Reference values are kept with all the digits mpmath printed.
#![allow(clippy::excessive_precision)]

use proptest::prelude::*;
use std::f64::consts::PI;
use stiction_contact::ContactError;
use stiction_contact::limits::max_hertz_pressure_pa;
use stiction_contact::single::*;

fn table1() -> AsperityParams {
    AsperityParams::table1()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// Hertz (eq. 3): a^2 = R z, P = a^3/(R D) = R^1/2 z^3/2 / D; stiffness dP/dz = 3a/(2D);
/// peak pressure from eq. 11. Exact to rounding (1e-14).
#[test]
fn hertz_closed_forms() {
    let p = table1();
    let (r, d) = (p.radius_m, p.compliance_per_pa);
    let z = 2e-9;
    let resp = summit_response(AdhesionLaw::Hertz, &p, z, Branch::Loading);
    assert!(resp.in_contact);
    assert!(rel(resp.contact_radius_m, (r * z).sqrt()) < 1e-14);
    assert!(rel(resp.load_n, r.sqrt() * z.powf(1.5) / d) < 1e-14);
    assert!(rel(resp.stiffness_n_per_m, 1.5 * (r * z).sqrt() / d) < 1e-14);
    assert!(rel(resp.max_pressure_pa, max_hertz_pressure_pa(z, r, d).unwrap()) < 1e-14);
    let a = 3e-8;
    let load = load_from_contact_radius(AdhesionLaw::Hertz, &p, a).unwrap();
    assert!(rel(load, a.powi(3) / (r * d)) < 1e-14);
    assert!(rel(contact_radius_from_load(AdhesionLaw::Hertz, &p, load).unwrap(), a) < 1e-14);
    assert!(rel(interference_from_contact_radius(AdhesionLaw::Hertz, &p, a).unwrap(), a * a / r) < 1e-14);
    assert_eq!(summit_response(AdhesionLaw::Hertz, &p, -1e-9, Branch::Loading), SummitResponse::NO_CONTACT);
    assert_eq!(pull_off_force(AdhesionLaw::Hertz, &p).unwrap(), 0.0);
}

/// DMT as in the paper (eq. 4): Hertz deformation and P + 2 pi dgamma R = a^3/(R D); pull-off
/// 2 pi dgamma R; the load jumps to -2 pi dgamma R at touch-down.
#[test]
fn dmt_eq4() {
    let p = table1();
    let adh = 2.0 * PI * 0.1 * 0.5e-6;
    assert!(rel(pull_off_force(AdhesionLaw::Dmt, &p).unwrap(), adh) < 1e-15);
    let z = 1e-9;
    let h = summit_response(AdhesionLaw::Hertz, &p, z, Branch::Loading);
    let dmt = summit_response(AdhesionLaw::Dmt, &p, z, Branch::Loading);
    assert!(rel(dmt.load_n, h.load_n - adh) < 1e-14);
    assert_eq!(dmt.contact_radius_m, h.contact_radius_m);
    let touch = summit_response(AdhesionLaw::Dmt, &p, 1e-30, Branch::Unloading);
    assert!(rel(touch.load_n, -adh) < 1e-9);
    assert!(!summit_response(AdhesionLaw::Dmt, &p, 0.0, Branch::Unloading).in_contact);
    // contact radius at zero load: a^3 = R D 2 pi dgamma R
    let a0 = contact_radius_from_load(AdhesionLaw::Dmt, &p, 0.0).unwrap();
    assert!(rel(a0, (0.5e-6 * 9.1e-12 * adh).cbrt()) < 1e-14);
    // below pull-off: no equilibrium
    assert!(matches!(
        contact_radius_from_load(AdhesionLaw::Dmt, &p, -1.01 * adh),
        Err(ContactError::NoEquilibrium { .. })
    ));
}

/// JKR closed forms (Johnson, Contact Mechanics, 1985, sec. 5.5): P = a^3/(RD) - sqrt(6 pi dgamma a^3/D),
/// zero-load radius a0^3 = 6 pi dgamma R^2 D, pull-off 3/2 pi dgamma R under load control,
/// 5/6 pi dgamma R at the end of the displacement-controlled branch, jump-in at delta = 0 to
/// P = -4/3 pi dgamma R.
#[test]
fn jkr_closed_forms() {
    let p = table1();
    let (r, d, w) = (p.radius_m, p.compliance_per_pa, p.work_of_adhesion_j_per_m2);
    let ls = PI * w * r;
    let a = 2.5e-8;
    let load = load_from_contact_radius(AdhesionLaw::Jkr, &p, a).unwrap();
    assert!(rel(load, a.powi(3) / (r * d) - (6.0 * PI * w * a.powi(3) / d).sqrt()) < 1e-13);
    let a0 = contact_radius_from_load(AdhesionLaw::Jkr, &p, 0.0).unwrap();
    assert!(rel(a0, (6.0 * PI * w * r * r * d).cbrt()) < 1e-14);
    assert!(rel(pull_off_force(AdhesionLaw::Jkr, &p).unwrap(), 1.5 * ls) < 1e-15);
    let lim = branch_limits(AdhesionLaw::Jkr, &p).unwrap();
    assert!(rel(lim.pull_off_interference_load_n, -5.0 / 6.0 * ls) < 1e-14);
    assert!(rel(lim.jump_in_load_n, -4.0 / 3.0 * ls) < 1e-14);
    assert_eq!(lim.jump_in_interference_m, 0.0);
    // delta_c = (6^-2/3 - sqrt(8/3) 6^-1/6) (pi^2 dgamma^2 R D^2)^(1/3)
    let dc =
        (6f64.powf(-2.0 / 3.0) - (8.0f64 / 3.0).sqrt() * 6f64.powf(-1.0 / 6.0)) * (PI * PI * w * w * r * d * d).cbrt();
    assert!(rel(lim.pull_off_interference_m, dc) < 1e-14);
    // hysteresis: between delta_c and 0 in contact only when unloading
    let mid = 0.5 * dc;
    assert!(!summit_response(AdhesionLaw::Jkr, &p, mid, Branch::Loading).in_contact);
    let un = summit_response(AdhesionLaw::Jkr, &p, mid, Branch::Unloading);
    assert!(un.in_contact && un.load_n < 0.0);
    let at0 = summit_response(AdhesionLaw::Jkr, &p, 0.0, Branch::Loading);
    assert!(rel(at0.load_n, -4.0 / 3.0 * ls) < 1e-12);
}

/// Maugis-Dugdale against an independent mpmath solution (30 digits, Maugis' original (A, m)
/// variables, golden-section minimum): `(lambda, P_min, A(P = 0), P(A = 1), Delta(A = 1))`.
/// Regenerated and compared with this table by `python3 crates/contact/tools/md_reference.py --check`
/// (40 digits; reproduces every value to 4e-17 relative).
const MD_REFERENCE: &[(f64, f64, f64, f64, f64)] = &[
    (0.01, -1.9982877843215089, 1.2693666336872057, -1.0279417377884137, 0.84906795343573513),
    (0.1, -1.9505948921234289, 1.336179808437504, -1.2081048643778529, 0.51608173162477122),
    (0.3482249560373307, -1.7881133973685406, 1.4621843821484098, -1.4588582920349352, 0.10629333674172629),
    (1.0, -1.6007349112540915, 1.6360904896091255, -1.5796270206018335, -0.33662777827242357),
    (3.0, -1.5167639000369278, 1.7749050688096476, -1.4935175811797251, -0.58224423456070978),
    (10.0, -1.5016248604263582, 1.812624954325559, -1.454292922191829, -0.62812706892046821),
];

#[test]
fn maugis_dugdale_matches_mpmath() {
    for &(lambda, p_min, a_zero, p_at1, d_at1) in MD_REFERENCE {
        let c = MaugisCurve::new(lambda).unwrap();
        // the minimum value is insensitive to the location: 1e-13
        assert!(rel(c.load_minimum.p_bar, p_min) < 1e-13, "lambda {lambda}: {} vs {p_min}", c.load_minimum.p_bar);
        assert!(rel(c.state_at_load(0.0).unwrap().a_hat, a_zero) < 1e-13);
        let s1 = c.state(1.0);
        assert!(rel(s1.p_bar, p_at1) < 1e-13);
        assert!((s1.delta_bar - d_at1).abs() < 1e-13);
    }
}

/// Pull-off must go from 2 pi dgamma R (lambda -> 0, DMT) to 1.5 pi dgamma R (lambda -> inf, JKR),
/// monotonically. Tolerances from the approach: ~ lambda at the DMT end, ~ lambda^-2 at the JKR end.
#[test]
fn maugis_dugdale_limits() {
    let dmt_end = MaugisCurve::new(1e-4).unwrap().load_minimum.p_bar;
    assert!((dmt_end + 2.0).abs() < 1e-3, "{dmt_end}");
    let jkr_end = MaugisCurve::new(1e3).unwrap().load_minimum.p_bar;
    assert!((jkr_end + 1.5).abs() < 1e-6, "{jkr_end}");
    let mut prev = -2.0;
    for i in 0..=40 {
        let lambda = 10f64.powf(-3.0 + 0.15 * i as f64);
        let pm = MaugisCurve::new(lambda).unwrap().load_minimum.p_bar;
        assert!(pm > prev && pm < -1.5, "lambda {lambda}: {pm}");
        prev = pm;
    }
    // JKR end: the whole curve approaches JKR (here at A = 1.5, within 1e-3)
    let md = MaugisCurve::new(1e3).unwrap().state(1.5);
    let jkr = jkr_state(1.5);
    assert!((md.p_bar - jkr.p_bar).abs() < 1e-3 && (md.delta_bar - jkr.delta_bar).abs() < 1e-3);
    // DMT end: P = A^3 - 2, Delta = A^2; measured approach: P ~ 7 lambda, Delta ~ -1.5 lambda^1/2
    // (Delta - A^2 = -(4/3) lambda Q with Q ~ lambda^-1/2), so at lambda = 1e-7: 1e-5 and 1e-3
    let md = MaugisCurve::new(1e-7).unwrap().state(1.5);
    assert!((md.p_bar - (1.5f64.powi(3) - 2.0)).abs() < 1e-5, "{}", md.p_bar);
    assert!((md.delta_bar - 2.25).abs() < 1e-3, "{}", md.delta_bar);
}

/// Table 1 (R = 0.5 um, dgamma = 0.1 J/m^2, D = 9.1e-12 1/Pa, z0 = 0.3 nm): Tabor's mu
/// = (R dgamma^2/(E*^2 z0^3))^(1/3) with E* = 3/(4D) is 0.30097 (hand calculation), lambda = 1.157 mu,
/// and Maugis-Dugdale is the law that applies. DMT then underestimates the zero-load contact area.
#[test]
fn table1_tabor_parameter_and_recommendation() {
    let p = table1();
    let rec = p.recommendation();
    assert!((rec.tabor_parameter - 0.30097).abs() < 1e-4, "{}", rec.tabor_parameter);
    assert!((rec.maugis_parameter / rec.tabor_parameter - 1.1570).abs() < 1e-4);
    assert_eq!(rec.law, AdhesionLaw::MaugisDugdale);
    let a_dmt = contact_radius_from_load(AdhesionLaw::Dmt, &p, 0.0).unwrap();
    let a_md = contact_radius_from_load(AdhesionLaw::MaugisDugdale, &p, 0.0).unwrap();
    let ratio = (a_dmt / a_md).powi(2);
    // mpmath: (2^(1/3)/1.46218...)^2 at lambda = 0.348 -> 0.7425
    assert!((ratio - 0.7425).abs() < 1e-3, "area ratio {ratio}");
    // other regimes of the adhesion map
    let mut stiff = p;
    stiff.work_of_adhesion_j_per_m2 = 0.001;
    assert_eq!(stiff.recommendation().law, AdhesionLaw::Dmt);
    let mut soft = p;
    soft.compliance_per_pa = 1e-8;
    assert_eq!(soft.recommendation().law, AdhesionLaw::Jkr);
}

/// Every law's interference-controlled response is consistent with its load/radius relations,
/// and its stiffness is dP/d(delta) (central differences, 1e-5 relative).
#[test]
fn summit_response_consistency() {
    let p = table1();
    for law in [AdhesionLaw::Hertz, AdhesionLaw::Dmt, AdhesionLaw::Jkr, AdhesionLaw::MaugisDugdale] {
        let model = SummitModel::new(law, p).unwrap();
        for &z in &[0.05e-9, 0.3e-9, 1e-9, 5e-9] {
            let r = summit_response(law, &p, z, Branch::Loading);
            let t = model.response(z, Branch::Loading);
            assert!(r.in_contact && t.in_contact);
            assert!(rel(t.load_n, r.load_n) < 1e-12, "{law:?} table vs curve");
            let a = r.contact_radius_m;
            assert!(rel(load_from_contact_radius(law, &p, a).unwrap(), r.load_n) < 1e-10);
            assert!((interference_from_contact_radius(law, &p, a).unwrap() - z).abs() < 1e-12 * 1e-9);
            let dz = 1e-4 * z;
            let fd = (summit_response(law, &p, z + dz, Branch::Loading).load_n
                - summit_response(law, &p, z - dz, Branch::Loading).load_n)
                / (2.0 * dz);
            assert!(rel(r.stiffness_n_per_m, fd) < 1e-5, "{law:?} z {z}: {} vs {fd}", r.stiffness_n_per_m);
            assert!(rel(r.max_pressure_pa, 1.5 * a / (PI * p.compliance_per_pa * p.radius_m)) < 1e-14);
        }
    }
}

/// Maugis-Dugdale branches: jump-in below zero interference; for Table 1 (lambda = 0.35) the
/// displacement-controlled branch reaches A = 0 (no interference hysteresis), for lambda = 1 it ends
/// at A > 0 below the jump-in.
#[test]
fn maugis_dugdale_branches() {
    let p = table1();
    let model = SummitModel::new(AdhesionLaw::MaugisDugdale, p).unwrap();
    let din = model.contact_start_interference_m(Branch::Loading);
    let dc = model.contact_start_interference_m(Branch::Unloading);
    assert!(din < 0.0 && dc <= din);
    assert!(!model.response(din * 1.01, Branch::Loading).in_contact);
    assert!(model.response(din * 0.99, Branch::Loading).in_contact);
    let c = MaugisCurve::new(1.0).unwrap();
    assert!(c.interference_minimum.a_hat > 0.0);
    assert!(c.interference_minimum.delta_bar < c.zero_radius.delta_bar);
    assert!(c.interference_minimum.ddelta_bar_da.abs() < 1e-6);
    let t = MaugisTable::new(1.0).unwrap();
    let mid = 0.5 * (c.interference_minimum.delta_bar + c.zero_radius.delta_bar);
    let s = t.state_at_interference(mid).unwrap();
    assert!(s.a_hat > c.interference_minimum.a_hat && (s.delta_bar - mid).abs() < 1e-13);
    assert!(t.state_at_interference(c.interference_minimum.delta_bar - 1e-6).is_none());
}

#[test]
fn invalid_parameters_name_the_field() {
    let mut p = table1();
    p.radius_m = -1.0;
    match contact_radius_from_load(AdhesionLaw::Dmt, &p, 1e-6) {
        Err(ContactError::InvalidParameter { field, value, .. }) => {
            assert_eq!(field, "radius_m");
            assert_eq!(value, -1.0);
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        AsperityParams::new(0.5e-6, f64::NAN, 0.1),
        Err(ContactError::InvalidParameter { field: "compliance_per_pa", .. })
    ));
    assert!(matches!(
        load_from_contact_radius(AdhesionLaw::Jkr, &table1(), -1e-9),
        Err(ContactError::InvalidParameter { field: "contact_radius_m", .. })
    ));
}

/// The serialised names of the laws (scenario files use them).
#[test]
fn law_names() {
    let names: Vec<String> = [AdhesionLaw::Hertz, AdhesionLaw::Dmt, AdhesionLaw::Jkr, AdhesionLaw::MaugisDugdale]
        .iter()
        .map(|l| serde_json_like(*l))
        .collect();
    assert_eq!(names, ["hertz", "dmt", "jkr", "maugis-dugdale"]);
    assert_eq!(AdhesionLaw::default(), AdhesionLaw::Dmt);
}

fn serde_json_like(l: AdhesionLaw) -> String {
    serde_json::to_value(l).unwrap().as_str().unwrap().to_string()
}

proptest! {
    /// Load-controlled solves round-trip for every adhesive law over the stable branch.
    #[test]
    fn load_round_trip(frac in 0.0f64..1.0, extra in 0.0f64..20e-6, law_i in 0usize..3) {
        let p = table1();
        let law = [AdhesionLaw::Dmt, AdhesionLaw::Jkr, AdhesionLaw::MaugisDugdale][law_i];
        let pc = pull_off_force(law, &p).unwrap();
        let load = -pc * frac + extra;
        let a = contact_radius_from_load(law, &p, load).unwrap();
        let back = load_from_contact_radius(law, &p, a).unwrap();
        prop_assert!((back - load).abs() <= 1e-10 * pc);
        // stable branch: the load increases with the radius
        let st = load_state(law, &p, load).unwrap();
        prop_assert!(st.dradius_dload_m_per_n > 0.0);
    }

    /// For any lambda the MD stable branch under displacement control is monotone and the table
    /// agrees with the direct solve.
    #[test]
    fn maugis_table_agrees(log_lambda in -2.0f64..2.0, d in -1.0f64..30.0) {
        let lambda = 10f64.powf(log_lambda);
        let t = MaugisTable::new(lambda).unwrap();
        let c = t.curve;
        let direct = c.state_at_interference(d);
        let fast = t.state_at_interference(d);
        prop_assert_eq!(direct.is_some(), fast.is_some());
        if let (Some(a), Some(b)) = (direct, fast) {
            prop_assert!((a.a_hat - b.a_hat).abs() <= 1e-12 * a.a_hat.max(1e-3));
            prop_assert!((b.delta_bar - d).abs() <= 1e-12 * d.abs().max(1.0));
        }
    }
}
