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
    grid(&mut varies, &[], d.points, 1, true).map(|g| g.len()).map_err(|e| e.to_string())
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

/// Fields of the paper's scenario and spellings of their values: equal values in two units,
/// objects equal key by key, a parent beside its children, fields a study ignores.
const FIELDS: &[(&str, &[&str])] = &[
    (
        "meter.spring_force",
        &[
            "7 uN",
            "0.007 mN",
            "7e-6",
            "7.00000000000001 uN",
            "7.02 uN",
            r#"{"value":"7 uN","sd":"2 uN"}"#,
            r#"{"value":"7000 nN","sd":"2000 nN"}"#,
            "null",
        ],
    ),
    ("meter.spring_force.value", &["7 uN", "0.007 mN", "7.02 uN", "6.98 uN"]),
    ("meter.spring_force.sd", &["2 uN", "0.002 mN", "1 uN", "0"]),
    (
        "surface.summit_radius",
        &[
            r#"{"value":"0.5 um"}"#,
            r#"{"value":"500 nm"}"#,
            "0.5 um",
            "500 nm",
            "0.6 um",
            r#"{"value":"0.5 um","sd":"0.3 um","distribution":"lognormal"}"#,
            r#"{"value":"500 nm","sd":"300 nm","distribution":"lognormal"}"#,
        ],
    ),
    ("surface.summit_radius.value", &["0.3 um", "300 nm", "0.8 um", "3e-7"]),
    ("surface.summit_radius.sd", &["0.3 um", "0.1 um", "100 nm"]),
    ("actuators.clamp.plate_count", &["30", "30.0", "60", "\"60\"", "45"]),
    ("actuators.pull.spring.stiffness", &["1 N/m", "1000 mN/m", "3 N/m", "1"]),
    (
        "actuators.pull.spring",
        &[r#"{"stiffness":"1 N/m"}"#, r#"{"stiffness":"1000 mN/m"}"#, r#"{"stiffness":"2 N/m"}"#],
    ),
    ("meter.reclamp", &["true", "false", "null"]),
    ("meter.clamp_voltages.to", &["29 V", "29000 mV", "31 V", "29"]),
    ("surface.seed", &["1", "2", "2000"]),
    ("description", &["a", "b"]),
    ("actuators.clamp.description", &["a", "b"]),
    ("reference.source", &["a", "b"]),
    ("design.points", &["2", "3"]),
    ("measured", &["null"]),
];

/// Hostile atoms for a value list.
const ATOMS: &[&str] = &[
    "null",
    "[]",
    "{}",
    "\"\"",
    "1e308",
    "-1",
    "x",
    "[1,2]",
    "{\"a\":1}",
    "'a,b'",
    "\"7 uN\"",
    "0",
    "nan",
    "1e-400",
    "=",
    "]",
];

/// What `stiction study --vary ... --set ...` does before any sample runs, through the same code:
/// parse the flags, the grid with its checks, the designs' scenarios and their distinctness, then
/// each design's scenario read as a study reads it (the trial draw included). Ok: the designs'
/// scenarios (JSON) and labels.
#[allow(clippy::type_complexity)]
fn vary_case(
    text: &str,
    origin: &Path,
    flags: &[String],
    sets: &[String],
    points: Option<usize>,
    vary_surface: bool,
) -> Result<(Vec<Vary>, Vec<Vec<String>>, Vec<Value>), String> {
    let mut varies: Vec<Vary> =
        flags.iter().map(|f| Vary::parse(f)).collect::<Result<_, _>>().map_err(|e| e.to_string())?;
    let grid = grid(&mut varies, sets, points, 1, vary_surface).map_err(|e| e.to_string())?;
    let base = Scenario::json_with_sets(text, origin, sets).map_err(|e| e.to_string())?;
    stiction_study::design::check_distinct(&base, &varies, &grid, vary_surface).map_err(|e| e.to_string())?;
    let scenarios = stiction_study::design::design_scenarios(&base, &varies, &grid).map_err(|e| e.to_string())?;
    let config = stiction_study::StudyConfig {
        samples: 2,
        seed: 1,
        vary_surface,
        shard_index: 0,
        shard_count: 1,
        calibration: stiction_study::Calibration::Nominal,
        slip_path: stiction_meter::SlipPath::Light,
    };
    for (d, (p, s)) in grid.iter().zip(&scenarios).enumerate() {
        let name = || stiction_study::design::label(&varies, p);
        // What the command line prepares for design d: the file with the user's --sets, then the
        // design's (the same JSON as the design's scenario, the `design` section aside).
        let all = stiction_study::design::sets_for(sets, &varies, p);
        let mut v =
            Scenario::json_with_sets(text, origin, &all).map_err(|e| format!("design {d} ({}): {e}", name()))?;
        if let Some(m) = v.as_object_mut() {
            m.remove("design");
        }
        assert_eq!(&v, s, "design {d}: the scenario the study reads is not the design's");
        stiction_study::Study::prepare_value(v, origin, origin.parent().unwrap(), &config)
            .map_err(|e| format!("design {d} ({}): {e}", name()))?;
    }
    Ok((varies, grid, scenarios))
}

/// A study's draw `i` of scenario `v` as the typed scenario it runs (the fields no sample reads
/// left out): the key to compare two designs by what runs.
fn drawn(v: &Value, i: u64, vary_surface: bool, origin: &Path) -> String {
    use rand::SeedableRng;
    let mut v = v.clone();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    rng.set_stream(i);
    stiction_study::sample_tree(&mut v, &mut rng).expect("a prepared study draws");
    if vary_surface && let Some(s) = v.get_mut("surface").and_then(Value::as_object_mut) {
        s.insert("seed".into(), Value::from(1 + i));
    }
    let typed = Scenario::from_value(v, origin).expect("a drawn scenario parses");
    let mut t = serde_json::to_value(&typed).unwrap();
    let m = t.as_object_mut().unwrap();
    for k in ["description", "reference", "measured", "format_version", "design"] {
        m.remove(k);
    }
    if let Some(a) = m.get_mut("actuators").and_then(Value::as_object_mut) {
        for spec in a.values_mut().filter_map(Value::as_object_mut) {
            spec.remove("description");
        }
    }
    t.to_string()
}

/// The design-study fuzzer: generated `--vary` sets (parents beside children, equal values in two
/// units, objects equal key by key, fields the study ignores, hostile atoms, lists past the limit,
/// ranges) with `--set`s that may write the same fields, through the command line's parsing, grid
/// and checks. Each case is refused naming a flag or field (`--vary`, `--set`, `design`), or gives
/// designs whose studies differ (two draws of each design's typed scenario, pairwise distinct) and
/// whose labels are what runs (each varied field holds its label's value). Short in CI;
/// `STICTION_FUZZ_CASES` for the long mode. Deliberate bug caught: the designs' distinctness check,
/// the unit-aware value comparison and the overlap check off (seen failing at case 2: `1 N/m` and
/// `1000 mN/m` run the same study).
#[test]
fn generated_vary_sets_are_refused_or_give_distinct_designs_labelled_as_they_run() {
    let origin = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json");
    let text = std::fs::read_to_string(&origin).unwrap();
    let cases: usize = std::env::var("STICTION_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(300);
    let (mut state, mut ran, mut refused, mut designs) = (29u64, 0usize, 0usize, 0usize);
    let pick = |n: usize, state: &mut u64| (next(state) % n as u64) as usize;
    for case in 0..cases {
        let mut flags = Vec::new();
        let mut points = None;
        for _ in 0..1 + pick(3, &mut state) {
            let (path, pool) = FIELDS[pick(FIELDS.len(), &mut state)];
            let r = pick(100, &mut state);
            let values: Vec<String> = if r < 3 {
                (0..1001 + pick(500, &mut state)).map(|i| i.to_string()).collect()
            } else if r < 8 {
                points = Some(2 + pick(3, &mut state));
                flags.push(format!("{path}=1 uN..9 uN"));
                continue;
            } else {
                let mut v: Vec<String> =
                    (0..1 + pick(3, &mut state)).map(|_| pool[pick(pool.len(), &mut state)].to_string()).collect();
                if pick(6, &mut state) == 0 {
                    v.push(ATOMS[pick(ATOMS.len(), &mut state)].to_string());
                }
                v
            };
            flags.push(format!("{path}={}", values.join(",")));
        }
        let sets: Vec<String> = (0..usize::from(pick(5, &mut state) == 0))
            .map(|_| {
                let (path, pool) = FIELDS[pick(FIELDS.len(), &mut state)];
                format!("{path}={}", pool[pick(pool.len(), &mut state)])
            })
            .collect();
        let vary_surface = pick(4, &mut state) != 0;
        let label = format!("case {case}: --vary {flags:?} --set {sets:?} (vary_surface {vary_surface})");
        let label = stiction_scenario::truncate(&label, 600);
        match std::panic::catch_unwind(|| vary_case(&text, &origin, &flags, &sets, points, vary_surface)) {
            Err(_) => panic!("{label}: panicked"),
            Ok(Err(e)) => {
                assert!(
                    e.contains("--vary")
                        || e.contains("--set")
                        || e.contains("design")
                        || e.contains("--design-points"),
                    "{label}: the refusal names no flag or field: {e}"
                );
                refused += 1;
            }
            Ok(Ok((varies, grid, scenarios))) => {
                ran += 1;
                designs += grid.len();
                // The labels are what runs: each varied field holds its label's value.
                for (p, s) in grid.iter().zip(&scenarios) {
                    for (v, x) in varies.iter().zip(p) {
                        let (segments, want) = stiction_scenario::parse_set(&format!("{}={x}", v.path)).unwrap();
                        let got = segments.iter().try_fold(s, |node, seg| node.get(seg.as_str()));
                        if want.is_null() {
                            assert!(got.is_none(), "{label}: {}={x} but the design has {got:?}", v.path);
                        } else {
                            assert_eq!(
                                got,
                                Some(&want),
                                "{label}: the design labelled {}={x} runs another value",
                                v.path
                            );
                        }
                    }
                }
                // Pairwise distinct studies: two draws of each design's typed scenario.
                let mut seen = std::collections::HashMap::new();
                for (d, s) in scenarios.iter().enumerate() {
                    let key = drawn(s, 0, vary_surface, &origin) + &drawn(s, 1, vary_surface, &origin);
                    if let Some(e) = seen.insert(key, d) {
                        panic!("{label}: designs {e} ({:?}) and {d} ({:?}) run the same study", grid[e], grid[d]);
                    }
                }
            }
        }
    }
    eprintln!(
        "design --vary fuzz: {cases} cases, {ran} accepted ({designs} designs, pairwise distinct), {refused} refused"
    );
    assert!(ran > 0 && refused > 0, "the generator should both pass and fail some cases");
}
