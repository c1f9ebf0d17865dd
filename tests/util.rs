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
