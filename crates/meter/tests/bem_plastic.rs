//! The hardness cap of the meter's `bem` model (`contact.bem.plastic`, the hardness being
//! `material.hardness`) on the bundled boundary-element scenario without adhesion (law "hertz"),
//! the patch coarsened to at most 8000 points so the test runs in seconds.

use std::path::Path;

use stiction_meter::Meter;
use stiction_scenario::Scenario;

mod common;
use common::root;

fn run(sets: &[&str]) -> stiction_meter::MeterResult {
    run_law("hertz", sets)
}

fn run_law(law: &str, sets: &[&str]) -> stiction_meter::MeterResult {
    let text = std::fs::read_to_string(root().join("scenarios/tas2000-bem.json")).unwrap();
    // Clamp voltages of 200-600 V: loads of 0.55-5 mN, mean pressures of 5.5-50 MPa, contacts of
    // tens to hundreds of the 120 nm pixels with elastic peaks of 1.6-3.0 GPa.
    let law = format!("contact.law=\"{law}\"");
    let mut all: Vec<String> = [
        law.as_str(),
        "contact.bem.points=8000",
        "meter.clamp_voltages={\"from\": \"200 V\", \"to\": \"600 V\", \"steps\": 5}",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    all.extend(sets.iter().map(|s| s.to_string()));
    let s = Scenario::from_str_with_sets(&text, Path::new("tas2000-bem.json"), &all).unwrap();
    Meter::from_scenario(&s, &root().join("scenarios")).unwrap().run(&mut |_, _| {}).unwrap()
}

/// With the pressure capped at H the contacts carry the load at p <= H, so the real area is at
/// least L/H (a bound of any capped contact, whatever the surface). At H = 1.5 GPa, below the
/// elastic peak of every load, each point has pixels at the hardness and no less contact than
/// the elastic model's (the cap moves load to new points; at the lowest load none enters). Every point in contact reports a plastic area within its
/// real area, a note, and `over_elastic_limit`; no pressure above H. A hardness far above every
/// pressure (150 GPa, the domain's end) leaves the elastic solution: the same real areas as the
/// model without the cap, and no plastic area.
#[test]
fn hardness_cap_bounds_the_real_area_and_reports_the_plastic_area() {
    let elastic = run(&[]);
    let h = 1.5e9;
    let capped = run(&["contact.bem.plastic=true", "material.hardness=1.5 GPa"]);
    let mut checked = 0;
    for (e, c) in elastic.points.iter().zip(&capped.points) {
        assert!(e.plastic_area_m2.is_none() && e.plastic_note.is_none());
        if !c.in_contact || c.error.is_some() {
            continue;
        }
        let a_p = c.plastic_area_m2.expect("plastic area");
        eprintln!(
            "L {:.3e} N: A_r elastic {:.3e}, capped {:.3e} (L/H {:.3e}), A_p {:.3e}",
            c.true_load_n,
            e.real_area_m2,
            c.real_area_m2,
            c.true_load_n / h,
            a_p
        );
        assert!(c.real_area_m2 >= c.true_load_n / h * (1.0 - 1e-9), "A_r below L/H");
        assert!(c.real_area_m2 >= e.real_area_m2, "the cap should not shrink the contact");
        assert!(a_p > 0.0 && a_p <= c.real_area_m2);
        assert!(c.over_elastic_limit && c.plastic_note.as_deref().is_some_and(|n| n.contains("contact.bem.plastic")));
        assert!(c.max_pressure_pa <= h * (1.0 + 1e-12), "{}", c.max_pressure_pa);
        checked += 1;
    }
    assert!(checked == 5, "{checked}");
    let high = run(&["contact.bem.plastic=true", "material.hardness=150 GPa"]);
    for (e, c) in elastic.points.iter().zip(&high.points) {
        assert_eq!(e.real_area_m2, c.real_area_m2);
        if c.in_contact && c.error.is_none() {
            assert_eq!(c.plastic_area_m2, Some(0.0));
            assert!(c.plastic_note.is_none());
        }
    }
}

/// With the scenario's Dugdale adhesion (w = 0.1 J/m^2 over z0/1.03: sigma0 = 0.34 GPa) the net
/// traction is capped, `p_c - sigma0 <= H`, so the contacts carry L plus the adhesive load at a
/// contact pressure of at most H + sigma0: A_r >= (L + L_adh)/(H + sigma0) (the same bound with
/// the zone's tension). At H = 1.5 GPa every point flows; at 150 GPa the model is the adhesive
/// one without the cap (the same real areas and adhesive loads to the bit, on the same loading
/// branch).
#[test]
fn hardness_cap_with_adhesion_caps_the_net_traction() {
    let adhesive = run_law("dmt", &[]);
    let (h, sigma0) = (1.5e9, 0.1 / (0.3e-9 / 1.03));
    let capped = run_law("dmt", &["contact.bem.plastic=true", "material.hardness=1.5 GPa"]);
    let mut checked = 0;
    for (e, c) in adhesive.points.iter().zip(&capped.points) {
        if !c.in_contact || c.error.is_some() {
            continue;
        }
        let a_p = c.plastic_area_m2.expect("plastic area");
        let bound = (c.true_load_n + c.adhesive_load_n) / (h + sigma0);
        eprintln!(
            "L {:.3e} N: A_r adhesive {:.3e}, capped {:.3e} (bound {bound:.3e}), A_p {a_p:.3e}, L_adh {:.3e}",
            c.true_load_n, e.real_area_m2, c.real_area_m2, c.adhesive_load_n
        );
        assert!(c.real_area_m2 >= bound * (1.0 - 1e-9), "A_r below (L + L_adh)/(H + sigma0)");
        assert!(a_p > 0.0 && a_p <= c.real_area_m2);
        assert!(c.max_pressure_pa <= (h + sigma0) * (1.0 + 1e-12), "{}", c.max_pressure_pa);
        checked += 1;
    }
    assert!(checked == 5, "{checked}");
    let high = run_law("dmt", &["contact.bem.plastic=true", "material.hardness=150 GPa"]);
    for (e, c) in adhesive.points.iter().zip(&high.points) {
        assert_eq!(e.real_area_m2, c.real_area_m2);
        assert_eq!(e.adhesive_load_n, c.adhesive_load_n);
    }
}

/// A tilting shoe on the periodic cell is refused naming the field; the hardness cap beside a
/// tilting shoe is accepted (each pose is the capped solve).
#[test]
fn periodic_tilt_is_refused_and_the_cap_with_tilt_accepted() {
    let text = std::fs::read_to_string(root().join("scenarios/tas2000-bem.json")).unwrap();
    let refuse = |sets: &[&str], needles: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let e = Scenario::from_str_with_sets(&text, Path::new("x.json"), &sets).unwrap_err().to_string();
        for n in needles {
            assert!(e.contains(n), "{sets:?}: {e}");
        }
    };
    refuse(&["contact.bem.tilt=true", "contact.bem.boundary=\"periodic\""], &["contact.bem.tilt"]);
    for sets in [&["contact.bem.plastic=true"][..], &["contact.bem.plastic=true", "contact.bem.tilt=true"]] {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        assert!(Scenario::from_str_with_sets(&text, Path::new("x.json"), &sets).is_ok(), "{sets:?}");
    }
}

/// The cap on the tilting shoe (each pose the capped solve, with the scenario's Dugdale adhesion,
/// sigma0 = 0.34 GPa): every load balances and keeps the bounds of the flat shoe's cap,
/// `A_r >= (L + L_adh)/(H + sigma0)`, the plastic area within the real area and no contact
/// pressure above H + sigma0, at H = 1.5 GPa (below the elastic peaks of 2.5-3.4 GPa); with
/// H = 150 GPa (the domain's end, far above every pressure) the tilting shoe is the elastic
/// tilting shoe to the bit (the same poses on the same path).
#[test]
fn hardness_cap_on_the_tilting_shoe_keeps_its_bounds() {
    let elastic = run_law("dmt", &["contact.bem.tilt=true"]);
    let high = run_law("dmt", &["contact.bem.tilt=true", "contact.bem.plastic=true", "material.hardness=150 GPa"]);
    for (e, c) in elastic.points.iter().zip(&high.points) {
        assert!(e.error.is_none() && c.error.is_none(), "{:?} {:?}", e.error, c.error);
        assert_eq!(e.real_area_m2, c.real_area_m2);
        assert_eq!(e.adhesive_load_n, c.adhesive_load_n);
    }
    let (h, sigma0) = (1.5e9, 0.1 / (0.3e-9 / 1.03));
    let capped = run_law("dmt", &["contact.bem.tilt=true", "contact.bem.plastic=true", "material.hardness=1.5 GPa"]);
    let mut checked = 0;
    for c in &capped.points {
        assert!(c.error.is_none() && c.in_contact, "{:?}", c.error);
        let a_p = c.plastic_area_m2.expect("plastic area");
        let bound = (c.true_load_n + c.adhesive_load_n) / (h + sigma0);
        eprintln!(
            "L {:.3e} N: A_r {:.3e} (bound {bound:.3e}), A_p {a_p:.3e}, q0 {:.4e}",
            c.true_load_n, c.real_area_m2, c.max_pressure_pa
        );
        assert!(c.real_area_m2 >= bound * (1.0 - 1e-9), "A_r below (L + L_adh)/(H + sigma0)");
        assert!(a_p > 0.0 && a_p <= c.real_area_m2);
        assert!(c.max_pressure_pa <= (h + sigma0) * (1.0 + 1e-12), "{}", c.max_pressure_pa);
        checked += 1;
    }
    assert_eq!(checked, 5);
}
