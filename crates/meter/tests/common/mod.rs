//! What the meter's fuzz tests share: the repository root and a seeded generator.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The repository root (bundled scenarios, data).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// SplitMix64: a tiny seeded generator (the cases must be the same on every machine).
pub struct Rng(pub u64);
impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
    /// A uniform draw in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `STICTION_FUZZ_CASES`, or `default`.
pub fn cases(default: usize) -> usize {
    std::env::var("STICTION_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(default)
}

/// `STICTION_FUZZ_SEED`, or `default`.
pub fn seed(default: u64) -> u64 {
    std::env::var("STICTION_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(default)
}
