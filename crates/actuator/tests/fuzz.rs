//! A seeded structured-mutation fuzzer over the actuator's measured files, in the style of
//! `crates/meter/tests/fuzz.rs`: the transients CSV (`actuator --transients`) and the validation
//! CSV (`actuator --validate`). Each case starts from the bundled measurements
//! (`data/gca-transients/`, `data/gca-pullin-release/`), applies one to three mutations (hostile
//! cells, unknown, duplicated or missing columns, long cells and lines, ragged rows, CR line ends,
//! a planted secret line, byte noise) and goes through the library code the binary calls
//! (`parse_transients`, `parse_measurements`; now and then `compare_transients` and `validate` on
//! the result). The contract:
//!
//! * no panic (caught and reported with the case);
//! * bounded time (each case under [`CASE_TIME_LIMIT`]);
//! * an error names the file and a line, is short and never holds the planted secret;
//! * parsed values are finite and within the documented limits; model results are finite or null.
//!
//! Short mode: 1500 cases per format (`cargo test`); long mode: `STICTION_FUZZ_CASES`,
//! `STICTION_FUZZ_SEED`, see docs/reliability.md.

mod common;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use stiction_actuator::{TransientPhysics, compare_transients, parse_measurements, parse_transients, validate};

const CASE_TIME_LIMIT: Duration = Duration::from_secs(20);
const MAX_ERROR_CHARS: usize = 400;
const SECRET: &str = "SECRET-do-not-echo-this-line-0123456789";
const ORIGIN: &str = "fuzz.csv";

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
    fn chance(&mut self, one_in: usize) -> bool {
        self.below(one_in) == 0
    }
}

fn cases() -> usize {
    std::env::var("STICTION_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(1500)
}

fn seed() -> u64 {
    std::env::var("STICTION_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(20)
}

const NASTY: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1e-308",
    "5e-324",
    "1e308",
    "1e400",
    "-1e400",
    "1e300",
    "inf",
    "-inf",
    "NaN",
    "",
    " ",
    "1,5",
    "0x10",
    "1e",
    "\"12\"",
    "\"1\"\"2\"",
    "4294967296",
    "99999999999999999999999",
    "release",
    "pull-in",
    "PULL-IN",
    "10001",
    "1000001",
    "9999",
    SECRET,
    "\u{202e}evil",
    "\u{1b}[2J",
];

/// The first `rows` data lines of a bundled file, with its header.
fn sample(path: &str, rows: usize) -> Vec<String> {
    let text = std::fs::read_to_string(common::root().join(path)).unwrap();
    text.lines().filter(|l| !l.trim().is_empty() && !l.starts_with('#')).take(rows + 1).map(str::to_string).collect()
}

fn mutate(rng: &mut Rng, lines: &mut Vec<String>, columns: &[&str]) {
    for _ in 0..rng.below(4) {
        let r = 1 + rng.below(lines.len().saturating_sub(1).max(1));
        let r = r.min(lines.len() - 1);
        match rng.below(12) {
            0..=3 => {
                let mut cells: Vec<String> = lines[r].split(',').map(str::to_string).collect();
                let c = rng.below(cells.len());
                cells[c] = rng.pick(NASTY).to_string();
                lines[r] = cells.join(",");
            }
            4 => {
                let mut cells: Vec<String> = lines[0].split(',').map(str::to_string).collect();
                let c = rng.below(cells.len());
                cells[c] = {
                    let col = *rng.pick(columns);
                    let long = "x".repeat(2000);
                    rng.pick(&[col, "unknown", SECRET, "", long.as_str()]).to_string()
                };
                lines[0] = cells.join(",");
            }
            5 => lines[r].push_str(",1"),
            6 => {
                let mut cells: Vec<&str> = lines[r].split(',').collect();
                cells.pop();
                lines[r] = cells.join(",");
            }
            7 => lines.insert(rng.below(lines.len() + 1), SECRET.to_string()),
            8 => lines[r].push_str(&"9".repeat(300 + rng.below(2000))),
            9 => lines.insert(r, ",".repeat(if rng.chance(5) { (1 << 20) + 1 } else { 1000 })),
            10 => lines.truncate(1),
            _ => {
                let l = lines[r].clone();
                lines.push(l);
            }
        }
    }
}

fn bytes_of(rng: &mut Rng, lines: &[String]) -> Vec<u8> {
    let eol = if rng.chance(5) { "\r\n" } else { "\n" };
    let mut b = lines.join(eol).into_bytes();
    if rng.chance(8) && !b.is_empty() {
        let k = rng.below(b.len());
        match rng.below(3) {
            0 => b[k] ^= 1 << rng.below(8),
            1 => b.insert(k, rng.next() as u8),
            _ => b.truncate(k),
        }
    }
    b
}

fn check_error(m: &str, case: &str) {
    assert!(!m.contains(SECRET), "an error echoes the file ({case}): {m}");
    assert!(m.chars().count() <= MAX_ERROR_CHARS, "an error of {} chars ({case}): {m}", m.chars().count());
    assert!(m.contains(ORIGIN) && m.contains("line"), "an error names no file or line ({case}): {m}");
    assert!(!m.chars().any(char::is_control), "an error holds control characters ({case}): {m:?}");
}

fn finite_debug(what: &str, s: &str, case: &str) {
    assert!(!s.contains("NaN") && !s.contains("inf"), "{case}: a {what} is not finite: {s}");
}

#[test]
fn transients_csvs_keep_the_contract() {
    let base = sample("data/gca-transients/measured_times.csv", 6);
    let spec = common::gca_spec();
    let cols = ["finger_length_um", "event", "voltage_v", "time_us", "repeat", "external_force_n"];
    let mut rng = Rng(seed() ^ 0x7472);
    let (mut parsed, mut simulated) = (0, 0);
    for case in 0..cases() {
        let mut lines = base.clone();
        mutate(&mut rng, &mut lines, &cols);
        let bytes = bytes_of(&mut rng, &lines);
        let simulate = simulated == 0 || rng.chance(300);
        let label = format!("transients case {case} (seed {})", seed());
        let start = Instant::now();
        let r = catch_unwind(AssertUnwindSafe(|| match parse_transients(&bytes, ORIGIN) {
            Err(e) => {
                check_error(&e.to_string(), &label);
                (false, false)
            }
            Ok(points) => {
                for p in &points {
                    let ok = p.finger_length_m > 0.0
                        && p.finger_length_m <= 1e-2
                        && p.voltage_v > 0.0
                        && p.voltage_v <= 1e4
                        && p.external_force_n.abs() <= 1.0
                        && p.times_s.iter().all(|t| *t > 0.0 && *t <= 1.0);
                    assert!(ok, "{label}: a parsed point beyond the limits: {p:?}");
                }
                if !simulate {
                    return (true, false);
                }
                let few: Vec<_> = points.into_iter().take(2).collect();
                if let Ok(report) = compare_transients(&spec, TransientPhysics::default(), &few) {
                    finite_debug("transient result", &format!("{report:?}"), &label);
                }
                (true, true)
            }
        }));
        let (p, s) = r.unwrap_or_else(|_| panic!("{label} panicked"));
        parsed += usize::from(p);
        simulated += usize::from(s);
        assert!(start.elapsed() < CASE_TIME_LIMIT, "{label} took {:?}", start.elapsed());
    }
    eprintln!("fuzz transients: {} cases, {parsed} parsed, {simulated} simulated", cases());
    assert!(parsed > 0 && parsed < cases(), "{parsed}");
}

#[test]
fn validation_csvs_keep_the_contract() {
    let base = sample("data/gca-pullin-release/measured.csv", 4);
    let spec = common::gca_spec();
    let cols = ["finger_length_drawn_um", "pull_in_v_1", "pull_in_v_9", "release_v", "release_v_2"];
    let mut rng = Rng(seed() ^ 0x7661);
    let (mut parsed, mut modelled) = (0, 0);
    for case in 0..cases() {
        let mut lines = base.clone();
        mutate(&mut rng, &mut lines, &cols);
        let bytes = bytes_of(&mut rng, &lines);
        let model = modelled == 0 || rng.chance(150);
        let label = format!("validation case {case} (seed {})", seed());
        let start = Instant::now();
        let r = catch_unwind(AssertUnwindSafe(|| {
            // The reader takes what `read_input_text` gives: UTF-8 without a BOM.
            let Ok(text) = std::str::from_utf8(&bytes) else { return (false, false) };
            match parse_measurements(text, ORIGIN) {
                Err(e) => {
                    check_error(&e.to_string(), &label);
                    (false, false)
                }
                Ok(points) => {
                    finite_debug("parsed point", &format!("{points:?}"), &label);
                    if !model {
                        return (true, false);
                    }
                    let few: Vec<_> = points.into_iter().take(2).collect();
                    if let Ok(report) = validate(&spec, &few) {
                        finite_debug("validation result", &format!("{report:?}"), &label);
                    }
                    (true, true)
                }
            }
        }));
        let (p, m) = r.unwrap_or_else(|_| panic!("{label} panicked"));
        parsed += usize::from(p);
        modelled += usize::from(m);
        assert!(start.elapsed() < CASE_TIME_LIMIT, "{label} took {:?}", start.elapsed());
    }
    eprintln!("fuzz validation: {} cases, {parsed} parsed, {modelled} modelled", cases());
    assert!(parsed > 0 && parsed < cases(), "{parsed}");
}
