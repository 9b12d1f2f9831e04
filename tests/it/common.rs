//! Helpers shared by the integration tests.
#![allow(dead_code)]

use dqsym::Scalar;

/// Parses nothing: builds a symbol.
pub fn s(name: &str) -> Scalar {
    Scalar::sym(name)
}

/// The integer `n` as a scalar.
pub fn n(v: i64) -> Scalar {
    Scalar::int(v)
}

/// `num / den` as a scalar.
pub fn q(num: i64, den: i64) -> Scalar {
    <Scalar as dqsym::Ring>::from_ratio(num, den)
}

/// insta settings that store snapshots in the top-level snapshots/ folder.
pub fn snapshot_settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path(concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"));
    s.set_prepend_module_to_snapshot(false);
    s
}

/// A deterministic pseudo-random generator for numeric checks (no global state).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407))
    }
    /// A uniform value in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let u = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }
    /// A uniform integer in [0, n), n > 0.
    pub fn below(&mut self, n: u64) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        // The high bits: the low bits of a power-of-two LCG have short periods.
        (((self.0 >> 32) * n) >> 32) % n.max(1)
    }
    /// An element of `v` (not empty), uniformly.
    pub fn pick<T: Copy>(&mut self, v: &[T]) -> T {
        v[self.below(v.len() as u64) as usize]
    }
    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.range(0.0, 1.0) < p
    }
}
