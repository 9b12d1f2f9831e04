//! The columns of a canonical basis and the order the greedy choice takes them in: shared by
//! the exact basis (`exact.rs`) and the one found modulo a prime (`fast.rs`), so both choose
//! the same columns.

use super::super::atoms::Small;
use super::field::Ints;
use super::level::lcm;
use num_integer::Integer;

/// One column of a basis: `sqrt(h) b` with `b = cos(theta)` (real) or `e^{i theta}` (times
/// `i` when `imag`), `theta = pi * angle`.
#[derive(Clone, PartialEq, Eq)]
pub(super) struct Col {
    pub(super) h: u64,
    pub(super) angle: Small,
    pub(super) imag: bool,
}

/// The order of `e^{2 pi i k / n}`.
pub(super) fn order(k: i64, n: u64) -> u64 {
    n / (k.unsigned_abs().gcd(&n))
}

/// What `zeta_o` adds to the field of all square roots and `i`: `o` without its factor 3 when
/// 9 does not divide it, and without its power of 2 when 16 does not (`zeta_3`, `zeta_8` are
/// in `K(i)`). Candidates are taken by this first.
pub(super) fn reduced(o: u64) -> u64 {
    let mut r = o;
    let mut two = 1;
    while r.is_multiple_of(2) {
        r /= 2;
        two *= 2;
    }
    if two >= 16 {
        r *= two;
    }
    if r.is_multiple_of(3) && !r.is_multiple_of(9) {
        r /= 3;
    }
    r
}

/// The order in which basis candidates are taken: the field they need first, then the
/// denominator of the angle as a multiple of pi (`pi/10` before `2 pi/15`), then the angle.
pub(super) fn rank(k: i64, n: u64) -> (u64, u64) {
    let o = order(k, n);
    (reduced(o), if o.is_multiple_of(2) { o / 2 } else { o })
}

/// A candidate column of a level-`m` basis: the angle `2 pi k / l` and the candidate's parts
/// in `Q(zeta_w)` (for a real basis `cos(2 pi k / l)`; for a complex one `e^{2 pi i k / l}` and
/// `i e^{2 pi i k / l}`), doubled (the exact path takes their [`super::field::halves`]).
pub(super) struct Candidate {
    pub(super) k: i64,
    pub(super) l: i64,
    pub(super) parts: Vec<Ints>,
}

/// The candidates of `R_M` (real) or `C_M` (complex), in the order the greedy basis takes
/// them ([`rank`]): real angles `2 pi k / l` in `[0, pi/2)` with `l = lcm(2, m)`, complex ones
/// `2 pi k / m` in `(-pi/4, pi/4]`. The exact and the fast basis both walk this list, so they
/// choose from the same columns in the same order.
pub(super) fn candidates(m: u64, w: u64, real: bool) -> Vec<Candidate> {
    if real {
        let l = lcm(2, m);
        // theta = 2 pi k / l in [0, pi/2): 4k < l.
        let mut ks: Vec<i64> = (0..).take_while(|k| 4 * k < l as i64).collect();
        ks.sort_by_key(|&k| (rank(k, l), k));
        ks.into_iter()
            .map(|k| {
                let a = k as u64 * (w / l);
                // (zeta^a + zeta^-a) / 2, `a < W / 4`.
                let c = if a == 0 {
                    vec![(0, 2)]
                } else {
                    vec![(a, 1), (w - a, 1)]
                };
                Candidate {
                    k,
                    l: l as i64,
                    parts: vec![c],
                }
            })
            .collect()
    } else {
        let bound = m as i64;
        // theta = 2 pi k / m in (-pi/4, pi/4]: -m < 8k <= m.
        let mut ks: Vec<i64> = (-(bound / 8)..=bound / 8)
            .filter(|k| 8 * k > -bound)
            .collect();
        ks.sort_by_key(|&k| (rank(k, m), k.abs(), k < 0));
        ks.into_iter()
            .map(|k| {
                let a = (k.rem_euclid(bound) as u64) * (w / m);
                // zeta^a and i zeta^a = zeta^(a + W/4).
                let c = vec![(a, 2)];
                let ic = vec![((w / 4 + a) % w, 2)];
                Candidate {
                    k,
                    l: bound,
                    parts: vec![c, ic],
                }
            })
            .collect()
    }
}
