//! The input side of the hardening of the map, BEM and actuator commands: derived sizes bounded
//! before allocation (cut-offs longer than the map), long lines and cells refused, errors that
//! quote at most a short excerpt of a file, results that are finite or an explicit null with a
//! reason, and the small flag checks (`bem --set` without `--scenario`, `actuator --out` checked
//! before the work).

use std::path::Path;
use std::process::Output;

use crate::util::{stiction, stiction_json, temp_dir};

const MAP: &str = "data/topography-example/wall.gsf";

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Status 2 and every fragment in the error.
fn assert_refused(o: &Output, fragments: &[&str], what: &str) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{what}: {e}");
    for f in fragments {
        assert!(e.contains(f), "{what}: `{f}` missing from: {e}");
    }
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `--cutoff` / `--long-cutoff` of 1 m, 1e10 m and 1e300 m on a 25.6 um x 8 um map ran past 60 s at
/// 5.3 GB, aborted on an allocation and panicked with "capacity overflow": each is now refused with
/// the map's size, for `topography`, `bem --map` and a scenario's `height_map` through `run --set`.
#[test]
fn cutoffs_longer_than_the_map_are_refused_with_its_size() {
    for cut in ["1 m", "1e10 m", "1e300 m"] {
        for flag in ["--cutoff", "--long-cutoff"] {
            let field = if flag == "--cutoff" { "short_cutoff" } else { "long_cutoff" };
            let o = stiction(&["topography", MAP, flag, cut]);
            assert_refused(&o, &[field, "25.6000 um", "no longer than the map"], &format!("topography {flag} {cut}"));
        }
    }
    let o = stiction(&["bem", "--map", MAP, "--cutoff", "1e300 m", "--pressure", "20 MPa"]);
    assert_refused(&o, &["short_cutoff", "25.6000 um"], "bem --map --cutoff");
    for field in ["short_cutoff", "long_cutoff"] {
        let set = format!("surface.height_map.{field}=1 m");
        let o = stiction(&["run", "scenarios/tas2000-height-map.json", "--set", &set]);
        assert_refused(&o, &[field, "25.6000 um"], &set);
        // `stiction scenario` checks the map as `run` reads it, so it refuses the same scenario.
        let o = stiction(&["scenario", "scenarios/tas2000-height-map.json", "--set", &set]);
        assert_refused(&o, &[field, "25.6000 um"], &format!("scenario --set {set}"));
    }
    // A cut-off just inside the map is still filtered.
    let v = stiction_json(&["topography", MAP, "--long-cutoff", "20 um", "--json"]);
    // "20 um" is 20 x 1e-6 m in f64 (1.9999999999999998e-5); the binary prints it in full, but
    // serde_json's default decimal parser (without `float_roundtrip`) may land one ulp away, so
    // the comparison allows 1e-15 relative.
    let twenty_um = stiction_units::parse_quantity("20 um", stiction_units::Dimension::Length).unwrap();
    let read = v["preparation"]["long_cutoff_m"].as_f64().expect("long_cutoff_m");
    assert!((read - twenty_um).abs() <= 1e-15 * twenty_um, "long_cutoff_m {read} != {twenty_um}");
}

/// A file of another kind (`/etc/passwd`, a secret note) given as a map, a transients or a
/// validation CSV, or a scenario's `height_map.file`: refused with a short excerpt at most, never
/// the whole line.
#[test]
fn foreign_files_are_not_echoed() {
    let dir = temp_dir("inputs-echo");
    let secret_line = "my-secret-password-is-hunter2-and-this-line-must-not-come-back";
    let secret = dir.join("notes.txt");
    std::fs::write(&secret, format!("{secret_line}\nsecond line\n")).unwrap();
    let s = path(&secret);
    let set = format!("surface.height_map.file={s}");
    let cases: Vec<(String, Vec<&str>)> = vec![
        ("topography".into(), vec!["topography", s]),
        ("bem --map".into(), vec!["bem", "--map", s, "--pressure", "20 MPa"]),
        ("actuator --transients".into(), vec!["actuator", "scenarios/gca-rauf2022.json", "--transients", s]),
        ("actuator --validate".into(), vec!["actuator", "scenarios/gca-rauf2022.json", "--validate", s]),
        ("height_map.file".into(), vec!["run", "scenarios/tas2000-height-map.json", "--set", &set]),
    ];
    for (what, args) in &cases {
        let o = stiction(args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{what}: {e}");
        assert!(e.contains("notes.txt"), "{what}: the file is not named: {e}");
        assert!(!e.contains(secret_line) && !e.contains("hunter2"), "{what} echoes the file: {e}");
        assert!(!e.contains("second line"), "{what} echoes the file: {e}");
    }
    #[cfg(target_os = "linux")]
    if let Ok(passwd) = std::fs::read_to_string("/etc/passwd")
        && let Some(first) = passwd.lines().next().filter(|l| l.len() > 24)
    {
        let o = stiction(&["topography", "/etc/passwd"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(!e.contains(first), "topography echoes /etc/passwd: {e}");
    }
}

/// A 1 MB header value comes back as a short message, and a grid that is one long line of commas
/// is refused by its length before its cells are split.
#[test]
fn long_lines_and_cells_give_short_errors() {
    let dir = temp_dir("inputs-long");
    let big = "9".repeat(1_000_000);
    let grid = dir.join("header.csv");
    std::fs::write(&grid, format!("# Width: {big} um\n1,2\n3,4\n")).unwrap();
    let o = stiction(&["topography", path(&grid), "--height-unit", "nm"]);
    assert_refused(&o, &["header.csv", "line 1", "Width", "1000003 bytes"], "1 MB header value");
    assert!(stderr(&o).len() < 400, "message of {} bytes", stderr(&o).len());

    let tr = dir.join("transients.csv");
    std::fs::write(&tr, format!("finger_length_um,event,voltage_v,time_us,{big}\n50,pull-in,40,50,1\n")).unwrap();
    let o = stiction(&["actuator", "scenarios/gca-rauf2022.json", "--transients", path(&tr)]);
    assert_refused(&o, &["transients.csv", "line 1", "column 5"], "1 MB transients header");
    assert!(stderr(&o).len() < 400, "message of {} bytes", stderr(&o).len());

    // 20 MB of commas on one line (the 300 MB allocated 4 GiB).
    let commas = dir.join("commas.csv");
    std::fs::write(&commas, ",".repeat(20 << 20)).unwrap();
    let o = stiction(&["topography", path(&commas), "--pixel-size", "10 nm", "--height-unit", "nm"]);
    assert_refused(&o, &["commas.csv", "line 1", "20971520 bytes", "1048576"], "one long line");
    let _ = std::fs::remove_file(&commas);
}

/// A map with every other row missing printed `autocorrelation length NaN um`: now `n/a (reason)`
/// in text and null with a note in JSON.
#[test]
fn autocorrelation_of_a_map_with_missing_rows_is_null_with_a_reason() {
    let dir = temp_dir("inputs-rows");
    let mut text = String::from("# Width: 3.2 um\n# Height: 3.2 um\n# Value units: nm\n");
    for iy in 0..32 {
        let row: Vec<String> = (0..32)
            .map(|ix| {
                if iy % 2 == 1 {
                    "NaN".to_string()
                } else {
                    format!("{:.4}", 5.0 * (0.7 * ix as f64).sin() * (0.4 * iy as f64).cos() + (ix * iy % 7) as f64)
                }
            })
            .collect();
        text.push_str(&row.join(","));
        text.push('\n');
    }
    let map = dir.join("rows.csv");
    std::fs::write(&map, text).unwrap();
    let o = stiction(&["topography", path(&map)]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");
    let line = out.lines().find(|l| l.contains("autocorrelation length")).unwrap();
    assert!(line.contains("n/a (") && line.contains("no pixel pairs"), "{line}");
    let v = stiction_json(&["topography", path(&map), "--json"]);
    assert!(v["autocorrelation_length_m"].is_null(), "{v}");
    assert!(v["autocorrelation_length_note"].as_str().is_some_and(|n| n.contains("missing")), "{v}");
    assert!(v["statistics"]["autocorrelation_length_y_m"].is_null());
}

/// `actuator --transients`: a point that never pulls in gave `NaN %` and `time_us` = 1e300 was
/// accepted.
#[test]
fn transients_are_finite_or_null_and_bounded() {
    let dir = temp_dir("inputs-transients");
    let never = dir.join("never.csv");
    // 1 V is far below the pull-in voltage (about 40 V): the spine never reaches the stop.
    std::fs::write(&never, "finger_length_um,event,voltage_v,time_us\n50,pull-in,1,50\n50,release,40,30\n").unwrap();
    let o = stiction(&["actuator", "scenarios/gca-rauf2022.json", "--transients", path(&never)]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");
    assert!(out.contains("n/a (no point predicted)"), "{out}");
    let v = stiction_json(&["actuator", "scenarios/gca-rauf2022.json", "--transients", path(&never), "--json"]);
    let pull_in = v["errors"].as_array().unwrap().iter().find(|e| e["event"] == "pull-in").unwrap();
    assert!(pull_in["mean_abs_rel_error"].is_null() && pull_in["rmse_s"].is_null(), "{pull_in}");
    assert!(v["release_time_mean_abs_rel_error"].as_f64().is_some_and(f64::is_finite), "{v}");

    for (cell, col) in [
        ("50,pull-in,40,1e300", "time_us"),
        ("1e300,pull-in,40,50", "finger_length_um"),
        ("50,pull-in,1e300,50", "voltage_v"),
    ] {
        let f = dir.join("huge.csv");
        std::fs::write(&f, format!("finger_length_um,event,voltage_v,time_us\n{cell}\n")).unwrap();
        let o = stiction(&["actuator", "scenarios/gca-rauf2022.json", "--transients", path(&f)]);
        assert_refused(&o, &["huge.csv", "line 2", col, "1e300", "must be finite and in ["], cell);
    }
    let f = dir.join("validate.csv");
    std::fs::write(&f, "finger_length_drawn_um,pull_in_v_1,release_v\n50,1e300,20\n").unwrap();
    let o = stiction(&["actuator", "scenarios/gca-rauf2022.json", "--validate", path(&f)]);
    assert_refused(&o, &["validate.csv", "line 2", "pull_in_v_1", ", 1e4]"], "validate 1e300 V");
}

/// `bem --set` without `--scenario` is an error, not ignored; `actuator --out <symlink>` is refused
/// before the scenario is even read.
#[test]
fn flags_that_were_ignored_or_late() {
    let o = stiction(&["bem", "--set", "surface.seed=3", "--pressure", "20 MPa", "--grid", "8"]);
    assert_refused(&o, &["--scenario"], "bem --set without --scenario");

    let dir = temp_dir("inputs-symlink");
    let target = dir.join("real");
    std::fs::create_dir_all(&target).unwrap();
    let link = dir.join("link");
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&target, &link).unwrap();
        // A scenario that does not exist: the --out refusal must come first.
        let o = stiction(&["actuator", "no-such-scenario.json", "--out", path(&link)]);
        assert_refused(&o, &["symbolic link"], "actuator --out symlink");
        assert!(!stderr(&o).contains("no-such-scenario"), "{}", stderr(&o));
    }
}
