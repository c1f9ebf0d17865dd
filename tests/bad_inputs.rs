//! Broken scenario files and flags: each must fail with exit status 2 and an error that names the
//! field (JSON path or flag), the value and what was expected. The expected fragments of each file
//! tests/data/bad/NAME.json are in NAME.expect, one per line.

use crate::util::{root, stiction};

#[test]
fn every_bad_scenario_gives_its_error() {
    let dir = root().join("tests/data/bad");
    let mut checked = 0;
    let mut entries: Vec<_> = std::fs::read_dir(&dir).expect("tests/data/bad").map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries.iter().filter(|p| p.extension().is_some_and(|e| e == "json")) {
        let expect_path = path.with_extension("expect");
        let expected =
            std::fs::read_to_string(&expect_path).unwrap_or_else(|_| panic!("{} has no .expect file", path.display()));
        let out = stiction(&["scenario", path.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{}: expected exit 2, stderr: {stderr}", path.display());
        assert!(!stderr.contains("panicked"), "{}: panicked: {stderr}", path.display());
        for line in expected.lines().filter(|l| !l.trim().is_empty()) {
            assert!(stderr.contains(line.trim()), "{}: error lacks `{}`:\n{stderr}", path.display(), line.trim());
        }
        checked += 1;
    }
    assert!(checked >= 8, "only {checked} bad scenarios checked");
}

#[test]
fn bad_flags_name_the_flag_value_and_expectation() {
    let cases: &[(&[&str], &[&str])] = &[
        (
            &[
                "discrete",
                "--contacts",
                "3",
                "--radius",
                "0.5 N",
                "--work-of-adhesion",
                "0.1",
                "--compliance",
                "9.1e-12",
                "--shear-strength",
                "1.4 GPa",
                "--load",
                "3 uN",
            ],
            &["--radius", "0.5 N", "is a force", "expected a positive length"],
        ),
        (
            &[
                "discrete",
                "--contacts",
                "3",
                "--radius",
                "0.5 um",
                "--work-of-adhesion",
                "0.1",
                "--compliance",
                "9.1e-12",
                "--shear-strength",
                "1.4 GPa",
                "--load",
                "NaN",
            ],
            &["--load", "NaN"],
        ),
        (&["gw", "--theta", "-3", "--load-star", "0"], &["--theta", "expected a positive adhesion parameter"]),
        (&["contact", "scenarios/tas2000.json", "--sweep", "0uN:1um:5"], &["--sweep TO", "1um", "expected a force"]),
        (&["run", "scenarios/tas2000.json", "--set", "surface.sumit_sd=40 nm"], &["sumit_sd", "nearest: `summit_sd`"]),
        (&["run", "does/not/exist.json"], &["cannot read scenario does/not/exist.json"]),
    ];
    for (args, needles) in cases {
        let out = stiction(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} should fail");
        assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
        for n in *needles {
            assert!(stderr.contains(n), "{args:?}: error lacks `{n}`:\n{stderr}");
        }
    }
}
