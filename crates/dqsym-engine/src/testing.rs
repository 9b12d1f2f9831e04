//! Helpers of the unit tests only.

/// A seeded xorshift generator for tests: each call returns the next value below `m` (the
/// tests need no dependency for it, and their runs repeat exactly).
pub(crate) fn xorshift_below(seed: u64) -> impl FnMut(u64) -> u64 {
    let mut x = seed;
    move |m: u64| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x % m
    }
}
