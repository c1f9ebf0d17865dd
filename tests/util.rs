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

/// mu_e,a and F_a0 of a `run --json` recomputed from its printed points: the ordinary least-squares
/// line F_f = mu (L + F_a0) through (load_n, friction_n) of the points in contact (eq. 10, written
/// here independently of stiction-fit); checked against the reported values to 1e-9 relative.
pub fn assert_fit_of_points(v: &serde_json::Value) {
    let xy: Vec<(f64, f64)> = v["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["in_contact"] == true && p["friction_n"].is_number())
        .map(|p| (num(p, "load_n"), num(p, "friction_n")))
        .collect();
    assert!(xy.len() >= 3, "{} points in contact with a slip", xy.len());
    let n = xy.len() as f64;
    let (mx, my) = (xy.iter().map(|p| p.0).sum::<f64>() / n, xy.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let slope = sxy / sxx;
    let fa0 = (my - slope * mx) / slope;
    let (mu, fa0_reported) = (num(v, "mu_apparent"), num(v, "apparent_adhesion_force_n"));
    assert!((mu / slope - 1.0).abs() < 1e-9, "mu_e,a {mu} vs least squares {slope}");
    assert!((fa0_reported / fa0 - 1.0).abs() < 1e-9, "F_a0 {fa0_reported} vs least squares {fa0}");
}
