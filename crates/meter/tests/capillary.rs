//! The meter in humid air: the capillary part of the adhesive load per point against closed
//! forms, and dry runs unchanged.

use std::f64::consts::PI;
use std::path::Path;

use stiction_meter::Meter;
use stiction_scenario::Scenario;

fn scenario(sets: &[&str]) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scenario::load(&path, &sets).expect("tas2000.json")
}

fn run(sets: &[&str]) -> stiction_meter::MeterResult {
    let mut sets = sets.to_vec();
    sets.push("meter.slip_dynamics=null");
    Meter::from_scenario(&scenario(&sets), Path::new(".")).unwrap().run(&mut |_, _| {}).unwrap()
}

/// Water at 25 C (IAPWS: 71.97 mN/m), theta = 0 on both faces: each touching summit of radius R
/// is pulled by 4 pi R gamma. Discrete N = 3 (R = 0.5 um): capillary load 3 * 4 pi R gamma =
/// 1.3566 uN at every point; with DMT (dgamma = 0.1 J/m^2) the rest of the adhesive load is
/// 3 * 2 pi dgamma R. GW: the summits in contact pull 2 pi R (2 gamma) each and those bridged within
/// h_m add to it, so capillary / adhesive exceeds the contact-only 2 gamma / (dgamma + 2 gamma), by
/// at most the bridged share `k h` (k = h_m / sigma = 0.025, h < 4 at the meter's loads).
/// Tolerances: 1e-4 relative against the tabulated gamma (given to 4 digits). Deliberate bug
/// caught: the meter copying the adhesive load into capillary_load_n.
#[test]
fn humid_points_carry_the_closed_form_capillary_load() {
    let gamma = 71.97e-3;
    let r = 0.5e-6;
    let res = run(&["environment.relative_humidity=0.35", "contact.model=\"discrete\"", "contact.contacts=3"]);
    let h = res.environment.expect("humid run reports its environment");
    assert!((h.kelvin_radius_m.unwrap() - 0.4997e-9).abs() < 0.001e-9);
    let mut n = 0;
    for p in res.points.iter().filter(|p| p.in_contact && p.error.is_none()) {
        let cap = p.capillary_load_n.unwrap();
        let want = 3.0 * 4.0 * PI * r * gamma;
        assert!((cap - want).abs() <= 1e-4 * want, "{cap} vs {want}");
        let dmt = 3.0 * 2.0 * PI * 0.1 * r;
        assert!((p.adhesive_load_n - cap - dmt).abs() <= 1e-9 * dmt, "{} {cap}", p.adhesive_load_n);
        n += 1;
    }
    assert!(n >= 10);
    let g = run(&["environment.relative_humidity=0.35", "contact.model=\"gw\""]);
    let share =
        2.0 * g.environment.map(|_| stiction_contact::capillary::water_surface_tension_n_per_m(298.15)).unwrap();
    let contact_only = share / (0.1 + share);
    for p in g.points.iter().filter(|p| p.in_contact && p.error.is_none()) {
        let ratio = p.capillary_load_n.unwrap() / p.adhesive_load_n;
        assert!(ratio > contact_only && ratio < contact_only * (1.0 + 4.0 * 0.025), "{ratio} vs {contact_only}");
    }
}

/// The summit models condense menisci within h_m = r_K (cos th1 + cos th2) of the counter face, and
/// r_K grows with RH (0.23 nm at 10 %, 5.0 nm at 90 %): the GW and explicit meters give more
/// capillary load, a larger F_a0 and a different mu_e,a at 90 % than at 10 %; the discrete model
/// (no gap, only its N contacts, each pulled by the RH-independent 4 pi R gamma) gives the same.
/// Deliberate bug caught: the GW meter left on the contact-only balance (F_a0 equal at both RH).
#[test]
fn summit_models_move_with_humidity() {
    for model in ["gw", "explicit"] {
        let set = format!("contact.model=\"{model}\"");
        let lo = run(&["environment.relative_humidity=0.1", &set]);
        let hi = run(&["environment.relative_humidity=0.9", &set]);
        let (flo, fhi) = (lo.apparent_adhesion_force_n.unwrap(), hi.apparent_adhesion_force_n.unwrap());
        assert!(fhi > flo * (1.0 + 1e-3), "{model}: F_a0 {flo:e} at 10 %, {fhi:e} at 90 %");
        assert_ne!(lo.mu_apparent, hi.mu_apparent, "{model}");
        let cap = |r: &stiction_meter::MeterResult| {
            r.points
                .iter()
                .filter(|p| p.in_contact && p.error.is_none())
                .map(|p| p.capillary_load_n.unwrap())
                .sum::<f64>()
        };
        assert!(cap(&hi) > cap(&lo), "{model}");
    }
    let set = ["contact.model=\"discrete\"", "contact.contacts=3"];
    let lo = run(&["environment.relative_humidity=0.1", set[0], set[1]]);
    let hi = run(&["environment.relative_humidity=0.9", set[0], set[1]]);
    assert_eq!(lo.apparent_adhesion_force_n, hi.apparent_adhesion_force_n);
}

/// Dry (no environment, or relative humidity 0) and hydrophobic faces: no capillary key, the same
/// bytes as without the section; 110 deg faces: capillary 0 and the dry numbers.
/// Deliberate bug caught: writing `capillary_load_n: 0` for a dry run (changes the dry JSON).
#[test]
fn dry_runs_are_unchanged() {
    let dry = serde_json::to_string(&run(&[])).unwrap();
    assert!(!dry.contains("capillary_load_n") && !dry.contains("environment"));
    let rh0 = serde_json::to_string(&run(&["environment.relative_humidity=0"])).unwrap();
    assert_eq!(dry, rh0);
    let coated = run(&["environment.relative_humidity=0.35", "material.contact_angle=110 deg"]);
    let plain = run(&[]);
    assert_eq!(coated.mu_apparent, plain.mu_apparent);
    assert_eq!(coated.apparent_adhesion_force_n, plain.apparent_adhesion_force_n);
    assert!(coated.points.iter().all(|p| p.capillary_load_n == Some(0.0)));
}
