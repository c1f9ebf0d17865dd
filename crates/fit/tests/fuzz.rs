//! Seeded mutation fuzzing of `stiction fit`'s input, the measured-voltage CSV: each case mutates
//! the bundled synthetic file (cells, separators, quotes, lines, extreme numbers, equal pull
//! voltages, many devices, long lines) and runs the reader and, when it reads, the whole fit with
//! cheap models. Every case must end in a result whose numbers are all finite (or null with a
//! reason) or in an error of bounded length; a panic fails the test with the case's seed.
//!
//! Short mode (default, CI): 300 cases. Long mode: `STICTION_FIT_FUZZ_CASES=20000 cargo test
//! --release -p stiction-fit --test fuzz -- --nocapture` (the counts of a long run are in
//! docs/reliability.md).

use std::path::Path;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiction_fit::{FitOptions, ModelKind, analyse, parse_measured_voltages};
use stiction_scenario::Scenario;

mod common;

const PIECES: [&str; 16] =
    [",", ";", "\t", "\n", "\r\n", "\"", "#", ".", "-", "e", "NaN", "inf", "1e308", "0", " ", "\u{feff}"];

fn mutate(base: &str, rng: &mut ChaCha8Rng) -> String {
    let mut lines: Vec<String> = base.lines().map(String::from).collect();
    for _ in 0..rng.random_range(1..=3) {
        let n = lines.len().max(1);
        match rng.random_range(0..11) {
            0 => {
                // Insert a piece into a line.
                let i = rng.random_range(0..n).min(lines.len().saturating_sub(1));
                if let Some(l) = lines.get_mut(i) {
                    let at =
                        l.char_indices().map(|c| c.0).nth(rng.random_range(0..=l.chars().count())).unwrap_or(l.len());
                    l.insert_str(at, PIECES[rng.random_range(0..PIECES.len())]);
                }
            }
            1 if !lines.is_empty() => {
                lines.remove(rng.random_range(0..lines.len()));
            }
            2 if !lines.is_empty() => {
                let l = lines[rng.random_range(0..lines.len())].clone();
                lines.insert(rng.random_range(0..=lines.len()), l);
            }
            3 => {
                let v: f64 = rng.random_range(0.0..60.0);
                let p: f64 = rng.random_range(0.0..60.0);
                lines.push(format!("{v},{p}"));
            }
            4 => {
                // All pull voltages equal.
                for l in lines.iter_mut().filter(|l| l.starts_with(|c: char| c.is_ascii_digit())) {
                    if let Some((c, _)) = l.split_once(',') {
                        *l = format!("{c},30");
                    }
                }
            }
            5 => {
                let extreme = ["1e308", "5e-324", "0", "-0", "9999", "1e6", "-1", "00000000000000000000027"];
                let i = rng.random_range(0..n).min(lines.len().saturating_sub(1));
                if let Some(l) = lines.get_mut(i)
                    && let Some((c, _)) = l.split_once(',')
                {
                    *l = format!("{c},{}", extreme[rng.random_range(0..extreme.len())]);
                }
            }
            6 => {
                let keep = rng.random_range(0..=lines.len());
                lines.truncate(keep);
            }
            7 => {
                // Another header.
                let headers = [
                    "v_clamp_v,v_pull_v,device",
                    "v_clamp_v,v_pull_v,v_pull_sd_v",
                    "v_clamp,v_pull",
                    "v_pull_v,v_clamp_v",
                    "v_clamp_v;v_pull_v",
                    "",
                ];
                if let Some(i) = lines.iter().position(|l| l.starts_with("v_clamp_v")) {
                    lines[i] = headers[rng.random_range(0..headers.len())].to_string();
                }
            }
            8 => {
                // Many devices, one row each (per-device fits) or several.
                let mut out = vec!["v_clamp_v,v_pull_v,device".to_string()];
                let devices = rng.random_range(1..400);
                for d in 0..devices {
                    for k in 0..rng.random_range(1..5) {
                        let v = 23.0 + 0.5 * ((d + k) % 13) as f64;
                        out.push(format!("{v},{},{d}", 20.0 + v * 0.5 + rng.random_range(-0.5..0.5)));
                    }
                }
                lines = out;
            }
            9 => {
                let len = rng.random_range(1..20_000);
                lines.push("9".repeat(len));
            }
            _ => {
                // Replace separators throughout.
                let sep = [";", "\t", " ", "|"][rng.random_range(0..4)];
                for l in lines.iter_mut() {
                    *l = l.replace(',', sep);
                }
            }
        }
    }
    lines.join(if rng.random_bool(0.2) { "\r\n" } else { "\n" })
}

#[test]
fn mutated_voltage_csvs_give_finite_results_or_bounded_errors() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let scenario_path = root.join("scenarios/tas2000-discrete.json");
    let scenario = Scenario::load(&scenario_path, &[]).unwrap();
    let json = Scenario::load_json(&scenario_path, &[]).unwrap();
    let base_dir = scenario_path.parent().unwrap().to_path_buf();
    let base = std::fs::read_to_string(root.join("data/measured-voltages-synthetic/voltages.csv")).unwrap();
    let cases: u64 = std::env::var("STICTION_FIT_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(300);
    let options = FitOptions {
        models: vec![ModelKind::Discrete(1), ModelKind::Gw],
        calibration_draws: 20,
        surfaces: 1,
        ..FitOptions::default()
    };
    let (mut read_errors, mut fit_errors, mut fitted, mut nulls) = (0u64, 0u64, 0u64, 0u64);
    for case in 0..cases {
        let mut rng = ChaCha8Rng::seed_from_u64(0xF17 + case);
        let text = mutate(&base, &mut rng);
        let outcome = std::panic::catch_unwind(|| match parse_measured_voltages(text.as_bytes(), "fuzz.csv") {
            Err(e) => Err((true, e.to_string())),
            Ok(data) => analyse(&data, &scenario, &json, &base_dir, &options).map_err(|e| (false, e.to_string())),
        });
        match outcome {
            Err(_) => panic!("case {case} (seed {:#x}) panicked", 0xF17 + case),
            Ok(Err((reading, message))) => {
                assert!(message.len() <= 2000, "case {case}: error of {} bytes", message.len());
                assert!(!message.contains(&"9".repeat(200)), "case {case}: the error echoes a long cell");
                if reading { read_errors += 1 } else { fit_errors += 1 }
            }
            Ok(Ok(report)) => {
                if let Some(at) = common::non_finite_in_debug(&format!("{report:?}")) {
                    panic!("case {case}: a non-finite number in the report: ...{at}");
                }
                nulls += report.mu_apparent.value.is_none() as u64;
                fitted += 1;
            }
        }
    }
    eprintln!(
        "{cases} cases: {fitted} fitted ({nulls} with mu_e,a null and a reason), {read_errors} refused by the reader, {fit_errors} refused by the fit"
    );
    assert_eq!(fitted + read_errors + fit_errors, cases);
    assert!(fitted > 0 && read_errors > 0, "the mutations must reach both the reader's errors and the fit");
}

/// The structure-threshold CSV of `stiction fit` with a `structure` scenario, fuzzed the same way,
/// against each bundled structure with the columns of each of its protocols (release: plate
/// voltage and displacement; comb ramp: normal and tangential comb voltages; lowered normal load:
/// tangential and normal loads at slip), a `device` column, both normal columns and hostile cells.
/// Every case ends in a report whose numbers are finite (or null with a reason) or in an error that
/// names the file and is bounded in length.
#[test]
fn mutated_structure_thresholds_give_finite_results_or_bounded_errors() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let files = [
        (
            "plate-released-spring.json",
            "# release\nv_normal_v,displacement_m\n0.5,3e-8\n0.7,1.1e-7\n0.9,2.2e-7\n1.1,3.5e-7\n1.3,5e-7\n",
        ),
        ("comb-sidewall.json", "v_normal_v,v_tangential_v\n30,20.1\n40,24\n50,27.9\n60,31.2\n70,34\n"),
        (
            "pad-uniform-pressure.json",
            "tangential_load_n,normal_load_n\n1e-6,2e-6\n2e-6,5e-6\n3e-6,8e-6\n4e-6,1.1e-5\n",
        ),
    ];
    let extra = [
        "v_normal_v,normal_load_n,displacement_m",
        "v_normal_v,displacement_m,device",
        "displacement_m",
        "v_normal,displacement",
        "v_tangential_v,v_normal_v",
        "normal_load_n;tangential_load_n",
    ];
    let cases: u64 = std::env::var("STICTION_FIT_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(300);
    let (mut read_errors, mut fit_errors, mut fitted) = (0u64, 0u64, 0u64);
    for case in 0..cases {
        let mut rng = ChaCha8Rng::seed_from_u64(0x57C + case);
        let (name, base) = files[(case % files.len() as u64) as usize];
        let path = root.join("scenarios").join(name);
        let scenario = Scenario::load(&path, &[]).unwrap();
        let json = Scenario::load_json(&path, &[]).unwrap();
        let mut text = mutate(base, &mut rng);
        if rng.random_bool(0.15) {
            let h = extra[rng.random_range(0..extra.len())];
            text = text.replacen(text.lines().find(|l| l.contains('_')).unwrap_or(""), h, 1);
        }
        let outcome = std::panic::catch_unwind(|| match stiction_fit::parse_thresholds(text.as_bytes(), "fuzz.csv") {
            Err(e) => Err((true, e.to_string())),
            Ok(data) => {
                stiction_fit::analyse_structure(&data, &scenario, &json, 20, 1).map_err(|e| (false, e.to_string()))
            }
        });
        match outcome {
            Err(_) => panic!("structure case {case} (seed {:#x}, {name}) panicked", 0x57C + case),
            Ok(Err((reading, message))) => {
                assert!(message.len() <= 2000, "case {case}: error of {} bytes", message.len());
                assert!(!message.contains(&"9".repeat(200)), "case {case}: the error echoes a long cell");
                if reading {
                    assert!(message.contains("fuzz.csv"), "case {case}: the error names no file: {message}");
                    read_errors += 1
                } else {
                    fit_errors += 1
                }
            }
            Ok(Ok(report)) => {
                if let Some(at) = common::non_finite_in_debug(&format!("{report:?}")) {
                    panic!("structure case {case}: a non-finite number in the report: ...{at}");
                }
                if report.mu_apparent.value.is_none() {
                    assert!(report.mu_apparent.value_note.is_some(), "case {case}: a null without a reason");
                }
                fitted += 1;
            }
        }
    }
    eprintln!(
        "{cases} structure cases: {fitted} fitted, {read_errors} refused by the reader, {fit_errors} refused by the fit"
    );
    assert_eq!(fitted + read_errors + fit_errors, cases);
    assert!(fitted > 0 && read_errors > 0, "the mutations must reach both the reader's errors and the fit");
}
