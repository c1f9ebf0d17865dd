//! Scenario-spec parsing and its errors: bad input gives an error naming the field.

use stiction_actuator::*;

fn parse(json: &str) -> Result<ArraySpec, String> {
    serde_json::from_str(json).map_err(|e| e.to_string())
}

const CLAMP: &str = r#"{
  "plate_count": 30, "overlap_length": "100 um", "thickness": "5 um",
  "conversion_factor": {"value": "1.4e-8 N/V^2", "sd": "0.5e-8 N/V^2", "distribution": "normal"},
  "fringing": "off",
  "spring": {"stiffness": "8 N/m", "parallel_stiffness": "1 N/m"},
  "stop": {"travel": "1 um"}
}"#;

#[test]
fn meter_array_from_conversion_factor() {
    let spec = parse(CLAMP).unwrap();
    let m = spec.to_model().unwrap();
    // a(0) reproduces the conversion factor; the gap is sqrt(n eps0 A / (2a)) = 2.178 um.
    assert!((m.conversion_factor_n_per_v2(0.0) / 1.4e-8 - 1.0).abs() < 1e-10);
    assert!((m.plates.front_gap_m - 2.178e-6).abs() < 0.005e-6);
    assert!((m.stiffness_n_per_m() - 9.0).abs() < 1e-12);
}

#[test]
fn errors_name_the_field() {
    let e = parse(&CLAMP.replace("\"thickness\"", "\"thicknes\"")).unwrap_err();
    assert!(e.contains("thicknes"), "{e}");
    let e = parse(&CLAMP.replace("\"5 um\"", "\"5 V\"")).unwrap_err();
    assert!(e.contains("5 V"), "{e}");
    let both = CLAMP.replace("\"fringing\"", "\"front_gap\": \"2 um\", \"fringing\"");
    let e = parse(&both).unwrap().to_model().unwrap_err().to_string();
    assert!(e.contains("front_gap") && e.contains("conversion_factor"), "{e}");
    let mut spec = parse(CLAMP).unwrap();
    spec.spring.stiffness = Some(-1.0);
    let e = spec.to_model().unwrap_err().to_string();
    assert!(e.contains("spring.stiffness") && e.contains("-1"), "{e}");
    let mut spec = parse(CLAMP).unwrap();
    spec.stop = Some(StopSpec { travel: 5e-6, contact_standoff: 0.0 });
    let e = spec.to_model().unwrap_err().to_string();
    assert!(e.contains("stop_travel"), "{e}");
}

#[test]
fn measured_csv_errors_carry_line_numbers() {
    let e = parse_measurements("finger_length_drawn_um,pull_in_v_1,release_v\n15.3,33,18\n22.9,x,14\n", "m.csv")
        .unwrap_err();
    assert_eq!(e.to_string(), "m.csv: line 3: column `pull_in_v_1`: `x` is not a number");
    let e = parse_measurements("finger_length_drawn_um,pull_in_v_1,release_v\n15.3,33\n", "m.csv").unwrap_err();
    assert!(e.to_string().contains("line 2"), "{e}");
    let e = parse_measurements("length,pull_in_v_1,release_v\n", "m.csv").unwrap_err();
    assert!(e.to_string().contains("line 1") && e.to_string().contains("finger_length_drawn_um"), "{e}");
    let e = parse_measurements("finger_length_drawn_um,pull_in_v_1,release_v\n15.3,-3,18\n", "m.csv").unwrap_err();
    assert!(e.to_string().contains("line 2") && e.to_string().contains("in [1e-5, 1e4]"), "{e}");
}
