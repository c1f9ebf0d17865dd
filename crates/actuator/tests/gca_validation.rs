//! Validation against hardware: pull-in and release voltages of the Rauf et al. (JMEMS 2022)
//! gap-closing actuator, data/gca-pullin-release/measured.csv, scenario
//! scenarios/gca-rauf2022.json. Floors from issue 6: mean |relative error| <= 10 % for pull-in
//! and for release over the nine finger lengths, with at most one global fitted parameter
//! (here the stop contact standoff, fitted to release only).

use stiction_actuator::*;

mod common;
use common::{gca_spec, root};

fn data() -> Vec<MeasuredPoint> {
    read_measurements(&root().join("data/gca-pullin-release/measured.csv")).unwrap()
}

#[test]
fn measured_file_reads_nine_lengths_with_three_pull_in_repeats() {
    let d = data();
    assert_eq!(d.len(), 9);
    assert!(d.iter().all(|p| p.pull_in_v.len() == 3 && p.release_v.len() == 1));
    // first row of measured.csv: 15.30 um, 35.3/33.5/33.3 V, 18.0 V
    assert!((d[0].finger_length_m - 15.30e-6).abs() < 1e-15);
    assert_eq!(d[0].release_v, vec![18.0]);
}

#[test]
fn gca_scenario_meets_the_floors() {
    let r = validate(&gca_spec(), &data()).unwrap();
    for p in &r.points {
        println!(
            "L = {:5.2} um  Vpi {:5.2} (meas {:5.2} +/- {:4.2}) {:+.3}   Vr {:5.2} (meas {:5.2}) {:+.3}",
            p.finger_length_m * 1e6,
            p.pull_in_v_model,
            p.pull_in_v_measured,
            p.pull_in_v_spread,
            p.pull_in_rel_error,
            p.release_v_model,
            p.release_v_measured,
            p.release_rel_error
        );
    }
    println!("pull-in {:.4}  release {:.4}", r.pull_in_mean_abs_rel_error, r.release_mean_abs_rel_error);
    // Floors of issue 6.
    assert!(r.pull_in_mean_abs_rel_error <= 0.10, "pull-in {}", r.pull_in_mean_abs_rel_error);
    assert!(r.release_mean_abs_rel_error <= 0.10, "release {}", r.release_mean_abs_rel_error);
    // Release below pull-in at every length, in model and measurement.
    assert!(
        r.points.iter().all(|p| p.release_v_model < p.pull_in_v_model && p.release_v_measured < p.pull_in_v_measured)
    );
}

#[test]
fn stored_stop_standoff_is_the_fit() {
    let spec = gca_spec();
    let (fit, report) = fit_stop_contact_standoff(&spec, &data()).unwrap();
    println!("fitted standoff {:.4} um, release error {:.4}", fit * 1e6, report.release_mean_abs_rel_error);
    let stored = spec.stop.as_ref().unwrap().contact_standoff;
    // The scenario stores the fit rounded to 0.01 um.
    assert!((fit - stored).abs() <= 0.005e-6, "fit {fit:e} vs stored {stored:e}");
}

#[test]
fn switch_effects_show_which_physics_matters() {
    let effects = switch_effects(&gca_spec(), &data()).unwrap();
    for e in &effects {
        println!(
            "{:34} pull-in {:6.4} ({:+.4})  release {:6.4} ({:+.4})",
            e.switch,
            e.pull_in_mean_abs_rel_error,
            e.pull_in_mean_rel_error,
            e.release_mean_abs_rel_error,
            e.release_mean_rel_error
        );
    }
    let get = |n: &str| effects.iter().find(|e| e.switch == n).unwrap();
    // README of the data: rigid parallel plate with back gap and undercut is 8-22 % high on
    // pull-in, 7-13 % low on release: our baseline must reproduce that direction and size.
    let base = get("rigid parallel plate (baseline)");
    assert!(base.pull_in_mean_rel_error > 0.08 && base.pull_in_mean_rel_error < 0.22);
    assert!(base.release_mean_rel_error < -0.07 && base.release_mean_rel_error > -0.13);
    // Fringing lowers pull-in (more force); it cannot raise release.
    assert!(get("fringing off").pull_in_mean_rel_error > get("as specified").pull_in_mean_rel_error);
    // The stop standoff is what closes the release gap.
    assert!(get("no stop contact standoff").release_mean_abs_rel_error > 0.10);
    // The scenario's protocol is the step (the measured times are step responses, docs/actuators.md):
    // a slow ramp (quasi-static) needs more voltage than a step; release is unchanged.
    let ramp = get("pull-in protocol quasi_static");
    assert!(ramp.pull_in_mean_rel_error > get("as specified").pull_in_mean_rel_error);
    assert_eq!(ramp.release_mean_abs_rel_error, get("as specified").release_mean_abs_rel_error);
    // Evidence for the step default: the same dynamic model that fits the measured times gives
    // the pull-in voltages within 5 % under a step, against about 9 % for the quasi-static ramp.
    assert!(get("as specified").pull_in_mean_abs_rel_error < 0.05);
    assert!(ramp.pull_in_mean_abs_rel_error > 0.085);
}
