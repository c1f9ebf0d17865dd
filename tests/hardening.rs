//! Issue 9: nothing hangs, panics, or is lost. Closed and full standard output, output folders
//! (manifest, stale files, symlinks, foreign files), measured CSVs, flags that were silently
//! ignored, and a kill test: a `run` killed at random moments leaves the previous complete
//! outputs or none, never a partial file.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::util::{assert_foreign_file_needs_force, root, stiction, temp_dir};

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_stiction"));
    c.current_dir(root());
    c
}

#[test]
fn closed_stdout_ends_quietly_with_status_0() {
    // `stiction scenario F | head -3`
    let mut child = bin()
        .args(["scenario", "scenarios/tas2000.json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = BufReader::new(child.stdout.take().unwrap());
    let mut line = String::new();
    for _ in 0..3 {
        out.read_line(&mut line).unwrap();
    }
    drop(out);
    let res = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&res.stderr);
    assert_eq!(res.status.code(), Some(0), "stderr: {stderr}");
    assert!(stderr.is_empty(), "a closed pipe should end quietly: {stderr}");
}

#[cfg(target_os = "linux")]
#[test]
fn full_disk_on_stdout_is_a_clean_error() {
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap();
    let res = bin().args(["scenario", "scenarios/tas2000.json"]).stdout(full).output().unwrap();
    let stderr = String::from_utf8_lossy(&res.stderr);
    assert_eq!(res.status.code(), Some(2), "stderr: {stderr}");
    assert!(stderr.contains("cannot write to standard output") && !stderr.contains("panicked"), "{stderr}");
}

#[test]
fn flags_that_were_ignored_or_defeated_are_errors() {
    let cases: &[(&[&str], &[&str])] = &[
        (&["gw", "--theta", "1e400", "--load-star", "0"], &["1e400", "infinity"]),
        (
            &[
                "discrete",
                "--contacts",
                "3",
                "--radius",
                "0.5 N^64 N^64 N^64 N^64 um",
                "--work-of-adhesion",
                "0.1",
                "--compliance",
                "9.1e-12",
                "--shear-strength",
                "1.4 GPa",
                "--load",
                "3 uN",
            ],
            &["--radius", "beyond"],
        ),
        (&["plot", "fig2", "--array", "clamp", "--out", "x.svg"], &["--array", "plot actuator"]),
        (&["plot", "fig2", "--out", "p.txt"], &["p.txt", "unknown image extension", ".svg or .png"]),
        (&["plot", "fig2"], &["plot fig2", "--out FILE.svg"]),
        (&["plot", "fig2", "--rh", "0.3", "--out", "x.svg"], &["--rh", "plot humidity"]),
        (&["plot", "fig3", "--json", "--out", "x.svg"], &["--json", "plot humidity"]),
        (&["plot", "humidity", "--rh", "0.3"], &["plot humidity", "--scenario"]),
        (&["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--rh", "1.2"], &["--rh", "1.2", "[0, 1)"]),
        (&["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--rh", "0.5,0.2"], &["--rh", "must increase"]),
        (&["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--rh", "0:0.9:0"], &["--rh", "STEPS"]),
        (&["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--rh", "NaN"], &["--rh", "NaN"]),
        (
            &["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--rh", "0.3", "--array", "clamp"],
            &["--array"],
        ),
        (
            &["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--set", "environment.temperature=900 K"],
            &["environment.temperature", "647.096 K"],
        ),
        (
            &["actuator", "scenarios/tas2000.json", "--array", "clamp", "--sweep", "--sweep-steps", "0"],
            &["--sweep-steps"],
        ),
        (&["actuator", "scenarios/tas2000.json", "--array", "clamp", "--switches"], &["--validate"]),
        (
            &["contact", "scenarios/tas2000.json", "--sweep", "0uN:10uN:18446744073709551615"],
            &["--sweep STEPS", "18446744073709551615", "--max-sweep-steps"],
        ),
        (
            &["run", "scenarios/tas2000.json", "--set", "meter.pull_voltage_step=1e-15 V"],
            &["pull_voltage_step", "2^53"],
        ),
        (
            &["run", "scenarios/tas2000.json", "--set", "actuators.pull.conversion_factor=1e-308"],
            &[], // runs (no slip anywhere) and must return: checked below
        ),
    ];
    for (args, needles) in cases {
        let out = stiction(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
        if needles.is_empty() {
            let stdout = String::from_utf8_lossy(&out.stdout);
            assert!(out.status.success(), "{args:?}: {stderr}");
            assert!(!stdout.contains("NaN") && !stdout.contains("inf"), "{args:?}: {stdout}");
            continue;
        }
        assert_eq!(out.status.code(), Some(2), "{args:?} should fail with 2: {stderr}");
        for n in *needles {
            assert!(stderr.contains(n), "{args:?}: error lacks `{n}`:\n{stderr}");
        }
    }
}

#[test]
fn a_wrong_scenario_file_is_not_echoed() {
    let dir = temp_dir("echo");
    let secret = dir.join("secret.txt");
    std::fs::write(&secret, "root:x:0:0:very-secret-line-of-a-file\n").unwrap();
    let out = stiction(&["run", secret.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(!stderr.contains("very-secret"), "{stderr}");
    // A FIFO or device is refused, not read.
    let out = stiction(&["run", "/dev/zero"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr.contains("/dev/zero") && stderr.contains("expected a regular file"), "{stderr}");
}

fn scenario_with_measured(dir: &Path, csv: &str) -> String {
    let text = std::fs::read_to_string(root().join("scenarios/tas2000-gw.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["measured"] = serde_json::json!({"voltages_csv": "m.csv"});
    v["meter"].as_object_mut().unwrap().remove("slip_dynamics");
    std::fs::write(dir.join("m.csv"), csv).unwrap();
    let p = dir.join("s.json");
    std::fs::write(&p, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn measured_csvs_one_row_duplicate_column_huge_voltage() {
    let dir = temp_dir("measured");
    let s = scenario_with_measured(&dir, "v_clamp_v,v_pull_v\n30,40\n");
    let out = stiction(&["run", &s]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("no eq. 10 fit of the measured data") && stdout.contains("at least 3"), "{stdout}");
    for (csv, needle) in [
        ("v_clamp_v,v_pull_v,v_pull_v\n30,40,41\n", "appears twice"),
        ("v_clamp_v,v_pull_v\n30,1e200\n", "line 2"),
        ("v_clamp_v,v_pull_v\n", "no data rows"),
    ] {
        let s = scenario_with_measured(&dir, csv);
        let out = stiction(&["run", &s]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{csv:?}: {stderr}");
        assert!(stderr.contains(needle) && stderr.contains("m.csv"), "{csv:?}: {stderr}");
    }
}

/// Checks that `dir` holds exactly one complete run: a manifest and every file it lists, each
/// complete (JSON parses, CSV has its rows, SVG closes, PNG has its end chunk).
fn assert_complete_run(dir: &Path) {
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("manifest.json")).expect("manifest")).unwrap();
    let files: Vec<String> =
        manifest["files"].as_array().unwrap().iter().map(|f| f.as_str().unwrap().to_string()).collect();
    let mut present: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    present.sort();
    let mut expected = files.clone();
    expected.push("manifest.json".into());
    expected.sort();
    assert_eq!(present, expected, "{}", dir.display());
    for f in &files {
        let bytes = std::fs::read(dir.join(f)).unwrap();
        if f.ends_with(".json") {
            serde_json::from_slice::<serde_json::Value>(&bytes).unwrap_or_else(|e| panic!("{f}: {e}"));
        } else if f.ends_with(".svg") {
            assert!(String::from_utf8_lossy(&bytes).trim_end().ends_with("</svg>"), "{f} is cut");
        } else if f.ends_with(".png") {
            assert!(bytes.len() > 12 && &bytes[bytes.len() - 8..bytes.len() - 4] == b"IEND", "{f} is cut");
        } else if f.ends_with(".csv") {
            let rows = String::from_utf8_lossy(&bytes).lines().count();
            assert!(rows >= 2 && bytes.ends_with(b"\n"), "{f} is cut");
        }
    }
}

#[test]
fn output_folder_holds_one_run_with_a_manifest() {
    let dir = temp_dir("outset");
    let out_dir = dir.join("out");
    let o = out_dir.to_str().unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["run", "scenarios/tas2000-gw.json", "--out", o];
        args.extend_from_slice(extra);
        stiction(&args)
    };
    assert!(run(&[]).status.success());
    assert_complete_run(&out_dir);
    // A stale output of an earlier run, listed in its manifest, is gone after the next run.
    let m = std::fs::read_to_string(out_dir.join("manifest.json")).unwrap();
    std::fs::write(out_dir.join("old.csv"), "a\n1\n").unwrap();
    std::fs::write(
        out_dir.join("manifest.json"),
        m.replace("\"results.json\",", "\"results.json\",\n    \"old.csv\","),
    )
    .unwrap();
    assert!(run(&[]).status.success());
    assert_complete_run(&out_dir);
    assert!(!out_dir.join("old.csv").exists());
    // A foreign file: refused without --force (naming it), kept with --force.
    assert_foreign_file_needs_force(&out_dir, &run, "run");
    // An output folder that is a symbolic link is refused; its target untouched.
    #[cfg(unix)]
    {
        let target = dir.join("target");
        std::fs::create_dir_all(&target).unwrap();
        let link = dir.join("link");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let r = stiction(&["run", "scenarios/tas2000-gw.json", "--out", link.to_str().unwrap()]);
        assert_eq!(r.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&r.stderr).contains("symbolic link"));
        assert_eq!(std::fs::read_dir(&target).unwrap().count(), 0);
    }
    // An unwritable --out names the path.
    let r = stiction(&["run", "scenarios/tas2000-gw.json", "--out", "/proc/stiction-no/out"]);
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2));
    assert!(stderr.contains("/proc/stiction-no"), "{stderr}");
}

/// A `run` killed at random moments (seeded, so the same moments every time) leaves the previous
/// complete outputs or none: never a partial file, never two runs' files side by side. Random
/// moments may all miss the short writing phase, so every other case watches the staging folder
/// and kills as soon as the first file appears in it; the test then requires that at least one kill
/// landed while files were being written (a staging folder left with some files and no manifest),
/// so it cannot pass without testing the write path.
#[test]
fn killed_runs_leave_complete_outputs_or_none() {
    let dir = temp_dir("kill");
    let out_dir = dir.join("out");
    let o = out_dir.to_str().unwrap().to_string();
    let args = ["run", "scenarios/tas2000-gw.json", "--out", o.as_str()];
    let t0 = Instant::now();
    assert!(stiction(&args).status.success());
    let full = t0.elapsed();
    assert_complete_run(&out_dir);
    // xorshift: fixed seed, kill moments spread over 0..1.2 of a full run (writing is at the end).
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let cases: usize = std::env::var("STICTION_KILL_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(12);
    // A staging folder of the parent holding some files (so a kill there is mid-write).
    let staging_files = |dir: &Path| -> Option<Vec<String>> {
        let staging = std::fs::read_dir(dir)
            .ok()?
            .filter_map(|e| e.ok())
            .find(|e| e.file_name().to_string_lossy().contains("staging-"))?;
        let names: Vec<String> = std::fs::read_dir(staging.path())
            .ok()?
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        (!names.is_empty()).then_some(names)
    };
    let mut mid_write = 0;
    for case in 0..cases {
        let frac = (next() % 1200) as f64 / 1000.0;
        let wait = full.mul_f64(frac);
        let mut child = bin().args(args).stdout(Stdio::null()).stderr(Stdio::null()).spawn().unwrap();
        if case % 2 == 1 {
            // Watch for the first file in the staging folder (up to 30 s), then kill.
            let t = Instant::now();
            while staging_files(&dir).is_none()
                && child.try_wait().unwrap().is_none()
                && t.elapsed() < Duration::from_secs(30)
            {
                std::thread::sleep(Duration::from_micros(200));
            }
        } else {
            std::thread::sleep(wait.min(Duration::from_secs(30)));
        }
        let _ = child.kill();
        let status = child.wait().unwrap();
        if let Some(names) = staging_files(&dir)
            && !status.success()
            && !names.iter().any(|n| n == "manifest.json")
        {
            mid_write += 1;
        }
        if out_dir.exists() {
            assert_complete_run(&out_dir);
        }
        // No partial file anywhere in the parent either (staging folders are hidden and are
        // removed by the next run).
        let r = stiction(&args);
        assert!(r.status.success(), "case {case}: {}", String::from_utf8_lossy(&r.stderr));
        assert_complete_run(&out_dir);
        let leftovers: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n != "out")
            .collect();
        assert!(leftovers.is_empty(), "case {case}: leftovers {leftovers:?}");
    }
    eprintln!("{mid_write} of {cases} kills landed while files were being written");
    assert!(cases < 2 || mid_write >= 1, "no kill out of {cases} landed while files were being written");
}

/// A full standard error (`2>/dev/full`) never turns an error into a panic (exit 101): the message
/// is dropped and the exit status still says what happened (issue 9).
#[cfg(target_os = "linux")]
#[test]
fn a_full_stderr_keeps_the_exit_status() {
    use std::process::{Command, Stdio};
    let full = || Stdio::from(std::fs::OpenOptions::new().write(true).open("/dev/full").expect("/dev/full"));
    let status = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_stiction"))
            .args(args)
            .current_dir(crate::util::root())
            .stdout(Stdio::null())
            .stderr(full())
            .status()
            .expect("run stiction")
            .code()
    };
    assert_eq!(status(&["scenario", "no-such-scenario.json"]), Some(2));
    assert_eq!(status(&["gw", "--theta", "15", "--load-star", "0"]), Some(0));
}
