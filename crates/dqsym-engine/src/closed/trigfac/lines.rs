//! The exact screen of [`super::find_factors`]' directions: a direction along which some
//! exponent of the sum has no other exponent on its line cannot carry a factor, at any phase,
//! and is not evaluated in floats (on the Jaco-style arm's Jacobian rows most directions are
//! such).
//!
//! Why: a factor `cos(d.x + phi)` vanishes on the plane `P: d.x + phi = pi/2`, and so does
//! the sum `f = sum_m c_m e^{i m.x}` then. On `P` the exponential `e^{i d.x}` is a constant,
//! so the exponentials of exponents on one line parallel to `d` are proportional there, while
//! those of exponents on distinct lines (distinct projections on the plane orthogonal to `d`)
//! are distinct characters of `P`, linearly independent. `f` vanishes on `P` only when the
//! coefficients of every line cancel at that constant; a line with a single exponent of
//! nonzero coefficient cannot. This holds for every phase, so the direction is skipped at all
//! of them, and it holds for the sum the float search evaluates (its amplitudes the `f64`
//! ones of the waves, its frequencies and phases exact): a skipped direction is one where no
//! phase's plane is a zero set of the sum, where the float test could pass only at a false
//! zero (a value below its tolerance at three generic points of a plane where the sum is not
//! zero), an entry the exact division would then reject.
//!
//! So the search finds what it found before except at such a false zero, which the screen
//! no longer lists: there the entry it listed (and its division's charge, `t.len()` units)
//! is gone, and since [`super::sinusoid_factors`] divides only the first `MAX_FACTORS` entries,
//! a real factor listed after it may now be divided where before it was not. The results and
//! the work charged are the same given no false zero at three generic points on a skipped
//! direction (a value within `1e-9` of the sum's scale at all three, where the sum is not
//! zero on the plane); none was met in the tests or the robots' and corpora's checks.

use super::Wave;
use crate::scalar::Small;

/// The relative size below which a coefficient computed in floats is not taken as surely
/// nonzero: its terms' phases are below 10 in magnitude (a mode's pi offset lies in `[0, 2)`,
/// `Mode`'s invariant), so their cosines and sines are within a few units of `2^-52` each,
/// and the coefficient within about `2^-48` of the sum of its amplitudes, far below it.
const SURE: f64 = 1e-12;

/// The distinct exponents of a sum (each up to sign) and which of them surely have a nonzero
/// coefficient, to tell the directions along which some exponent is alone on its line.
pub(super) struct Lines {
    /// The distinct exponents `m` of the terms, each with its first nonzero entry positive
    /// (the term's `-m` gives the same pair `+-m`), as integers over one common denominator.
    exps: Vec<Vec<i64>>,
    /// Whether the coefficient of `e^{i m.x}` (the sum of the terms' `amp e^{+-i phase}/2`)
    /// is surely nonzero; never for `m = 0`.
    sure: Vec<bool>,
    /// The common denominator of `exps`.
    den: i64,
}

impl Lines {
    /// The lines of the terms' exponents with their waves `ws`, from the exponents `+m, -m`
    /// of each term in turn as integers over one common denominator ([`super::integer_exponents`]
    /// of [`super::find_factors`]' signed exponents); `None` without them (then nothing is
    /// skipped).
    pub(super) fn new(signed: Option<&(Vec<Vec<i64>>, i64)>, ws: &[Wave]) -> Option<Lines> {
        let (ints, den) = signed?;
        let mut out: Vec<Vec<i64>> = Vec::new();
        // Per distinct exponent: the coefficient's real and imaginary parts (doubled) and the
        // sum of the amplitudes it was made of.
        let mut coef: Vec<(f64, f64, f64)> = Vec::new();
        for (e, w) in ints.iter().step_by(2).zip(ws) {
            let (e, sign) = match e.iter().find(|k| **k != 0) {
                Some(k) if *k < 0 => (e.iter().map(|k| -k).collect(), -1.0),
                _ => (e.clone(), 1.0),
            };
            // amp cos(m.x + phase) = amp/2 (e^{i(m.x + phase)} + e^{-i(m.x + phase)}): the
            // coefficient of e^{i m.x} is amp/2 e^{i phase}, that of e^{-i m.x} its conjugate.
            let (sin, cos) = w.phase.sin_cos();
            let add = (w.amp * cos, sign * w.amp * sin, w.amp.abs());
            match out.iter().position(|x| *x == e) {
                Some(i) => {
                    let c = &mut coef[i];
                    (c.0, c.1, c.2) = (c.0 + add.0, c.1 + add.1, c.2 + add.2);
                }
                None => {
                    out.push(e);
                    coef.push(add);
                }
            }
        }
        let sure = out
            .iter()
            .zip(&coef)
            .map(|(e, (re, im, abs))| {
                e.iter().any(|k| *k != 0) && abs.is_finite() && re.hypot(*im) > SURE * abs
            })
            .collect();
        Some(Lines {
            exps: out,
            sure,
            den: *den,
        })
    }

    /// Whether along `d` some exponent of surely nonzero coefficient is alone on its line
    /// among all the exponents `+-m` (see the module doc: then no phase carries a factor of
    /// direction `d`). `false` when that is not decided in machine integers.
    pub(super) fn lonely_along(&self, d: &[Small]) -> bool {
        // `d` has denominators dividing `2 den` (halves of differences of the exponents):
        // `2 den d` in integers (only its line matters).
        let Some(two_den) = self.den.checked_mul(2) else {
            return false;
        };
        let mut dir: Vec<i64> = Vec::with_capacity(d.len());
        for k in d {
            match (
                two_den % k.denom(),
                k.numer().checked_mul(two_den / k.denom()),
            ) {
                (0, Some(k)) => dir.push(k),
                _ => return false,
            }
        }
        // Two exponents lie on one line parallel to `dir` exactly when their keys
        // `(dir.dir) m - (m.dir) dir` (the projection orthogonal to `dir`, scaled) are equal;
        // `-m`'s key is the negated key of `m`. In checked `i64`: the entries are small.
        let dot = |e: &[i64]| {
            e.iter()
                .zip(&dir)
                .try_fold(0i64, |s, (a, b)| s.checked_add(a.checked_mul(*b)?))
        };
        let Some(norm) = dot(&dir) else {
            return false;
        };
        let n = dir.len();
        let mut keys: Vec<i64> = Vec::with_capacity(self.exps.len() * n);
        for e in &self.exps {
            let Some(m) = dot(e) else {
                return false;
            };
            for (a, b) in e.iter().zip(&dir) {
                let Some(k) = norm
                    .checked_mul(*a)
                    .and_then(|x| x.checked_sub(m.checked_mul(*b)?))
                else {
                    return false;
                };
                keys.push(k);
            }
        }
        let key = |i: usize| &keys[i * n..(i + 1) * n];
        (0..self.exps.len()).any(|i| {
            let ki = key(i);
            // Alone: `-m` is not on its line (the key is not zero: `m` is not along `dir`),
            // and no other exponent `+-m'` is (the exponents are distinct up to sign).
            self.sure[i]
                && ki.iter().any(|k| *k != 0)
                && (0..self.exps.len()).all(|j| {
                    let kj = key(j);
                    j == i || (kj != ki && kj.iter().zip(ki).any(|(a, b)| *a != -*b))
                })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{
        directions, exponents, find_factors, integer_exponents, on_plane, surely_above, value,
        waves, Points, Wave, PHASES,
    };
    use super::*;
    use crate::Scalar;
    use num_rational::BigRational;
    use num_traits::{ToPrimitive, Zero};

    /// `find_factors` as it was before the screen, the reference the test below compares with:
    /// every direction evaluated in floats.
    fn unscreened(exps: &[Vec<Small>], ws: &[Wave], n: usize) -> Vec<(Vec<Small>, i64)> {
        let signed: Vec<Vec<Small>> = exps
            .iter()
            .flat_map(|e| [e.clone(), e.iter().map(|k| -*k).collect()])
            .collect();
        let dirs = directions(&signed, n);
        let scale: f64 = ws.iter().map(|w| w.amp.abs()).sum();
        let tol = 1e-9 * scale;
        let mut pts = Points(0x2545_f491_4f6c_dd1d);
        let bases: Vec<Vec<f64>> = (0..3).map(|_| pts.point(n)).collect();
        let mut found = Vec::new();
        for d in dirs {
            let df: Vec<f64> = d.iter().map(|k| k.to_f64().unwrap_or(0.0)).collect();
            let dd: f64 = df.iter().map(|k| k * k).sum();
            let surely = surely_above(ws, &bases[0], &df, dd, tol);
            for (k, surely) in (0..PHASES).zip(surely) {
                if !surely
                    && bases
                        .iter()
                        .all(|b| value(ws, &on_plane(b, &df, dd, k)).abs() <= tol)
                {
                    found.push((d.clone(), k));
                }
            }
        }
        found
    }

    fn q(n: i64, d: i64) -> Scalar {
        Scalar::rational(BigRational::new(n.into(), d.into()))
    }

    /// A random sinusoid `cos` or `sin` of `sum k_s s + j pi/12` over the first `n` of four
    /// angle symbols, coefficients `k_s` in `{-2, ..., 2}` over 1 or 2.
    fn sinusoid(next: &mut impl FnMut(u64) -> u64, n: usize) -> Scalar {
        let mut a = q(next(24) as i64, 12) * Scalar::pi();
        for s in ["a", "b", "c", "e"].into_iter().take(n) {
            a = a + q(next(5) as i64 - 2, 1 + next(2) as i64) * Scalar::sym(s);
        }
        if next(2) == 0 {
            a.cos()
        } else {
            a.sin()
        }
    }

    /// A random coefficient: a small rational, times `sqrt(3)` or a length `l` at times.
    fn weight(next: &mut impl FnMut(u64) -> u64) -> Scalar {
        let c = q(next(7) as i64 - 3, 1 + next(3) as i64);
        let c = if c.is_zero() { Scalar::int(1) } else { c };
        match next(4) {
            0 => c * Scalar::int(3).sqrt(),
            1 => c * Scalar::sym("l"),
            _ => c,
        }
    }

    /// A random weight times a product of `least` or `least + 1` random sinusoids.
    fn product(next: &mut impl FnMut(u64) -> u64, n: usize, least: u64) -> Scalar {
        let k = least + next(2);
        (0..k).fold(weight(next), |x, _| x * sinusoid(next, n))
    }

    /// With the screen, `find_factors` finds exactly what it found without it, on seeded
    /// random sums: products of two or three sinusoids (so factors exist, some of several
    /// symbols), the same products with one term dropped or another product of comparable
    /// size added (near misses: a factor's direction still among the exponents' differences),
    /// and plain sums of sinusoids; and the screen skips many of their directions.
    #[test]
    fn the_screened_search_finds_what_the_unscreened_one_found() {
        let mut next = crate::testing::xorshift_below(0x11e5_a10e_5ca1_0001);
        let (mut sums, mut factors, mut skipped, mut tried) = (0, 0, 0, 0);
        for round in 0..600 {
            let n = 2 + next(3) as usize;
            let x = match round % 4 {
                0 => product(&mut next, n, 2),
                1 => {
                    let x = product(&mut next, n, 2);
                    let Ok(t) = x.terms() else { continue };
                    let drop = next(t.len().max(1) as u64) as usize;
                    Scalar::from_terms_sorted(
                        t.iter()
                            .enumerate()
                            .filter(|(i, _)| *i != drop)
                            .map(|(_, u)| u.clone())
                            .collect(),
                    )
                }
                2 => product(&mut next, n, 2) + product(&mut next, n, 1),
                _ => (0..2 + next(6)).fold(Scalar::zero(), |s, _| {
                    s + weight(&mut next) * sinusoid(&mut next, n)
                }),
            };
            let Ok(t) = x.terms() else { continue };
            if t.len() < 2 || t.len() > super::super::MAX_TERMS {
                continue;
            }
            let (syms, exps) = exponents(t);
            let Some(ws) = waves(t, &exps) else { continue };
            let n = syms.len();
            if n == 0 {
                continue;
            }
            let got = find_factors(&exps, &ws, n);
            assert_eq!(got, unscreened(&exps, &ws, n), "round {round}: {x:?}");
            sums += 1;
            factors += got.len();
            let signed: Vec<Vec<Small>> = exps
                .iter()
                .flat_map(|e| [e.clone(), e.iter().map(|k| -*k).collect()])
                .collect();
            if let Some(l) = Lines::new(integer_exponents(&signed).as_ref(), &ws) {
                for d in directions(&signed, n) {
                    tried += 1;
                    skipped += usize::from(l.lonely_along(&d));
                }
            }
        }
        assert!(sums > 400, "sums compared ({sums})");
        assert!(factors > 200, "factors found ({factors})");
        assert!(
            skipped * 2 > tried,
            "directions skipped ({skipped} of {tried})"
        );
    }
}
