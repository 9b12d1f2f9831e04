//! Systems of linear congruences over the integers, `sum_s a[g][s] z_s = b[g] (mod m)` with
//! each `z_s` in `0..range[s]`, their solutions enumerated in lexicographic order without a
//! search: the offsets of `offsets.rs` are found with it (each phase scaled to an integer
//! residue modulo the lcm of the denominators).
//!
//! How: the rows are put in echelon form from the last unknown to the first by unimodular
//! row operations modulo `m` (an extended gcd merges every row that holds an unknown into one
//! pivot row `p z_j + r . z_{<j} = c`). A pivot row is solvable in `z_j` exactly when
//! `g = gcd(p, m)` divides `c - r . z_{<j}`, a congruence in the earlier unknowns alone
//! (the pivot row times `m / g`) that joins the rows still to eliminate; then `z_j` is one
//! residue modulo `m / g`. Forward, each unknown takes the values of its residue class in its
//! range given the earlier ones, so every prefix met extends to a solution when the ranges are
//! multiples of the steps (as the periods of the offsets are), and the enumeration costs one
//! step per value it lists.

use crate::scalar::charge;
use crate::ScalarError;

/// The most values [`solutions`] lists (every unknown's value in every prefix) before it
/// stops.
pub const MAX_VISITS: usize = 200_000;

/// Work charged to the Context every this many values listed.
const CHARGE_EVERY: usize = 256;

/// One unknown's pivot: `z_j = inv ((c - r . z_{<j}) / g) (mod step)`, solvable when `g`
/// divides `c - r . z_{<j}`.
struct Pivot {
    r: Vec<i64>,
    c: i64,
    g: i64,
    step: i64,
    inv: i64,
}

/// Why [`solutions`] stopped before listing every solution.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Stop {
    /// The visitor asked to stop.
    Visitor,
    /// [`MAX_VISITS`] values listed.
    Visits,
    /// The Context's work budget ran out, or it was cancelled.
    Work(ScalarError),
}

fn gcd(a: i64, b: i64) -> i64 {
    let (mut a, mut b) = (a.abs(), b.abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// `(g, x, y)` with `g = gcd(a, b) = x a + y b`, for `a, b >= 0`.
fn ext_gcd(a: i64, b: i64) -> (i64, i64, i64) {
    let (mut r0, mut r1, mut x0, mut x1, mut y0, mut y1) = (a, b, 1i64, 0i64, 0i64, 1i64);
    while r1 != 0 {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (x0, x1) = (x1, x0 - q * x1);
        (y0, y1) = (y1, y0 - q * y1);
    }
    (r0, x0, y0)
}

/// `v` modulo `m` (`m >= 1`), in `[0, m)`: in machine words when `v` fits in one (the common
/// case: the moduli of `closed::offsets`' systems are usually far below 2^31, so a product of
/// two residues fits), the same value as the remainder in 128 bits (one division instruction
/// in place of a call to the 128-bit division routine: 0.85% of the Jaco-style arm's
/// `fk --jacobian`, mostly eliminations).
pub(super) fn md(v: i128, m: i64) -> i64 {
    match i64::try_from(v) {
        Ok(w) => w.rem_euclid(m),
        Err(_) => v.rem_euclid(i128::from(m)) as i64,
    }
}

/// `x p + y q (mod m)`, rows with their right-hand side last.
fn combine(x: i64, p: &[i64], y: i64, q: &[i64], m: i64) -> Vec<i64> {
    p.iter()
        .zip(q)
        .map(|(a, b)| {
            md(
                i128::from(x) * i128::from(*a) + i128::from(y) * i128::from(*b),
                m,
            )
        })
        .collect()
}

/// Calls `visit` on every `z` with `0 <= z[s] < ranges[s]` and `a[g] . z = b[g] (mod m)` for
/// every row `g` (each row `ranges.len()` long), in lexicographic order, until it returns
/// false. `Ok(())` when every solution was listed; [`Stop`] says why not. Charges the
/// Context's work budget for the elimination and every value listed.
///
/// # Errors
/// [`Stop::Visitor`] when `visit` returned false, [`Stop::Visits`] past [`MAX_VISITS`],
/// [`Stop::Work`] when the work budget ran out or the Context was cancelled.
///
/// # Panics
/// When `m < 1` or a row's length is not `ranges.len()`.
pub fn solutions(
    a: &[Vec<i64>],
    b: &[i64],
    m: i64,
    ranges: &[i64],
    visit: &mut dyn FnMut(&[i64]) -> bool,
) -> Result<(), Stop> {
    walk(a, b, m, ranges, false, &mut |node| match node {
        Node::Solution(z) => visit(z),
        Node::Prefix(..) => false,
    })
}

/// What [`walk`] shows its visitor.
pub enum Node<'z> {
    /// A solution, as [`solutions`] lists it: the visitor returns false to stop.
    Solution(&'z [i64]),
    /// A proper prefix `z[..k]` before its extensions are listed, with the number of its
    /// extensions that are solutions when the walk may skip them (`None` when it may not): the
    /// visitor returns true to skip them (ignored with `None`).
    Prefix(&'z [i64], Option<u128>),
}

/// [`solutions`], and with `prefixes` each proper prefix `z[..k]` shown to `visit` as
/// [`Node::Prefix`] before its extensions, for every `k` at or past the first length from
/// which every later unknown's range is a multiple of its step (then every prefix the walk
/// meets has as many solutions among its extensions as [`count`] says, `ranges[j] / step` per
/// later unknown `j`, see its proof). A prefix whose extensions are skipped is charged as the
/// values listing them would have been (`c_k + c_k c_{k+1} + ...`, `c_j` the values per later
/// unknown), and may be skipped only when they leave [`MAX_VISITS`] unreached: so the work
/// charged, [`Stop::Visits`] and every other solution listed are those of the walk that lists
/// them all. The prefixes of one length come in lexicographic order, each after the prefixes
/// it extends.
///
/// # Errors
/// As [`solutions`].
///
/// # Panics
/// As [`solutions`].
pub fn walk(
    a: &[Vec<i64>],
    b: &[i64],
    m: i64,
    ranges: &[i64],
    prefixes: bool,
    visit: &mut dyn FnMut(Node) -> bool,
) -> Result<(), Stop> {
    echelon(a, b, m, ranges.len())?.walk(ranges, prefixes, visit)
}

/// A system put in echelon form once (see the module docs), for several uses: its pivots
/// (`None` when it has no solution), its modulus, and the work each step of its elimination
/// charged. Each use after the first charges that work again, step by step
/// ([`Echelon::recharge`]): the work budget sees what eliminating the system afresh for each
/// use charged, and runs out at the same step.
pub struct Echelon {
    pivots: Option<Vec<Option<Pivot>>>,
    m: i64,
    charges: Vec<u64>,
}

/// The system `a z = b (mod m)` in `n` unknowns in echelon form, its elimination charged.
///
/// # Errors
/// [`Stop::Work`] when the work budget ran out or the Context was cancelled.
///
/// # Panics
/// As [`solutions`].
pub fn echelon(a: &[Vec<i64>], b: &[i64], m: i64, n: usize) -> Result<Echelon, Stop> {
    let mut charges = Vec::with_capacity(n);
    let pivots = eliminate(a, b, m, n, &mut charges)?;
    Ok(Echelon { pivots, m, charges })
}

impl Echelon {
    /// Charges the work of the elimination again, step by step as it was charged.
    ///
    /// # Errors
    /// [`Stop::Work`] when the work budget ran out or the Context was cancelled.
    pub fn recharge(&self) -> Result<(), Stop> {
        self.charges
            .iter()
            .try_for_each(|c| charge(*c).map_err(Stop::Work))
    }

    /// [`walk`] of this system, its elimination not charged again (see [`Echelon::recharge`]).
    ///
    /// # Errors
    /// As [`solutions`].
    pub fn walk(
        &self,
        ranges: &[i64],
        prefixes: bool,
        visit: &mut dyn FnMut(Node) -> bool,
    ) -> Result<(), Stop> {
        let Some(pivots) = &self.pivots else {
            return Ok(());
        };
        let below = if prefixes {
            subtrees(pivots, ranges)
        } else {
            vec![None; ranges.len()]
        };
        let mut walk = Walk {
            pivots,
            ranges,
            below,
            m: self.m,
            visits: 0,
            charged: 0,
            z: vec![0; ranges.len()],
        };
        let done = walk.go(0, visit);
        charge((walk.visits - walk.charged) as u64).map_err(Stop::Work)?;
        done
    }

    /// [`count`] of this system, its elimination not charged again (see
    /// [`Echelon::recharge`]).
    pub fn count(&self, ranges: &[i64]) -> Option<u128> {
        let Some(pivots) = &self.pivots else {
            return Some(0);
        };
        let mut n: u128 = 1;
        for (p, &range) in pivots.iter().zip(ranges) {
            let step = p.as_ref().map_or(1, |p| p.step);
            if range < 0 || range % step != 0 {
                return None;
            }
            n = n.saturating_mul((range / step) as u128);
        }
        Some(n)
    }
}

/// For each `i`, the solutions and the values listed under a prefix `z[..=i]`, when every
/// later unknown's range is a multiple of its step (`None` otherwise, and for the last
/// unknown, which has no proper prefix under it): `c_j = ranges[j] / step_j` values of each
/// later unknown `j` under each prefix (see [`count`]), so `prod c_j` solutions and
/// `c_{i+1} (1 + c_{i+2} (1 + ...))` values.
fn subtrees(pivots: &[Option<Pivot>], ranges: &[i64]) -> Vec<Option<(u128, u128)>> {
    let n = ranges.len();
    let mut below = vec![None; n];
    let mut under: Option<(u128, u128)> = Some((1, 0));
    for j in (1..n).rev() {
        let step = pivots[j].as_ref().map_or(1, |p| p.step);
        under = under.and_then(|(count, values)| {
            let c = u128::try_from(ranges[j])
                .ok()
                .filter(|_| ranges[j] % step == 0)?
                / step as u128;
            Some((
                c.saturating_mul(count),
                c.saturating_mul(values.saturating_add(1)),
            ))
        });
        below[j - 1] = under;
    }
    below
}

/// The number of solutions [`solutions`] would list for the same system, without listing
/// them, when every unknown's range is a multiple of its step (`Ok(None)` when one is not).
///
/// Why the count is a product: the elimination keeps, for each unknown `z_j` with a pivot
/// row `p z_j + r . z_{<j} = c` (`g = gcd(p, m)`, step `m / g`), the row `(m / g)` times the
/// pivot row among the rows of the earlier unknowns; that row says exactly that `g` divides
/// `c - r . z_{<j}`. Every other step is a unimodular row operation, which keeps the set of
/// solutions. So every prefix `z_{<j}` that the earlier pivots admit satisfies all the rows
/// in the earlier unknowns, the pivot row of `z_j` is solvable, and its solutions are one
/// residue class modulo the step: `ranges[j] / step` values in `0..ranges[j]` whatever the
/// residue, when the step divides the range. An unknown without a pivot takes all of its
/// `ranges[j]` values. When a row without unknowns is left (`0 = c`, `c != 0`) there is none.
/// Charges the elimination only.
///
/// # Errors
/// [`Stop::Work`] when the work budget ran out or the Context was cancelled.
///
/// # Panics
/// As [`solutions`].
pub fn count(a: &[Vec<i64>], b: &[i64], m: i64, ranges: &[i64]) -> Result<Option<u128>, Stop> {
    Ok(echelon(a, b, m, ranges.len())?.count(ranges))
}

/// The pivots of the system in echelon form (see the module docs), one per unknown (`None`
/// for an unknown that no row holds once the later ones are eliminated); `Ok(None)` when the
/// system has no solution (a row `0 = c` with `c != 0` is left). Each step's charge is pushed
/// to `charges` before it is charged.
fn eliminate(
    a: &[Vec<i64>],
    b: &[i64],
    m: i64,
    n: usize,
    charges: &mut Vec<u64>,
) -> Result<Option<Vec<Option<Pivot>>>, Stop> {
    assert!(m >= 1, "a modulus is positive");
    let mut rows: Vec<Vec<i64>> = a
        .iter()
        .zip(b)
        .map(|(r, c)| {
            assert_eq!(r.len(), n, "one coefficient per unknown");
            r.iter()
                .chain(std::iter::once(c))
                .map(|v| md(i128::from(*v), m))
                .collect()
        })
        .collect();
    rows.sort_unstable();
    rows.dedup();
    let mut pivots: Vec<Option<Pivot>> = (0..n).map(|_| None).collect();
    for j in (0..n).rev() {
        let units = (rows.len() * (n + 1)) as u64;
        charges.push(units);
        charge(units).map_err(Stop::Work)?;
        let mut pivot: Option<Vec<i64>> = None;
        let mut rest: Vec<Vec<i64>> = Vec::with_capacity(rows.len() + 1);
        for row in rows {
            if row[j] == 0 {
                rest.push(row);
                continue;
            }
            let Some(p) = pivot.take() else {
                pivot = Some(row);
                continue;
            };
            // Unimodular: [x y; e/g -a/g] has determinant -1.
            let (pa, e) = (p[j], row[j]);
            let (g, x, y) = ext_gcd(pa, e);
            pivot = Some(combine(x, &p, y, &row, m));
            rest.push(combine(e / g, &p, -(pa / g), &row, m));
        }
        if let Some(p) = pivot {
            let g = gcd(p[j], m);
            let step = m / g;
            // The rows in the earlier unknowns that make the pivot row solvable in z_j.
            rest.push(
                p.iter()
                    .map(|v| md(i128::from(*v) * i128::from(step), m))
                    .collect(),
            );
            let (_, inv, _) = ext_gcd((p[j] / g) % step, step);
            pivots[j] = Some(Pivot {
                r: p[..j].to_vec(),
                c: p[n],
                g,
                step,
                inv: inv.rem_euclid(step),
            });
        }
        rest.retain(|r| r.iter().any(|v| *v != 0));
        rest.sort_unstable();
        rest.dedup();
        rows = rest;
    }
    // What is left has no unknown: `0 = c` with `c != 0`, no solution.
    Ok(rows.is_empty().then_some(pivots))
}

struct Walk<'a> {
    pivots: &'a [Option<Pivot>],
    ranges: &'a [i64],
    /// Under each prefix `z[..=i]` shown to the visitor: its solutions and values (see
    /// [`subtrees`]).
    below: Vec<Option<(u128, u128)>>,
    m: i64,
    visits: usize,
    charged: usize,
    z: Vec<i64>,
}

impl Walk<'_> {
    fn go(&mut self, i: usize, visit: &mut dyn FnMut(Node) -> bool) -> Result<(), Stop> {
        if i == self.z.len() {
            return if visit(Node::Solution(&self.z)) {
                Ok(())
            } else {
                Err(Stop::Visitor)
            };
        }
        let (start, step) = match &self.pivots[i] {
            None => (0, 1),
            Some(p) => {
                let mut v = i128::from(p.c);
                for (r, z) in p.r.iter().zip(&self.z) {
                    v -= i128::from(*r) * i128::from(*z);
                }
                let v = md(v, self.m);
                if v % p.g != 0 {
                    return Ok(());
                }
                let r = md(i128::from(v / p.g) * i128::from(p.inv), p.step);
                (r, p.step)
            }
        };
        let mut v = start;
        while v < self.ranges[i] {
            self.visits += 1;
            if self.visits > MAX_VISITS {
                return Err(Stop::Visits);
            }
            self.charge_due()?;
            self.z[i] = v;
            if !self.skipped(i, visit)? {
                self.go(i + 1, visit)?;
            }
            v += step;
        }
        Ok(())
    }

    /// Shows the prefix `z[..=i]` to the visitor when [`walk`] shows it; whether its
    /// extensions were skipped (then charged as listed, see [`walk`]).
    fn skipped(&mut self, i: usize, visit: &mut dyn FnMut(Node) -> bool) -> Result<bool, Stop> {
        let Some((count, values)) = self.below[i] else {
            return Ok(false);
        };
        let fits = usize::try_from(values)
            .ok()
            .and_then(|v| v.checked_add(self.visits))
            .filter(|v| *v <= MAX_VISITS);
        let offer = fits.map(|_| count);
        if !visit(Node::Prefix(&self.z[..=i], offer)) {
            return Ok(false);
        }
        let Some(visits) = fits else {
            return Ok(false);
        };
        self.visits = visits;
        self.charge_due()?;
        Ok(true)
    }

    /// Charges the visits made since the last charge to the work budget once they reach
    /// [`CHARGE_EVERY`].
    fn charge_due(&mut self) -> Result<(), Stop> {
        if self.visits - self.charged >= CHARGE_EVERY {
            charge((self.visits - self.charged) as u64).map_err(Stop::Work)?;
            self.charged = self.visits;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `md` (the remainder in machine words when the value fits in one) against the remainder
    /// in 128 bits (the old route, kept here), on seeded random values around zero, near the
    /// ends of a machine word and past them, and moduli from 1 to 2^40 and up to `i64::MAX`.
    #[test]
    fn a_residue_in_machine_words_is_the_residue_in_128_bits() {
        let mut next = crate::testing::xorshift_below(0x6d0d_5eed_0000_0001);
        let old = |v: i128, m: i64| v.rem_euclid(i128::from(m)) as i64;
        let (mut words, mut wide) = (0, 0);
        for round in 0..20_000u64 {
            let m = match round % 4 {
                0 => 1 + next(100) as i64,
                1 => 1 + next(1 << 40) as i64,
                2 => i64::MAX - next(3) as i64,
                _ => 1 + next(1 << 20) as i64,
            };
            let small = next(1 << 62) as i128 - (1 << 61);
            let v = match (round / 4) % 5 {
                0 => next(1000) as i128 - 500,
                1 => small,
                2 => i128::from(i64::MIN) + next(4) as i128,
                3 => i128::from(i64::MAX) - next(4) as i128 + next(8) as i128,
                _ => small * (next(1 << 62) as i128 - (1 << 61)),
            };
            if i64::try_from(v).is_ok() {
                words += 1;
            } else {
                wide += 1;
            }
            let r = md(v, m);
            assert_eq!(r, old(v, m), "{v} mod {m}");
            assert!((0..m).contains(&r), "{v} mod {m}");
        }
        assert!(
            words > 10_000 && wide > 4000,
            "{words} in words, {wide} wider"
        );
    }

    fn all(a: &[Vec<i64>], b: &[i64], m: i64, ranges: &[i64]) -> Vec<Vec<i64>> {
        let mut out = Vec::new();
        solutions(a, b, m, ranges, &mut |z| {
            out.push(z.to_vec());
            true
        })
        .expect("complete");
        out
    }

    fn brute(a: &[Vec<i64>], b: &[i64], m: i64, ranges: &[i64]) -> Vec<Vec<i64>> {
        let mut out = Vec::new();
        let mut z = vec![0i64; ranges.len()];
        loop {
            if a.iter().zip(b).all(|(r, c)| {
                (r.iter().zip(&z).map(|(x, y)| x * y).sum::<i64>() - c).rem_euclid(m) == 0
            }) {
                out.push(z.clone());
            }
            // The next z in lexicographic order.
            let mut i = ranges.len();
            loop {
                if i == 0 {
                    return out;
                }
                i -= 1;
                z[i] += 1;
                if z[i] < ranges[i] {
                    break;
                }
                z[i] = 0;
            }
        }
    }

    #[test]
    fn a_sum_and_a_difference_fix_both_unknowns_modulo_the_odd_part() {
        // z0 + z1 = 3, z0 - z1 = 1 (mod 12): 2 z0 = 4, so z0 = 2 or 8.
        let a = vec![vec![1, 1], vec![1, -1]];
        assert_eq!(
            all(&a, &[3, 1], 12, &[12, 12]),
            brute(&a, &[3, 1], 12, &[12, 12])
        );
        assert_eq!(
            all(&a, &[3, 1], 12, &[12, 12]),
            vec![vec![2, 1], vec![8, 7]]
        );
    }

    #[test]
    fn contradictory_rows_have_no_solution() {
        let a = vec![vec![2, 4], vec![1, 2]];
        assert!(all(&a, &[1, 0], 6, &[6, 6]).is_empty());
    }

    /// A random system of `rows` congruences in `n` unknowns modulo `m`: coefficients in
    /// `[-m, m)`, right-hand sides in `[0, m)`, drawn from `next`.
    fn random_system(
        next: &mut impl FnMut(u64) -> u64,
        m: i64,
        n: usize,
        rows: usize,
    ) -> (Vec<Vec<i64>>, Vec<i64>) {
        let a = (0..rows)
            .map(|_| (0..n).map(|_| next(2 * m as u64) as i64 - m).collect())
            .collect();
        let b = (0..rows).map(|_| next(m as u64) as i64).collect();
        (a, b)
    }

    /// `count` against the solutions listed by brute force, on seeded random systems: ranges
    /// that are multiples of the modulus (so of every step: the count is known) and ranges
    /// drawn at random (known only when each step divides its range); both kinds, systems
    /// with and without solutions, all met.
    #[test]
    fn the_count_is_the_number_of_solutions_whenever_it_is_known() {
        let mut next = crate::testing::xorshift_below(0x9e37_79b9_7f4a_7c15);
        let (mut known, mut unknown, mut empty) = (0, 0, 0);
        for round in 0..400 {
            let (m, n) = ([4i64, 6, 8, 9, 12][next(5) as usize], 1 + next(3) as usize);
            let rows = 1 + next(3) as usize;
            let (a, b) = random_system(&mut next, m, n, rows);
            let ranges: Vec<i64> = (0..n)
                .map(|_| {
                    if round % 2 == 0 {
                        m * (1 + next(2) as i64)
                    } else {
                        1 + next(2 * m as u64) as i64
                    }
                })
                .collect();
            let want = brute(&a, &b, m, &ranges).len() as u128;
            match count(&a, &b, m, &ranges).expect("no budget") {
                Some(c) => {
                    assert_eq!(c, want, "a {a:?}, b {b:?}, m {m}, ranges {ranges:?}");
                    known += 1;
                    empty += usize::from(c == 0);
                }
                None => {
                    assert!(round % 2 == 1, "a range that is a multiple of m is known");
                    unknown += 1;
                }
            }
        }
        assert!(
            known > 100 && unknown > 20 && empty > 10,
            "{known} {unknown} {empty}"
        );
    }

    /// `walk` with prefixes, skipping seeded random ones, against brute force: the solutions
    /// listed are those no skipped prefix starts, in order; each skipped prefix's count is
    /// the number of brute-force solutions it starts; every prefix comes before its
    /// extensions.
    #[test]
    fn a_walk_skipping_prefixes_lists_the_other_solutions_and_counts_the_skipped() {
        let mut next = crate::testing::xorshift_below(0x005e_ed0f_91e5_u64);
        let (mut skipped_some, mut offered) = (0, 0);
        for _ in 0..300 {
            let (m, n) = ([4i64, 6, 8, 9, 12][next(5) as usize], 2 + next(3) as usize);
            let rows = 1 + next(2) as usize;
            let (a, b) = random_system(&mut next, m, n, rows);
            let ranges: Vec<i64> = (0..n).map(|_| m * (1 + next(2) as i64)).collect();
            let want = brute(&a, &b, m, &ranges);
            let mut listed: Vec<Vec<i64>> = Vec::new();
            let mut skips: Vec<(Vec<i64>, u128)> = Vec::new();
            walk(&a, &b, m, &ranges, true, &mut |node| match node {
                Node::Solution(z) => {
                    listed.push(z.to_vec());
                    true
                }
                Node::Prefix(p, count) => {
                    assert!(p.len() < n);
                    offered += 1;
                    let c = count.expect("ranges that are multiples of m: skippable");
                    if next(4) == 0 {
                        skips.push((p.to_vec(), c));
                        return true;
                    }
                    false
                }
            })
            .expect("complete");
            let under = |z: &Vec<i64>, p: &Vec<i64>| z[..p.len()] == p[..];
            let kept: Vec<Vec<i64>> = want
                .iter()
                .filter(|z| !skips.iter().any(|(p, _)| under(z, p)))
                .cloned()
                .collect();
            assert_eq!(listed, kept, "a {a:?}, b {b:?}, m {m}, ranges {ranges:?}");
            for (p, c) in &skips {
                let n_under = want.iter().filter(|z| under(z, p)).count() as u128;
                assert_eq!(*c, n_under, "prefix {p:?}");
            }
            skipped_some += usize::from(!skips.is_empty());
        }
        assert!(
            skipped_some > 50 && offered > 500,
            "{skipped_some} {offered}"
        );
    }

    /// What a route of uses of one system lists, counts, and charges: the solutions listed, the
    /// count, and the work budget's answer (`Err` with the work used when it ran out).
    type Used = (
        Vec<Vec<i64>>,
        Option<Option<u128>>,
        Result<u64, ScalarError>,
    );

    /// One system put in echelon form once, walked and then counted with its elimination
    /// charged again, lists, counts and charges what walking and counting it afresh (two
    /// eliminations) does, on seeded random systems, under budgets from none to past the
    /// work: every budget that runs out does so at the same unit with the same work used.
    #[test]
    fn an_echelon_used_twice_charges_what_two_eliminations_charge() {
        let mut next = crate::testing::xorshift_below(0x0ec4_e1a5_7e55_u64);
        let route =
            |a: &[Vec<i64>], b: &[i64], m: i64, ranges: &[i64], budget: u64, once: bool| -> Used {
                let ctx = crate::Context::new().with_work_budget(budget);
                let guard = ctx.enter();
                let mut listed = Vec::new();
                let mut list = |node: Node| {
                    if let Node::Solution(z) = node {
                        listed.push(z.to_vec());
                    }
                    true
                };
                let mut counted = None;
                let mut run = || -> Result<(), Stop> {
                    if once {
                        let e = echelon(a, b, m, ranges.len())?;
                        e.walk(ranges, false, &mut list)?;
                        e.recharge()?;
                        counted = Some(e.count(ranges));
                    } else {
                        walk(a, b, m, ranges, false, &mut list)?;
                        counted = Some(count(a, b, m, ranges)?);
                    }
                    Ok(())
                };
                let used = match run() {
                    Ok(()) => Ok(guard.work_used()),
                    Err(Stop::Work(e)) => Err(e),
                    Err(other) => panic!("{other:?}"),
                };
                (listed, counted, used)
            };
        let (mut ran_out, mut finished) = (0, 0);
        for _ in 0..150 {
            let (m, n) = ([4i64, 6, 8, 9, 12][next(5) as usize], 1 + next(3) as usize);
            let rows = 1 + next(4) as usize;
            let (a, b) = random_system(&mut next, m, n, rows);
            let ranges: Vec<i64> = (0..n).map(|_| m * (1 + next(2) as i64)).collect();
            let Ok(full) = route(&a, &b, m, &ranges, u64::MAX, false).2 else {
                panic!("no budget");
            };
            for budget in [0, 1, full / 3, full / 2, full - 1, full, full + 5] {
                let fresh = route(&a, &b, m, &ranges, budget, false);
                assert_eq!(
                    route(&a, &b, m, &ranges, budget, true),
                    fresh,
                    "a {a:?}, b {b:?}, m {m}, ranges {ranges:?}, budget {budget}"
                );
                ran_out += usize::from(fresh.2.is_err());
                finished += usize::from(fresh.2.is_ok() && !fresh.0.is_empty());
            }
        }
        assert!(ran_out > 300 && finished > 100, "{ran_out} {finished}");
    }
}
