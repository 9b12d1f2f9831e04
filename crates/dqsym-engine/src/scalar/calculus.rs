//! Differentiation, substitution and numeric evaluation of canonical scalars.

use super::atoms::{Mode, Sym};
use super::{Scalar, ScalarError, Term, Q};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;
use std::fmt;

impl Scalar {
    /// The partial derivative with respect to the symbol `x`.
    ///
    /// Works term by term on the canonical form: the power rule on the monomial, and
    /// `d cos(k x + ...)/dx = -k sin(k x + ...)`, `d sin(k x + ...)/dx = k cos(k x + ...)`.
    pub fn diff(&self, x: &str) -> Scalar {
        let t = match self.terms() {
            Ok(t) => t,
            Err(e) => return Scalar::error(e.clone()),
        };
        let mut out = Vec::with_capacity(t.len());
        // The origin of every term with a pi offset: 1 from a monomial's derivative, 2 from
        // an angle's. A group of the derivative with one origin is canonical once like terms
        // merge: a monomial's derivative carries the group `(f, m x)` to `(f, m)` times the
        // exponent, an angle's the group `(f, m)` to itself times `i k` (`k` the frequency of
        // `x`, nonzero), so its value is that of one canonical group times a nonzero element
        // of `K(i)`, the same smallest level, and its terms are that group's coordinates
        // times it (see `cyclo::settled_groups`, and `product.rs` for the argument). Only
        // the groups holding both are rewritten.
        let mut marks: Vec<(usize, u64)> = Vec::new();
        for term in t {
            let offset = !term.mode.pi.is_zero();
            if let Some(pos) = term.mono.iter().position(|(s, _)| s.name() == x) {
                if offset {
                    marks.push((out.len(), 1));
                }
                let e = term.mono[pos].1;
                let mut mono = term.mono.to_vec();
                if e == 1 {
                    mono.remove(pos);
                } else {
                    mono[pos].1 = e - 1;
                }
                out.push(Term {
                    mode: term.mode.clone(),
                    mono: mono.into(),
                    rad: term.rad,
                    coef: &term.coef * &Q::from_u64(u64::from(e)),
                });
            }
            if let Some((_, k)) = term.mode.freq.iter().find(|(s, _)| s.name() == x) {
                let k = Q::new(*k.numer(), *k.denom());
                let coef = if term.mode.sin {
                    &term.coef * &k
                } else {
                    -(&term.coef * &k)
                };
                let mode = Mode {
                    sin: !term.mode.sin,
                    ..term.mode.clone()
                };
                if offset {
                    marks.push((out.len(), 2));
                }
                out.push(Term {
                    mode,
                    mono: term.mono.clone(),
                    rad: term.rad,
                    coef,
                });
            }
        }
        if marks.is_empty() {
            return Scalar::from_terms(out);
        }
        // Every term with a pi offset of one origin (`x` only in the angles, say: a joint
        // variable in the DQ of a chain whose every angle has an offset): so is every group,
        // and each is canonical as argued above, without sorting the groups out.
        if marks.iter().all(|&(_, o)| o == marks[0].1) {
            return Scalar::from_terms_settled(out);
        }
        let known = super::cyclo::settled_groups(&out, &marks);
        Scalar::from_terms_known(out, &known)
    }

    /// `self` with its symbols renamed, `names[k].0` to `names[k].1`, in one pass over the
    /// terms (no multiplication). `names` must be sorted by old name, the new names sorted
    /// too and cover every symbol of `self`, so that the sorted monomials and frequencies stay
    /// sorted; otherwise (or for an error value) the result is `None`. For such a renaming the
    /// closed form of the result is that of `self` renamed (closed forms only compare
    /// symbols), which lets a caller share one closed form between entries of the same shape.
    pub fn rename_symbols_monotone(&self, names: &[(String, String)]) -> Option<Scalar> {
        let t = self.terms().ok()?;
        let sorted =
            |v: &[(String, String)]| v.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 < w[1].1);
        if !sorted(names) {
            return None;
        }
        let new: Vec<Sym> = names.iter().map(|(_, n)| Sym::new(n)).collect();
        renamed(t, |s: &Sym| -> Option<Sym> {
            names
                .binary_search_by(|(o, _)| o.as_str().cmp(s.name()))
                .ok()
                .map(|k| new[k].clone())
        })
    }

    /// [`Scalar::rename_symbols_monotone`] of the names of `from` to those of `to`, given as
    /// symbols: the recurrence's shapes rename every entry to the same few placeholders,
    /// interned once (with the names' strings, each placeholder formatted and interned again
    /// per entry, and interned back per occurrence, the sharing of a symbolic 6R's closed
    /// forms took 7.9 M instructions; now 5.3 M).
    pub(crate) fn rename_syms_monotone(&self, from: &[Sym], to: &[Sym]) -> Option<Scalar> {
        let t = self.terms().ok()?;
        let sorted = |v: &[Sym]| v.windows(2).all(|w| w[0].name() < w[1].name());
        if from.len() != to.len() || !sorted(from) || !sorted(to) {
            return None;
        }
        renamed(t, |s: &Sym| -> Option<Sym> {
            from.binary_search_by(|o| o.name().cmp(s.name()))
                .ok()
                .map(|k| to[k].clone())
        })
    }

    /// `self` with the symbol `x` replaced by `value` everywhere, re-canonicalized.
    /// Inside a trigonometric argument `value` must be an angle.
    pub fn subs(&self, x: &str, value: &Scalar) -> Scalar {
        let t = match self.terms() {
            Ok(t) => t,
            Err(e) => return Scalar::error(e.clone()),
        };
        let mut keep = Vec::new();
        let mut acc = Scalar::int(0);
        for term in t {
            let in_mono = term.mono.iter().any(|(s, _)| s.name() == x);
            let in_freq = term.mode.freq.iter().any(|(s, _)| s.name() == x);
            if !in_mono && !in_freq {
                keep.push(term.clone());
                continue;
            }
            let mut f = Scalar::from_terms_sorted(vec![Term {
                mode: Mode::unit(),
                mono: super::atoms::empty_mono(),
                rad: term.rad,
                coef: term.coef.clone(),
            }]);
            for (s, e) in term.mono.iter() {
                let base = if s.name() == x {
                    value.clone()
                } else {
                    Scalar::sym(s.name())
                };
                f = f * base.pow(u64::from(*e));
            }
            if !term.mode.is_unit() {
                f = f * mode_value(&term.mode, Some((x, value)));
            }
            acc = acc + f;
        }
        Scalar::from_terms(keep) + acc
    }

    /// The value under a binding of symbols (`pi` defaults to pi).
    pub fn eval(&self, env: &dyn Fn(&str) -> Option<f64>) -> Result<f64, ScalarError> {
        self.eval_by(|s: &Sym| match env(s.name()) {
            Some(v) => Some(v),
            None if s.is_pi() => Some(std::f64::consts::PI),
            None => None,
        })
    }

    /// The value under a binding of the named symbols: `pi` is pi, and `env` is asked for
    /// every other symbol.
    pub fn eval_symbols(&self, env: &dyn Fn(&Sym) -> Option<f64>) -> Result<f64, ScalarError> {
        self.eval_by(|s: &Sym| {
            if s.is_pi() {
                Some(std::f64::consts::PI)
            } else {
                env(s)
            }
        })
    }

    /// The value with `env` giving each named symbol's (the constant 1 of a frequency vector
    /// is never asked for).
    fn eval_by(&self, env: impl Fn(&Sym) -> Option<f64>) -> Result<f64, ScalarError> {
        let t = self.terms().map_err(Clone::clone)?;
        let look = |s: &Sym| -> Result<f64, ScalarError> {
            if s.is_one() {
                return Ok(1.0);
            }
            env(s).ok_or_else(|| ScalarError::Unbound(s.name().to_string()))
        };
        let mut sum = 0.0;
        // The last mode's cosine or sine: the terms are sorted by mode first, so the terms of
        // one mode (one per monomial and radicand: `d4 c1`, `d5 c1`) are adjacent, and a
        // repeated mode's value is the float its own evaluation gives (the same operations on
        // the same operands), without the call of libm (the release build's numeric checks
        // of the Jaco-style arm's closed forms: 2.95 -> 2.61 M instructions; the PUMA 560's
        // modes seldom repeat: 1.02 -> 1.05 M).
        let mut last: Option<(&Mode, f64)> = None;
        for term in t {
            let mut v = term.coef.to_f64().unwrap_or(f64::NAN) * (term.rad as f64).sqrt();
            for (s, e) in term.mono.iter() {
                v *= look(s)?.powi(*e as i32);
            }
            if !term.mode.is_unit() {
                let trig = match last {
                    Some((m, trig)) if same_mode(m, &term.mode) => trig,
                    _ => {
                        let trig = mode_f64(&term.mode, &look)?;
                        last = Some((&term.mode, trig));
                        trig
                    }
                };
                v *= trig;
            }
            sum += v;
        }
        Ok(sum)
    }

    /// [`Scalar::eval`] over a list of `(name, value)` pairs.
    pub fn eval_at(&self, values: &[(&str, f64)]) -> Result<f64, ScalarError> {
        self.eval(&|n| values.iter().find(|(k, _)| *k == n).map(|(_, v)| *v))
    }
}

/// The cosine or sine of the angle of `mode` (not the unit mode), each symbol's value from
/// `look`.
fn mode_f64(
    mode: &Mode,
    look: &impl Fn(&Sym) -> Result<f64, ScalarError>,
) -> Result<f64, ScalarError> {
    let mut phi = (*mode.pi.numer() as f64 / *mode.pi.denom() as f64) * std::f64::consts::PI;
    for (s, k) in mode.freq.iter() {
        phi += (*k.numer() as f64 / *k.denom() as f64) * look(s)?;
    }
    Ok(if mode.sin { phi.sin() } else { phi.cos() })
}

/// Whether two modes are equal: the sine flags, the frequency vectors (symbols and
/// coefficients) and the offsets, compared by their reduced numerators and denominators
/// (every `Small` is kept reduced) instead of `Ratio`'s divisions.
fn same_mode(a: &Mode, b: &Mode) -> bool {
    a.sin == b.sin
        && a.pi.numer() == b.pi.numer()
        && a.pi.denom() == b.pi.denom()
        && super::atoms::freq_cmp(&a.freq, &b.freq).is_eq()
}

/// The angle of a mode as a scalar, optionally with one symbol substituted.
pub(crate) fn mode_angle(mode: &Mode, sub: Option<(&str, &Scalar)>) -> Scalar {
    let q = |k: &super::Small| BigRational::new(BigInt::from(*k.numer()), BigInt::from(*k.denom()));
    let mut angle = Scalar::pi() * Scalar::rational(q(&mode.pi));
    for (s, k) in mode.freq.iter() {
        let v = match sub {
            Some((x, v)) if s.name() == x => v.clone(),
            _ if s.is_one() => Scalar::int(1),
            _ => Scalar::sym(s.name()),
        };
        angle = angle + v * Scalar::rational(q(k));
    }
    angle
}

/// The value of a mode (`cos` or `sin` of its angle), optionally with one symbol substituted.
pub(crate) fn mode_value(mode: &Mode, sub: Option<(&str, &Scalar)>) -> Scalar {
    let angle = mode_angle(mode, sub);
    if mode.sin {
        angle.sin()
    } else {
        angle.cos()
    }
}

/// A plain, unsimplified rendering of the canonical form, for messages and debugging; the
/// closed-form printers give what users read.
impl fmt::Display for Scalar {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = match self.terms() {
            Ok(t) => t,
            Err(e) => return write!(f, "<error: {e}>"),
        };
        if t.is_empty() {
            return f.write_str("0");
        }
        for (i, term) in t.iter().enumerate() {
            let mut factors: Vec<String> = Vec::new();
            if term.rad != 1 {
                factors.push(format!("sqrt({})", term.rad));
            }
            for (s, e) in term.mono.iter() {
                factors.push(if *e == 1 {
                    s.to_string()
                } else {
                    format!("{s}^{e}")
                });
            }
            if !term.mode.is_unit() {
                factors.push(format!(
                    "{}({})",
                    if term.mode.sin { "sin" } else { "cos" },
                    angle_text(&term.mode)
                ));
            }
            let neg = term.coef.is_negative();
            let c = if neg {
                -term.coef.clone()
            } else {
                term.coef.clone()
            };
            let sep = match (i, neg) {
                (0, true) => "-",
                (0, false) => "",
                (_, true) => " - ",
                (_, false) => " + ",
            };
            f.write_str(sep)?;
            let body = factors.join("*");
            if body.is_empty() {
                write!(f, "{c}")?;
            } else if c.is_one() {
                f.write_str(&body)?;
            } else {
                write!(f, "{c}*{body}")?;
            }
        }
        Ok(())
    }
}

fn angle_text(mode: &Mode) -> String {
    let mut s = String::new();
    for (i, (sym, k)) in mode.freq.iter().enumerate() {
        let neg = *k < super::Small::zero();
        let a = if neg { -*k } else { *k };
        if i > 0 || neg {
            s.push_str(if neg { " - " } else { " + " });
        }
        let name = if sym.is_one() {
            String::new()
        } else {
            sym.to_string()
        };
        let coef = if a == super::Small::from_integer(1) {
            String::new()
        } else {
            format!("{a}*")
        };
        if name.is_empty() {
            s.push_str(&a.to_string());
        } else {
            s.push_str(&format!("{coef}{name}"));
        }
    }
    if !mode.pi.is_zero() {
        s.push_str(&format!(" + {}*pi", mode.pi));
    }
    s.trim_start().to_string()
}

impl Scalar {
    /// An angle `phi` with `self == cos(phi)`, when `self` is visibly one: `cos(x)`, `-cos(x)`
    /// (then `phi = x + pi`), or a number equal to `cos(k pi/12)`.
    pub fn as_cos_of_angle(&self) -> Option<Scalar> {
        let t = self.terms().ok()?;
        if let [x] = t {
            if !x.mode.is_unit() && !x.mode.sin && x.mono.is_empty() && x.rad == 1 {
                let phi = mode_angle(&x.mode, None);
                if x.coef.is_one() {
                    return Some(phi);
                }
                if x.coef.is_negative() && (-self.clone()) == phi.cos() {
                    return Some(phi + Scalar::pi());
                }
            }
        }
        if self.is_constant() {
            return (0..24)
                .map(|k| Scalar::pi() * Scalar::from_ratio_i64(k, 12))
                .find(|phi| phi.cos() == *self);
        }
        None
    }

    fn from_ratio_i64(n: i64, d: i64) -> Scalar {
        Scalar::rational(BigRational::new(BigInt::from(n), BigInt::from(d)))
    }
}

/// The terms `t` with each symbol renamed by `r` (`None` for one it does not rename: then
/// the result is `None`), in one pass, the order kept (see
/// [`Scalar::rename_symbols_monotone`]).
fn renamed(t: &[Term], r: impl Fn(&Sym) -> Option<Sym>) -> Option<Scalar> {
    let mut out = Vec::with_capacity(t.len());
    for term in t {
        let mono: Option<Vec<(Sym, u32)>> =
            term.mono.iter().map(|(s, e)| Some((r(s)?, *e))).collect();
        let freq: Option<Vec<_>> = term
            .mode
            .freq
            .iter()
            .map(|(s, k)| Some((r(s)?, *k)))
            .collect();
        let mono = mono?;
        out.push(Term {
            mode: Mode {
                sin: term.mode.sin,
                freq: super::atoms::freq_rc(freq?),
                pi: term.mode.pi,
            },
            mono: if mono.is_empty() {
                super::atoms::empty_mono()
            } else {
                std::sync::Arc::from(mono)
            },
            rad: term.rad,
            coef: term.coef.clone(),
        });
    }
    Some(Scalar::from_terms(out))
}
