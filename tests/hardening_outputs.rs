//! The output layer as a hostile user tries it: every command's output flag pointed at
//! /dev/null, a FIFO, a symbolic link, the command's own input and a hard link to that input;
//! studies and merges that check what they resume and combine; Ctrl-C during a study; merges
//! killed midway. Every refusal is exit status 2 with a message naming the flag or folder, and
//! leaves the target as it was.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::util::{root, stiction, temp_dir};

fn s(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

fn run(args: &[String]) -> Output {
    let a: Vec<&str> = args.iter().map(String::as_str).collect();
    stiction(&a)
}

fn refused(r: &Output, what: &str, needles: &[&str]) {
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{what}: expected status 2, stderr: {err}");
    for n in needles {
        assert!(err.contains(n), "{what}: the error does not say {n:?}: {err}");
    }
}

#[cfg(unix)]
fn mkfifo(p: &Path) {
    let ok = Command::new("mkfifo").arg(p).status().is_ok_and(|s| s.success());
    assert!(ok, "mkfifo {}", p.display());
}

/// A character device to write to, like /dev/null. As root (where a broken output layer would
/// replace the system's /dev/null by a regular file), a private null device node in `dir`;
/// otherwise /dev/null itself, which a non-root process cannot replace.
#[cfg(unix)]
fn null_device(dir: &Path) -> PathBuf {
    let node = dir.join("null");
    let made = Command::new("mknod")
        .args(["-m", "666"])
        .arg(&node)
        .args(["c", "1", "3"])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if made { node } else { PathBuf::from("/dev/null") }
}

/// A single-file output flag: `cmd(target)` builds the command line writing to `target`.
/// /dev/null, a FIFO and a symlink are refused and left as they were.
#[cfg(unix)]
fn single_file_flag_refuses_special_targets(name: &str, flag: &str, cmd: &dyn Fn(&Path) -> Vec<String>) {
    let dir = temp_dir(&format!("out-targets-{name}"));
    // A character device like /dev/null (a rename over it would replace the device node, as root).
    let null = null_device(&dir);
    let r = run(&cmd(&null));
    refused(&r, &format!("{name} {flag} {}", null.display()), &[flag, &s(&null), "a device"]);
    {
        use std::os::unix::fs::FileTypeExt;
        let t = std::fs::symlink_metadata(&null).unwrap().file_type();
        assert!(t.is_char_device(), "{name}: {} was replaced", null.display());
    }
    // A FIFO: refused at once, never opened (a write would block).
    let fifo = dir.join("fifo");
    mkfifo(&fifo);
    let r = run(&cmd(&fifo));
    refused(&r, &format!("{name} {flag} FIFO"), &[flag, "FIFO"]);
    {
        use std::os::unix::fs::FileTypeExt;
        assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo(), "{name}: the FIFO was replaced");
    }
    // A symbolic link: never written through, never replaced.
    let target = dir.join("target.txt");
    std::fs::write(&target, "keep").unwrap();
    let link = dir.join("link.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let r = run(&cmd(&link));
    refused(&r, &format!("{name} {flag} symlink"), &[flag, "symbolic link"]);
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
}

#[cfg(unix)]
#[test]
fn single_file_outputs_never_replace_devices_fifos_or_links() {
    single_file_flag_refuses_special_targets("surface", "--csv", &|t| {
        vec!["surface".into(), "scenarios/tas2000.json".into(), "--csv".into(), s(t)]
    });
    single_file_flag_refuses_special_targets("topography", "--summits", &|t| {
        vec!["topography".into(), "data/topography-example/wall.gsf".into(), "--summits".into(), s(t)]
    });
    single_file_flag_refuses_special_targets("fit", "--synthesize", &|t| {
        vec![
            "fit".into(),
            "--scenario".into(),
            "scenarios/tas2000-fit-synthetic.json".into(),
            "--synthesize".into(),
            s(t),
        ]
    });
}

/// `plot --out` (its extension names the format, so /dev/null is refused for that already): the
/// figure and its data CSV beside it are never a FIFO or a link.
#[cfg(unix)]
#[test]
fn plot_refuses_a_fifo_or_link_as_its_svg_or_data_csv() {
    let dir = temp_dir("out-targets-plot");
    for (i, special) in ["fig.svg", "fig.csv"].iter().enumerate() {
        let sub = dir.join(format!("{i}"));
        std::fs::create_dir_all(&sub).unwrap();
        mkfifo(&sub.join(special));
        let r = run(&["plot".into(), "fig2".into(), "--out".into(), s(&sub.join("fig.svg"))]);
        refused(&r, &format!("plot with {special} a FIFO"), &["FIFO"]);
        // And a symbolic link.
        let other = dir.join(format!("l{i}"));
        std::fs::create_dir_all(&other).unwrap();
        std::fs::write(other.join("keep.txt"), "keep").unwrap();
        std::os::unix::fs::symlink(other.join("keep.txt"), other.join(special)).unwrap();
        let r = run(&["plot".into(), "fig2".into(), "--out".into(), s(&other.join("fig.svg"))]);
        refused(&r, &format!("plot with {special} a symlink"), &["symbolic link"]);
        assert_eq!(std::fs::read_to_string(other.join("keep.txt")).unwrap(), "keep");
    }
}

/// An output that is the command's own input, by the same name or by a hard link: refused before
/// the work with status 2, naming the output flag and the input; the input is left as it was.
#[cfg(unix)]
#[test]
fn an_output_never_replaces_the_commands_own_input() {
    let dir = temp_dir("out-own-input");
    // topography map.gsf --summits map.gsf (and a hard link to it)
    let map = dir.join("map.gsf");
    std::fs::copy(root().join("data/topography-example/wall.gsf"), &map).unwrap();
    let link = dir.join("hard-link.gsf");
    std::fs::hard_link(&map, &link).unwrap();
    let before = std::fs::read(&map).unwrap();
    for target in [&map, &link] {
        let r = run(&["topography".into(), s(&map), "--summits".into(), s(target)]);
        refused(&r, "topography --summits <its map>", &["--summits", "is the input", &s(&map)]);
        assert!(std::fs::read(&map).unwrap() == before, "the map was replaced");
    }
    // fit my.csv --synthesize my.csv: DATA is the input even though synthesizing does not read it.
    let csv = dir.join("my.csv");
    std::fs::copy(root().join("data/measured-voltages-synthetic/voltages.csv"), &csv).unwrap();
    let csv_link = dir.join("my-link.csv");
    std::fs::hard_link(&csv, &csv_link).unwrap();
    let before = std::fs::read(&csv).unwrap();
    for target in [&csv, &csv_link] {
        let r = run(&[
            "fit".into(),
            s(&csv),
            "--scenario".into(),
            "scenarios/tas2000-fit-synthetic.json".into(),
            "--synthesize".into(),
            s(target),
        ]);
        refused(&r, "fit DATA --synthesize DATA", &["--synthesize", "is the input", &s(&csv)]);
        assert!(std::fs::read(&csv).unwrap() == before, "the measured data were replaced");
    }
    // surface --csv over the summit CSV its scenario reads.
    let summits = dir.join("summits.csv");
    let r = stiction(&["surface", "scenarios/tas2000.json", "--csv", &s(&summits)]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let scenario = dir.join("from-csv.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root().join("scenarios/tas2000.json")).unwrap()).unwrap();
    let surface = v["surface"].as_object_mut().unwrap();
    surface.retain(|k, _| !["seed", "summit_density", "summit_sd", "summit_radius"].contains(&k.as_str()));
    surface.insert("source".into(), "csv".into());
    surface.insert("csv_path".into(), "summits.csv".into());
    std::fs::write(&scenario, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    let ok = stiction(&["surface", &s(&scenario)]);
    if ok.status.success() {
        let before = std::fs::read(&summits).unwrap();
        let r = stiction(&["surface", &s(&scenario), "--csv", &s(&summits)]);
        refused(&r, "surface --csv <the summit CSV it reads>", &["--csv", "is the input"]);
        assert!(std::fs::read(&summits).unwrap() == before);
    }
}

/// Output folders: a device like /dev/null, a FIFO and a symlink are refused for every command with --out.
#[cfg(unix)]
#[test]
fn output_folders_are_never_devices_fifos_or_links() {
    let dir = temp_dir("out-folders");
    let fifo = dir.join("fifo");
    mkfifo(&fifo);
    let real = dir.join("real");
    std::fs::create_dir_all(&real).unwrap();
    let link = dir.join("link");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let null = null_device(&dir);
    let commands: [(&str, Vec<&str>); 4] = [
        ("run", vec!["run", "scenarios/tas2000.json"]),
        ("topography", vec!["topography", "data/topography-example/wall.gsf"]),
        ("study", vec!["study", "scenarios/tas2000.json", "--samples", "2", "--quiet"]),
        ("merge", vec!["merge", "no-such-shard"]),
    ];
    for (name, base) in &commands {
        for target in [null.as_path(), &fifo, &link] {
            let mut a: Vec<String> = base.iter().map(|x| x.to_string()).collect();
            a.extend(["--out".into(), s(target)]);
            let r = run(&a);
            let err = String::from_utf8_lossy(&r.stderr);
            assert_eq!(r.status.code(), Some(2), "{name} --out {}: {err}", target.display());
            assert!(
                err.contains(&s(target)) || err.contains("no-such-shard"),
                "{name} --out {}: {err}",
                target.display()
            );
        }
        assert!(std::fs::read_dir(&real).unwrap().next().is_none(), "{name} wrote through the link");
    }
}

fn study_args(out: &Path, samples: &str, extra: &[&str]) -> Vec<String> {
    // --quiet: no progress line (the tests read stderr).
    let mut a: Vec<String> = ["study", "scenarios/tas2000.json", "--samples", samples, "--seed", "3", "--quiet"]
        .iter()
        .map(|x| x.to_string())
        .collect();
    a.extend(["--out".into(), s(out)]);
    a.extend(extra.iter().map(|x| x.to_string()));
    a
}

/// `study --out` is a manifested folder that says what it wrote; --force is the rule for foreign
/// files and for a new study over a finished one; `merge --out` the same, and it refuses one of
/// its own shards' folders as --out.
#[test]
fn study_and_merge_folders_are_manifested_and_take_force() {
    let dir = temp_dir("study-folders");
    let one = dir.join("one");
    let r = run(&study_args(&one, "6", &[]));
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let out = String::from_utf8_lossy(&r.stdout);
    assert!(out.contains("wrote") && out.contains("manifest.json") && out.contains("samples.log"), "{out}");
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(one.join("manifest.json")).unwrap()).unwrap();
    let files: Vec<&str> = m["files"].as_array().unwrap().iter().map(|f| f.as_str().unwrap()).collect();
    for f in ["samples.log", "samples.csv", "study.json", "sensitivity.csv"] {
        assert!(files.contains(&f), "{f} not in the manifest: {files:?}");
    }
    for f in &files {
        assert!(one.join(f).is_file(), "the manifest lists {f}, which is not there");
    }
    // A finished study is not overwritten without --resume or --force; with --force it is.
    let r = run(&study_args(&one, "6", &[]));
    refused(&r, "study over a finished one", &["--resume"]);
    let r = run(&study_args(&one, "6", &["--force"]));
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    // Foreign files need --force.
    let foreign = dir.join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    crate::util::assert_foreign_file_needs_force(
        &foreign,
        &|extra| run(&study_args(&foreign, "4", extra)),
        "study --out",
    );
    // Shards, merged into a new folder, then again into the same folder (replaced as a whole).
    let mut shards = Vec::new();
    for k in 0..2 {
        let d = dir.join(format!("shard{k}"));
        let r = run(&study_args(&d, "6", &["--shard", &format!("{k}/2")]));
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        shards.push(s(&d));
    }
    let merged = dir.join("merged");
    let merge = |out: &Path, extra: &[&str]| {
        let mut a = vec!["merge".to_string(), shards[1].clone(), shards[0].clone(), "--out".into(), s(out)];
        a.extend(extra.iter().map(|x| x.to_string()));
        run(&a)
    };
    for _ in 0..2 {
        let r = merge(&merged, &[]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        assert!(String::from_utf8_lossy(&r.stdout).contains("wrote"));
    }
    assert!(std::fs::read(merged.join("samples.log")).unwrap() == std::fs::read(one.join("samples.log")).unwrap());
    assert!(merged.join("manifest.json").is_file());
    crate::util::assert_foreign_file_needs_force(&merged, &|extra| merge(&merged, extra), "merge --out");
    // One of its own shards as --out: refused, the shard left as it was.
    let before = std::fs::read(Path::new(&shards[0]).join("samples.log")).unwrap();
    let r = merge(Path::new(&shards[0]), &[]);
    refused(&r, "merge --out <a shard>", &["samples.log", "is the input"]);
    assert!(std::fs::read(Path::new(&shards[0]).join("samples.log")).unwrap() == before);
    // Nothing hidden is left beside the folders.
    let hidden: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(hidden.is_empty(), "left behind: {hidden:?}");
}

/// A study pointing at a height map: the map's content is part of the fingerprint, so resume
/// and merge refuse a changed map; an edited log line is refused naming the line; a CR LF log is
/// refused and never reaches samples.csv.
#[test]
fn studies_check_the_maps_and_lines_they_resume_and_merge() {
    let dir = temp_dir("study-inputs");
    let map = dir.join("wall.gsf");
    std::fs::copy(root().join("data/topography-example/wall.gsf"), &map).unwrap();
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root().join("scenarios/tas2000-height-map.json")).unwrap())
            .unwrap();
    v["surface"]["height_map"]["file"] = "wall.gsf".into();
    let scenario = dir.join("scenario.json");
    std::fs::write(&scenario, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    let args = |out: &Path, extra: &[&str]| -> Vec<String> {
        let mut a: Vec<String> =
            ["study", &s(&scenario), "--samples", "4", "--seed", "2", "--quiet", "--fixed-surface", "--out", &s(out)]
                .iter()
                .map(|x| x.to_string())
                .collect();
        a.extend(extra.iter().map(|x| x.to_string()));
        a
    };
    let (a, b) = (dir.join("shard0"), dir.join("shard1"));
    let r = run(&args(&a, &["--shard", "0/2"]));
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    // The map changes (one byte near the end: the data, not the header).
    let mut bytes = std::fs::read(&map).unwrap();
    let n = bytes.len();
    bytes[n - 3] ^= 0x01;
    std::fs::write(&map, &bytes).unwrap();
    let r = run(&args(&b, &["--shard", "1/2"]));
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let r = stiction(&["merge", &s(&a), &s(&b), "--out", &s(&dir.join("merged"))]);
    refused(&r, "merge of shards on different maps", &["surface.height_map.file", "different studies"]);
    let r = run(&args(&a, &["--shard", "0/2", "--resume"]));
    refused(&r, "resume on a changed map", &["surface.height_map.file", "another study"]);
    // An edited number in a sample line.
    let log = b.join("samples.log");
    let text = std::fs::read_to_string(&log).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let k = lines.len() - 1;
    let pos = lines[k].find(|c: char| c.is_ascii_digit() && c != '1').unwrap_or(0);
    lines[k].replace_range(pos..pos + 1, "1");
    std::fs::write(&log, lines.join("\n") + "\n").unwrap();
    let r = run(&args(&b, &["--shard", "1/2", "--resume"]));
    refused(&r, "resume of an edited log", &[&format!("line {}", k + 1), "checksum"]);
    // CR LF line ends.
    std::fs::write(&log, text.replace('\n', "\r\n")).unwrap();
    let r = run(&args(&b, &["--shard", "1/2", "--resume"]));
    refused(&r, "resume of a CR LF log", &["line 1", "CR LF"]);
    let csv = std::fs::read(b.join("samples.csv")).unwrap();
    assert!(!csv.contains(&b'\r'), "a carriage return reached samples.csv");
}

fn wait_for_lines(path: &Path, n: usize, limit: Duration) -> usize {
    let start = Instant::now();
    loop {
        let got = std::fs::read(path).map_or(0, |b| b.iter().filter(|&&c| c == b'\n').count());
        if got >= n || start.elapsed() > limit {
            return got;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Ctrl-C (SIGINT) and SIGTERM during a study: the samples in flight are finished and logged
/// (no torn line), the message says how many samples are kept and gives the command to resume,
/// the status is 130, and the folder has no manifest (it is not complete). The study is far too
/// long to finish first (1e6 samples); resuming to the same bytes is tested in tests/study.rs.
#[cfg(unix)]
#[test]
fn an_interrupted_study_says_how_to_resume_and_exits_130() {
    let dir = temp_dir("study-interrupt");
    for signal in ["INT", "TERM"] {
        let out = dir.join(format!("sig{signal}"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_stiction"))
            .args(study_args(&out, "1000000", &["--threads", "2"]))
            .current_dir(root())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let log = out.join("samples.log");
        wait_for_lines(&log, 50, Duration::from_secs(60));
        let killed = Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().unwrap();
        assert!(killed.success());
        let start = Instant::now();
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > Duration::from_secs(30) {
                let _ = child.kill();
                panic!("SIG{signal}: the study did not stop within 30 s");
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        let r = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(130), "SIG{signal}: {err}");
        let bytes = std::fs::read(&log).unwrap();
        assert_eq!(bytes.last(), Some(&b'\n'), "SIG{signal}: a torn line was left");
        let rows = bytes.iter().filter(|&&c| c == b'\n').count() - 1;
        assert!(err.contains(&format!("{rows} of 1000000 samples")), "SIG{signal}: {err}");
        assert!(err.contains("--resume") && err.contains(&s(&out)), "SIG{signal}: {err}");
        assert!(!out.join("manifest.json").exists() && !out.join("study.json").exists());
    }
}

/// `--resume` says how many samples it found.
#[test]
fn resume_says_how_many_samples_it_found() {
    let dir = temp_dir("study-resume-count");
    let out = dir.join("s");
    let r = run(&study_args(&out, "5", &[]));
    assert!(r.status.success());
    // Drop the last two sample lines (whole lines), then resume without --quiet.
    let log = out.join("samples.log");
    let text = std::fs::read_to_string(&log).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    std::fs::write(&log, lines[..lines.len() - 2].join("\n") + "\n").unwrap();
    let mut a = study_args(&out, "5", &["--resume"]);
    a.retain(|x| x != "--quiet");
    let r = run(&a);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(r.status.success(), "{err}");
    assert!(err.contains("resuming: 3 of 5 samples found"), "{err}");
    assert_eq!(std::fs::read_to_string(&log).unwrap(), text);
}

/// A merge killed midway (SIGKILL: no clean-up) leaves the earlier folder or none, never a
/// partial one; the next merge cleans up what it left and succeeds, leaving nothing hidden.
#[cfg(unix)]
#[test]
fn a_killed_merge_leaves_nothing_behind_after_the_next_merge() {
    let dir = temp_dir("merge-kill");
    let mut shards: Vec<PathBuf> = Vec::new();
    for k in 0..2 {
        let d = dir.join(format!("shard{k}"));
        let r = run(&study_args(&d, "400", &["--shard", &format!("{k}/2")]));
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        shards.push(d);
    }
    let merged = dir.join("merged");
    let merge_cmd = || {
        let mut c = Command::new(env!("CARGO_BIN_EXE_stiction"));
        c.args(["merge", &s(&shards[0]), &s(&shards[1]), "--out", &s(&merged)]).current_dir(root());
        c
    };
    for delay_ms in [5u64, 40, 150] {
        let mut child = merge_cmd().stdout(Stdio::null()).stderr(Stdio::null()).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        let _ = child.kill();
        let _ = child.wait();
        // The folder is absent or complete (its manifest lists files that are all there).
        if merged.exists() {
            let m: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(merged.join("manifest.json")).unwrap()).unwrap();
            for f in m["files"].as_array().unwrap() {
                assert!(merged.join(f.as_str().unwrap()).is_file());
            }
        }
        let r = merge_cmd().output().unwrap();
        assert!(r.status.success(), "a merge after a killed one: {}", String::from_utf8_lossy(&r.stderr));
        let hidden: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .chain(std::fs::read_dir(&merged).unwrap())
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with('.'))
            .collect();
        assert!(hidden.is_empty(), "left behind after {delay_ms} ms: {hidden:?}");
    }
}
