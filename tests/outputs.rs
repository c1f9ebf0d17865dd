//! Text and JSON outputs (issue 14): user-facing names, units in keys, readable tables, paths.

use crate::util::{stiction, stiction_json};

fn stdout(args: &[&str]) -> String {
    let out = stiction(args);
    assert!(out.status.success(), "stiction {args:?} failed:\n{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("UTF-8 stdout")
}

/// Debug names of Rust enums (`Dmt`, `MaugisDugdale`, `Tilt`) never reach a user: text and JSON
/// spell each name as the scenario files do.
#[test]
fn enums_have_their_scenario_names_in_text_and_json() {
    let discrete = [
        "discrete",
        "--contacts",
        "3",
        "--radius",
        "0.5 um",
        "--work-of-adhesion",
        "0.1 J/m^2",
        "--compliance",
        "9.1e-12",
        "--shear-strength",
        "1.4 GPa",
        "--load",
        "3 uN",
    ];
    let j = stiction_json(&[&discrete[..], &["--json"]].concat());
    assert_eq!(j["law"], "dmt");
    // Tabor parameter 0.30 for these numbers (Maugis lambda 0.35): between DMT and JKR.
    assert_eq!(j["recommended_law"], "maugis-dugdale");
    let text = stdout(&discrete);
    assert!(text.contains("3, dmt") && text.contains("recommended law: maugis-dugdale"), "{text}");
    let text = stdout(&["contact", "scenarios/tas2000.json", "--load", "3 uN"]);
    assert!(text.contains("(mode tilt, law dmt)"), "{text}");
    for debug in ["Dmt", "MaugisDugdale", "Tilt", "Flat", "Fixed"] {
        assert!(!text.contains(debug), "{debug} in\n{text}");
    }
}
