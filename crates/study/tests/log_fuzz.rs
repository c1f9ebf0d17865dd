//! A mutation fuzzer for the study log `samples.log`: CR LF line ends, edited numbers, truncated
//! lines, swapped lines, wrong checksums and random byte damage. The oracle: the reader either
//! refuses the log (an error that names the file, and the line for a line's damage) or returns
//! exactly a prefix of the rows that were written; it never accepts a changed row, never panics.
//!
//! Short by default (2,000 cases); the long mode runs `STICTION_FUZZ_CASES` cases:
//! `STICTION_FUZZ_CASES=30000 cargo test --release -p stiction-study --test log_fuzz -- --nocapture`
//! (the counts it prints are in docs/reliability.md).

use std::path::{Path, PathBuf};

use stiction_meter::SlipPath;
use stiction_study::log::{self, Header, LogWriter};
use stiction_study::{Calibration, SampleResult};

/// xorshift64*: a small deterministic generator (the fuzzer needs no statistical quality).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn header(samples: usize) -> Header {
    Header {
        format: log::FORMAT,
        scenario: "scenarios/tas2000.json".into(),
        scenario_hash: "0123456789abcdef".into(),
        samples,
        seed: 7,
        vary_surface: true,
        calibration: Calibration::Nominal,
        slip_path: SlipPath::Light,
        shard_index: 0,
        shard_count: 1,
        reduction: ["1e-8".into(), "2e-8".into(), "3e-6".into()],
        parameters: vec![("surface.summit_radius".into(), "m".into()), ("meter.spring_force".into(), "N".into())],
        reference: None,
        program_version: "0.1.0".into(),
        input_files: vec![log::InputFile {
            field: "surface.height_map.file".into(),
            path: "wall.gsf".into(),
            content_hash: "fedcba9876543210".into(),
        }],
        calibration_draws: 200,
    }
}

fn sample(i: usize, rng: &mut Rng) -> SampleResult {
    let fit = rng.below(4) != 0;
    SampleResult {
        index: i,
        draws: vec![1e-6 * (1.0 + rng.unit()), if rng.below(5) == 0 { f64::NAN } else { 3e-6 * rng.unit() }],
        mu_apparent: fit.then(|| 0.2 + rng.unit()),
        apparent_adhesion_force_n: fit.then(|| 1e-6 * rng.unit()),
        mean_contacts: Some(10.0 * rng.unit()),
        interface_mu: fit.then(|| 0.5 + rng.unit()),
        intervals: stiction_study::FitIntervals {
            mu_ci95_width: fit.then(|| 0.1 * rng.unit()),
            mu_ci95_width_with_calibration: fit.then(|| rng.unit()),
            fa0_ci95_width_n: None,
            fa0_ci95_width_with_calibration_n: fit.then(|| 1e-6 * rng.unit()),
        },
        reason: (!fit).then(|| "too-few-slips".into()),
        detail: (!fit).then(|| "1 slip point(s), \"quoted\", with commas".into()),
    }
}

/// Writes a fresh log of `n` samples in `dir`; returns the csv rows written.
fn write_log(dir: &Path, n: usize, rng: &mut Rng) -> Vec<Vec<u8>> {
    let _ = std::fs::remove_file(dir.join(log::LOG_NAME));
    let h = header(n);
    let mut w = LogWriter::create(dir, &h).unwrap();
    let mut rows = Vec::new();
    for i in 0..n {
        let r = log::row(&sample(i, rng)).unwrap();
        w.append(&r).unwrap();
        rows.push(r);
    }
    rows
}

fn read_rows(path: &Path) -> Result<Vec<Vec<u8>>, String> {
    let mut got = Vec::new();
    log::for_each_row(path, |_, l| {
        got.push(l.to_vec());
        Ok(())
    })
    .map(|_| got)
    .map_err(|e| e.to_string())
}

/// Byte ranges of the lines (each with its newline).
fn lines(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &b) in bytes.iter().enumerate() {
        if b == b'\n' {
            out.push((start, i + 1));
            start = i + 1;
        }
    }
    out
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Class {
    Crlf,
    EditedNumber,
    TruncatedLine,
    SwappedLines,
    WrongChecksum,
    RandomBytes,
}

const CLASSES: [Class; 6] = [
    Class::Crlf,
    Class::EditedNumber,
    Class::TruncatedLine,
    Class::SwappedLines,
    Class::WrongChecksum,
    Class::RandomBytes,
];

/// Mutates `bytes`; returns the 1-based line the damage must be named at (None: any outcome
/// that is an error or a prefix is fine), and whether an error is required.
fn mutate(class: Class, bytes: &mut Vec<u8>, rng: &mut Rng) -> (Option<usize>, bool) {
    let ls = lines(bytes);
    let pick = |rng: &mut Rng| 1 + rng.below(ls.len() - 1); // a sample line (0 is the header)
    match class {
        Class::Crlf => {
            // All line ends, or only one: the first converted line is named.
            let all = rng.below(2) == 0;
            let k = if all { 0 } else { rng.below(ls.len()) };
            let mut out = Vec::with_capacity(bytes.len() + ls.len());
            for (j, &(a, b)) in ls.iter().enumerate() {
                out.extend_from_slice(&bytes[a..b - 1]);
                if all || j == k {
                    out.push(b'\r');
                }
                out.push(b'\n');
            }
            *bytes = out;
            (Some(k + 1), true)
        }
        Class::EditedNumber => {
            let k = pick(rng);
            let (a, b) = ls[k];
            let tab = a + bytes[a..b].iter().rposition(|&c| c == b'\t').unwrap();
            let digits: Vec<usize> = (a..tab).filter(|&i| bytes[i].is_ascii_digit()).collect();
            let i = digits[rng.below(digits.len())];
            let old = bytes[i];
            bytes[i] = b'0' + ((old - b'0' + 1 + rng.below(9) as u8) % 10);
            (Some(k + 1), true)
        }
        Class::TruncatedLine => {
            // Cut a line short (dropping its end and checksum); the next line follows at once.
            let k = pick(rng);
            let (a, b) = ls[k];
            let cut = a + 1 + rng.below(b - a - 2);
            let last = k == ls.len() - 1;
            if last && rng.below(2) == 0 {
                // A torn last line, as a kill leaves it: refused by the reader (resume cuts it).
                bytes.truncate(cut);
            } else {
                bytes.drain(cut..b - 1);
            }
            (Some(k + 1), true)
        }
        Class::SwappedLines => {
            let k = pick(rng);
            let mut m = pick(rng);
            if m == k {
                m = if k + 1 < ls.len() { k + 1 } else { k - 1 };
            }
            if m == 0 {
                return (None, false);
            }
            let (k, m) = (k.min(m), k.max(m));
            let mut out = bytes[..ls[k].0].to_vec();
            out.extend_from_slice(&bytes[ls[m].0..ls[m].1]);
            out.extend_from_slice(&bytes[ls[k].1..ls[m].0]);
            out.extend_from_slice(&bytes[ls[k].0..ls[k].1]);
            out.extend_from_slice(&bytes[ls[m].1..]);
            *bytes = out;
            (Some(k + 1), true)
        }
        Class::WrongChecksum => {
            let k = rng.below(ls.len());
            let (_, b) = ls[k];
            let i = b - 2 - rng.below(16);
            let old = bytes[i];
            let hex = b"0123456789abcdef";
            let mut new = hex[rng.below(16)];
            if new == old {
                new = if old == b'0' { b'1' } else { b'0' };
            }
            bytes[i] = new;
            (Some(k + 1), true)
        }
        Class::RandomBytes => {
            for _ in 0..1 + rng.below(3) {
                if bytes.is_empty() {
                    break;
                }
                let i = rng.below(bytes.len());
                match rng.below(3) {
                    0 => bytes[i] = rng.next() as u8,
                    1 => {
                        bytes.remove(i);
                    }
                    _ => bytes.insert(i, rng.next() as u8),
                }
            }
            (None, false)
        }
    }
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stiction-log-fuzz-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn mutated_logs_are_refused_naming_the_line_or_read_as_a_prefix() {
    let cases: usize = std::env::var("STICTION_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(2000);
    let dir = temp_dir("mutations");
    let path = dir.join(log::LOG_NAME);
    let mut rng = Rng(0x5eed_1234_abcd_ef01);
    let mut counts = std::collections::BTreeMap::<(Class, &str), usize>::new();
    for case in 0..cases {
        let class = CLASSES[case % CLASSES.len()];
        let n = 2 + rng.below(12);
        let rows = write_log(&dir, n, &mut rng);
        let mut bytes = std::fs::read(&path).unwrap();
        let original = bytes.clone();
        let (line, must_fail) = mutate(class, &mut bytes, &mut rng);
        std::fs::write(&path, &bytes).unwrap();
        let outcome = std::panic::catch_unwind(|| read_rows(&path));
        let what = format!("case {case} ({class:?}, {n} rows)");
        let result = outcome.unwrap_or_else(|_| panic!("{what}: the reader panicked"));
        match result {
            Ok(got) => {
                assert!(!must_fail || bytes == original, "{what}: a damaged log was accepted");
                assert!(got.len() <= rows.len() && got[..] == rows[..got.len()], "{what}: a changed row was accepted");
                *counts.entry((class, "accepted as a prefix")).or_default() += 1;
            }
            Err(e) => {
                assert!(e.contains(&path.display().to_string()), "{what}: the error does not name the file: {e}");
                if let Some(k) = line {
                    assert!(e.contains(&format!("line {k}")), "{what}: the error does not name line {k}: {e}");
                }
                assert!(e.len() < 400, "{what}: the error is {} bytes long", e.len());
                *counts.entry((class, "refused")).or_default() += 1;
            }
        }
    }
    for ((class, outcome), n) in &counts {
        println!("log fuzz: {class:?} {outcome}: {n}");
    }
    println!("log fuzz: {cases} cases");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_crlf_log_is_refused_on_resume_and_its_cr_never_reaches_samples_csv() {
    let dir = temp_dir("crlf");
    let mut rng = Rng(42);
    write_log(&dir, 5, &mut rng);
    let path = dir.join(log::LOG_NAME);
    let text = std::fs::read_to_string(&path).unwrap().replace('\n', "\r\n");
    std::fs::write(&path, text).unwrap();
    let e = LogWriter::resume(&dir, &header(5)).err().expect("a CR LF log is refused").to_string();
    assert!(e.contains("line 1") && e.contains("CR LF") && e.contains("dos2unix"), "{e}");
    let e = stiction_study::summary::finalize(&dir).err().expect("no samples.csv from a CR LF log").to_string();
    assert!(e.contains("CR LF"), "{e}");
    assert!(!dir.join("samples.csv").exists());
}

#[test]
fn an_untouched_log_reads_back_and_resumes_at_its_end() {
    let dir = temp_dir("clean");
    let mut rng = Rng(7);
    let rows = write_log(&dir, 6, &mut rng);
    assert_eq!(read_rows(&dir.join(log::LOG_NAME)).unwrap(), rows);
    // A torn last line is cut by resume, which then continues after the complete rows.
    let mut bytes = std::fs::read(dir.join(log::LOG_NAME)).unwrap();
    bytes.extend_from_slice(b"6,7.1e-1,2.");
    std::fs::write(dir.join(log::LOG_NAME), &bytes).unwrap();
    let (_, done) = LogWriter::resume(&dir, &header(6)).unwrap();
    assert_eq!(done, 6);
    // Another map is another study.
    let mut h = header(6);
    h.input_files[0].content_hash = "0000000000000000".into();
    let e = LogWriter::resume(&dir, &h).err().expect("another map is refused").to_string();
    assert!(e.contains("surface.height_map.file") && e.contains("another study"), "{e}");
}
