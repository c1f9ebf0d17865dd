//! A seeded mutation fuzzer of the `.npy` summit reader (stable Rust, no extra tool): the NumPy
//! fixtures and files this crate writes, mutated (bytes flipped or overwritten, header text
//! edited, shapes and dtypes swapped for hostile ones, the data truncated or extended), each read
//! by [`read_npy_summits`] and, when accepted, turned into a surface by [`npy_surface`]. Contract:
//!
//! * no panic (caught and reported with the case that made it);
//! * bounded time and memory: a declared shape is never allocated before the data length is
//!   checked against it (each case under [`CASE_TIME_LIMIT`]);
//! * every error names the file;
//! * an accepted file gives finite values only.
//!
//! The bounded run (the default, 3000 cases, well under a second in release) is a normal test; set
//! `STICTION_FUZZ_CASES=1000000` (and optionally `STICTION_FUZZ_SEED`) for a long run, see
//! docs/reliability.md.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::time::{Duration, Instant};

use stiction_surface::*;

const CASE_TIME_LIMIT: Duration = Duration::from_secs(5);

/// SplitMix64: a tiny seeded generator (the cases must be the same on every machine).
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
}

fn cases() -> usize {
    std::env::var("STICTION_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(3000)
}

fn seed() -> u64 {
    std::env::var("STICTION_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(26)
}

/// Header fragments a hostile or careless writer produces.
const NASTY: &[&str] = &[
    "(18446744073709551615, 4)",
    "(4294967296, 4)",
    "(99999999999999999999999, 4)",
    "(1000000000000000000,)",
    "(0, 4)",
    "(5, 4, 1)",
    "()",
    "(-5, 4)",
    "'<i8'",
    "'|b1'",
    "'<c16'",
    "'<f2'",
    "'>f4'",
    "[('x', '<f8')]",
    "[('x', '<f8'), ('x', '<f8'), ('y', '<f8'), ('height', '<f8')]",
    "[('x', '<f8', (2,)), ('y', '<f8'), ('height', '<f8')]",
    "((((((((((((1,),),),),),),),),),),),)",
    "True",
    "None",
    "'\\x00'",
    "{",
    "[",
    "'",
];

fn seeds() -> Vec<Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut out: Vec<Vec<u8>> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| std::fs::read(e.unwrap().path()).unwrap())
        .filter(|b| b.starts_with(b"\x93NUMPY"))
        .collect();
    out.sort();
    let layout = Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed: 5 };
    out.push(generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).unwrap().to_npy_bytes());
    out
}

fn mutate(rng: &mut Rng, input: &[u8]) -> Vec<u8> {
    let mut b = input.to_vec();
    for _ in 0..1 + rng.below(3) {
        let n = b.len().max(1);
        match rng.below(8) {
            0 if !b.is_empty() => {
                let i = rng.below(n);
                b[i] ^= 1 << rng.below(8);
            }
            1 if !b.is_empty() => {
                let i = rng.below(n);
                b[i] = rng.next() as u8;
            }
            2 => b.truncate(rng.below(n + 1)),
            3 => {
                let extra = rng.below(40);
                b.extend((0..extra).map(|_| rng.next() as u8));
            }
            4 | 5 => {
                // Replace a header value (after a ':' inside the first 128 bytes) by a nasty one.
                let head = &b[..b.len().min(128)];
                let colons: Vec<usize> = head.iter().enumerate().filter(|(_, c)| **c == b':').map(|(i, _)| i).collect();
                if colons.is_empty() {
                    continue;
                }
                let at = colons[rng.below(colons.len())] + 1;
                let end = (at..b.len().min(at + 80)).find(|&i| b[i] == b',' || b[i] == b'}').unwrap_or(at);
                let nasty = NASTY[rng.below(NASTY.len())].as_bytes();
                b.splice(at..end, nasty.iter().copied());
            }
            6 if b.len() > 10 => {
                // The header length field.
                let i = 8 + rng.below(2);
                b[i] = rng.next() as u8;
            }
            _ => {
                // The version byte.
                if b.len() > 6 {
                    b[6] = [0u8, 1, 2, 3, 4, 255][rng.below(6)];
                }
            }
        }
    }
    b
}

#[test]
fn mutated_npy_files_never_panic_and_errors_name_the_file() {
    let seeds = seeds();
    let mut rng = Rng(seed());
    let (mut accepted, mut refused) = (0usize, 0usize);
    for case in 0..cases() {
        let base = &seeds[rng.below(seeds.len())];
        let bytes = mutate(&mut rng, base);
        let t0 = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| {
            read_npy_summits(&bytes, "fuzz.npy").and_then(|s| {
                let finite = match &s {
                    NpySummits::Heights(h) => h.iter().all(|v| v.is_finite()),
                    NpySummits::Summits { x_m, y_m, height_m, radius_m } => {
                        x_m.iter().chain(y_m).chain(height_m).chain(radius_m.iter().flatten()).all(|v| v.is_finite())
                    }
                };
                assert!(finite, "an accepted file holds a non-finite value");
                let layout =
                    Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed: 1 };
                // The scenario's radius only where the file has none (as a scenario must give it).
                let radius = match &s {
                    NpySummits::Summits { radius_m: Some(_), .. } => None,
                    _ => Some(0.5e-6),
                };
                npy_surface(s, "fuzz.npy", 20e-6, 5e-6, radius, |n| uniform_positions(&layout, n))
            })
        }));
        let dt = t0.elapsed();
        assert!(dt < CASE_TIME_LIMIT, "case {case} (seed {}) took {dt:?}", seed());
        match result {
            Err(_) => panic!(
                "case {case} (seed {}) panicked on {} bytes: {:?}",
                seed(),
                bytes.len(),
                &bytes[..bytes.len().min(160)]
            ),
            Ok(Ok(_)) => accepted += 1,
            Ok(Err(e)) => {
                let m = e.to_string();
                assert!(m.contains("fuzz.npy"), "case {case}: the error does not name the file: {m}");
                refused += 1;
            }
        }
    }
    // The mutations must reach both outcomes (a fuzzer that only produces garbage tests nothing).
    assert!(accepted > 0 && refused > 0, "accepted {accepted}, refused {refused}");
}
