//! Monomials over trigonometric atoms: the working form between the canonical Fourier series
//! and a display expression.

use super::expr::Angle;
use crate::scalar::atoms::{freq_combine, Mode};
use crate::scalar::{Mono, Small};
use crate::Scalar;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use std::collections::BTreeMap;

/// `cos(angle)` or `sin(angle)` as a factor of a monomial.
#[derive(Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub(crate) struct Atom {
    pub(crate) angle: Angle,
    pub(crate) sin: bool,
}

/// `q * sqrt(rad) * syms * atoms`, atoms sorted.
#[derive(Clone, PartialEq, Eq, Debug)]
pub(crate) struct Mon {
    pub(crate) q: BigRational,
    pub(crate) rad: u64,
    pub(crate) syms: Mono,
    pub(crate) atoms: Vec<Atom>,
}

type MonKey = (u64, Mono, Vec<Atom>);

/// Sums monomials with equal factors and drops zeros; output sorted by factors.
pub(crate) fn merge(mons: Vec<Mon>) -> Vec<Mon> {
    let mut map: BTreeMap<MonKey, BigRational> = BTreeMap::new();
    for m in mons {
        *map.entry((m.rad, m.syms, m.atoms))
            .or_insert_with(BigRational::zero) += m.q;
    }
    map.into_iter()
        .filter(|(_, q)| !q.is_zero())
        .map(|((rad, syms, atoms), q)| Mon {
            q,
            rad,
            syms,
            atoms,
        })
        .collect()
}

/// A mode's angle, as stored in the canonical form.
fn mode_angle(mode: &Mode) -> Angle {
    Angle {
        terms: mode.freq.to_vec(),
        pi: mode.pi,
    }
}

/// The canonical form as monomials, each mode kept whole (`cos(t1 + t2)` is one atom).
pub(crate) fn whole_modes(x: &Scalar) -> Vec<Mon> {
    let Ok(terms) = x.terms() else {
        return Vec::new();
    };
    terms
        .iter()
        .map(|t| Mon {
            q: t.coef.to_big(),
            rad: t.rad,
            syms: t.mono.to_vec(),
            atoms: if t.mode.is_unit() {
                Vec::new()
            } else {
                vec![Atom {
                    angle: mode_angle(&t.mode),
                    sin: t.mode.sin,
                }]
            },
        })
        .collect()
}

/// The canonical form as monomials in single-symbol atoms: every mode is split with the
/// angle-sum formulas, `cos(a + b) = cos a cos b - sin a sin b`, so that recombination can
/// regroup the angles the way the expression is best read.
pub(crate) fn split_modes(x: &Scalar) -> Vec<Mon> {
    let Ok(terms) = x.terms() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for t in terms {
        let base = Mon {
            q: t.coef.to_big(),
            rad: t.rad,
            syms: t.mono.to_vec(),
            atoms: Vec::new(),
        };
        if t.mode.is_unit() {
            out.push(base);
            continue;
        }
        // Each symbol's part is its own angle; a leftover pi part rides on the last one.
        let mut parts: Vec<Angle> = t
            .mode
            .freq
            .iter()
            .map(|(s, k)| Angle {
                terms: vec![(s.clone(), *k)],
                pi: Small::zero(),
            })
            .collect();
        if !t.mode.pi.is_zero() {
            match parts.last_mut() {
                Some(p) => p.pi = t.mode.pi,
                None => parts.push(Angle {
                    terms: Vec::new(),
                    pi: t.mode.pi,
                }),
            }
        }
        expand(&parts, t.mode.sin, base, &mut out);
    }
    merge(out)
}

/// Pushes `m * trig(sum of parts)` expanded into products of single-part atoms.
fn expand(parts: &[Angle], sin: bool, m: Mon, out: &mut Vec<Mon>) {
    let Some((first, rest)) = parts.split_first() else {
        // trig(0): cos 0 = 1, sin 0 = 0.
        if !sin {
            out.push(m);
        }
        return;
    };
    if rest.is_empty() {
        out.push(with_atom(
            m,
            Atom {
                angle: first.clone(),
                sin,
            },
            1,
        ));
        return;
    }
    // cos(a + r) = cos a cos r - sin a sin r;  sin(a + r) = sin a cos r + cos a sin r.
    let (ca, sa) = (
        Atom {
            angle: first.clone(),
            sin: false,
        },
        Atom {
            angle: first.clone(),
            sin: true,
        },
    );
    if sin {
        expand(rest, false, with_atom(m.clone(), sa, 1), out);
        expand(rest, true, with_atom(m, ca, 1), out);
    } else {
        expand(rest, false, with_atom(m.clone(), ca, 1), out);
        expand(rest, true, with_atom(m, sa, -1), out);
    }
}

pub(crate) fn with_atom(mut m: Mon, mut a: Atom, mut sign: i64) -> Mon {
    // cos(-x) = cos x, sin(-x) = -sin x: atoms keep a positive leading coefficient.
    if a.angle.terms.first().is_some_and(|(_, k)| k.is_negative())
        || (a.angle.terms.is_empty() && a.angle.pi.is_negative())
    {
        for (_, k) in a.angle.terms.iter_mut() {
            *k = -*k;
        }
        a.angle.pi = -a.angle.pi;
        if a.sin {
            sign = -sign;
        }
    }
    let pos = m.atoms.partition_point(|x| x < &a);
    m.atoms.insert(pos, a);
    if sign < 0 {
        m.q = -m.q;
    }
    m
}

/// `a + sign * b` as a normalized angle, with the sign flip the normalization needed.
pub(crate) fn angle_combine(a: &Angle, b: &Angle, sign: i64) -> (Angle, bool) {
    let mut terms = freq_combine(&a.terms, &b.terms, sign);
    let mut pi = a.pi + b.pi * Small::from_integer(sign);
    let flip = terms.first().is_some_and(|(_, k)| k.is_negative());
    if flip {
        for (_, k) in terms.iter_mut() {
            *k = -*k;
        }
        pi = -pi;
    }
    (Angle { terms, pi }, flip)
}

/// The rational gcd of the coefficients (positive), e.g. `1/4` for `3/4 x + 1/2 y`.
pub(crate) fn content(mons: &[Mon]) -> BigRational {
    use num_integer::Integer;
    let mut num = BigInt::zero();
    let mut den = BigInt::from(1);
    for m in mons {
        num = num.gcd(m.q.numer());
        den = den.lcm(m.q.denom());
    }
    if num.is_zero() {
        return BigRational::from_integer(1.into());
    }
    BigRational::new(num, den)
}
