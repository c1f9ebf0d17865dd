//! Text and JSON outputs (issue 14): user-facing names, units in keys, readable tables, paths.

use crate::util::{assert_foreign_file_needs_force, stiction, stiction_json};

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

/// The lines of the table that follows the line containing `title`, up to the next blank line.
fn table_after<'a>(text: &'a str, title: &str) -> Vec<&'a str> {
    let mut lines = text.lines().skip_while(|l| !l.contains(title));
    assert!(lines.next().is_some(), "no `{title}` in\n{text}");
    lines.take_while(|l| !l.trim().is_empty()).filter(|l| !l.trim_start().starts_with("mean |")).collect()
}

/// A table whose last column is right-aligned: every line (header too) ends in the same column.
fn assert_aligned(lines: &[&str], what: &str) {
    assert!(lines.len() >= 3, "{what}: too few lines: {lines:#?}");
    let width = lines[0].chars().count();
    for l in lines {
        assert_eq!(l.chars().count(), width, "{what}: misaligned line\n{}", lines.join("\n"));
    }
}

/// `contact --sweep`: events as sentences, no raw JSON; --help says what --json returns, and it
/// returns that: an object with `points` and `events`.
#[test]
fn contact_sweep_prints_events_as_sentences_and_json_as_documented() {
    let text = stdout(&["contact", "scenarios/tas2000.json", "--sweep", "1uN:-2uN:4"]);
    assert!(!text.contains("event:") && !text.contains('{'), "{text}");
    assert!(text.contains("jump_in at L = 1.0000 uN (point 0): contacts 0 -> 3"), "{text}");
    assert!(text.contains("pull_off: no equilibrium at L = -1.0000 uN"), "{text}");
    let table = table_after(&text, "Load sweep on");
    assert_aligned(&table, "contact sweep");
    let help = stdout(&["contact", "--help"]);
    assert!(help.contains(r#"{"points": [one such equilibrium per load"#) && help.contains("\"events\""), "{help}");
    let j = stiction_json(&["contact", "scenarios/tas2000.json", "--sweep", "1uN:-2uN:4", "--json"]);
    assert_eq!(j["points"].as_array().map(Vec::len), Some(2), "{j}");
    let events = j["events"].as_array().expect("events");
    assert_eq!(events[0]["event"], "jump_in");
    assert_eq!(events.last().unwrap()["event"], "pull_off");
}

/// `actuator --sweep` shows its sweep in the text output; the validation and switch tables are aligned.
#[test]
fn actuator_sweep_and_switch_tables_are_printed_aligned() {
    let text = stdout(&["actuator", "scenarios/gca-rauf2022.json", "--sweep", "--sweep-steps", "40"]);
    assert!(text.contains("Voltage sweep, loading (increasing V): 41 steps"), "{text}");
    // Pull-in 18.11 V (the summary above) lies inside the printed jump interval.
    let line = text.lines().find(|l| l.contains("pulls in to the stop between")).expect("pull-in line");
    let v: Vec<f64> = line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
    assert!(v.len() == 2 && v[0] < 18.11 && 18.11 < v[1], "{line}");
    assert!(text.contains("releases from the stop between"), "{text}");
    // The last column (at stop: yes/no) is text, left-aligned: compare the lines without it.
    let sweep: Vec<&str> = table_after(&text, "Voltage sweep, unloading")[1..]
        .iter()
        .map(|l| l.rsplit_once("  ").map_or(*l, |(head, _)| head))
        .collect();
    assert_aligned(&sweep, "sweep");
    let text = stdout(&[
        "actuator",
        "scenarios/gca-rauf2022.json",
        "--validate",
        "data/gca-pullin-release/measured.csv",
        "--switches",
        // The quasi-static protocol: the same tables in 3 s instead of 20 s.
        "--set",
        r#"actuators.gca.pull_in_protocol="quasi_static""#,
    ]);
    assert_aligned(&table_after(&text, "Validation against"), "validation");
    assert_aligned(&table_after(&text, "Physics switches"), "switches");
}

/// The meter's table: one aligned column per quantity, units in the titles.
#[test]
fn run_table_is_aligned() {
    let text = stdout(&["run", "scenarios/tas2000.json"]);
    let mut lines = text.lines().skip_while(|l| !l.contains("V_clamp (V)"));
    let table: Vec<&str> = lines.by_ref().take_while(|l| !l.trim().is_empty()).collect();
    assert!(table.len() >= 10, "{text}");
    // Without notes every line ends at the last numeric column.
    assert_aligned(&table[1..], "run");
}

fn stiction_in(cwd: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run stiction")
}

/// A path inside a scenario file is relative to the file's folder; a path typed with --set is
/// relative to the current directory (docs/scenario.md).
#[test]
fn paths_in_files_follow_the_file_and_paths_on_the_command_line_the_current_directory() {
    let dir = crate::util::temp_dir("paths");
    let (scen, work) = (dir.join("scen"), dir.join("work"));
    std::fs::create_dir_all(&scen).unwrap();
    std::fs::create_dir_all(&work).unwrap();
    let text = std::fs::read_to_string(crate::util::root().join("scenarios/tas2000-gw.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["measured"] = serde_json::json!({"voltages_csv": "m.csv"});
    v["meter"].as_object_mut().unwrap().remove("slip_dynamics");
    std::fs::write(scen.join("s.json"), serde_json::to_string_pretty(&v).unwrap()).unwrap();
    std::fs::write(scen.join("m.csv"), "v_clamp_v,v_pull_v\n24,27.5\n26,32.0\n28,36.2\n").unwrap();
    std::fs::write(work.join("m.csv"), "v_clamp_v,v_pull_v\n24,27.5\n25,30\n26,32.0\n28,36.2\n").unwrap();
    let points = |out: std::process::Output| {
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        j["measured"]["points"].as_array().unwrap().len()
    };
    // From the file: scen/m.csv (3 rows), wherever the command runs.
    assert_eq!(points(stiction_in(&dir, &["run", "scen/s.json", "--json"])), 3);
    assert_eq!(points(stiction_in(&work, &["run", "../scen/s.json", "--json"])), 3);
    // From the command line: the m.csv of the current directory, work/m.csv (4 rows).
    let set = "measured.voltages_csv=m.csv";
    assert_eq!(points(stiction_in(&work, &["run", "../scen/s.json", "--set", set, "--json"])), 4);
    // ... and not the scenario's folder: dir/m.csv does not exist, and the error names it.
    let out = stiction_in(&dir, &["run", "scen/s.json", "--set", set]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    let missing = dir.join("m.csv");
    assert!(err.contains(missing.to_str().unwrap()), "{err}");
}

/// `run` (a scenario's `measured` section) and `fit` read measured voltages with one reader: the
/// same files are accepted, and a bad file gives the same message from both.
#[test]
fn run_and_fit_read_measured_voltages_alike() {
    let dir = crate::util::temp_dir("readers");
    let text = std::fs::read_to_string(crate::util::root().join("scenarios/tas2000-gw.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["measured"] = serde_json::json!({"voltages_csv": "m.csv"});
    v["meter"].as_object_mut().unwrap().remove("slip_dynamics");
    let s = dir.join("s.json");
    std::fs::write(&s, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    let m = dir.join("m.csv");
    let (s, m_arg) = (s.to_str().unwrap(), m.to_str().unwrap());
    for (csv, needle) in [
        ("v_clamp_v,v_pull_v,v_pull_v\n30,40,41\n", "appears twice"),
        ("v_clamp_v,v_pull_v\n30,1e200\n", "at most"),
        ("v_clamp_v,v_pull_v\n25,30\n26,abc\n", "line 3, column `v_pull_v`: value \"abc\""),
        ("v_clamp,v_pull\n25,30\n", "gives no unit"),
        ("v_clamp_v,v_pull_v\n", "no data rows"),
    ] {
        std::fs::write(&m, csv).unwrap();
        let run = stiction(&["run", s]);
        let fit = stiction(&["fit", m_arg, "--scenario", s, "--models", "discrete-n3"]);
        let (e_run, e_fit) = (String::from_utf8_lossy(&run.stderr), String::from_utf8_lossy(&fit.stderr));
        assert_eq!(run.status.code(), Some(2), "{csv:?}: {e_run}");
        assert_eq!(fit.status.code(), Some(2), "{csv:?}: {e_fit}");
        assert!(e_run.contains(needle) && e_run.contains(m_arg), "{csv:?}: {e_run}");
        assert_eq!(e_run, e_fit, "{csv:?}");
    }
    // A readable file: rows below first contact (L <= 0 at V_clamp = 10 V) and without slip are
    // left out of the measured eq. 10 fit with the same reasons in both.
    std::fs::write(&m, "# comment\nv_clamp_v,v_pull_v,device\n10,5,a\n25,0,a\n24,27.5,a\n26,32,a\n28,36.2,a\n")
        .unwrap();
    let run = stiction_json(&["run", s, "--json"]);
    let fit = stiction_json(&["fit", m_arg, "--scenario", s, "--models", "discrete-n3", "--draws", "100", "--json"]);
    assert_eq!(run["measured"]["rows_rejected"], fit["rows_rejected"]);
    let lines: Vec<u64> =
        fit["rows_rejected"].as_array().unwrap().iter().map(|r| r["line"].as_u64().unwrap()).collect();
    assert_eq!(lines, [3, 4]);
    assert_eq!(run["measured"]["points"].as_array().unwrap().len(), 5);
}

/// `fit --out` and `topography --out` write a whole folder with a manifest, as `run` does: a
/// second run replaces it, a folder with someone else's files is refused without --force.
#[test]
fn fit_and_topography_out_folders_have_a_manifest_and_refuse_foreign_files() {
    let dir = crate::util::temp_dir("outsets");
    let fit_out = dir.join("fit");
    let topo_out = dir.join("topo");
    let fit = |extra: &[&str]| {
        let mut a = vec![
            "fit",
            "--scenario",
            "scenarios/tas2000-fit-synthetic.json",
            "--models",
            "discrete-n3",
            "--draws",
            "100",
            "--out",
            fit_out.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        stiction(&a)
    };
    let topo = |extra: &[&str]| {
        let mut a = vec!["topography", "data/topography-example/wall.gsf", "--out", topo_out.to_str().unwrap()];
        a.extend_from_slice(extra);
        stiction(&a)
    };
    for (what, run, out, expect) in [
        ("fit", &fit as &dyn Fn(&[&str]) -> std::process::Output, &fit_out, "report.json"),
        ("topography", &topo, &topo_out, "statistics.json"),
    ] {
        let r = run(&[]);
        assert!(r.status.success(), "{what}: {}", String::from_utf8_lossy(&r.stderr));
        let manifest: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("manifest.json")).unwrap()).unwrap();
        assert_eq!(manifest["command"], what);
        let files: Vec<&str> = manifest["files"].as_array().unwrap().iter().map(|f| f.as_str().unwrap()).collect();
        assert!(files.contains(&expect), "{what}: {files:?}");
        let mut present: Vec<String> =
            std::fs::read_dir(out).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        present.sort();
        let mut listed: Vec<String> = files.iter().map(|f| f.to_string()).chain(["manifest.json".into()]).collect();
        listed.sort();
        assert_eq!(present, listed, "{what}: the folder holds exactly the listed files");
        // A second run replaces the folder; a foreign file makes it refuse, unless --force.
        assert!(run(&[]).status.success());
        assert_foreign_file_needs_force(out, run, what);
    }
}
