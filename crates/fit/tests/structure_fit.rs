//! `stiction fit` of a test structure's measured thresholds against closed forms: thresholds made
//! from a Coulomb contact, `F_f = mu (L + F_adh)` with known mu and F_adh, carried through each
//! part's force law written out here (not the code's), are fitted back.
//!
//! The parts (the bundled scenarios'):
//! * comb (`scenarios/comb-sidewall.json`): `a = alpha N eps0 t / g` = 1 x 100 x eps0 x 10 um / 2 um,
//!   `F_0 = k_x x_c` = 1 N/m x 2 um; side pull-in at the wall `V_s^2 = k_y g^3 / (2 N eps0 t (x0 + x_c))`
//!   (100 N/m, 5 um + 2 um engaged): 80.3 V;
//! * plate (`scenarios/plate-released-spring.json`): `a = eps0 A / (2 (t / eps_r)^2)` over 2500 um^2 and
//!   100 nm of eps_r 7.5, `F_0 = k_z g0` = 5 N/m x 2 um; released spring `k = m (2 pi f)^2` with
//!   12 ng at 200 kHz.

use std::path::Path;

use serde_json::{Value, json};
use stiction_fit::{analyse_structure, parse_thresholds};
use stiction_scenario::Scenario;

const EPS0: f64 = 8.854_187_812_8e-12;
const MU: f64 = 0.35;
const F_ADH: f64 = 3e-6;

fn scenario_json(name: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios").join(name);
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn scenario(v: &Value) -> Scenario {
    Scenario::from_value(v.clone(), Path::new("test.json")).unwrap()
}

fn comb_a() -> f64 {
    100.0 * EPS0 * 10e-6 / 2e-6
}
const COMB_F0: f64 = 1.0 * 2e-6;

fn plate_a() -> f64 {
    EPS0 * 2500e-12 / (2.0 * (100e-9 / 7.5f64).powi(2))
}
const PLATE_F0: f64 = 5.0 * 2e-6;

fn spring_k() -> f64 {
    12e-12 * (2.0 * std::f64::consts::PI * 2e5).powi(2)
}

fn fit(csv: &str, v: &Value, draws: usize) -> stiction_fit::StructureFitReport {
    let data = parse_thresholds(csv.as_bytes(), "t.csv").unwrap();
    analyse_structure(&data, &scenario(v), v, draws, 1).unwrap()
}

/// Comb tester, ramp: V_t at slip from `a_t V_t^2 = mu (a_n V_n^2 - F_0 + F_adh)` with no
/// quantisation: mu and F_adh come back to 1e-9 (rounding only).
#[test]
fn comb_ramp_thresholds_fit_back_to_the_coulomb_contact() {
    let v = scenario_json("comb-sidewall.json");
    let mut csv = String::from("v_normal_v,v_tangential_v\n");
    for k in 0..9 {
        let vn = 30.0 + 5.0 * k as f64;
        let load = comb_a() * vn * vn - COMB_F0;
        let vt = (MU * (load + F_ADH) / comb_a()).sqrt();
        csv.push_str(&format!("{vn},{vt:.17e}\n"));
    }
    let r = fit(&csv, &v, 10);
    let (mu, fa) = (r.mu_apparent.value.unwrap(), r.apparent_adhesion_force_n.value.unwrap());
    assert!((mu - MU).abs() < 1e-9 && (fa - F_ADH).abs() < 1e-9 * F_ADH, "mu {mu}, F_a0 {fa}");
    assert_eq!(r.rows_used, 9);
    // The lab reduces by eq. 10 in this scenario: its number is mu_e,a itself.
    assert!((r.lab_coefficient.coefficient.unwrap() - MU).abs() < 1e-9);
    // No uncertain part: no Monte Carlo, said so.
    assert!(r.mu_apparent.ci95_with_calibration.is_none() && r.calibration.note.is_some());
}

/// Comb tester, lowered normal load: at each tangential voltage the normal voltage at slip solves
/// `mu (a_n V_n^2 - F_0 + F_adh) = a_t V_t^2`; mu and F_adh come back to 1e-9.
#[test]
fn lowered_normal_thresholds_fit_back_to_the_coulomb_contact() {
    let mut v = scenario_json("comb-sidewall.json");
    v["structure"]["protocol"] = json!({"kind": "lower_normal", "tangential_voltages": ["20 V", "25 V", "30 V"]});
    let mut csv = String::from("# lower_normal\nv_tangential_v;v_normal_v\n");
    for k in 0..6 {
        let vt = 20.0 + 3.0 * k as f64;
        let load = comb_a() * vt * vt / MU - F_ADH;
        let vn = ((load + COMB_F0) / comb_a()).sqrt();
        csv.push_str(&format!("{vt};{vn:.17e}\n"));
    }
    let r = fit(&csv, &v, 10);
    let (mu, fa) = (r.mu_apparent.value.unwrap(), r.apparent_adhesion_force_n.value.unwrap());
    assert!((mu - MU).abs() < 1e-9 && (fa - F_ADH).abs() < 1e-9 * F_ADH, "mu {mu}, F_a0 {fa}");
    // Given as loads (tangential load, normal load at slip): the same numbers.
    let mut loads = String::from("tangential_load_n,normal_load_n\n");
    for k in 0..6 {
        let t = 2e-6 + 1e-6 * k as f64;
        loads.push_str(&format!("{t:e},{:.17e}\n", t / MU - F_ADH));
    }
    let r = fit(&loads, &v, 10);
    assert!((r.mu_apparent.value.unwrap() - MU).abs() < 1e-9);
    assert!((r.apparent_adhesion_force_n.value.unwrap() - F_ADH).abs() < 1e-9 * F_ADH);
}

/// Plate with a released spring (displacement step 1 nm): the largest displacement that sticks is
/// `x = floor(mu (L + F_adh) / (k dx)) dx`, so each friction is low by `e_i` in `[0, k dx)`. For an
/// ordinary least-squares line that error moves the slope by at most
/// `d_mu = k dx sum |L_i - Lbar| / S_LL` and F_a0 by at most
/// `(k dx + d_mu (Lbar + F_adh)) / (mu - d_mu)` (from `a'/b' - a/b = -(e b + db (Lbar b + a)) / (b b')`);
/// the fit must land inside both bounds, and the report states the resolution.
#[test]
fn release_thresholds_fit_back_within_one_displacement_step() {
    let mut v = scenario_json("plate-released-spring.json");
    v["structure"]["protocol"]["displacement_step"] = json!("1 nm");
    let (a, k, dx) = (plate_a(), spring_k(), 1e-9);
    let mut csv = String::from("v_normal_v,displacement_m\n");
    let mut loads = Vec::new();
    for i in 0..11 {
        let vn = 0.5 + 0.1 * i as f64;
        let load = a * vn * vn - PLATE_F0;
        let x = (MU * (load + F_ADH) / (k * dx)).floor() * dx;
        loads.push(load);
        csv.push_str(&format!("{vn},{x:.17e}\n"));
    }
    let r = fit(&csv, &v, 10);
    let lbar = loads.iter().sum::<f64>() / loads.len() as f64;
    let sll: f64 = loads.iter().map(|l| (l - lbar).powi(2)).sum();
    let d_mu = k * dx * loads.iter().map(|l| (l - lbar).abs()).sum::<f64>() / sll;
    let d_fa = (k * dx + d_mu * (lbar + F_ADH)) / (MU - d_mu);
    let (mu, fa) = (r.mu_apparent.value.unwrap(), r.apparent_adhesion_force_n.value.unwrap());
    assert!((mu - MU).abs() <= d_mu, "mu {mu} against {MU} +/- {d_mu}");
    assert!((fa - F_ADH).abs() <= d_fa, "F_a0 {fa} against {F_ADH} +/- {d_fa}");
    // The bounds are tight enough to mean something: 0.2 % of mu, 5 % of F_adh.
    assert!(d_mu < 2e-3 * MU && d_fa < 0.05 * F_ADH, "{d_mu} {d_fa}");
    assert!(r.resolution_note.as_deref().unwrap().contains("k dx"), "{:?}", r.resolution_note);
    // Normal loads given directly (a released-spring device whose load is measured): the same.
    let mut by_load = String::from("normal_load_n,displacement_m\n");
    for (l, line) in loads.iter().zip(csv.lines().skip(1)) {
        by_load.push_str(&format!("{l:.17e},{}\n", line.split(',').nth(1).unwrap()));
    }
    let r2 = fit(&by_load, &v, 10);
    assert!((r2.mu_apparent.value.unwrap() - mu).abs() < 1e-9 * mu);
}

/// The parts' uncertainty: the tangential comb's fringing factor, 1.2 with a normal SD of 0.06
/// (5 %; the factor must stay >= 1, 3.3 SD below), scales every friction, so the fitted mu_e,a is
/// 1.2 mu (the lab's nominal factor on a device whose true one is 1) with a calibration SD of 5 %
/// of it; F_a0, a ratio of intercept and slope, does not move. With 4000 draws the robust SD is
/// within 5 % of that (its Monte Carlo error is about 1.7 %).
#[test]
fn calibration_of_an_uncertain_comb_scales_mu_only() {
    let mut v = scenario_json("comb-sidewall.json");
    v["structure"]["tangential"]["fringing_factor"] = json!({"value": 1.2, "sd": 0.06});
    let mut csv = String::from("v_normal_v,v_tangential_v\n");
    for k in 0..9 {
        let vn = 30.0 + 5.0 * k as f64;
        let vt = (MU * (comb_a() * vn * vn - COMB_F0 + F_ADH) / comb_a()).sqrt();
        csv.push_str(&format!("{vn},{vt:.17e}\n"));
    }
    let r = fit(&csv, &v, 4000);
    let mu = r.mu_apparent.value.unwrap();
    assert!((mu - 1.2 * MU).abs() < 1e-9, "{mu}");
    let sd = r.mu_apparent.sd_calibration.unwrap();
    assert!((sd / (0.05 * mu) - 1.0).abs() < 0.05, "sd {sd}");
    assert!(r.apparent_adhesion_force_n.sd_calibration.unwrap() < 1e-12 * F_ADH);
    let [lo, hi] = r.mu_apparent.ci95_with_calibration.unwrap();
    assert!(lo < mu && mu < hi && hi - lo > 3.0 * 0.05 * mu, "[{lo}, {hi}]");
    assert_eq!(r.calibration.sources.len(), 1);
    // The draws below 1 (P = 4.3e-4, about 2 of 4000) are refused by the comb and counted.
    assert!(r.calibration.failed_draws < 10, "{}", r.calibration.failed_draws);
}

/// The rules of a fit: rows past the normal comb's side pull-in (80.3 V here) imply no load and are
/// rejected with their line; one friction at every load is not a slope (null with the reason);
/// the columns must fit the parts.
#[test]
fn undetermined_fits_and_invalid_rows_are_named() {
    let v = scenario_json("comb-sidewall.json");
    let r = fit("v_normal_v,v_tangential_v\n30,20\n40,25\n50,30\n60,35\n85,40\n20,10\n", &v, 10);
    assert_eq!(r.rows_used, 4);
    let side = r.rows_rejected.iter().find(|x| x.line == 6).unwrap();
    assert!(side.reason.contains("side pull-in") && side.reason.contains("80.3"), "{side:?}");
    let below = r.rows_rejected.iter().find(|x| x.line == 7).unwrap();
    assert!(below.reason.contains("below contact"), "{below:?}");
    let flat = fit("v_normal_v,v_tangential_v\n30,20\n40,20\n50,20\n", &v, 10);
    assert!(flat.mu_apparent.value.is_none() && flat.fit.is_none());
    assert!(flat.fit_note.as_deref().unwrap().contains("flat"), "{:?}", flat.fit_note);
    assert!(flat.mu_apparent.value_note.is_some() && flat.apparent_adhesion_force_n.value_note.is_some());
    let data = parse_thresholds(b"v_normal_v,displacement_m\n30,1e-7\n40,2e-7\n50,3e-7\n", "t.csv").unwrap();
    let e = analyse_structure(&data, &scenario(&v), &v, 10, 1).unwrap_err().to_string();
    assert!(e.contains("displacement_m") && e.contains("lateral_comb"), "{e}");
    let data = parse_thresholds(b"v_normal_v,v_tangential_v\n30,20\n90,25\n", "t.csv").unwrap();
    let e = analyse_structure(&data, &scenario(&v), &v, 10, 1).unwrap_err().to_string();
    assert!(e.contains("1 usable row") && e.contains("line 3"), "{e}");
}

/// The lab's interval of a release experiment (what `stiction study` reports per device): from its
/// (plate voltage, displacement that sticks) readings, the regression width of mu_e,a is
/// `2 t_0.975(n - 2) se(slope)` of the ordinary least-squares line through
/// `(a_n V^2 - F_0, k x)`, computed here by hand (`se^2 = SSE / (n - 2) / S_LL`; t_0.975(9) =
/// 2.262, Student's table); with the resonance's mass uncertain by 4 % (k = m (2 pi f)^2, so
/// every friction and mu_e,a scale by m / m0, a 4 % SD) the calibrated width is close to
/// `2 x 1.96 x 4 % mu` widened by the regression's (within 10 %).
#[test]
fn the_lab_interval_of_a_release_experiment_matches_its_closed_form() {
    let mut v = scenario_json("plate-released-spring.json");
    let (a, k, dx) = (plate_a(), spring_k(), 5e-9);
    let readings: Vec<(f64, f64)> = (0..11)
        .map(|i| {
            let vn = 0.5 + 0.1 * i as f64;
            (vn, (MU * (a * vn * vn - PLATE_F0 + F_ADH) / (k * dx)).floor() * dx)
        })
        .collect();
    let device = stiction_fit::structure::device_of(&scenario(&v)).unwrap();
    let w = stiction_fit::structure::release_interval_widths(&readings, &device, &v, 2000, 7).unwrap();
    let pts: Vec<(f64, f64)> = readings.iter().map(|&(vn, x)| (a * vn * vn - PLATE_F0, k * x)).collect();
    let n = pts.len() as f64;
    let (lbar, fbar) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sll: f64 = pts.iter().map(|p| (p.0 - lbar).powi(2)).sum();
    let slope = pts.iter().map(|p| (p.0 - lbar) * (p.1 - fbar)).sum::<f64>() / sll;
    let sse: f64 = pts.iter().map(|p| (p.1 - fbar - slope * (p.0 - lbar)).powi(2)).sum();
    let width = 2.0 * 2.262 * (sse / (n - 2.0) / sll).sqrt();
    let got = w.mu.unwrap();
    assert!((got / width - 1.0).abs() < 1e-3, "regression width {got} against {width}");
    // No uncertain part: no calibrated width.
    assert!(w.mu_with_calibration.is_none());
    v["structure"]["tangential"]["resonance"]["mass"] = json!({"value": "12 ng", "sd": "0.48 ng"});
    let w = stiction_fit::structure::release_interval_widths(&readings, &device, &v, 2000, 7).unwrap();
    let expected = 2.0 * 1.96 * ((0.04 * MU).powi(2) + (width / 3.92).powi(2)).sqrt();
    let got = w.mu_with_calibration.unwrap();
    assert!((got / expected - 1.0).abs() < 0.1, "calibrated width {got} against {expected}");
}

/// A Monte Carlo study of the release structure gives each device the lab's intervals (they were
/// null: the study computed them from pull voltages, which a released spring does not have).
#[test]
fn a_release_study_reports_the_lab_interval() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/plate-released-spring.json");
    let sets = vec!["structure.tangential.resonance.mass={\"value\": \"12 ng\", \"sd\": \"0.48 ng\"}".to_string()];
    let config = stiction_study::StudyConfig {
        samples: 2,
        seed: 1,
        vary_surface: true,
        shard_index: 0,
        shard_count: 1,
        calibration: stiction_study::Calibration::Nominal,
        slip_path: stiction_meter::SlipPath::Light,
    };
    let study =
        stiction_fit::with_lab_intervals(stiction_study::Study::prepare(&path, &sets, &config).unwrap()).unwrap();
    let s = study.run_sample(0);
    assert!(s.mu_apparent.is_some(), "{s:?}");
    let i = s.intervals;
    assert!(i.mu_ci95_width.is_some() && i.mu_ci95_width_with_calibration.is_some(), "{i:?}");
    assert!(i.mu_ci95_width_with_calibration.unwrap() > i.mu_ci95_width.unwrap());
}
