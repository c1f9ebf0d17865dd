//! The test structures built from parts (scenario `structure`, docs/experiment.md "Other test
//! structures") against closed forms:
//!
//! * the release protocol's threshold for a Coulomb contact, `k x_max = mu L + F_adh`, through the
//!   explicit solver on one DMT summit, whose adhesive load is `2 pi R w` (DMT) and whose Coulomb
//!   friction under the plastic criterion is `(s/H)(L + 2 pi R w)`;
//! * the comb ramp and the lowered normal load on the same contact;
//! * a flat pad whose friction does not depend on its apparent area when the adhesion is zero, and
//!   does when it is not (the adhesive load grows with the summits under the pad);
//! * the lab's reductions (friction over load) against their closed forms.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use serde_json::{Value, json};
use stiction_meter::{Meter, MeterResult};
use stiction_scenario::Scenario;

const EPS0: f64 = 8.8541878128e-12;
const R: f64 = 1e-6; // summit radius, m
const W: f64 = 0.1; // work of adhesion, J/m^2
const S: f64 = 1.4e9; // shear strength, Pa
const H: f64 = 9e9; // hardness, Pa
const MU: f64 = S / H; // Coulomb coefficient of the plastic criterion

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stiction-structures-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A summit list: `copies` copies of a 3 x 3 grid of equal summits (each copy shifted by the pad
/// length), all at height 0.
fn summits(d: &Path, copies: usize) -> (PathBuf, f64) {
    let mut text = String::from("x_m,y_m,height_m,radius_m\n");
    for c in 0..copies {
        for i in 0..3 {
            for j in 0..3 {
                let x = c as f64 * 6e-6 + 1e-6 + 2e-6 * i as f64;
                let y = 1e-6 + 2e-6 * j as f64;
                text.push_str(&format!("{x:e},{y:e},0,{R:e}\n"));
            }
        }
    }
    let p = d.join(format!("summits-{copies}.csv"));
    std::fs::write(&p, text).unwrap();
    (p, 6e-6 * copies as f64)
}

fn one_summit(d: &Path) -> PathBuf {
    let p = d.join("one.csv");
    std::fs::write(&p, format!("x_m,y_m,height_m,radius_m\n2.5e-6,2.5e-6,0,{R:e}\n")).unwrap();
    p
}

fn scenario(csv: &Path, length_m: f64, work: f64, tangential: Value, protocol: Value, lab: Value) -> Scenario {
    let v = json!({
        "format_version": 1,
        "surface": {"source": "csv", "csv_path": csv.to_str().unwrap(), "apparent_length": length_m,
                     "apparent_width": 6e-6, "seed": 1},
        "material": {"compliance": 9.1e-12, "work_of_adhesion": work, "shear_strength": S, "hardness": H,
                      "equilibrium_spacing": 3e-10},
        "contact": {"law": if work > 0.0 { "dmt" } else { "hertz" }, "model": "explicit", "mode": "flat"},
        "structure": {
            "normal": {"kind": "plate_electrode", "electrode_area": "1e-8 m^2", "air_gap_at_contact": "1 um",
                        "travel_to_contact": "1 um", "stiffness": "1 N/m"},
            "normal_voltages": [20.0, 25.0, 30.0, 35.0, 40.0],
            "tangential": tangential,
            "geometry": {"kind": "pad"},
            "protocol": protocol,
            "slip": {"kind": "plastic"},
            "lab_reduction": lab
        }
    });
    Scenario::from_value(v, Path::new("structures-test.json")).unwrap()
}

fn run(s: &Scenario) -> MeterResult {
    let mut m = Meter::from_scenario(s, Path::new(".")).unwrap();
    m.run(&mut |_, _| {}).unwrap()
}

/// L = eps0 A V^2 / (2 g_c^2) - k_z g0 for the plate of these scenarios.
fn plate_load(v: f64) -> f64 {
    EPS0 * 1e-8 * v * v / (2.0 * 1e-12) - 1.0 * 1e-6
}

/// Release protocol on one DMT summit under the plastic (Coulomb) criterion:
/// k x_stick <= mu L + mu 2 pi R w < k (x_stick + dx) at every normal voltage (the threshold
/// lies within one displacement step above the largest displacement that sticks).
#[test]
fn release_threshold_is_mu_l_plus_adhesion_for_a_coulomb_contact() {
    let d = dir("release");
    let csv = one_summit(&d);
    let (k, dx) = (2.0, 1e-9);
    let s = scenario(
        &csv,
        5e-6,
        W,
        json!({"kind": "released_spring", "stiffness": k}),
        json!({"kind": "release", "displacement_step": dx, "displacement_max": "100 um"}),
        json!({"kind": "eq10"}),
    );
    let r = run(&s);
    assert_eq!(r.points.len(), 5);
    let f_adh = MU * 2.0 * PI * R * W;
    for p in &r.points {
        let l = plate_load(p.v_clamp);
        assert!((p.load_n - l).abs() <= 1e-12 * l, "load {} vs {l}", p.load_n);
        // The explicit solver's DMT summit: adhesive load 2 pi R w (relative 1e-9).
        assert!((p.adhesive_load_n - 2.0 * PI * R * W).abs() <= 1e-9 * 2.0 * PI * R * W, "{}", p.adhesive_load_n);
        let x = p.displacement_m.expect("a displacement that sticks");
        let threshold = MU * l + f_adh;
        assert!(k * x <= threshold && threshold < k * (x + dx), "k x = {} vs {threshold}", k * x);
        assert_eq!(p.friction_n, Some(k * x));
    }
    // Eq. 10 over the release points: slope mu and intercept F_adh within the step's k dx.
    let mu = r.mu_apparent.unwrap();
    assert!((mu - MU).abs() < 1e-3 * MU, "{mu}");
    let fa0 = r.apparent_adhesion_force_n.unwrap();
    assert!((mu * fa0 - f_adh).abs() < 2.0 * k * dx, "{} vs {f_adh}", mu * fa0);
    let lab = r.lab_coefficient.as_ref().unwrap();
    assert_eq!(lab.coefficient, r.mu_apparent);
    let _ = std::fs::remove_dir_all(&d);
}

/// Comb ramp on the same contact: the tangential voltage at slip is the first step with
/// a_t V^2 >= mu L + mu 2 pi R w, a_t = N eps0 t / g. Lowered normal load: at a held tangential
/// voltage the contact slips at the first (descending) normal voltage whose capacity is at most
/// a_t V_t^2.
#[test]
fn comb_ramp_and_lowered_normal_load_slip_at_the_coulomb_threshold() {
    let d = dir("ramp");
    let csv = one_summit(&d);
    let comb = json!({"kind": "lateral_comb", "finger_count": 100, "thickness": "2 um", "gap": "2 um",
                      "engagement": "5 um", "stiffness": "1 N/m"});
    let a_t = 100.0 * EPS0 * 2e-6 / 2e-6;
    let dv = 0.01;
    let s = scenario(
        &csv,
        5e-6,
        W,
        comb.clone(),
        json!({"kind": "ramp", "voltage_step": dv, "voltage_max": 300.0}),
        json!({"kind": "friction_over_load"}),
    );
    let r = run(&s);
    let f_adh = MU * 2.0 * PI * R * W;
    let mut ratios = Vec::new();
    for p in &r.points {
        let cap = MU * plate_load(p.v_clamp) + f_adh;
        let v = p.v_pull.unwrap();
        assert!(a_t * v * v >= cap && a_t * (v - dv) * (v - dv) < cap, "V_t {v}");
        ratios.push(p.friction_n.unwrap() / p.load_n);
    }
    // Friction over load folds the adhesion into the coefficient: mean of mu + F_adh / L.
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    let lab = r.lab_coefficient.as_ref().unwrap();
    assert_eq!(lab.kind, "friction_over_load");
    assert!((lab.coefficient.unwrap() - mean).abs() < 1e-12);
    let closed: f64 = r.points.iter().map(|p| MU + f_adh / plate_load(p.v_clamp)).sum::<f64>() / r.points.len() as f64;
    assert!((lab.coefficient.unwrap() - closed).abs() < 0.01 * closed, "{} vs {closed}", lab.coefficient.unwrap());

    // Lowered normal load at held tangential voltages.
    let s = scenario(
        &csv,
        5e-6,
        W,
        comb,
        json!({"kind": "lower_normal", "tangential_voltages": [40.0, 50.0]}),
        json!({"kind": "eq10"}),
    );
    let mut s = s;
    if let Some(st) = s.structure.as_mut() {
        st.normal_voltages = stiction_scenario::VoltageSchedule::List((6..=40).map(|v| v as f64).collect());
    }
    let r = run(&s);
    assert_eq!(r.points.len(), 2);
    for p in &r.points {
        let force = a_t * p.v_pull.unwrap().powi(2);
        let cap_at = |v: f64| MU * plate_load(v) + f_adh;
        assert!(cap_at(p.v_clamp) <= force, "slipped with capacity above the load");
        assert!(cap_at(p.v_clamp + 1.0) > force, "held one volt higher");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A flat pad on equal summits, friction by the plastic (Coulomb) criterion at the same loads: with
/// no adhesion (Hertz) the friction of a pad and of a pad twice as large (the same summits, twice)
/// is mu L for both (relative 1e-12 plus the ramp's step); with DMT adhesion the larger pad's
/// friction exceeds the smaller's by mu times the extra summits' adhesive load, 9 x 2 pi R w.
#[test]
fn pad_friction_does_not_depend_on_apparent_area_without_adhesion() {
    let d = dir("pad");
    let (one, l1) = summits(&d, 1);
    let (two, l2) = summits(&d, 2);
    let spring = json!({"kind": "released_spring", "stiffness": 1.0});
    let dx = 1e-10;
    let protocol = json!({"kind": "release", "displacement_step": dx, "displacement_max": "1 mm"});
    let lab = json!({"kind": "eq10"});
    for work in [0.0, W] {
        let small = run(&scenario(&one, l1, work, spring.clone(), protocol.clone(), lab.clone()));
        let large = run(&scenario(&two, l2, work, spring.clone(), protocol.clone(), lab.clone()));
        for (a, b) in small.points.iter().zip(&large.points) {
            assert_eq!(a.load_n, b.load_n);
            let (fa, fb) = (a.friction_n.unwrap(), b.friction_n.unwrap());
            let extra = MU * 9.0 * 2.0 * PI * R * work;
            assert!(((fb - fa) - extra).abs() <= 2.0 * dx + 1e-12 * fb, "w = {work}: {fa} vs {fb}");
            if work == 0.0 {
                assert!((fa - MU * a.load_n).abs() <= dx + 1e-12 * fa);
            }
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// Dimples: the discrete model's N spheres of the dimple radius (not the surface's summits) share
/// the load; under the plastic criterion with DMT each carries 2 pi R_d w of adhesion, so the
/// release threshold is mu (L + N 2 pi R_d w) to one displacement step. The lab that measured the
/// adhesion force separately (`friction_over_total_load` with F_a = N 2 pi R_d w) recovers mu to
/// the step's k dx / L.
#[test]
fn dimples_share_the_load_and_the_lab_with_the_adhesion_recovers_mu() {
    let d = dir("dimples");
    let csv = one_summit(&d);
    let (k, dx, r_d, n) = (1.0, 1e-10, 3e-6, 3.0);
    let f_a = n * 2.0 * PI * r_d * W;
    let mut v = scenario(
        &csv,
        5e-6,
        W,
        json!({"kind": "released_spring", "stiffness": k}),
        json!({"kind": "release", "displacement_step": dx, "displacement_max": "1 mm"}),
        json!({"kind": "eq10"}),
    )
    .source_json;
    v["contact"] = json!({"law": "dmt", "model": "discrete"});
    v["structure"]["geometry"] = json!({"kind": "dimples", "count": n as u32, "radius": r_d});
    v["structure"]["lab_reduction"] = json!({"kind": "friction_over_total_load", "adhesion_force": f_a});
    let s = Scenario::from_value(v, Path::new("dimples.json")).unwrap();
    let r = run(&s);
    for p in &r.points {
        let l = plate_load(p.v_clamp);
        assert!((p.adhesive_load_n - f_a).abs() <= 1e-9 * f_a, "{} vs {f_a}", p.adhesive_load_n);
        let threshold = MU * (l + f_a);
        let x = p.displacement_m.unwrap();
        assert!(k * x <= threshold && threshold < k * (x + dx), "k x = {} vs {threshold}", k * x);
    }
    let lab = r.lab_coefficient.as_ref().unwrap();
    assert_eq!(lab.kind, "friction_over_total_load");
    let l_min = plate_load(20.0);
    assert!((lab.coefficient.unwrap() - MU).abs() <= k * dx / l_min, "{} vs {MU}", lab.coefficient.unwrap());
    let _ = std::fs::remove_dir_all(&d);
}

/// The paper's meter with a stated lab reduction: `meter.lab_reduction` = friction over load gives
/// the mean of F_f / L over the points of the eq. 10 fit, beside mu_e,a; with the discrete model
/// (F_f = mu_e,a (L + F_a0) exactly on a line only in the limit) it exceeds mu_e,a, by the
/// adhesion folded in: mean of mu (1 + F_a0 / L) against the fit's own mu and F_a0 (2 %, the
/// discrete curve's departure from its fitted line). Without the field the result has no
/// `lab_coefficient` (the bundled scenarios' bytes).
#[test]
fn the_paper_meter_reports_the_lab_reduction_it_is_given() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let text = std::fs::read_to_string(root.join("scenarios/tas2000-discrete.json")).unwrap();
    let mut v: Value = serde_json::from_str(&text).unwrap();
    let plain = run(&Scenario::from_value(v.clone(), Path::new("tas2000-discrete.json")).unwrap());
    assert!(plain.lab_coefficient.is_none());
    v["meter"]["lab_reduction"] = json!({"kind": "friction_over_load"});
    let r = run(&Scenario::from_value(v, Path::new("tas2000-discrete.json")).unwrap());
    let lab = r.lab_coefficient.as_ref().unwrap();
    let step = 0.05;
    let used: Vec<(f64, f64)> = r
        .points
        .iter()
        .filter(|p| p.load_n > 0.0 && p.v_pull.is_some_and(|v| v > step))
        .map(|p| (p.load_n, p.friction_n.unwrap()))
        .collect();
    assert_eq!(lab.points, used.len());
    let mean = used.iter().map(|(l, f)| f / l).sum::<f64>() / used.len() as f64;
    assert!((lab.coefficient.unwrap() - mean).abs() < 1e-12);
    let (mu, fa0) = (r.mu_apparent.unwrap(), r.apparent_adhesion_force_n.unwrap());
    let closed = used.iter().map(|(l, _)| mu * (1.0 + fa0 / l)).sum::<f64>() / used.len() as f64;
    assert!(lab.coefficient.unwrap() > mu);
    assert!((lab.coefficient.unwrap() - closed).abs() < 0.02 * closed, "{} vs {closed}", lab.coefficient.unwrap());
}

fn bundled(name: &str) -> Value {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios").join(name);
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

/// One device per scenario: the paper's `actuators` or `meter` beside a `structure` (even an empty
/// `"actuators": {}`, which used to be accepted and ignored) is refused naming both fields; and a
/// normal comb driven at or past its side pull-in voltage at the wall (80.3 V on the bundled comb
/// tester: `V_s^2 = k_y g^3 / (2 N eps0 t (x0 + x_c))` with 100 N/m, 2 um, 100 fingers, 10 um,
/// 5 um + 2 um) is refused naming `structure.normal_voltages`, instead of printing a point whose
/// load `a_n V^2 - F_0` the comb does not apply.
#[test]
fn a_structure_refuses_the_paper_sections_and_voltages_past_side_pull_in() {
    for (field, value) in [("actuators", json!({})), ("meter", json!({"clamp_voltages": ["25 V"]}))] {
        let mut v = bundled("comb-sidewall.json");
        v[field] = value;
        let e = Scenario::from_value(v, Path::new("c.json")).unwrap_err().to_string();
        assert!(e.contains(&format!("`{field}`")) && e.contains("beside `structure`"), "{e}");
    }
    let v_side = (100.0 * 8e-18 / (2.0 * 100.0 * EPS0 * 10e-6 * 7e-6)).sqrt();
    assert!((v_side - 80.3).abs() < 0.05, "{v_side}");
    let mut v = bundled("comb-sidewall.json");
    v["structure"]["normal_voltages"] = json!(["30 V", "80.4 V"]);
    let e = Scenario::from_value(v, Path::new("c.json")).unwrap_err().to_string();
    assert!(e.contains("structure.normal_voltages") && e.contains("side pull-in") && e.contains("80.3"), "{e}");
    let mut v = bundled("comb-sidewall.json");
    v["structure"]["normal_voltages"] = json!(["30 V", "80.2 V"]);
    Scenario::from_value(v, Path::new("c.json")).unwrap();
}

/// A Monte Carlo sample whose released spring is 10 % stiffer than its nominal value (the
/// resonance mass drawn 10 % high, `k = m (2 pi f)^2`) sticks at displacements about 1/1.1 of the
/// nominal device's; the lab reduces them with its nominal k, so its mu_e,a is the device's own
/// divided by 1.1 (to the 5 nm displacement step, 1 %), while `true_friction_n` keeps `k' x`.
#[test]
fn a_structure_sample_is_reduced_with_the_lab_s_nominal_parts() {
    let nominal = bundled("plate-released-spring.json");
    let mut drawn = nominal.clone();
    drawn["structure"]["tangential"]["resonance"]["mass"] = json!("13.2 ng");
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    let scen = |v: &Value| Scenario::from_value(v.clone(), &base.join("p.json")).unwrap();
    let own = Meter::from_scenario(&scen(&drawn), &base).unwrap().run(&mut |_, _| {}).unwrap();
    let mut m = Meter::from_scenario(&scen(&drawn), &base).unwrap();
    let lab_parts =
        stiction_meter::structure::StructureDevice::from_spec(scen(&nominal).structure.as_ref().unwrap()).unwrap();
    m.set_lab_structure(lab_parts);
    let lab = m.run(&mut |_, _| {}).unwrap();
    let (mu_own, mu_lab) = (own.mu_apparent.unwrap(), lab.mu_apparent.unwrap());
    assert!((mu_lab * 1.1 / mu_own - 1.0).abs() < 0.01, "lab {mu_lab}, device {mu_own}");
    for (p, q) in lab.points.iter().zip(&own.points) {
        assert_eq!(p.true_friction_n, q.friction_n);
        if let (Some(f), Some(t)) = (p.friction_n, p.true_friction_n) {
            assert!((t / f - 1.1).abs() < 1e-12, "{f} {t}");
        }
    }
}

/// The lab's friction over load with a load too close to zero to divide by (5e-324 N: the ratio
/// is infinite) is null with the reason, never `inf` (the structure-threshold fuzzer's find).
#[test]
fn friction_over_load_of_a_vanishing_load_is_null_with_a_reason() {
    use stiction_meter::structure::lab_coefficient;
    use stiction_scenario::structure::LabReductionSpec;
    let pairs = [(5e-324, 1e-6), (2e-6, 2e-6), (3e-6, 2.5e-6)];
    let eq10 = stiction_meter::fit::eq10(&pairs);
    let c = lab_coefficient(&LabReductionSpec::FrictionOverLoad, &pairs, &eq10);
    assert!(c.coefficient.is_none() && c.coefficient_reason.as_deref().unwrap().contains("not a finite"), "{c:?}");
    let ok = lab_coefficient(&LabReductionSpec::FrictionOverLoad, &pairs[1..], &eq10);
    assert!((ok.coefficient.unwrap() - (1.0 + 2.5 / 3.0) / 2.0).abs() < 1e-12);
}
