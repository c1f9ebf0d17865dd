//! Running the binary and reading its output.

use std::path::PathBuf;
use std::process::{Command, Output};

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().expect("workspace root")
}

/// Runs `stiction ARGS` in the workspace root.
pub fn stiction(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stiction")).args(args).current_dir(root()).output().expect("run stiction")
}

/// Runs `stiction ARGS`, asserts success and parses stdout as JSON.
pub fn stiction_json(args: &[&str]) -> serde_json::Value {
    let out = stiction(args);
    assert!(out.status.success(), "stiction {args:?} failed:\n{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!("stiction {args:?}: stdout is not JSON ({e}):\n{}", String::from_utf8_lossy(&out.stdout))
    })
}

/// A fresh temporary folder under target/.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = root().join("target").join("e2e-tmp").join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create temp dir");
    dir
}

/// A JSON field as f64, with a clear failure.
pub fn num(v: &serde_json::Value, key: &str) -> f64 {
    v.get(key).and_then(serde_json::Value::as_f64).unwrap_or_else(|| panic!("no number `{key}` in {v}"))
}

/// The `--out` rule for a folder that holds a file no stiction run wrote (`notes.txt` is put in
/// `out_dir`): `run(&[])` refuses with status 2 naming the file and `--force`; `run(&["--force"])`
/// succeeds and leaves the file as it was. `what` names the command in failure messages.
pub fn assert_foreign_file_needs_force(out_dir: &std::path::Path, run: &dyn Fn(&[&str]) -> Output, what: &str) {
    std::fs::write(out_dir.join("notes.txt"), "mine").unwrap();
    let r = run(&[]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{what}: {err}");
    assert!(err.contains("notes.txt") && err.contains("--force"), "{what}: {err}");
    assert!(run(&["--force"]).status.success(), "{what} --force");
    assert_eq!(std::fs::read_to_string(out_dir.join("notes.txt")).unwrap(), "mine", "{what}");
}
