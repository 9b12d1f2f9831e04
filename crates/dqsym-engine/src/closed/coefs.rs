//! Constant coefficients lifted out of the angles: a scalar whose symbolic modes carry pi
//! offsets outside the multiples of pi/12 and no common shift (`offsets.rs`) that absorbs them
//! holds its constants inside its angles: `sin(pi/7) cos(pi/9) cos(q)` is canonically a sum of
//! `cos(q +- k pi/63)` and `sin(q +- k pi/63)` with radical coefficients. Written back in
//! `cos F` and `sin F` of the offset-free angles `F` (`cos(F + a) = cos F cos a - sin F sin a`),
//! its coefficients are constants of the cyclotomic field; each distinct one (up to a rational
//! factor) outside the multiples of pi/12 stands in for a fresh symbol `K_i`, the scalar in
//! those symbols goes through the offset-free path (regrouped, factored), and each `K_i` is
//! replaced by the closed form of its constant (a product `sin(pi/7) cos(pi/9)` where the
//! constant is one, see `cprod.rs`). The result is kept when shorter, after the exact check
//! every closed form gets.

use super::expr::Expr;
use crate::scalar::atoms::{empty_mono, Freq};
use crate::scalar::{Mode, MonoRc, Small, Sym, Term, Q};
use crate::Scalar;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::collections::hash_map::Entry;
use std::collections::BTreeMap;

/// A hash map under the crate's FxHash (std's SipHash was 1.4% of the Jaco-style arm's
/// `fk --jacobian`, most of it here); for maps whose order reaches no output.
type FxMap<K, V> =
    std::collections::HashMap<K, V, std::hash::BuildHasherDefault<crate::scalar::FxHasher>>;

/// The most terms a scalar may have for its constants to be lifted.
const MAX_TERMS: usize = 4096;

/// The most distinct constants lifted into symbols.
const MAX_CONSTANTS: usize = 8;

/// The prefix of the fresh symbols' names (not a name the parser reads).
const PREFIX: &str = "~K";

/// A scalar in fresh symbols and the constant each symbol stands for.
pub(crate) struct Lifted {
    pub(crate) scalar: Scalar,
    constants: Vec<(Sym, Expr, BigRational)>,
}

/// Whether some coefficient of `cos F` or `sin F` (or the amplitude of the two) may be a
/// short product of constant cosines and sines, tested in f64 before the constants are
/// computed exactly (which costs arithmetic in a large field for every term).
fn worth_lifting(terms: &[Term]) -> bool {
    type Key<'a> = (&'a MonoRc, &'a [(Sym, Small)], bool);
    let mut values: BTreeMap<Key, f64> = BTreeMap::new();
    let (mut n, mut l) = (24i64, 1i64);
    for t in terms {
        let Some(c) = t.coef.to_f64() else {
            return false;
        };
        let v = c * (t.rad as f64).sqrt();
        let p = *t.mode.pi.numer() as f64 / *t.mode.pi.denom() as f64;
        let (ca, sa) = (
            (p * std::f64::consts::PI).cos(),
            (p * std::f64::consts::PI).sin(),
        );
        n = n.lcm(&(2 * t.mode.pi.denom()));
        l = l.lcm(t.mode.pi.denom());
        let key = |sin: bool| (&t.mono, &*t.mode.freq, sin);
        if t.mode.freq.is_empty() {
            *values.entry(key(false)).or_default() += v * if t.mode.sin { sa } else { ca };
        } else if t.mode.sin {
            *values.entry(key(true)).or_default() += v * ca;
            *values.entry(key(false)).or_default() += v * sa;
        } else {
            *values.entry(key(false)).or_default() += v * ca;
            *values.entry(key(true)).or_default() -= v * sa;
        }
    }
    if n > 20_000 {
        return false;
    }
    let mut all: Vec<f64> = values.values().copied().collect();
    let keys: Vec<_> = values.keys().collect();
    for w in keys.windows(2) {
        if !w[0].2 && w[1].2 && w[0].0 == w[1].0 && w[0].1 == w[1].1 {
            all.push(values[w[0]].hypot(values[w[1]]));
        }
    }
    super::cprod::may_be_small_product(&all, n, l)
}

/// A term's rational and radical, `coef sqrt(rad)`, as a constant scalar.
fn constant_of(t: &Term) -> Scalar {
    Scalar::from_terms(vec![Term {
        mode: Mode::unit(),
        mono: empty_mono(),
        rad: t.rad,
        coef: t.coef.clone(),
    }])
}

/// The monomial `mono` as a scalar.
fn monomial(mono: MonoRc) -> Scalar {
    Scalar::from_terms(vec![Term {
        mode: Mode::unit(),
        mono,
        rad: 1,
        coef: Q::ONE,
    }])
}

/// `cos F` (or `sin F`) of an offset-free frequency vector `F`; `1` for the empty one.
fn offset_free(freq: &Freq, sin: bool) -> Scalar {
    if freq.is_empty() {
        return Scalar::int(1);
    }
    Scalar::from_terms(vec![Term {
        mode: Mode {
            sin,
            freq: freq.clone(),
            pi: Small::zero(),
        },
        mono: empty_mono(),
        rad: 1,
        coef: Q::ONE,
    }])
}

/// `cos(p pi)` (or `sin`), canonical.
fn trig_pi(p: Small, sin: bool) -> Scalar {
    let a = Scalar::pi() * Scalar::from_q(Q::new(*p.numer(), *p.denom()));
    if sin {
        a.sin()
    } else {
        a.cos()
    }
}

/// The values of [`trig_pi`] found during one [`lift`]: its terms share a few offsets (the
/// Jaco-style arm's pose entries, hundreds of terms at multiples of pi/18), and each value
/// costs a canonicalization in the cyclotomic field (a quarter of `lift`'s instructions).
/// Error values (a limit reached) are not kept. Keyed by the offset's numerator and
/// denominator as they stand (`Ratio`'s own `Hash` walks the continued fraction, a division
/// per step; `Small` arithmetic reduces, as do the `Small::new_raw` sites of the offsets
/// (`reduce2`, `centred`, `dot_of_pairs`, `small_add`), and an unreduced key would only
/// miss, its value made again from the same offset) under
/// FxHash: the table is only looked up, never iterated, so the hasher reaches no output.
#[derive(Default)]
struct TrigPi(FxMap<(i64, i64, bool), Scalar>);

impl TrigPi {
    fn get(&mut self, p: Small, sin: bool) -> Scalar {
        let key = (*p.numer(), *p.denom(), sin);
        if let Some(v) = self.0.get(&key) {
            return v.clone();
        }
        let v = trig_pi(p, sin);
        if v.as_error().is_none() {
            self.0.insert(key, v.clone());
        }
        v
    }
}

/// The angle `F - phi pi`, `F` a frequency vector (its constant entry included).
fn angle(freq: &Freq, phi: Small) -> Scalar {
    let mut a = -(Scalar::pi() * Scalar::from_q(Q::new(*phi.numer(), *phi.denom())));
    for (s, k) in freq.iter() {
        let k = Scalar::from_q(Q::new(*k.numer(), *k.denom()));
        a = a + if s.is_one() {
            k
        } else {
            Scalar::sym(s.name()) * k
        };
    }
    a
}

/// `phi` (a multiple of `pi/(2n)`, over `pi`) and `R` with `A = R cos(phi pi)`,
/// `B = R sin(phi pi)`, when there is one: `phi` found numerically from `atan2(B, A)` and
/// checked exactly (`A sin phi = B cos phi`); `R = A cos phi + B sin phi`.
fn phase(a: &Scalar, b: &Scalar, n: i64, trig: &mut TrigPi) -> Option<(Small, Scalar)> {
    let value = |c: &Scalar| c.eval_symbols(&|_| None).ok();
    let (va, vb) = (value(a)?, value(b)?);
    if va.hypot(vb) < 1e-12 {
        return None;
    }
    let m = 2 * n;
    let k = (vb.atan2(va) / std::f64::consts::PI * m as f64).round() as i64;
    let phi = Small::new(k, m);
    let (c, s) = (trig.get(phi, false), trig.get(phi, true));
    crate::scalar::charge(a.len() as u64 + b.len() as u64).ok()?;
    if a.clone() * s.clone() != b.clone() * c.clone() {
        return None;
    }
    Some((phi, a.clone() * c + b.clone() * s))
}

/// Whether the canonical constant `c` lies outside the field of the multiples of pi/12 (it
/// has a term with a pi offset).
fn outside_twelfths(c: &Scalar) -> bool {
    c.terms()
        .is_ok_and(|t| t.iter().any(|t| !t.mode.pi.is_zero()))
}

/// What the two liftings of one scalar (joined into phases or not) share: the constant
/// coefficient of each (monomial, angle, cos or sin), and the values of `cos(p pi)` found on
/// the way. Computed once for both ([`Lifting::lift`]): the Jaco-style arm's `fk --jacobian`
/// computed them twice per pose entry.
pub(crate) struct Lifting {
    coefs: BTreeMap<Key, Scalar>,
    n: i64,
    trig_pi: TrigPi,
    /// Whether the phased lifting found every constant inside the multiples of pi/12 (see
    /// [`Lifting::lift`]): the unphased one is then not made.
    phases_inside: bool,
}

impl Lifting {
    /// The coefficients of `x` when it has a symbolic mode with a pi offset and they may be
    /// short products of constant cosines and sines (`worth_lifting`); `None` otherwise.
    pub(crate) fn new(x: &Scalar) -> Option<Lifting> {
        let terms = x.terms().ok()?;
        let symbolic = |t: &Term| t.mode.freq.iter().any(|(s, _)| !s.is_one());
        // Not for a constant (whose closed form is the one each lifted symbol is replaced by).
        let offsets = terms.iter().any(|t| !t.mode.pi.is_zero());
        let symbols = terms.iter().any(|t| symbolic(t) || !t.mono.is_empty());
        if !offsets || !symbols || terms.len() > MAX_TERMS {
            return None;
        }
        crate::scalar::charge(terms.len() as u64).ok()?;
        // Neither lifting can lift anything (see `phases_inside`): the unphased one is not
        // made when the phased one lifts nothing (`lift`), and the phased one lifts nothing.
        if phases_inside(terms) {
            return None;
        }
        let n = terms
            .iter()
            .fold(12i64, |acc, t| acc.lcm(t.mode.pi.denom()));
        if !worth_lifting(terms) {
            return None;
        }
        let mut trig_pi = TrigPi::default();
        let coefs = coefficients(terms, &mut trig_pi);
        Some(Lifting {
            coefs,
            n,
            trig_pi,
            phases_inside: false,
        })
    }

    /// The scalar with its constants lifted (see the module docs), the two coefficients of
    /// one angle joined into `R cos(F - phi)` when `phased`; `None` when no constant outside
    /// the multiples of pi/12 is left once the offsets are taken out of the angles.
    ///
    /// Called phased first, the unphased lifting is not made when the phased one left no
    /// constant outside the multiples of pi/12 (the Jaco-style arm's entries, offsets at
    /// multiples of 5 pi/18): every (monomial, angle) of the scalar is then `R cos(F - phi)`
    /// with `R` inside them, or a pair of such constants, and the unphased lifting would only
    /// write each `cos(F - phi)` back as `cos(phi) cos(F) + sin(phi) sin(F)`, two products and
    /// two constant calls where the scalar has one sinusoid, whose offset the shifted search
    /// (`offsets.rs`) or the search of the scalar itself already shows in its angle.
    pub(crate) fn lift(&mut self, phased: bool) -> Option<Lifted> {
        if !phased && self.phases_inside {
            return None;
        }
        let items = items(self.coefs.clone(), phased, self.n, &mut self.trig_pi)?;
        let (norms, uses) = normalized(items)?;
        if phased && norms.is_empty() {
            self.phases_inside = true;
        }
        // Many distinct constants: nothing reads shorter (each would be a sum of its own).
        if norms.is_empty() || norms.len() > MAX_CONSTANTS {
            return None;
        }
        let (constants, symbol) = products(&norms)?;
        let scalar = assemble(uses, &norms, &constants, &symbol)?;
        Some(Lifted { scalar, constants })
    }
}

/// Whether the phased lifting ([`Lifting::lift`]) of a scalar of `terms` is sure to leave
/// no constant outside the multiples of pi/12, decided from the terms alone, without the
/// arithmetic in the cyclotomic field the lifting does (the Jaco-style arm's pose entries,
/// whose offsets are multiples of 5 pi/18: a fifth of its `fk --jacobian`).
///
/// The phased lifting joins the terms of one (monomial, angle `F`) into `R cos(F - phi)` and
/// lifts `R` when it lies outside those multiples, or, when `phi` is not a rational multiple
/// of pi, lifts the coefficients of `cos F` and `sin F`. A term is `c cos(F + p pi)` (a sine
/// is the cosine at `p - 1/2`), `c = q sqrt(r)` a rational times a square root. True when no
/// constant term carries an offset and each (monomial, angle) holds
/// - one term: `R = |c|`, `phi = -p pi`;
/// - two terms at offsets `p1`, `p2` with `p2 - p1` a multiple of 1 (`R = |c1 +- c2|`, a sum
///   of square roots, `phi` as for one term; the amplitude checked to be far from 0, where the
///   lifting would find no phase), or an odd multiple of 1/2: then `c1 cos X -+ c2 sin X` with
///   `X = F + p1 pi` has a phase `psi` that is a rational multiple of pi exactly when
///   `tan^2 psi = c2^2/c1^2` is 1/3, 1 or 3 (Niven: `cos 2 psi = (1 - t^2)/(1 + t^2)` is then
///   rational, so `2 psi` is a multiple of pi/3 or pi/2), and `R = sqrt(c1^2 + c2^2)` is the
///   square root of a rational.
///
/// In each case `R` has no term with an offset and `phi` is a multiple of `pi/(2n)` (the
/// offsets' denominators divide `n`, a multiple of 12), which `phase` finds and checks.
fn phases_inside(terms: &[Term]) -> bool {
    type Group<'a> = (&'a MonoRc, &'a Freq);
    // FxHash: the groups are only tested all together (`all` of a pure predicate), so their
    // order reaches no output.
    let mut groups: FxMap<Group, (&Term, Option<&Term>)> =
        FxMap::with_capacity_and_hasher(terms.len(), Default::default());
    for t in terms {
        if t.mode.freq.is_empty() {
            if !t.mode.pi.is_zero() {
                return false;
            }
            continue;
        }
        match groups.entry((&t.mono, &t.mode.freq)) {
            Entry::Vacant(v) => {
                v.insert((t, None));
            }
            Entry::Occupied(mut o) => {
                if o.get().1.is_some() {
                    return false;
                }
                o.get_mut().1 = Some(t);
            }
        }
    }
    // The offset of a term as a cosine's, and `c^2 = q^2 r`.
    let offset = |t: &Term| {
        if t.mode.sin {
            t.mode.pi - Small::new(1, 2)
        } else {
            t.mode.pi
        }
    };
    let value = |t: &Term| t.coef.to_f64().map(|q| q * (t.rad as f64).sqrt());
    // Far from the 1e-12 below which `phase` finds none (`R >= |c|` for one term and for two
    // at right angles).
    let audible = |v: f64| v.abs() > 1e-9;
    groups.values().all(|&(a, b)| {
        let Some(b) = b else {
            return a.mode.pi.is_zero() || value(a).is_some_and(audible);
        };
        if a.mode.pi.is_zero() && b.mode.pi.is_zero() {
            // Both coefficients inside already, phased or not.
            return true;
        }
        let d = (offset(b) - offset(a)) * Small::from_integer(2);
        if !d.is_integer() {
            return false;
        }
        if d.numer().rem_euclid(2) == 0 {
            // Collinear: `(c1 +- c2) cos X`, the amplitude far from the lifting's 1e-12.
            let (Some(va), Some(vb)) = (value(a), value(b)) else {
                return false;
            };
            let r = (va + vb).abs().min((va - vb).abs());
            return audible(r) && r > 1e-6 * (va.abs() + vb.abs());
        }
        if !value(a).is_some_and(audible) || !value(b).is_some_and(audible) {
            return false;
        }
        square_ratio_in(
            (&a.coef, a.rad),
            (&b.coef, b.rad),
            &[(1, 1), (3, 1), (1, 3)],
        )
    })
}

/// Whether the ratio `c_b^2 / c_a^2` of the squares of two nonzero coefficients `c = q
/// sqrt(r)`, given as `(q, r)`, is one of `ratios` (`(num, den)` pairs): cross-multiplied in
/// 128-bit words when they hold the products (the Jaco-style arm's coefficients:
/// `sqrt(3)/4`, `1/2`), in big rationals otherwise (each a few hundred instructions more: 2%
/// of that arm's `fk --jacobian`).
fn square_ratio_in(a: (&Q, u64), b: (&Q, u64), ratios: &[(u8, u8)]) -> bool {
    // `n^2 r` and `d^2` of a coefficient `n / d` times `sqrt(r)`.
    let words = |(q, r): (&Q, u64)| -> Option<(u128, u128)> {
        let q = q.to_ratio_i64()?;
        let (n, d) = (q.numer().unsigned_abs(), q.denom().unsigned_abs());
        let n2 = u128::from(n).checked_mul(u128::from(n))?;
        Some((
            n2.checked_mul(u128::from(r))?,
            u128::from(d) * u128::from(d),
        ))
    };
    let small = || -> Option<bool> {
        let ((na, da), (nb, db)) = (words(a)?, words(b)?);
        // c_b^2 / c_a^2 = (nb da) / (db na).
        let (x, y) = (nb.checked_mul(da)?, db.checked_mul(na)?);
        let mut any = false;
        for &(p, q) in ratios {
            any |= x.checked_mul(u128::from(q))? == y.checked_mul(u128::from(p))?;
        }
        Some(any)
    };
    small().unwrap_or_else(|| {
        let square = |(q, r): (&Q, u64)| {
            let q = q.to_big();
            &q * &q * BigRational::from_integer(r.into())
        };
        let t = square(b) / square(a);
        ratios
            .iter()
            .any(|&(p, q)| t == BigRational::new(p.into(), q.into()))
    })
}

/// A coefficient's place: (monomial, offset-free angle, sine).
type Key = (MonoRc, Freq, bool);

/// (monomial, trigonometric factor, constant).
type Item = (MonoRc, Scalar, Scalar);

/// (monomial, trigonometric factor, the constant's index among the normalized constants and
/// its rational factor, or the constant itself).
type Use = (MonoRc, Scalar, Result<(usize, BigRational), Scalar>);

/// A lifted constant: its symbol, closed form and rational factor.
type Constant = (Sym, Expr, BigRational);

/// The constant coefficient of each (monomial, angle, cos or sin).
/// Each coefficient's parts are gathered as terms and made canonical once, at the end:
/// adding them one by one rewrote the growing sum in its cyclotomic basis at every step
/// (the Jaco-style arm's `fk --jacobian` spent 43% of its instructions there).
fn coefficients(terms: &[Term], trig_pi: &mut TrigPi) -> BTreeMap<Key, Scalar> {
    let mut parts: BTreeMap<Key, Result<Vec<Term>, Scalar>> = BTreeMap::new();
    for t in terms {
        let c = constant_of(t);
        let mut add = |sin: bool, k: Scalar| {
            let e = parts
                .entry((t.mono.clone(), t.mode.freq.clone(), sin))
                .or_insert_with(|| Ok(Vec::new()));
            if let Ok(v) = e {
                match k.terms() {
                    Ok(kt) => v.extend_from_slice(kt),
                    // An error value stays the sum's value, as it would in `+`.
                    Err(_) => *e = Err(k),
                }
            }
        };
        if t.mode.freq.is_empty() || t.mode.pi.is_zero() {
            let k = if t.mode.freq.is_empty() {
                // A constant term: its mode is the constant cos/sin.
                let mut u = t.clone();
                u.mono = empty_mono();
                Scalar::from_terms(vec![u])
            } else {
                c
            };
            add(t.mode.sin && !t.mode.freq.is_empty(), k);
            continue;
        }
        // cos(F + a) = cos F cos a - sin F sin a; sin(F + a) = sin F cos a + cos F sin a.
        let (ca, sa) = (trig_pi.get(t.mode.pi, false), trig_pi.get(t.mode.pi, true));
        if t.mode.sin {
            add(true, c.clone() * ca);
            add(false, c * sa);
        } else {
            add(false, c.clone() * ca);
            add(true, -(c * sa));
        }
    }
    parts
        .into_iter()
        .map(|(k, v)| (k, v.map_or_else(|e| e, Scalar::from_terms)))
        .collect()
}

/// Each (monomial, angle) as one cosine `cos(F - phi)` when its two coefficients are
/// `R cos(phi)` and `R sin(phi)` with `phi` a rational multiple of pi (`phased`), else as
/// `A cos F + B sin F`: (monomial, trigonometric factor, constant).
fn items(
    coefs: BTreeMap<Key, Scalar>,
    phased: bool,
    n: i64,
    trig_pi: &mut TrigPi,
) -> Option<Vec<Item>> {
    let mut items: Vec<(MonoRc, Scalar, Scalar)> = Vec::with_capacity(coefs.len());
    let mut coefs = coefs.into_iter().peekable();
    while let Some(((mono, freq, sin), c)) = coefs.next() {
        if freq.is_empty() {
            items.push((mono, Scalar::int(1), c));
            continue;
        }
        let trig = |sin: bool| offset_free(&freq, sin);
        // The keys are sorted: the sine of the same angle and monomial follows the cosine.
        let pair = !sin
            && coefs
                .peek()
                .is_some_and(|((m, f, s), _)| *s && *m == mono && *f == freq);
        if phased && (pair || outside_twelfths(&c)) {
            let (a, b) = if pair {
                let (_, b) = coefs.next()?;
                (c, b)
            } else if sin {
                (Scalar::int(0), c)
            } else {
                (c, Scalar::int(0))
            };
            if let Some((phi, r)) = phase(&a, &b, n, trig_pi) {
                items.push((mono, angle(&freq, phi).cos(), r));
            } else {
                items.push((mono.clone(), trig(false), a));
                items.push((mono, trig(true), b));
            }
            continue;
        }
        items.push((mono, trig(sin), c));
    }
    Some(items)
}

/// Each constant outside the multiples of pi/12, up to a rational factor, one symbol:
/// normalized by its first term's rational coefficient (`lead`).
fn normalized(items: Vec<Item>) -> Option<(Vec<Vec<Term>>, Vec<Use>)> {
    let mut norms: Vec<Vec<Term>> = Vec::new();
    // Only looked up (the constants are numbered in `items`' order): FxHash.
    let mut index: FxMap<Vec<Term>, usize> = Default::default();
    let mut uses: Vec<Use> = Vec::new();
    for (mono, trig, c) in items {
        let ct = c.terms().ok()?;
        if ct.is_empty() {
            continue;
        }
        if !outside_twelfths(&c) {
            uses.push((mono, trig, Err(c)));
            continue;
        }
        let lead = ct[0].coef.to_big();
        let norm: Vec<Term> = ct
            .iter()
            .map(|u| {
                let mut u = u.clone();
                u.coef = Q::big(u.coef.to_big() / &lead);
                u
            })
            .collect();
        let i = *index.entry(norm).or_insert_with_key(|norm| {
            norms.push(norm.clone());
            norms.len() - 1
        });
        uses.push((mono, trig, Ok((i, lead))));
    }
    Some((norms, uses))
}

/// The normalized constants that are products of one or two cosines and sines (with a
/// rational and radical factor), each lifted into a symbol standing for its product without
/// the rational factor (`sin(pi/7) cos(pi/9)`, not `-12/17 sin(pi/7) cos(pi/9)`), and for each
/// constant its symbol's index (`None`: the constant stays). `None` when none is lifted.
fn products(norms: &[Vec<Term>]) -> Option<(Vec<Constant>, Vec<Option<usize>>)> {
    let mut constants: Vec<(Sym, Expr, BigRational)> = Vec::with_capacity(norms.len());
    let mut symbol: Vec<Option<usize>> = Vec::with_capacity(norms.len());
    for norm in norms {
        crate::scalar::charge(norm.len() as u64).ok()?;
        symbol.push(product_form(norm).map(|e| {
            let (r, form) = rational_factor(e);
            constants.push((Sym::new(&format!("{PREFIX}{}", constants.len())), form, r));
            constants.len() - 1
        }));
    }
    (!constants.is_empty()).then_some((constants, symbol))
}

/// The lifted scalar: each use's monomial, trigonometric factor and constant (its symbol
/// where it has one). The sum's terms are gathered and made canonical once (the growing sum
/// was rewritten in its cyclotomic basis at every step: 29% of the Jaco-style arm's
/// `fk --jacobian`).
fn assemble(
    uses: Vec<Use>,
    norms: &[Vec<Term>],
    constants: &[Constant],
    symbol: &[Option<usize>],
) -> Option<Scalar> {
    let mut out: Vec<Term> = Vec::new();
    for (mono, trig, c) in uses {
        let m = monomial(mono);
        let k = match c {
            Err(c) => c,
            Ok((i, lead)) => match symbol[i] {
                Some(k) => {
                    let (sym, _, r) = &constants[k];
                    Scalar::rational(lead * r) * Scalar::sym(sym.name())
                }
                None => Scalar::rational(lead) * Scalar::from_terms(norms[i].clone()),
            },
        };
        // An error value makes the sum one, which is refused below as before.
        out.extend_from_slice((k * m * trig).terms().ok()?);
    }
    Scalar::from_terms(out).check().ok()
}

/// The most product forms of constants remembered per thread.
const MEMO: usize = 256;

thread_local! {
    /// Only looked up and cleared, never iterated: FxHash.
    static FORMS: std::cell::RefCell<FxMap<Vec<Term>, Option<Expr>>> = Default::default();
}

/// [`super::cprod::small_product`] of the constant of canonical terms `t`, remembered: the
/// entries of one robot's pose share their constants.
fn product_form(t: &[Term]) -> Option<Expr> {
    if let Some(e) = FORMS.with(|m| m.borrow().get(t).cloned()) {
        return e;
    }
    let e = super::cprod::small_product(t);
    FORMS.with(|m| {
        let mut m = m.borrow_mut();
        if m.len() >= MEMO {
            m.clear();
        }
        m.insert(t.to_vec(), e.clone());
    });
    e
}

impl Lifted {
    /// `e` (in the fresh symbols) with each symbol replaced by the closed form of its constant.
    pub(crate) fn substitute(&self, e: Expr) -> Expr {
        replace(e, &self.constants)
    }
}

/// `e` as a rational times an expression without a rational factor.
fn rational_factor(e: Expr) -> (BigRational, Expr) {
    match e {
        Expr::Neg(x) => {
            let (r, x) = rational_factor(*x);
            (-r, x)
        }
        Expr::Mul(v) => {
            let (nums, rest): (Vec<Expr>, Vec<Expr>) =
                v.into_iter().partition(|x| matches!(x, Expr::Num(_)));
            let r = nums.into_iter().fold(BigRational::one(), |acc, x| match x {
                Expr::Num(q) => acc * q,
                _ => acc,
            });
            let rest = match rest.len() {
                0 => Expr::Num(BigRational::one()),
                1 => rest.into_iter().next().unwrap_or_else(Expr::zero),
                _ => Expr::Mul(rest),
            };
            (r, rest)
        }
        e => (BigRational::one(), e),
    }
}

fn replace(e: Expr, forms: &[(Sym, Expr, BigRational)]) -> Expr {
    match e {
        Expr::Sym(s) => match forms.iter().find(|(k, _, _)| *k == s) {
            Some((_, f, _)) => f.clone(),
            None => Expr::Sym(s),
        },
        Expr::Add(v) => Expr::Add(v.into_iter().map(|e| replace(e, forms)).collect()),
        Expr::Mul(v) => Expr::Mul(v.into_iter().map(|e| replace(e, forms)).collect()),
        Expr::Neg(e) => Expr::Neg(Box::new(replace(*e, forms))),
        Expr::Pow(e, n) => Expr::Pow(Box::new(replace(*e, forms)), n),
        e => e,
    }
}

/// The prefix of the fresh angle symbols of [`phase_angles`].
const ANGLE_PREFIX: &str = "~W";

/// A scalar whose angles at offsets that are multiples of pi/12 hide in radicals, with each
/// such angle a fresh symbol: `l1 sin(x + pi/6)` is canonically `l1 (cos(x) + sqrt(3)
/// sin(x))/2`; the two coefficients of `cos F` and `sin F` of one monomial, `R cos(phi)` and
/// `R sin(phi)` with `phi` a multiple of pi/24 other than of pi/2, make `R cos(W)` with
/// `W = F - phi` a fresh symbol (one per angle, shared by the monomials).
pub(crate) struct Angles {
    pub(crate) scalar: Scalar,
    angles: Vec<(Sym, super::expr::Angle)>,
}

/// [`Angles`] for `x`, when `x` has a radical beside a symbolic mode without an offset, and
/// some monomial's `cos F` and `sin F` at such a phase; `None` otherwise. Terms at offsets
/// outside pi/12 are kept as they are.
pub(crate) fn phase_angles(x: &Scalar) -> Option<Angles> {
    let terms = x.terms().ok()?;
    let symbolic = |t: &Term| t.mode.freq.iter().any(|(s, _)| !s.is_one());
    if terms.len() > 256
        || !terms
            .iter()
            .any(|t| t.rad != 1 && t.mode.pi.is_zero() && symbolic(t))
    {
        return None;
    }
    crate::scalar::charge(terms.len() as u64).ok()?;
    type Key = (MonoRc, Freq, bool);
    let mut coefs: BTreeMap<Key, Scalar> = BTreeMap::new();
    // Terms at offsets outside pi/12 are kept as they are.
    let mut out = Scalar::from_terms(
        terms
            .iter()
            .filter(|t| !t.mode.pi.is_zero())
            .cloned()
            .collect(),
    );
    for t in terms.iter().filter(|t| t.mode.pi.is_zero()) {
        let c = constant_of(t);
        let e = coefs
            .entry((t.mono.clone(), t.mode.freq.clone(), t.mode.sin))
            .or_insert_with(|| Scalar::int(0));
        *e = e.clone() + c;
    }
    let (unit, trig) = (monomial, offset_free);
    let mut angles: Vec<(Sym, super::expr::Angle)> = Vec::new();
    let mut coefs = coefs.into_iter().peekable();
    while let Some(((mono, freq, sin), a)) = coefs.next() {
        let pair = !sin
            && !freq.is_empty()
            && coefs
                .peek()
                .is_some_and(|((m, f, s), _)| *s && *m == mono && *f == freq);
        if !pair {
            out = out + a * unit(mono) * trig(&freq, sin);
            continue;
        }
        let (_, b) = coefs.next()?;
        match phase(&a, &b, 24, &mut TrigPi::default())
            .filter(|(phi, _)| !(*phi * Small::from_integer(2)).is_integer())
        {
            Some((phi, r)) => {
                let angle = super::expr::Angle::from_freq(&freq, -phi);
                let i = match angles.iter().position(|(_, g)| *g == angle) {
                    Some(i) => i,
                    None => {
                        let name = format!("{ANGLE_PREFIX}{}", angles.len());
                        angles.push((Sym::new(&name), angle));
                        angles.len() - 1
                    }
                };
                out = out + r * unit(mono) * Scalar::sym(angles[i].0.name()).cos();
            }
            None => {
                out = out + a * unit(mono.clone()) * trig(&freq, false);
                out = out + b * unit(mono) * trig(&freq, true);
            }
        }
    }
    if angles.is_empty() {
        return None;
    }
    Some(Angles {
        scalar: out.check().ok()?,
        angles,
    })
}

impl Angles {
    /// `e` (in the fresh angle symbols) with each angle symbol replaced by its angle, each
    /// call shown as the cosine or sine with the fewer operations in its angle; `None` when a
    /// fresh symbol is left outside an angle.
    pub(crate) fn substitute(&self, e: Expr) -> Option<Expr> {
        use super::expr::Angle;
        Some(match e {
            Expr::Sym(s) => {
                if self.angles.iter().any(|(w, _)| *w == s) {
                    return None;
                }
                Expr::Sym(s)
            }
            Expr::Trig { f, angle } => {
                let mut terms: BTreeMap<Sym, Small> = BTreeMap::new();
                let (mut constant, mut pi) = (angle.constant, angle.pi);
                for (s, k) in angle.terms {
                    match self.angles.iter().find(|(w, _)| *w == s) {
                        Some((_, g)) => {
                            for (t, m) in &g.terms {
                                *terms.entry(t.clone()).or_insert_with(Small::zero) += k * m;
                            }
                            constant += k * g.constant;
                            pi += k * g.pi;
                        }
                        None => *terms.entry(s).or_insert_with(Small::zero) += k,
                    }
                }
                let terms: Vec<(Sym, Small)> =
                    terms.into_iter().filter(|(_, k)| !k.is_zero()).collect();
                let a = Angle::new(terms, constant, pi).offset_reduced();
                // cos(a) = sin(a + pi/2), sin(a) = cos(a - pi/2): the cheaper angle.
                let half = Small::new(1, 2);
                let (g, other) = match f {
                    super::Trig::Cos => (super::Trig::Sin, half),
                    super::Trig::Sin => (super::Trig::Cos, -half),
                };
                let b = Angle::new(a.terms.clone(), a.constant, a.pi + other).offset_reduced();
                let first = Expr::Trig { f, angle: a };
                let second = Expr::Trig { f: g, angle: b };
                if super::alt::full_cost(&second) < super::alt::full_cost(&first) {
                    second
                } else {
                    first
                }
            }
            Expr::Add(v) => Expr::Add(
                v.into_iter()
                    .map(|e| self.substitute(e))
                    .collect::<Option<_>>()?,
            ),
            Expr::Mul(v) => Expr::Mul(
                v.into_iter()
                    .map(|e| self.substitute(e))
                    .collect::<Option<_>>()?,
            ),
            Expr::Neg(e) => Expr::Neg(Box::new(self.substitute(*e)?)),
            Expr::Pow(e, n) => Expr::Pow(Box::new(self.substitute(*e)?), n),
            e => e,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `square_ratio_in` in machine words says what the ratio of the squares in big rationals
    /// says, on coefficients small and large (past the words, where it falls back on them),
    /// with the ratios met (1, 3, 1/3) and without.
    #[test]
    fn the_ratio_of_squares_in_words_is_the_one_in_big_rationals() {
        let mut below = crate::testing::xorshift_below(0x5a_c0ef_0001);
        let (mut hits, mut big) = (0, 0);
        for k in 0..4000 {
            // Numerators and denominators of a few bits, or past 2^40 (then the products
            // leave 128 bits and the big rationals decide).
            let bits = if k % 7 == 0 { 62 } else { 4 };
            let parts: Vec<i64> = (0..4).map(|_| 1 + below(1 << bits) as i64).collect();
            let qa = Q::new(parts[0], parts[1]);
            let rad = |x: u64| [1, 2, 3, 6][x as usize];
            let ra = rad(below(4));
            // `b` often `a` times 1, sqrt(3) or 1/sqrt(3), so that the ratios occur.
            let (qb, rb) = match below(4) {
                0 => (qa.clone(), ra),
                1 if ra == 1 => (qa.clone(), 3),
                2 if ra == 3 => (qa.clone(), 1),
                _ => (Q::new(parts[2], parts[3]), rad(below(4))),
            };
            let ratios: &[(u8, u8)] = &[(1, 1), (3, 1), (1, 3)];
            let found = square_ratio_in((&qa, ra), (&qb, rb), ratios);
            let square = |q: &Q, r: u64| {
                let q = q.to_big();
                &q * &q * BigRational::from_integer(r.into())
            };
            let t = square(&qb, rb) / square(&qa, ra);
            let expected = [(1, 1), (3, 1), (1, 3)]
                .iter()
                .any(|&(p, q): &(i64, i64)| t == BigRational::new(p.into(), q.into()));
            assert_eq!(found, expected, "{qa:?} sqrt({ra}), {qb:?} sqrt({rb})");
            hits += usize::from(expected);
            big += usize::from(qa.to_ratio_i64().is_some_and(|q| q.numer().abs() > 1 << 40));
        }
        assert!(hits > 500 && hits < 3500, "{hits} of 4000 in the ratios");
        assert!(big > 100, "{big} large coefficients");
    }

    /// `k pi / n` as a scalar.
    fn pi_times(k: i64, n: i64) -> Scalar {
        Scalar::pi() * Scalar::rational(BigRational::new(k.into(), n.into()))
    }

    /// `TrigPi` gives `trig_pi`'s value for every offset and kind, computed and remembered
    /// (its key is the offset's numerator and denominator): cosines and sines of the same
    /// offsets asked in turn, and an unreduced offset (a finer key can only miss).
    #[test]
    fn remembered_trig_pi_is_trig_pi() {
        let mut next = crate::testing::xorshift_below(0x7f4a_7c15);
        let mut cache = TrigPi::default();
        for _ in 0..3 {
            for n in [7i64, 9, 18, 24] {
                let p = Small::new(next(2 * n as u64) as i64, n);
                for sin in [false, true, false] {
                    assert_eq!(cache.get(p, sin), trig_pi(p, sin), "{p} {sin}");
                }
            }
        }
        let half = num_rational::Ratio::new_raw(2, 4);
        assert_eq!(cache.get(half, true), trig_pi(Small::new(1, 2), true));
        assert_eq!(cache.get(Small::new(1, 2), false), Scalar::int(0));
    }

    /// `phases_inside` claims only what the phased lifting finds: on random sums of sinusoids
    /// at offsets of several fields (one or two per angle, cosines and sines, coefficients
    /// rational or with `sqrt(3)`), whenever it holds, the phased lifting's constants
    /// (`coefficients`, `items`, `normalized`, as `Lifting::lift` makes them) are all inside
    /// the multiples of pi/12. Both answers occur.
    #[test]
    fn phases_inside_never_claims_what_the_phased_lifting_does_not_find() {
        let mut next = crate::testing::xorshift_below(0x2545_f491_4f6c_dd1du64);
        let angles = [
            Scalar::sym("q"),
            Scalar::sym("q") + Scalar::sym("r"),
            Scalar::sym("q") * Scalar::int(2) - Scalar::sym("r"),
        ];
        let dens = [18i64, 9, 7, 8, 12];
        let coefs = [
            Scalar::int(1),
            Scalar::int(-2),
            Scalar::int(3).sqrt(),
            Scalar::rational(BigRational::new(1.into(), 2.into())),
            Scalar::int(3).sqrt() * Scalar::int(2),
        ];
        let (mut held, mut not) = (0, 0);
        for _ in 0..150 {
            let n = dens[next(dens.len() as u64) as usize];
            let mut x = Scalar::int(0);
            for a in &angles {
                for _ in 0..next(3) {
                    let k = next(2 * n as u64) as i64;
                    let arg = a.clone() + pi_times(k, n);
                    let trig = if next(2) == 0 { arg.cos() } else { arg.sin() };
                    x = x + coefs[next(coefs.len() as u64) as usize].clone() * trig;
                }
            }
            let Ok(terms) = x.terms() else {
                panic!("an error value");
            };
            if terms.iter().all(|t| t.mode.pi.is_zero()) {
                continue;
            }
            if !phases_inside(terms) {
                not += 1;
                continue;
            }
            held += 1;
            let n = terms
                .iter()
                .fold(12i64, |acc, t| acc.lcm(t.mode.pi.denom()));
            let mut trig_pi = TrigPi::default();
            let c = coefficients(terms, &mut trig_pi);
            let items = items(c, true, n, &mut trig_pi).expect("items");
            let (norms, _) = normalized(items).expect("normalized");
            assert!(
                norms.is_empty(),
                "{x:?}: the phased lifting lifts {norms:?}"
            );
        }
        assert!(held > 10 && not > 10, "held {held}, not {not}");
    }
}
