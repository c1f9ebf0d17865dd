//! The Slurm scripts keep every argument's quoting: extra study flags given to submit-study.sh
//! reach `stiction study` word for word, a flag with a space in it included
//! (`--set "surface.summit_sd=20 nm"` is two words, not three). Slurm is not part of CI
//! (docs/cluster.md): a stand-in `sbatch` on PATH records each of its arguments on its own line and
//! runs the script it is given as the array task 0 (or the merge job) would run.

use std::path::Path;
use std::process::Command;

use crate::util::{root, temp_dir};

/// A stand-in `sbatch`: logs its arguments one per line (then a `--` line), runs the script
/// (the first argument not starting with `-`) with the arguments after it, as Slurm would, once
/// per task of `--array=0-N` (SLURM_ARRAY_TASK_ID set) or once, and prints a job id.
fn fake_sbatch(bin: &Path, calls: &Path) {
    std::fs::create_dir_all(bin).unwrap();
    let script = format!(
        r#"#!/bin/bash
set -euo pipefail
printf '%s\n' "$@" -- >> '{calls}'
last=0
while [ $# -gt 0 ] && [ "${{1#-}}" != "$1" ]; do
    case "$1" in --array=0-*) last="${{1#--array=0-}}" ;; esac
    shift
done
script="$1"; shift
for ((k = 0; k <= last; k++)); do
    SLURM_ARRAY_TASK_ID=$k SLURM_CPUS_PER_TASK=1 bash "$script" "$@" >&2
done
echo 4242
"#,
        calls = calls.display()
    );
    std::fs::write(bin.join("sbatch"), script).unwrap();
    assert!(Command::new("chmod").arg("+x").arg(bin.join("sbatch")).status().unwrap().success());
}

fn submit(dir: &Path, stiction: &str, extra: &[&str]) -> std::process::Output {
    submit_shards(dir, stiction, "1", extra)
}

fn submit_shards(dir: &Path, stiction: &str, shards: &str, extra: &[&str]) -> std::process::Output {
    let bin = dir.join("bin");
    fake_sbatch(&bin, &dir.join("sbatch-calls"));
    let path = format!("{}:{}", bin.display(), std::env::var("PATH").unwrap_or_default());
    let mut args = vec!["scripts/slurm/submit-study.sh", "scenarios/tas2000.json", "8", shards];
    let out = dir.join("study");
    args.push(out.to_str().unwrap());
    args.push("3");
    args.extend_from_slice(extra);
    Command::new("bash").args(&args).current_dir(root()).env("PATH", path).env("STICTION", stiction).output().unwrap()
}

#[test]
fn a_flag_with_a_space_reaches_stiction_as_one_word() {
    // A stand-in `stiction` that writes its arguments one per line: the exact words.
    let dir = temp_dir("slurm-quoting");
    let argv = dir.join("argv");
    let fake = dir.join("fake-stiction");
    std::fs::write(
        &fake,
        format!(
            "#!/bin/bash\nprintf '%s\\n' \"$@\" >> '{}'\nprintf '%s\\n' -- >> '{}'\n",
            argv.display(),
            argv.display()
        ),
    )
    .unwrap();
    assert!(Command::new("chmod").arg("+x").arg(&fake).status().unwrap().success());
    let r = submit(&dir, fake.to_str().unwrap(), &["--set", "surface.summit_sd=20 nm", "--quiet"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let got = std::fs::read_to_string(&argv).unwrap();
    let calls: Vec<&str> = got.split("--\n").filter(|c| !c.is_empty()).collect();
    assert_eq!(calls.len(), 2, "one shard and one merge call:\n{got}");
    let shard: Vec<&str> = calls[0].lines().collect();
    let tail = &shard[shard.len() - 3..];
    assert_eq!(tail, ["--set", "surface.summit_sd=20 nm", "--quiet"], "shard call:\n{}", calls[0]);
    assert!(shard.contains(&"--shard") && shard.contains(&"0/1") && shard[0] == "study", "{}", calls[0]);
    assert!(calls[1].starts_with("merge\n"), "{}", calls[1]);
    // The sbatch call for the array job got them as separate words too.
    let sb = std::fs::read_to_string(dir.join("sbatch-calls")).unwrap();
    assert!(sb.contains("\nsurface.summit_sd=20 nm\n--quiet\n--\n"), "{sb}");
}

#[test]
fn the_real_binary_accepts_the_quoted_flag_through_the_scripts() {
    // The same chain with the real binary: the shard's study.json has the summit SD of the --set
    // (20 nm differs from the file's 40 nm, so the fingerprint differs from a run without it),
    // and the merge of the one shard gives the bytes of a single run with the same --set.
    let dir = temp_dir("slurm-real");
    let r = submit(&dir, env!("CARGO_BIN_EXE_stiction"), &["--set", "surface.summit_sd=20 nm", "--quiet"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let single = dir.join("single");
    let r = crate::util::stiction(&[
        "study",
        "scenarios/tas2000.json",
        "--samples",
        "8",
        "--seed",
        "3",
        "--quiet",
        "--set",
        "surface.summit_sd=20 nm",
        "--out",
        single.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    for f in ["samples.log", "samples.csv", "study.json"] {
        let (a, b) = (std::fs::read(single.join(f)).unwrap(), std::fs::read(dir.join("study/merged").join(f)).unwrap());
        assert!(a == b, "{f} differs between the single run and the Slurm chain");
    }
}

#[test]
fn a_design_study_runs_as_one_array_task_per_shard_across_all_designs() {
    // Two shards, two designs: each array task runs its shard of both designs; the merge job
    // merges each design and finishes the design table. The result is the unsharded design
    // study's bytes.
    let dir = temp_dir("slurm-design");
    let vary = ["--vary", "actuators.pull.spring.stiffness=1 N/m,3 N/m", "--quiet"];
    let r = submit_shards(&dir, env!("CARGO_BIN_EXE_stiction"), "2", &vary);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let single = dir.join("single");
    let mut a =
        vec!["study", "scenarios/tas2000.json", "--samples", "8", "--seed", "3", "--out", single.to_str().unwrap()];
    a.extend(vary);
    let r = crate::util::stiction(&a);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let merged = dir.join("study/merged");
    for f in ["designs.csv", "design-000/samples.log", "design-001/samples.csv", "design-001/study.json"] {
        let (x, y) = (std::fs::read(single.join(f)).unwrap(), std::fs::read(merged.join(f)).unwrap());
        assert!(x == y, "{f} differs between the single design study and the Slurm chain");
    }
}
