//! Seeded fuzzing of the scenario's `design` section (the design study a file offers): the paper's
//! scenario with a `design` section whose fields are replaced by hostile values, removed, or given
//! unknown keys. Each case runs what `stiction study` runs on the section (the typed parse, the
//! section's checks, the varied fields, the design grid) and must give an answer without a panic,
//! and a refusal must name the `design` field (or the `--vary`-like setting) it is about.
//! `STICTION_FUZZ_CASES` sets the number of cases (default 2000).

use std::path::Path;

use serde_json::{Value, json};
use stiction_scenario::Scenario;
use stiction_study::design::{Vary, grid};

/// Values a hostile user writes.
const NASTY: &[&str] = &[
    "0",
    "-1",
    "1e300",
    "null",
    "true",
    "[]",
    "{}",
    "\"\"",
    "\"..\"",
    "\"1..\"",
    "\"40 V..29 V\"",
    "\"1 V..2 mV\"",
    "\"29 V..40 V\"",
    "[1, 1]",
    "[\"\", 2]",
    "[30, 60]",
    "[\"1 N/m\", \"3 N/m\"]",
    "\"narrowest\"",
    "\"best\"",
    "1000000",
    "2",
    "[[1, 2], {\"a\": 1}]",
    "\"x,y\"",
    "[1e308, -1e308]",
];

fn next(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// What `stiction study` does with a design section; Err: the refusal's message.
fn design_case(value: Value, origin: &Path) -> Result<usize, String> {
    let s = Scenario::from_value(value, origin).map_err(|e| e.to_string())?;
    let Some(d) = s.design else { return Ok(0) };
    let mut varies: Vec<Vary> = d
        .varied()?
        .into_iter()
        .map(|(p, v, r)| Vary::from_section(&p, v, r.as_deref()))
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    grid(&mut varies, &[], d.points, 1).map(|g| g.len()).map_err(|e| e.to_string())
}

#[test]
fn hostile_design_sections_are_answered_without_a_panic_naming_the_field() {
    let origin = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json");
    let base: Value = serde_json::from_str(&std::fs::read_to_string(&origin).unwrap()).unwrap();
    let design = json!({
        "vary": {"actuators.clamp.plate_count": [30, 60], "actuators.pull.spring.stiffness": ["1 N/m", "3 N/m"]},
        "ranges": {"meter.clamp_voltages.to": "29 V..40 V"},
        "points": 3,
        "criterion": "least-bias"
    });
    let mut with = base.clone();
    with["design"] = design.clone();
    // The unmutated section: 2 x 2 listed values crossed with 3 hypercube points.
    assert_eq!(design_case(with, &origin), Ok(12));
    let cases: usize = std::env::var("STICTION_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(2000);
    let slots: [&[&str]; 8] = [
        &["vary"],
        &["vary", "actuators.clamp.plate_count"],
        &["vary", "actuators.pull.spring.stiffness"],
        &["ranges"],
        &["ranges", "meter.clamp_voltages.to"],
        &["points"],
        &["criterion"],
        &["extra"],
    ];
    let (mut state, mut ran, mut refused) = (11u64, 0, 0);
    for case in 0..cases {
        let mut d = design.clone();
        for _ in 0..1 + next(&mut state) % 3 {
            let slot = slots[(next(&mut state) % slots.len() as u64) as usize];
            let nasty = NASTY[(next(&mut state) % NASTY.len() as u64) as usize];
            let v: Value = serde_json::from_str(nasty).unwrap();
            let (last, parent) = slot.split_last().unwrap();
            let mut target = &mut d;
            for k in parent {
                target = &mut target[*k];
            }
            if let Value::Object(m) = target {
                if next(&mut state).is_multiple_of(5) {
                    m.remove(*last);
                } else {
                    m.insert((*last).to_string(), v);
                }
            }
        }
        let mut s = base.clone();
        s["design"] = d.clone();
        let label = format!("case {case}: design = {d}");
        match std::panic::catch_unwind(|| design_case(s, &origin)) {
            Err(_) => panic!("{label}: panicked"),
            Ok(Ok(n)) => {
                assert!((1..=stiction_study::design::MAX_DESIGNS).contains(&n), "{label}: {n} designs");
                ran += 1;
            }
            Ok(Err(e)) => {
                assert!(
                    e.contains("design") || e.contains("--vary") || e.contains("--design-points"),
                    "{label}: the refusal names no field: {e}"
                );
                refused += 1;
            }
        }
    }
    eprintln!("design fuzz: {cases} cases, {ran} accepted, {refused} refused");
    assert!(ran > 0 && refused > 0, "the mutations should both pass and fail some cases");
}
