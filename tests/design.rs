//! Design studies (`stiction study --vary`): every design point's folder is byte for byte the
//! single study of that scenario with the same `--set`s (common random numbers: same seed, same
//! draws), the design table has one row per design with the varied values in columns named by
//! their paths, sharded and resumed design studies give the same bytes, and bad grids are
//! refused with exit status 2.

use std::path::Path;

use crate::util::{num, stiction, stiction_json, temp_dir};

const PLATES: &str = "actuators.clamp.plate_count=30,60";
const SPRING: &str = "actuators.pull.spring.stiffness=1 N/m,3 N/m";

fn run(args: &[&str]) {
    let r = stiction(args);
    assert!(r.status.success(), "stiction {args:?}: {}", String::from_utf8_lossy(&r.stderr));
}

fn files(dir: &Path) -> Vec<String> {
    let mut f: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    f.sort();
    f
}

fn same_folder(a: &Path, b: &Path) {
    let (fa, fb) = (files(a), files(b));
    assert_eq!(fa, fb, "{} vs {}", a.display(), b.display());
    assert!(fa.contains(&"samples.log".to_string()) && fa.contains(&"study.json".to_string()), "{fa:?}");
    for f in fa {
        assert!(
            std::fs::read(a.join(&f)).unwrap() == std::fs::read(b.join(&f)).unwrap(),
            "{f} differs: {} vs {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn each_design_is_the_single_study_of_its_scenario_byte_for_byte() {
    let dir = temp_dir("design-bytes");
    let out = dir.join("designs");
    let o = out.to_str().unwrap();
    let base = ["study", "scenarios/tas2000.json", "--samples", "24", "--seed", "7", "--quiet"];
    let mut args = base.to_vec();
    args.extend(["--vary", PLATES, "--vary", SPRING, "--rank-by", "most-usable", "--out", o]);
    run(&args);
    // Grid order: the first --vary slowest.
    let points = [("30", "1 N/m"), ("30", "3 N/m"), ("60", "1 N/m"), ("60", "3 N/m")];
    for (d, (plates, spring)) in points.iter().enumerate() {
        let single = dir.join(format!("single-{d}"));
        let (p, s) =
            (format!("actuators.clamp.plate_count={plates}"), format!("actuators.pull.spring.stiffness={spring}"));
        let mut a = base.to_vec();
        a.extend(["--set", &p, "--set", &s, "--out", single.to_str().unwrap()]);
        run(&a);
        same_folder(&single, &out.join(format!("design-{d:03}")));
    }
    let table = std::fs::read_to_string(out.join("designs.csv")).unwrap();
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(lines.len(), 5, "{table}");
    assert!(
        lines[0].starts_with("design,actuators.clamp.plate_count,actuators.pull.spring.stiffness,samples,"),
        "{table}"
    );
    assert!(lines[4].starts_with("3,60,3 N/m,24,"), "{table}");
    for f in ["design_actuators_clamp_plate_count.svg", "design_actuators_pull_spring_stiffness.csv", "designs.json"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    // The design chart's points and error bars are the table's: the criterion (here the usable
    // fraction, --rank-by most-usable: the 5-95 % width has no standard error at 24 samples) at
    // each plate count with a 95 % bar of 1.96 standard errors, one series per spring stiffness.
    // Deliberate bug caught: the bars drawn as one standard error (seen failing).
    let chart = std::fs::read_to_string(out.join("design_actuators_clamp_plate_count.csv")).unwrap();
    let ch: Vec<&str> = chart.lines().next().unwrap().split(',').collect();
    let at = |h: &[&str], name: &str| h.iter().position(|c| *c == name).unwrap_or_else(|| panic!("no column {name}"));
    assert_eq!(ch[3], "usable_fraction", "{chart}");
    let th: Vec<&str> = lines[0].split(',').collect();
    let (mut drawn, mut with_bar) = (0, 0);
    for row in chart.lines().skip(1) {
        let c: Vec<&str> = row.split(',').collect();
        let (plates, spring) = (c[at(&ch, "actuators_clamp_plate_count")], c[0].rsplit("= ").next().unwrap());
        let t: Vec<&str> = lines[1..]
            .iter()
            .map(|l| l.split(',').collect::<Vec<&str>>())
            .find(|t| t[1] == plates && t[2] == spring)
            .unwrap_or_else(|| panic!("chart row {row} has no design in the table"));
        let f = |v: &[&str], i: usize| v[i].parse::<f64>().unwrap();
        let (y, se) = (f(&t, at(&th, "usable_fraction")), f(&t, at(&th, "usable_fraction_se")));
        let (drawn_y, bar) = (f(&c, at(&ch, "usable_fraction")), f(&c, at(&ch, "usable_fraction_err")));
        assert!((drawn_y - y).abs() < 1e-12, "chart {drawn_y} vs table {y}");
        assert!((bar - 1.96 * se).abs() <= 1e-9 * se, "error bar {bar} vs 1.96 x {se}");
        drawn += 1;
        with_bar += usize::from(se > 0.0);
    }
    // The 60-plate designs are all usable at 24 samples (no binomial error, no bar); the
    // 30-plate ones are not, so their bars are checked.
    assert!(with_bar >= 2, "{chart}");
    assert_eq!(drawn, 4, "{chart}");
    // The same in --json.
    let mut j = base.to_vec();
    j.extend(["--vary", PLATES, "--vary", SPRING, "--json", "--rank-by", "most-usable"]);
    let v = stiction_json(&j);
    let designs = v["designs"].as_array().unwrap();
    assert_eq!(designs.len(), 4);
    assert_eq!(designs[2]["values"]["actuators.clamp.plate_count"], "60");
    assert_eq!(v["rank_by"], "most-usable");
    // The interface's own coefficient is each sample's: s A_r / (L + F_adh) of that sample's
    // device (its drawn parameters and its own sidewall, surface.seed = seed + i), averaged over
    // its clamp voltages in contact with L > 0. Replayed here with `stiction run --json` of
    // design 0's scenario with sample 1's draws from samples.csv (the explicit solver's real
    // area, true load and adhesive load at each clamp voltage). Deliberate bug caught: the
    // coefficient of the nominal device (the file's sidewall and values) for every sample.
    let csv = std::fs::read_to_string(out.join("design-000/samples.csv")).unwrap();
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    let row = &rows[1];
    let cell = |name: &str| row[col(name)].to_string();
    let spring = format!("meter.spring_force={{\"value\": {}, \"sd\": \"10 uN\"}}", cell("meter.spring_force_n"));
    let sets = [
        "actuators.clamp.plate_count=30".to_string(),
        "actuators.pull.spring.stiffness=1 N/m".into(),
        format!("actuators.clamp.conversion_factor={}", cell("actuators.clamp.conversion_factor_n_per_v2")),
        format!("actuators.pull.conversion_factor={}", cell("actuators.pull.conversion_factor_n_per_v2")),
        spring,
        format!("surface.summit_radius={}", cell("surface.summit_radius_m")),
        "surface.seed=8".into(),
    ];
    let mut r_args = vec!["run", "scenarios/tas2000.json", "--json"];
    for s in &sets {
        r_args.extend(["--set", s]);
    }
    let r = stiction_json(&r_args);
    let mus: Vec<f64> = r["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["in_contact"] == true && num(p, "true_load_n") > 0.0)
        .map(|p| 1.4e9 * num(p, "real_area_m2") / (num(p, "true_load_n") + num(p, "adhesive_load_n")))
        .collect();
    let want = mus.iter().sum::<f64>() / mus.len() as f64;
    let got: f64 = cell("interface_mu").parse().unwrap();
    assert!((got - want).abs() < 1e-12 * want, "sample 1's interface mu {got} vs {want} from its replayed run");
    // The design's bias is the median of each experiment's mu_e,a minus its own coefficient.
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        let n = v.len();
        if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
    };
    let bias: Vec<f64> = rows
        .iter()
        .filter(|r| !r[col("mu_apparent")].is_empty() && !r[col("interface_mu")].is_empty())
        .map(|r| r[col("mu_apparent")].parse::<f64>().unwrap() - r[col("interface_mu")].parse::<f64>().unwrap())
        .collect();
    let want_bias = median(bias);
    let got_bias = num(&designs[0], "mu_bias");
    assert!((got_bias - want_bias).abs() < 1e-12, "design bias {got_bias} vs {want_bias} from samples.csv");
    // Both lab intervals per design, the calibrated one wider than the regression's alone.
    let li = &designs[0]["lab_intervals"];
    let (w, wc) = (num(&li["mu_ci95_width"], "median"), num(&li["mu_ci95_width_with_calibration"], "median"));
    assert!(w > 0.0 && wc > w, "lab interval widths {w} (regression) and {wc} (with calibration)");
}

#[test]
fn sharded_and_resumed_design_studies_give_the_same_bytes() {
    let dir = temp_dir("design-shards");
    let base = ["study", "scenarios/tas2000.json", "--samples", "12", "--seed", "3", "--quiet", "--vary", SPRING];
    let one = dir.join("one");
    let mut a = base.to_vec();
    a.extend(["--out", one.to_str().unwrap()]);
    run(&a);
    let shards: Vec<_> = (0..2).map(|k| dir.join(format!("shard{k}"))).collect();
    for (k, s) in shards.iter().enumerate() {
        let shard = format!("{k}/2");
        let mut a = base.to_vec();
        a.extend(["--shard", &shard, "--out", s.to_str().unwrap()]);
        run(&a);
    }
    // Merge design by design (stiction merge of each design's shard folders), then finish the
    // design study on the merged folders with --resume: nothing left to run, the same outputs.
    let merged = dir.join("merged");
    for d in 0..2 {
        let name = format!("design-{d:03}");
        let (s0, s1, m) = (shards[0].join(&name), shards[1].join(&name), merged.join(&name));
        run(&["merge", s0.to_str().unwrap(), s1.to_str().unwrap(), "--out", m.to_str().unwrap()]);
    }
    let mut a = base.to_vec();
    a.extend(["--out", merged.to_str().unwrap(), "--resume"]);
    run(&a);
    for d in 0..2 {
        let name = format!("design-{d:03}");
        for f in ["samples.log", "samples.csv", "study.json"] {
            assert!(
                std::fs::read(one.join(&name).join(f)).unwrap() == std::fs::read(merged.join(&name).join(f)).unwrap(),
                "{name}/{f}"
            );
        }
    }
    assert!(std::fs::read(one.join("designs.csv")).unwrap() == std::fs::read(merged.join("designs.csv")).unwrap());
    // A killed design study: cut design 1's log to its header and 3 rows, resume.
    let log = one.join("design-001/samples.log");
    let text = std::fs::read_to_string(&log).unwrap();
    let keep: Vec<&str> = text.lines().take(4).collect();
    std::fs::write(&log, keep.join("\n") + "\n").unwrap();
    let mut a = base.to_vec();
    a.extend(["--out", one.to_str().unwrap(), "--resume"]);
    run(&a);
    assert_eq!(std::fs::read_to_string(&log).unwrap(), text);
}

#[test]
fn bad_grids_are_refused_naming_the_field() {
    for (args, needle) in [
        (vec!["--vary", "actuators.clamp.plate_count"], "PATH=V1,V2"),
        (vec!["--vary", "actuators.clamp.plate_count=30,,60"], "value 2 is empty"),
        (vec!["--vary", PLATES, "--set", "actuators.clamp.plate_count=40"], "both set and varied"),
        (vec!["--vary", "meter.spring_force=7 uN,-1 mm"], "design 1 (meter.spring_force=-1 mm)"),
    ] {
        let mut a = vec!["study", "scenarios/tas2000.json", "--samples", "4", "--quiet"];
        a.extend(args.iter().copied());
        let r = stiction(&a);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{a:?}: {err}");
        assert!(err.contains(needle), "{a:?}: {err}");
    }
}

/// A range `--vary "PATH=LO..HI"` with `--design-points 3`: three designs whose values fall one in
/// each third of the range (a centred Latin hypercube, seeded by --seed), each design byte for byte
/// the single study with that value `--set`; a range without --design-points is refused.
/// Deliberate bug caught: every range value placed at the range's low end (seen failing: the
/// three designs share one third).
#[test]
fn a_range_is_filled_by_a_seeded_space_filling_design() {
    let out = temp_dir("design-range");
    let base = ["study", "scenarios/tas2000.json", "--samples", "12", "--seed", "3", "--threads", "1", "--quiet"];
    let mut a = base.to_vec();
    a.extend(["--vary", "meter.clamp_voltages.to=29 V..41 V", "--design-points", "3", "--out", out.to_str().unwrap()]);
    run(&a);
    let table = std::fs::read_to_string(out.join("designs.csv")).unwrap();
    let mut thirds = Vec::new();
    for (d, line) in table.lines().skip(1).enumerate() {
        let value = line.split(',').nth(1).unwrap().to_string();
        let volts: f64 = value.strip_suffix(" V").unwrap_or_else(|| panic!("{value}")).parse().unwrap();
        assert!((29.0..=41.0).contains(&volts), "{volts}");
        thirds.push(((volts - 29.0) / 4.0).floor() as usize);
        let single = out.join(format!("single-{d}"));
        let set = format!("meter.clamp_voltages.to={value}");
        let mut s = base.to_vec();
        s.extend(["--set", &set, "--out", single.to_str().unwrap()]);
        run(&s);
        same_folder(&single, &out.join(format!("design-{d:03}")));
    }
    thirds.sort_unstable();
    assert_eq!(thirds, vec![0, 1, 2], "{table}");
    let o = stiction(&[
        "study",
        "scenarios/tas2000.json",
        "--samples",
        "4",
        "--vary",
        "meter.clamp_voltages.to=29 V..41 V",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--design-points"));
}

/// Runs `stiction ARGS` in `dir` and asserts success.
fn run_in(dir: &Path, args: &[&str]) -> String {
    let r = std::process::Command::new(env!("CARGO_BIN_EXE_stiction"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run stiction");
    assert!(r.status.success(), "stiction {args:?} in {}: {}", dir.display(), String::from_utf8_lossy(&r.stderr));
    String::from_utf8_lossy(&r.stderr).into_owned() + &String::from_utf8_lossy(&r.stdout)
}

/// The scenario file's `design` section runs the same design study as the same `--vary` flags on
/// the file without it: the same designs.csv and, per design, the same study.json and samples.csv
/// (the file is named alike in two folders, since study.json records the path as given). The
/// section's fields are in another order than the flags (`vary` is keyed by path), which the grid
/// order (paths alphabetical, the first slowest) makes irrelevant. Then `--vary` on the file with
/// the section replaces it, says so, and gives the flags' study again.
/// Deliberate bug caught: the section's values read in reverse order (seen failing: designs.csv
/// rows in another order).
#[test]
fn the_design_section_is_the_same_study_as_its_vary_flags() {
    let dir = temp_dir("design-section");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(crate::util::root().join("scenarios/tas2000.json")).unwrap())
            .unwrap();
    let (plain, sectioned) = (dir.join("plain"), dir.join("sectioned"));
    std::fs::create_dir_all(&plain).unwrap();
    std::fs::create_dir_all(&sectioned).unwrap();
    std::fs::write(plain.join("meter.json"), serde_json::to_string_pretty(&json).unwrap()).unwrap();
    let mut with = json.clone();
    with["design"] = serde_json::json!({
        "vary": {"actuators.pull.spring.stiffness": ["1 N/m", "3 N/m"], "actuators.clamp.plate_count": [30, 60]},
        "criterion": "most-usable"
    });
    std::fs::write(sectioned.join("meter.json"), serde_json::to_string_pretty(&with).unwrap()).unwrap();
    let base = ["study", "meter.json", "--samples", "8", "--seed", "5", "--quiet"];
    let mut flags = base.to_vec();
    flags.extend(["--vary", PLATES, "--vary", SPRING, "--rank-by", "most-usable", "--out", "out"]);
    run_in(&plain, &flags);
    let mut from_section = base.to_vec();
    from_section.extend(["--out", "out"]);
    run_in(&sectioned, &from_section);
    let same = |a: &Path, b: &Path, f: &str| {
        assert!(
            std::fs::read(a.join(f)).unwrap() == std::fs::read(b.join(f)).unwrap(),
            "{f}: {} vs {}",
            a.display(),
            b.display()
        )
    };
    let (a, b) = (plain.join("out"), sectioned.join("out"));
    same(&a, &b, "designs.csv");
    let table = std::fs::read_to_string(a.join("designs.csv")).unwrap();
    assert_eq!(table.lines().count(), 5, "{table}");
    for d in 0..4 {
        let name = format!("design-{d:03}");
        for f in ["study.json", "samples.csv"] {
            same(&a.join(&name), &b.join(&name), f);
        }
    }
    // Flags win over the section, and say so.
    let mut over = base.to_vec();
    over.extend(["--vary", SPRING, "--out", "over"]);
    let said = run_in(&sectioned, &over);
    assert!(said.contains("design"), "no word of the overridden section: {said}");
    let mut plain_over = base.to_vec();
    plain_over.extend(["--vary", SPRING, "--out", "over"]);
    run_in(&plain, &plain_over);
    same(&plain.join("over"), &sectioned.join("over"), "designs.csv");
    for d in 0..2 {
        let name = format!("design-{d:03}");
        same(&plain.join("over").join(&name), &sectioned.join("over").join(&name), "samples.csv");
    }
}

/// A design point reproduces the single study of its scenario byte for byte when both are
/// sharded, merged and resumed: the design study over the spring stiffness in two shards merged
/// design by design, against the single study with `--set` of design 1's value in two shards,
/// merged, then resumed after cutting its log.
/// Deliberate bug caught: each design's seed offset by its index, no common random numbers
/// (seen failing: samples.log differs).
#[test]
fn a_sharded_merged_resumed_design_point_is_its_sharded_merged_resumed_single_study() {
    let dir = temp_dir("design-single-shards");
    let base = ["study", "scenarios/tas2000.json", "--samples", "10", "--seed", "9", "--quiet"];
    let single_set = ["--set", "actuators.pull.spring.stiffness=3 N/m"];
    for k in 0..2 {
        let shard = format!("{k}/2");
        let mut d = base.to_vec();
        let out = dir.join(format!("design-shard{k}"));
        d.extend(["--vary", SPRING, "--shard", &shard, "--out", out.to_str().unwrap()]);
        run(&d);
        let mut s = base.to_vec();
        let out = dir.join(format!("single-shard{k}"));
        s.extend(single_set);
        s.extend(["--shard", &shard, "--out", out.to_str().unwrap()]);
        run(&s);
    }
    let p = |s: &str| dir.join(s).to_str().unwrap().to_string();
    run(&["merge", &p("design-shard0/design-001"), &p("design-shard1/design-001"), "--out", &p("design-merged")]);
    run(&["merge", &p("single-shard0"), &p("single-shard1"), "--out", &p("single-merged")]);
    // Cut the merged single study's log to its header and 4 rows and resume it.
    let log = dir.join("single-merged/samples.log");
    let text = std::fs::read_to_string(&log).unwrap();
    std::fs::write(&log, text.lines().take(5).collect::<Vec<_>>().join("\n") + "\n").unwrap();
    let mut s = base.to_vec();
    s.extend(single_set);
    let out = p("single-merged");
    s.extend(["--out", &out, "--resume"]);
    run(&s);
    for f in ["samples.log", "samples.csv", "study.json"] {
        assert!(
            std::fs::read(dir.join("design-merged").join(f)).unwrap()
                == std::fs::read(dir.join("single-merged").join(f)).unwrap(),
            "{f}: the merged design point differs from the merged, resumed single study"
        );
    }
}

/// `stiction study scenarios/tas2000.json --samples 2 --quiet ARGS`: status and stderr.
fn study_err(args: &[&str]) -> (Option<i32>, String) {
    let mut a = vec!["study", "scenarios/tas2000.json", "--samples", "2", "--quiet"];
    a.extend(args.iter().copied());
    let r = stiction(&a);
    (r.status.code(), String::from_utf8_lossy(&r.stderr).into_owned())
}

/// A refusal: status 2, every needle in the message, and a message under 300 characters.
fn refused(args: &[&str], needles: &[&str]) {
    let (code, err) = study_err(args);
    assert_eq!(code, Some(2), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: no {n:?} in: {err}");
    }
    assert!(err.trim().chars().count() < 300, "{args:?}: {} characters: {err}", err.trim().chars().count());
}

/// Two varied fields where one holds the other (the parent's value would replace the child's, so
/// designs labelled 0.3 um and 0.8 um would run the same scenario), a field varied twice, and a
/// field that a `--set` also writes (same, parent or child) are refused naming both, with
/// --vary flags and in a scenario's `design` section alike.
/// Deliberate bug caught: the overlap check reduced to equal paths (seen failing: only the
/// designs' safety net refused, naming two designs, not the two flags).
#[test]
fn overlapping_varied_fields_are_refused_naming_both() {
    let child = "surface.summit_radius.value=0.3 um,0.8 um";
    let parent = r#"surface.summit_radius={"value":"0.5 um"},{"value":"0.6 um"}"#;
    refused(
        &["--vary", child, "--vary", parent],
        &["--vary surface.summit_radius", "--vary surface.summit_radius.value"],
    );
    refused(
        &["--vary", parent, "--vary", child],
        &["--vary surface.summit_radius", "--vary surface.summit_radius.value"],
    );
    refused(&["--vary", SPRING, "--vary", "actuators.pull.spring.stiffness=2 N/m"], &["varied twice"]);
    refused(
        &["--vary", child, "--set", r#"surface.summit_radius={"value":"0.5 um"}"#],
        &["--vary surface.summit_radius.value", "--set surface.summit_radius="],
    );
    refused(
        &["--vary", parent, "--set", "surface.summit_radius.value=0.5 um"],
        &["--vary surface.summit_radius", "--set surface.summit_radius.value"],
    );
    // The same in a design section.
    let dir = temp_dir("design-overlap");
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(crate::util::root().join("scenarios/tas2000.json")).unwrap())
            .unwrap();
    json["design"] = serde_json::json!({"vary": {
        "surface.summit_radius": [r#"{"value": "0.5 um"}"#, r#"{"value": "0.6 um"}"#],
        "surface.summit_radius.value": ["0.3 um", "0.8 um"]}});
    let file = dir.join("s.json");
    std::fs::write(&file, serde_json::to_string(&json).unwrap()).unwrap();
    let r = stiction(&["study", file.to_str().unwrap(), "--samples", "2", "--quiet"]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(
        err.contains("`design.vary.surface.summit_radius`")
            && err.contains("`design.vary.surface.summit_radius.value`"),
        "{err}"
    );
}

/// Values that mean the same once units are read ("7 uN" and "0.007 mN", 30 and 30.0, objects
/// equal key by key) are refused naming both spellings; two fields whose designs would run the same
/// scenario otherwise (a value that only differs in a way the study ignores) are refused naming both
/// designs.
/// Deliberate bug caught: values compared as text (seen failing: only the designs' safety net
/// refused, naming two designs, not the two spellings).
#[test]
fn equivalent_values_are_refused_naming_both_spellings() {
    refused(
        &["--vary", "meter.spring_force=7 uN,0.007 mN"],
        &["--vary meter.spring_force", "\"7 uN\"", "\"0.007 mN\""],
    );
    refused(
        &["--vary", "actuators.clamp.plate_count=30,30.0"],
        &["--vary actuators.clamp.plate_count", "\"30\"", "\"30.0\""],
    );
    refused(
        &["--vary", r#"surface.summit_radius={"value":"0.5 um"},{"value":"500 nm"}"#],
        &["--vary surface.summit_radius", "500 nm"],
    );
    refused(&["--vary", "meter.spring_force=7 uN,\"7uN\""], &["--vary meter.spring_force"]);
}

/// A field the study overrides or never reads (the surface seed, replaced by --seed + i in every
/// sample; the description; the reference; the measured data; the design section) is refused with
/// the reason; with --fixed-surface the surface seed counts and is accepted.
/// Deliberate bug caught: the ignored-field check left out (seen failing: only the designs' safety
/// net refused, without the reason or --fixed-surface).
#[test]
fn fields_the_study_ignores_cannot_be_varied() {
    refused(&["--vary", "surface.seed=1,2"], &["--vary surface.seed", "--fixed-surface"]);
    refused(&["--vary", "description=a,b"], &["--vary description", "printed"]);
    refused(&["--vary", "reference.source=a,b"], &["--vary reference.source"]);
    refused(&["--vary", "design.points=2,3"], &["--vary design.points"]);
    let out = temp_dir("design-fixed-seed");
    let o = out.join("o");
    let r = stiction(&[
        "study",
        "scenarios/tas2000.json",
        "--samples",
        "2",
        "--quiet",
        "--fixed-surface",
        "--vary",
        "surface.seed=1,2",
        "--out",
        o.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
}

/// A huge value list is refused by its count first, before its values are compared pairwise: each
/// list repeats its first value, so a pairwise comparison run first would answer "given twice"
/// (and take seconds to minutes); the count's error must be the one given. 20,000 values on the
/// command line and 1,000,000 in a design section. No wall-clock bound: the order of the checks is
/// what the test pins.
/// Deliberate bug caught: the values compared pairwise before the count (seen failing: "the value
/// ... is given twice" instead of the count).
#[test]
fn huge_value_lists_are_refused_by_count_first() {
    let mut many: Vec<String> = (0..20_000).map(|i| i.to_string()).collect();
    many[1] = many[0].clone();
    let arg = format!("actuators.clamp.plate_count={}", many.join(","));
    refused(&["--vary", &arg], &["--vary actuators.clamp.plate_count", "20000 values", "1000"]);
    let (_, err) = study_err(&["--vary", &arg]);
    assert!(!err.contains("twice") && !err.contains("same value"), "{err}");
    let dir = temp_dir("design-huge");
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(crate::util::root().join("scenarios/tas2000.json")).unwrap())
            .unwrap();
    let mut values: Vec<u32> = (0..1_000_000).collect();
    values[1] = values[0];
    json["design"] = serde_json::json!({"vary": {"actuators.clamp.plate_count": values}});
    let file = dir.join("s.json");
    std::fs::write(&file, serde_json::to_string(&json).unwrap()).unwrap();
    let r = stiction(&["study", file.to_str().unwrap(), "--samples", "2", "--quiet"]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(err.contains("`design.vary.actuators.clamp.plate_count`") && err.contains("1000000 values"), "{err}");
    assert!(!err.contains("twice") && !err.contains("same value"), "{err}");
}

/// A spring force that contradicts the clamp spring is refused by `study` as by `run` (the same
/// check in shared code), in a single study and in the design it appears in.
/// Deliberate bug caught: the study's check removed (seen failing: the study ran).
#[test]
fn study_refuses_the_spring_force_that_run_refuses() {
    let r = stiction(&["run", "scenarios/tas2000.json", "--set", "meter.spring_force=20 uN"]);
    assert_eq!(r.status.code(), Some(2), "run: {}", String::from_utf8_lossy(&r.stderr));
    // (The message is `run`'s own, longer than the others: the two values, the tolerance and both
    // ways out.)
    let (code, err) = study_err(&["--set", "meter.spring_force=20 uN"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("`meter.spring_force` = 20 uN disagrees"), "{err}");
    let (code, err) = study_err(&["--vary", "meter.spring_force=7 uN,20 uN"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("design 1 (meter.spring_force=20 uN)") && err.contains("`meter.spring_force`"), "{err}");
}

/// The design study's --out follows every command's output rules: a user's own file (designs.csv
/// or notes) is refused before any design runs unless --force (then the user's notes stay, the
/// design files are written); an earlier design study's logs need --resume or --force; --resume
/// with fewer values removes the stale design folders this folder's earlier study made, and keeps
/// a folder that holds a user's file (with that file).
/// Deliberate bugs caught: the top folder unchecked (seen failing: designs.csv replaced without
/// --force), stale folders left (seen failing: design-002 still there).
#[test]
fn the_design_folder_follows_the_output_rules() {
    let dir = temp_dir("design-out");
    let out = dir.join("o");
    let o = out.to_str().unwrap();
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("designs.csv"), "mine").unwrap();
    let three = "actuators.pull.spring.stiffness=1 N/m,2 N/m,3 N/m";
    refused(&["--vary", three, "--out", o], &["designs.csv", "--force"]);
    assert!(!out.join("design-000").exists(), "work started before the refusal");
    let (code, err) = study_err(&["--vary", three, "--out", o, "--force"]);
    assert_eq!(code, Some(0), "{err}");
    assert_ne!(std::fs::read_to_string(out.join("designs.csv")).unwrap(), "mine");
    // Again without --resume or --force: the logs are there.
    refused(&["--vary", three, "--out", o], &["--resume", "--force"]);
    // --force starts again (the design folders' files replaced).
    let (code, err) = study_err(&["--vary", three, "--out", o, "--force"]);
    assert_eq!(code, Some(0), "{err}");
    // A user's file in the folder, a user's file in design-001; then two values with --resume.
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    refused(&["--vary", three, "--out", o, "--resume"], &["notes.txt", "--force"]);
    std::fs::remove_file(out.join("notes.txt")).unwrap();
    let r = stiction(&[
        "study",
        "scenarios/tas2000.json",
        "--samples",
        "2",
        "--vary",
        "actuators.pull.spring.stiffness=1 N/m,2 N/m",
        "--out",
        o,
        "--resume",
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{err}");
    assert!(err.contains("design-002"), "the removal is not said: {err}");
    assert!(!out.join("design-002").exists(), "stale design-002 left");
    assert!(out.join("design-001/samples.log").is_file());
    assert_eq!(std::fs::read_to_string(out.join("designs.csv")).unwrap().lines().count(), 3);
    // A stale folder with a user's file: its study files go, the folder and the file stay.
    let (code, err) = study_err(&["--vary", three, "--out", o, "--resume"]);
    assert_eq!(code, Some(0), "{err}");
    std::fs::write(out.join("design-002/mine.txt"), "mine").unwrap();
    let r = stiction(&[
        "study",
        "scenarios/tas2000.json",
        "--samples",
        "2",
        "--vary",
        "actuators.pull.spring.stiffness=1 N/m,2 N/m",
        "--out",
        o,
        "--resume",
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success() && err.contains("kept design-002"), "{err}");
    assert_eq!(std::fs::read_to_string(out.join("design-002/mine.txt")).unwrap(), "mine");
    assert!(!out.join("design-002/samples.log").exists());
}

/// `stiction merge` of design-study folders says what they are and how to merge them.
/// Deliberate bug caught: the check off (seen failing: "cannot open A/samples.log").
#[test]
fn merge_of_design_study_folders_says_how() {
    let dir = temp_dir("design-merge");
    let (a, b) = (dir.join("a"), dir.join("b"));
    for (k, d) in [&a, &b].iter().enumerate() {
        let shard = format!("{k}/2");
        let (code, err) = study_err(&["--vary", SPRING, "--shard", &shard, "--out", d.to_str().unwrap()]);
        assert_eq!(code, Some(0), "{err}");
    }
    let r = stiction(&["merge", a.to_str().unwrap(), b.to_str().unwrap(), "--out", dir.join("m").to_str().unwrap()]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(err.contains("design study") && err.contains("design-000") && err.contains("--resume"), "{err}");
}
