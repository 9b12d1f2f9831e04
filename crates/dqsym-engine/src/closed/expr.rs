//! Display expressions: what a closed form is made of, its cost, and its exact value.

use crate::scalar::atoms::small_ok;
use crate::scalar::{Small, Sym, Trig};
use crate::Scalar;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

/// An angle: a rational combination of symbols, plus a rational constant, plus a rational
/// multiple of pi (`t1 - 2 t2 + 1/2 + pi/7`).
///
/// Ordered as the canonical form orders frequency vectors: by the sequence of `(symbol,
/// coefficient)` with the constant, when nonzero, first (the canonical form carries it as
/// [`Sym::is_one`], which sorts before every name), then by the multiple of pi.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub struct Angle {
    /// `(symbol, coefficient)`, sorted by symbol, nonzero; neither `pi` nor the constant.
    pub terms: Vec<(Sym, Small)>,
    /// The rational constant (not a multiple of pi): `1` in `t + 1`.
    pub constant: Small,
    /// The multiple of pi.
    pub pi: Small,
}

impl Ord for Angle {
    fn cmp(&self, other: &Self) -> Ordering {
        let head = |a: &Angle| (!a.constant.is_zero()).then_some(a.constant);
        match (head(self), head(other)) {
            (Some(x), Some(y)) => x.cmp(&y).then_with(|| self.terms.cmp(&other.terms)),
            (None, None) => self.terms.cmp(&other.terms),
            // The constant comes before any symbol, after the end of the sequence.
            (Some(_), None) if other.terms.is_empty() => Ordering::Greater,
            (Some(_), None) => Ordering::Less,
            (None, Some(_)) if self.terms.is_empty() => Ordering::Less,
            (None, Some(_)) => Ordering::Greater,
        }
        .then_with(|| self.pi.cmp(&other.pi))
    }
}

impl PartialOrd for Angle {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Each symbol met (by its interned address) with the call it stands for as a placeholder,
/// if any (see [`Expr::with_placeholders_as_trig`]).
type SymCalls = std::collections::HashMap<
    usize,
    Option<(Trig, Sym)>,
    std::hash::BuildHasherDefault<crate::scalar::FxHasher>,
>;

impl Angle {
    /// The angle `terms + constant + pi * pi` (`terms` sorted by symbol, nonzero, without
    /// `pi` or the constant 1 of a frequency vector).
    pub fn new(terms: Vec<(Sym, Small)>, constant: Small, pi: Small) -> Angle {
        debug_assert!(terms.iter().all(|(s, _)| !s.is_one()));
        Angle {
            terms,
            constant,
            pi,
        }
    }

    /// The angle `1 * s` of one symbol.
    pub fn of_symbol(s: Sym) -> Angle {
        Angle::new(vec![(s, Small::one())], Small::zero(), Small::zero())
    }

    /// The angle of a canonical frequency vector (its constant carried by the entry
    /// [`Sym::is_one`]) and a multiple of pi.
    pub fn from_freq(freq: &[(Sym, Small)], pi: Small) -> Angle {
        let mut constant = Small::zero();
        let mut terms = Vec::with_capacity(freq.len());
        for (s, k) in freq {
            if s.is_one() {
                constant += *k;
            } else {
                terms.push((s.clone(), *k));
            }
        }
        Angle {
            terms,
            constant,
            pi,
        }
    }

    /// The angle's frequency vector as the canonical form stores it: the constant, when
    /// nonzero, as a leading entry [`Sym::is_one`], then the symbols.
    pub fn freq(&self) -> Vec<(Sym, Small)> {
        let mut v = Vec::with_capacity(self.terms.len() + 1);
        if !self.constant.is_zero() {
            v.push((Sym::one(), self.constant));
        }
        v.extend(self.terms.iter().cloned());
        v
    }

    /// The first coefficient of the angle in the canonical order (the constant, when nonzero,
    /// before the symbols), which the canonical sign rule keeps positive; `None` when the
    /// angle is a multiple of pi.
    pub fn leading(&self) -> Option<Small> {
        if self.constant.is_zero() {
            self.terms.first().map(|(_, k)| *k)
        } else {
            Some(self.constant)
        }
    }

    /// The angle with its offset in `(-pi, pi]` when it has symbols or a constant: the canonical
    /// form stores offsets in `[0, 2 pi)`, and `x - pi/7` reads better than `x + 13*pi/7` (cos
    /// and sin have period `2 pi`, so the value is the same).
    pub fn offset_reduced(mut self) -> Angle {
        self.reduce_offset();
        self
    }

    /// [`Angle::offset_reduced`] in place.
    pub fn reduce_offset(&mut self) {
        // No offset (the common case) is in range already.
        if !self.pi.is_zero() && !self.is_pi_multiple() {
            let (one, two) = (Small::one(), Small::from_integer(2));
            while self.pi > one {
                self.pi -= two;
            }
            while self.pi <= -one {
                self.pi += two;
            }
        }
    }

    /// Whether the angle has no symbols and no constant (a multiple of pi, zero included).
    pub fn is_pi_multiple(&self) -> bool {
        self.terms.is_empty() && self.constant.is_zero()
    }

    /// The negated angle.
    pub fn negate(&mut self) {
        for (_, k) in self.terms.iter_mut() {
            *k = -*k;
        }
        self.constant = -self.constant;
        self.pi = -self.pi;
    }

    /// The angle with every symbol's and the constant's coefficient, and the multiple of pi,
    /// multiplied by `m`.
    pub fn scaled(&self, m: Small) -> Angle {
        Angle {
            terms: self
                .terms
                .iter()
                .map(|(s, k)| (s.clone(), *k * m))
                .collect(),
            constant: self.constant * m,
            pi: self.pi * m,
        }
    }

    /// The angle as an exact scalar.
    pub fn to_scalar(&self) -> Scalar {
        let mut a = Scalar::pi() * small(&self.pi) + small(&self.constant);
        for (s, k) in &self.terms {
            a = a + Scalar::sym(s.name()) * small(k);
        }
        a
    }

    /// `cos` or `sin` of the angle: what `to_scalar().cos()` (or `.sin()`) gives, built from
    /// the parts directly when they are what reading the angle back would give.
    fn trig(&self, f: Trig) -> Scalar {
        let direct = small_ok(&self.pi)
            && small_ok(&self.constant)
            && self.terms.is_sorted_by(|a, b| a.0 < b.0)
            && self
                .terms
                .iter()
                .all(|(s, k)| !s.is_pi() && !k.is_zero() && small_ok(k));
        if direct {
            return Scalar::trig_of_parts(f.is_sin(), self.freq(), self.pi);
        }
        let a = self.to_scalar();
        match f {
            Trig::Cos => a.cos(),
            Trig::Sin => a.sin(),
        }
    }

    /// True when every coefficient is 1 and there is no constant and no pi part: `theta1 +
    /// theta2`.
    pub fn is_plain_sum(&self) -> bool {
        self.pi.is_zero() && self.constant.is_zero() && self.terms.iter().all(|(_, k)| k.is_one())
    }
}

fn small_f64(k: &Small) -> f64 {
    *k.numer() as f64 / *k.denom() as f64
}

fn big_f64(q: &BigRational) -> f64 {
    use num_traits::ToPrimitive;
    match (q.numer().to_i64(), q.denom().to_i64()) {
        (Some(n), Some(d)) => n as f64 / d as f64,
        _ => q.to_f64().unwrap_or(f64::NAN),
    }
}

fn sym_value(s: &Sym, env: &dyn Fn(&Sym) -> f64) -> f64 {
    if s.is_pi() {
        std::f64::consts::PI
    } else {
        env(s)
    }
}

pub(crate) fn small(k: &Small) -> Scalar {
    Scalar::rational(BigRational::new(
        BigInt::from(*k.numer()),
        BigInt::from(*k.denom()),
    ))
}

/// A display expression. Built by the closed-form extractor; read by the printers, which never
/// simplify.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Expr {
    /// A non-negative rational.
    Num(BigRational),
    /// `sqrt(n)`, `n` square-free.
    Sqrt(u64),
    /// A symbol (`pi` included).
    Sym(Sym),
    /// `cos(angle)` or `sin(angle)`.
    Trig {
        /// Cosine or sine.
        f: Trig,
        /// The argument.
        angle: Angle,
    },
    /// A sum; negative terms are `Neg`.
    Add(Vec<Expr>),
    /// A product.
    Mul(Vec<Expr>),
    /// `-e`.
    Neg(Box<Expr>),
    /// `e^n`, `n >= 2`.
    Pow(Box<Expr>, u32),
}

/// A rewrite of one call `f(angle)`: the new call, its angle and whether it is negated.
pub(crate) type TrigMap<'a> = dyn FnMut(Trig, &Angle) -> Option<(Trig, Angle, bool)> + 'a;

/// What a closed form costs to read or to evaluate.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug, Default)]
pub struct Cost {
    /// Additions, subtractions, multiplications, divisions, negations and calls.
    pub ops: usize,
    /// Calls of cos, sin and sqrt.
    pub calls: usize,
}

impl Expr {
    /// The names of the symbols the expression reads (angle symbols included, the symbol of a
    /// `cos(x)` placeholder as `x`, `pi` left out), sorted, found without evaluating it: the
    /// exact value of a large cos/sin polynomial may be far over the term limit.
    pub fn symbol_names(&self) -> Vec<String> {
        fn walk(e: &Expr, out: &mut Vec<String>) {
            match e {
                Expr::Num(_) | Expr::Sqrt(_) => {}
                Expr::Sym(s) if s.is_pi() => {}
                Expr::Sym(s) => match crate::scalar::parse_trig_placeholder(s.name()) {
                    Some((x, _)) => out.push(x.to_owned()),
                    None => out.push(s.name().to_owned()),
                },
                Expr::Trig { angle, .. } => {
                    out.extend(angle.terms.iter().map(|(s, _)| s.name().to_owned()))
                }
                Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| walk(x, out)),
                Expr::Neg(x) | Expr::Pow(x, _) => walk(x, out),
            }
        }
        let mut out = Vec::new();
        walk(self, &mut out);
        out.sort();
        out.dedup();
        out
    }

    /// The exact value, re-canonicalized: every closed form must equal its input.
    pub fn to_scalar(&self) -> Scalar {
        self.eval(&mut Vec::new())
    }

    /// The expression with every placeholder symbol `cos(x)` / `sin(x)` of a
    /// [`Scalar::to_cos_sin_polynomial`] form replaced by the cosine or sine of `x`.
    pub fn with_placeholders_as_trig(self) -> Expr {
        self.placeholders_as_trig(&mut SymCalls::default())
    }

    /// [`Expr::with_placeholders_as_trig`], each distinct symbol read once: `seen` holds each
    /// symbol met so far (by its interned address) with the call it stands for, if any (a
    /// symbolic 6R's recurrence: 4,712 placeholders of a few dozen names, each parsed and its
    /// angle's symbol interned again).
    fn placeholders_as_trig(self, seen: &mut SymCalls) -> Expr {
        match self {
            Expr::Sym(s) => {
                let call = seen
                    .entry(s.addr())
                    .or_insert_with(|| {
                        crate::scalar::parse_trig_placeholder(s.name())
                            .map(|(x, f)| (f, Sym::new(x)))
                    })
                    .clone();
                match call {
                    Some((f, x)) => Expr::Trig {
                        f,
                        angle: Angle::of_symbol(x),
                    },
                    None => Expr::Sym(s),
                }
            }
            Expr::Add(v) => Expr::Add(
                v.into_iter()
                    .map(|e| e.placeholders_as_trig(seen))
                    .collect(),
            ),
            Expr::Mul(v) => Expr::Mul(
                v.into_iter()
                    .map(|e| e.placeholders_as_trig(seen))
                    .collect(),
            ),
            Expr::Neg(e) => Expr::Neg(Box::new(e.placeholders_as_trig(seen))),
            Expr::Pow(e, n) => Expr::Pow(Box::new(e.placeholders_as_trig(seen)), n),
            e => e,
        }
    }

    /// The value in f64 with the symbols bound by `values` (`pi` is pi); `None` when a symbol
    /// has no value.
    pub fn value_at(&self, values: &[(&str, f64)]) -> Option<f64> {
        let missing = std::cell::Cell::new(false);
        let (v, _) = self.eval_f64(&|s: &Sym| {
            values
                .iter()
                .find(|(n, _)| *n == s.name())
                .map(|(_, v)| *v)
                .unwrap_or_else(|| {
                    missing.set(true);
                    f64::NAN
                })
        });
        (!missing.get()).then_some(v)
    }

    /// The value in f64 with every symbol bound by `env` (`pi` is pi, the pseudo-symbol `1`
    /// is 1), and the sum of the magnitudes of the terms met along the way: a scale for
    /// comparing two evaluations of an expression with cancellation.
    pub(crate) fn eval_f64(&self, env: &dyn Fn(&Sym) -> f64) -> (f64, f64) {
        match self {
            Expr::Num(q) => {
                let v = big_f64(q);
                (v, v.abs())
            }
            Expr::Sqrt(n) => {
                let v = (*n as f64).sqrt();
                (v, v)
            }
            Expr::Sym(s) => {
                let v = sym_value(s, env);
                (v, v.abs())
            }
            Expr::Trig { f, angle } => {
                let mut phi = small_f64(&angle.pi) * std::f64::consts::PI;
                if !angle.constant.is_zero() {
                    phi += small_f64(&angle.constant);
                }
                for (s, k) in &angle.terms {
                    phi += small_f64(k) * sym_value(s, env);
                }
                let v = f.f64(phi);
                (v, v.abs())
            }
            Expr::Add(v) => v.iter().fold((0.0, 0.0), |(a, m), e| {
                let (x, y) = e.eval_f64(env);
                (a + x, m + y)
            }),
            Expr::Mul(v) => v.iter().fold((1.0, 1.0), |(a, m), e| {
                let (x, y) = e.eval_f64(env);
                (a * x, m * y)
            }),
            Expr::Neg(e) => {
                let (x, y) = e.eval_f64(env);
                (-x, y)
            }
            Expr::Pow(e, n) => {
                let (x, y) = e.eval_f64(env);
                let n = i32::try_from(*n).unwrap_or(i32::MAX);
                (x.powi(n), y.powi(n))
            }
        }
    }

    /// [`Expr::to_scalar`], with the trigonometric factors computed once per distinct atom.
    fn eval<'a>(&'a self, trig: &mut Vec<(Trig, &'a Angle, Scalar)>) -> Scalar {
        match self {
            Expr::Num(q) => Scalar::rational(q.clone()),
            Expr::Sqrt(n) => Scalar::int(*n as i64).sqrt(),
            Expr::Sym(s) => Scalar::sym(s.name()),
            Expr::Trig { f, angle } => {
                if let Some((_, _, v)) = trig.iter().find(|(g, a, _)| g == f && *a == angle) {
                    return v.clone();
                }
                let v = angle.trig(*f);
                trig.push((*f, angle, v.clone()));
                v
            }
            // Folded from the first operand: `0 + x` and `1 * x` are `x` exactly.
            Expr::Add(v) => match v.split_first() {
                Some((first, rest)) => rest
                    .iter()
                    .fold(first.eval(trig), |acc, e| acc + e.eval(trig)),
                None => Scalar::int(0),
            },
            Expr::Mul(v) => match v.split_first() {
                Some((first, rest)) => rest
                    .iter()
                    .fold(first.eval(trig), |acc, e| acc * e.eval(trig)),
                None => Scalar::int(1),
            },
            Expr::Neg(e) => -e.eval(trig),
            Expr::Pow(e, n) => e.eval(trig).pow(u64::from(*n)),
        }
    }

    /// Operation and call counts: `a + b - c` is 2 ops, `2 l1 c1` is 2 ops and 1 call,
    /// `1/2` is one division, `-x` alone one negation, `-2 l1 c1` 2 ops (the sign is the
    /// number's).
    pub fn cost(&self) -> Cost {
        let mut c = Cost::default();
        self.add_cost(&mut c, false);
        c
    }

    fn add_cost(&self, c: &mut Cost, in_sum: bool) {
        match self {
            Expr::Num(q) => {
                if !q.denom().is_one() {
                    c.ops += 1;
                }
            }
            Expr::Sqrt(_) => {
                c.ops += 1;
                c.calls += 1;
            }
            Expr::Sym(_) => {}
            Expr::Trig { .. } => {
                c.ops += 1;
                c.calls += 1;
            }
            Expr::Add(v) => {
                c.ops += v.len().saturating_sub(1);
                for e in v {
                    e.add_cost(c, true);
                }
            }
            Expr::Mul(v) => {
                c.ops += v.len().saturating_sub(1);
                for e in v {
                    e.add_cost(c, false);
                }
            }
            Expr::Neg(e) => {
                // In a sum a negation is the subtraction; in a product with a number it is
                // that number's sign (`-1/2 sin(x)^2` multiplies by `-1/2`).
                let signed_number =
                    matches!(&**e, Expr::Mul(v) if v.iter().any(|f| matches!(f, Expr::Num(_))));
                if !in_sum && !signed_number {
                    c.ops += 1;
                }
                e.add_cost(c, false);
            }
            Expr::Pow(e, n) => {
                c.ops += (*n as usize).saturating_sub(1);
                e.add_cost(c, false);
            }
        }
    }

    /// The number zero.
    pub fn zero() -> Expr {
        Expr::Num(BigRational::zero())
    }

    /// The expression times the nonzero rational `c`, as the closed-form search shows a
    /// number times a form: `c` merged into a leading number (`1/2 (a + b)` times `-1/2` is
    /// `-1/4 (a + b)`), a sign in front taken into it, and a negative product's sign placed
    /// as [`minus`] places it. Unchanged when `c` is 1. The value is `c` times this one's
    /// (every step is an identity of `Expr`'s arithmetic).
    pub(crate) fn scaled(self, c: &BigRational) -> Expr {
        if c.is_one() {
            return self;
        }
        let (e, c) = match self {
            Expr::Neg(x) => (*x, -c),
            e => (e, c.clone()),
        };
        let (k, rest) = match e {
            Expr::Num(k) => (k * c, Vec::new()),
            Expr::Mul(mut v) => match v.first() {
                Some(Expr::Num(k)) => {
                    let k = k * c;
                    v.remove(0);
                    (k, v)
                }
                _ => (c, v),
            },
            e => (c, vec![e]),
        };
        let body = super::decimals::product(k.abs(), rest);
        if k.is_negative() {
            minus(body)
        } else {
            body
        }
    }

    /// The expression with each call `f(a + phi pi)` (`a` with symbols, `phi` nonzero) shown
    /// as the one of its four equal forms, `f(a + phi pi)`, `g(a + (phi - q/2) pi)` with a
    /// sign (`q` = 1, 2, 3 quarter turns, [`quarter_turned`]; the offset reduced into
    /// `(-1, 1]`), whose call `cost` is strictly lowest (the first such on ties, a form without
    /// a sign before one with; the call as it is when none is lower): `sin(a + pi/18)`
    /// for `cos(a - 4*pi/9)`. The signs are moved as [`Expr::map_trig_signed`] moves them.
    /// Each call keeps its value, so the expression does.
    pub(crate) fn cheapest_offsets(self, cost: &dyn Fn(&Expr) -> usize) -> Expr {
        self.map_trig_signed(&mut |f, angle| {
            if angle.pi.is_zero() || angle.terms.is_empty() {
                return None;
            }
            let call = |g: Trig, b: &Angle| {
                cost(&Expr::Trig {
                    f: g,
                    angle: b.clone(),
                })
            };
            let mut best = (call(f, angle), None);
            for q in 1..4 {
                let mut b = angle.clone();
                b.pi -= Small::new(q, 2);
                b.reduce_offset();
                let (g, neg) = quarter_turned(f, q);
                let c = call(g, &b);
                let better = match &best {
                    (d, None) => c < *d,
                    (d, Some((_, _, was_neg))) => c < *d || (c == *d && *was_neg && !neg),
                };
                if better {
                    best = (c, Some((g, b, neg)));
                }
            }
            best.1
        })
    }

    /// The expression with each call `f(angle)` for which `map` returns `Some((g, b, neg))`
    /// replaced by `g(b)`, negated when `neg`: the signs met are moved out of products and
    /// powers (as [`Expr::symbols_leading`] moves them), kept on the terms of sums, and a
    /// sign left at the top of a product that holds a sum is taken into that sum.
    pub(crate) fn map_trig_signed(self, map: &mut TrigMap) -> Expr {
        match walk_signed(self, map) {
            // `-(1/4 (a - b))` is `1/4 (b - a)`, one negation fewer.
            Expr::Neg(x) => match *x {
                Expr::Mul(mut v) if v.iter().any(|f| matches!(f, Expr::Add(_))) => {
                    if let Some(Expr::Add(terms)) = v.iter_mut().find(|f| matches!(f, Expr::Add(_)))
                    {
                        *terms = std::mem::take(terms).into_iter().map(negated).collect();
                    }
                    Expr::Mul(v)
                }
                Expr::Add(terms) => Expr::Add(terms.into_iter().map(negated).collect()),
                x => Expr::Neg(Box::new(x)),
            },
            e => e,
        }
    }

    /// The expression with every angle that holds a rational constant shown with its first
    /// symbol's coefficient positive, as angles without a constant are: the canonical form
    /// keeps the constant's sign (it leads the frequency vector), the text puts the symbols
    /// first (`t/2 - 1/3`), so `sin(1/3 - t/2)` is shown `-sin(t/2 - 1/3)` and `cos(1/3 - t/2)`
    /// `cos(t/2 - 1/3)` (cos is even, sin odd). The signs met are moved out of products and
    /// powers. Unchanged (and not rebuilt) when no angle needs it.
    pub(crate) fn symbols_leading(self) -> Expr {
        fn needs(a: &Angle) -> bool {
            !a.constant.is_zero() && a.terms.first().is_some_and(|(_, k)| *k < Small::zero())
        }
        fn any(e: &Expr) -> bool {
            match e {
                Expr::Trig { angle, .. } => needs(angle),
                Expr::Add(v) | Expr::Mul(v) => v.iter().any(any),
                Expr::Neg(x) | Expr::Pow(x, _) => any(x),
                _ => false,
            }
        }
        if any(&self) {
            walk_signed(self, &mut |f, angle| {
                needs(angle).then(|| {
                    let mut angle = angle.clone();
                    angle.negate();
                    angle.reduce_offset();
                    (f, angle, f.is_sin())
                })
            })
        } else {
            self
        }
    }
}

/// The characters of `e`'s plain text (`print/plain.rs`) that its signs and sums make, at
/// the printer's precedence `prec` (1 a sum's term, 2 a factor or what follows a minus):
/// minus signs, ` + ` and ` - `, a product's separators and the brackets around sums and
/// negations; and the minus signs alone. The leaves (numbers, symbols, calls) are left out:
/// ways of placing the same signs differ only in these ([`minus`] compares them, read off
/// each node's [`Shape`] once; this walk checks what it builds).
fn sign_text(e: &Expr, prec: u8) -> (usize, usize) {
    let brackets = |inner: bool| if inner { 2 } else { 0 };
    match e {
        Expr::Add(v) => {
            v.iter()
                .enumerate()
                .fold((brackets(prec > 1), 0), |(len, minus), (i, t)| {
                    // Each term with the separator before it (none before the first, else
                    // ` + ` or ` - `): `-x` is its minus sign or ` - `, then `x` as a factor
                    // (a number as a term).
                    let (l, m) = match t {
                        Expr::Neg(x) => {
                            let (l, m) =
                                sign_text(x, if matches!(**x, Expr::Num(_)) { 1 } else { 2 });
                            (l + if i == 0 { 1 } else { 3 }, m + 1)
                        }
                        t => {
                            let (l, m) = sign_text(t, 1);
                            (l + if i == 0 { 0 } else { 3 }, m)
                        }
                    };
                    (len + l, minus + m)
                })
        }
        Expr::Mul(v) => v.iter().fold(
            (brackets(prec > 2) + v.len().saturating_sub(1), 0),
            |(len, minus), f| {
                let (l, m) = sign_text(f, 2);
                (len + l, minus + m)
            },
        ),
        Expr::Neg(x) => {
            let (l, m) = sign_text(x, 2);
            (brackets(prec > 1) + 1 + l, m + 1)
        }
        Expr::Pow(x, _) => sign_text(x, 3),
        _ => (0, 0),
    }
}

/// What [`sign_text`] reads of an expression at every precedence, found once per node: its
/// text at precedence 0, the precedence above which it takes brackets, and whether it is a
/// negation (as a sum's term it then brings its own ` - `, not a ` + `).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct Shape {
    /// `sign_text(e, 0)`.
    text: (usize, usize),
    /// Brackets (2 characters) at a precedence above this: a sum's or a negation's above 1, a
    /// product's above 2, never a power's (at every precedence its base's at 3) or a leaf's.
    open: u8,
    /// Whether `e` is `Expr::Neg`.
    neg: bool,
}

impl Shape {
    /// A number, symbol or call: no signs or brackets of its own.
    const LEAF: Shape = Shape {
        text: (0, 0),
        open: u8::MAX,
        neg: false,
    };

    /// `sign_text(e, prec)`.
    fn at(self, prec: u8) -> (usize, usize) {
        let (l, m) = self.text;
        (l + if prec > self.open { 2 } else { 0 }, m)
    }

    /// The text `e` makes as a term of a sum with the separator before it (none before the
    /// first term, ` + ` or ` - ` before a later one): a negation's own minus sign is its
    /// ` - `, then what it negates as a factor (or a number as a term: a number's text is
    /// empty at every precedence, so that is the same).
    fn term(self, first: bool) -> (usize, usize) {
        if self.neg {
            let (l, m) = self.text;
            (l + if first { 0 } else { 2 }, m)
        } else {
            let (l, m) = self.at(1);
            (l + if first { 0 } else { 3 }, m)
        }
    }

    /// The shape of `Expr::Neg(e)`: a minus sign, then `e` as a factor.
    fn minus_sign(self) -> Shape {
        let (l, m) = self.at(2);
        Shape {
            text: (1 + l, m + 1),
            open: 1,
            neg: true,
        }
    }

    /// The shape of the sum of terms of these shapes, in this order.
    fn sum(terms: impl Iterator<Item = Shape>) -> Shape {
        let text = terms.enumerate().fold((0, 0), |(len, minus), (i, t)| {
            let (l, m) = t.term(i == 0);
            (len + l, minus + m)
        });
        Shape {
            text,
            open: 1,
            neg: false,
        }
    }
}

/// The [`Shape`] of `e`, read in one walk.
fn shape(e: &Expr) -> Shape {
    match e {
        Expr::Add(v) => Shape::sum(v.iter().map(shape)),
        Expr::Mul(v) => Shape {
            text: v
                .iter()
                .fold((v.len().saturating_sub(1), 0), |(len, minus), f| {
                    let (l, m) = shape(f).at(2);
                    (len + l, minus + m)
                }),
            open: 2,
            neg: false,
        },
        Expr::Neg(x) => shape(x).minus_sign(),
        Expr::Pow(x, _) => Shape {
            text: shape(x).at(3),
            ..Shape::LEAF
        },
        _ => Shape::LEAF,
    }
}

/// `-e` with its sign placed where it prints shortest ([`sign_text`]), then with the fewest
/// minus signs: taken into a sum (each term turned, or its own sign cancelled inside it, a
/// positive term moved first when the first would be negative) or into a product's sum
/// factor, or kept in front. `-(1/4 (a - b))` is
/// `1/4 (b - a)`, `-(-a + b)` is `a - b`, `-(c (-a + b))` is `c (a - b)`; `-1/4 (a + b)`
/// stays (`1/4 (-a - b)` prints as long with one minus more), never a `-(-...)`.
///
/// Each way is judged by its text, read off the operands' [`Shape`]s ([`plan`]), and only the
/// way taken is built ([`turn`]) of `e`'s own operands: one walk of `e` and one of what is
/// rebuilt. Building each sub-sum's turned form to compare it (the route before) cloned,
/// walked and dropped each subtree once for every sum and product above it.
pub(super) fn minus(e: Expr) -> Expr {
    match e {
        Expr::Neg(x) => *x,
        e @ (Expr::Add(_) | Expr::Mul(_)) => {
            let mut steps = Vec::new();
            let (_, turned) = plan(&e, &mut steps);
            let e = turn(e, &steps, 0);
            debug_assert_eq!(sign_text(&e, 0), turned.text, "the text planned is built");
            e
        }
        e => Expr::Neg(Box::new(e)),
    }
}

/// What [`minus`] does at a sum or product that it turns: one per node, in the order
/// [`plan`] meets them (a node's own, then those of the sums and products its turning
/// reaches, operand by operand).
#[derive(Clone, Copy, Debug)]
struct Step {
    /// The index past this node's steps and those of the nodes under it.
    end: usize,
    /// Whether the sign goes into the node (else it is left in front, `-(...)`).
    into: bool,
    /// A product's sum factor that takes the sign (when `into`).
    factor: usize,
    /// As a sum's term: whether its [`minus`] is taken (else it is put under a minus sign).
    taken: bool,
}

/// The shapes of the sum or product `e` and of [`minus`] of it, the choices pushed on
/// `steps` (this node's first): each way compared by its text as the route that built every
/// way compared it (kept in the tests as `minus_before`), with the same ties (the first way
/// met is kept on equal texts).
fn plan(e: &Expr, steps: &mut Vec<Step>) -> (Shape, Shape) {
    let at = steps.len();
    steps.push(Step {
        end: at,
        into: false,
        factor: 0,
        taken: false,
    });
    let (whole, turned) = match e {
        Expr::Add(terms) => {
            // The turned terms' texts as later terms; the one moved first (a positive term
            // if there is one, else the first) is read as first at the end.
            let (mut text, mut turned, mut front) = ((0, 0), (0, 0), None::<Shape>);
            for (i, t) in terms.iter().enumerate() {
                let (s, m) = match t {
                    Expr::Add(_) | Expr::Mul(_) => {
                        let k = steps.len();
                        let (s, inside) = plan(t, steps);
                        let under = s.minus_sign();
                        // As a later term, where its own sign costs nothing.
                        let taken = inside.term(false) < under.term(false);
                        steps[k].taken = taken;
                        (s, if taken { inside } else { under })
                    }
                    // `minus` of any other term is its negation.
                    Expr::Neg(x) => {
                        let x = shape(x);
                        (x.minus_sign(), x)
                    }
                    t => {
                        let s = shape(t);
                        (s, s.minus_sign())
                    }
                };
                let ((l, n), (tl, tn)) = (s.term(i == 0), m.term(false));
                text = (text.0 + l, text.1 + n);
                turned = (turned.0 + tl, turned.1 + tn);
                if front.is_none_or(|f| f.neg && !m.neg) {
                    front = Some(m);
                }
            }
            if let Some(f) = front {
                turned.0 -= f.term(false).0 - f.term(true).0;
            }
            let whole = Shape {
                text,
                open: 1,
                neg: false,
            };
            let outside = whole.minus_sign();
            let into = turned < outside.text;
            steps[at].into = into;
            let turned = Shape {
                text: turned,
                ..whole
            };
            (whole, if into { turned } else { outside })
        }
        Expr::Mul(v) => {
            // The texts of the ways differ from the product's text by a sign in front or by
            // one factor's: compared by those differences, the first way met kept on ties.
            let (mut text, mut best) = ((v.len().saturating_sub(1), 0), None);
            let mut least: (isize, isize) = (1, 1);
            for (i, f) in v.iter().enumerate() {
                let s = match f {
                    Expr::Add(_) => {
                        let (s, turned) = plan(f, steps);
                        let ((fl, fm), (tl, tm)) = (s.at(2), turned.at(2));
                        let change = (tl as isize - fl as isize, tm as isize - fm as isize);
                        if !turned.neg && change < least {
                            (least, best) = (change, Some(i));
                        }
                        s
                    }
                    f => shape(f),
                };
                let (l, m) = s.at(2);
                text = (text.0 + l, text.1 + m);
            }
            let whole = Shape {
                text,
                open: 2,
                neg: false,
            };
            let turned = match best {
                Some(i) => {
                    steps[at].into = true;
                    steps[at].factor = i;
                    let moved = |x: usize, d: isize| x.checked_add_signed(d).expect("a text");
                    Shape {
                        text: (moved(text.0, least.0), moved(text.1, least.1)),
                        ..whole
                    }
                }
                None => whole.minus_sign(),
            };
            (whole, turned)
        }
        _ => unreachable!("only sums and products are planned"),
    };
    steps[at].end = steps.len();
    (whole, turned)
}

/// [`minus`] of the sum or product `e` as [`plan`] chose it (its step `steps[at]`): only the
/// way taken is built, of `e`'s own operands.
fn turn(e: Expr, steps: &[Step], at: usize) -> Expr {
    let step = steps[at];
    match e {
        Expr::Add(terms) if step.into => {
            let mut next = at + 1;
            let mut turned: Vec<Expr> = terms
                .into_iter()
                .map(|t| match t {
                    t @ (Expr::Add(_) | Expr::Mul(_)) => {
                        let k = next;
                        next = steps[k].end;
                        if steps[k].taken {
                            turn(t, steps, k)
                        } else {
                            Expr::Neg(Box::new(t))
                        }
                    }
                    t => negated(t),
                })
                .collect();
            // A positive term first, the others in their order (a Fourier sum keeps its
            // modes' order but one).
            if matches!(turned.first(), Some(Expr::Neg(_))) {
                if let Some(p) = turned.iter().position(|t| !matches!(t, Expr::Neg(_))) {
                    turned[..=p].rotate_right(1);
                }
            }
            Expr::Add(turned)
        }
        Expr::Mul(mut v) if step.into => {
            // The factor's steps follow those of the sum factors before it.
            let k = v[..step.factor]
                .iter()
                .filter(|f| matches!(f, Expr::Add(_)))
                .fold(at + 1, |k, _| steps[k].end);
            let f = std::mem::replace(&mut v[step.factor], Expr::zero());
            v[step.factor] = turn(f, steps, k);
            Expr::Mul(v)
        }
        e => Expr::Neg(Box::new(e)),
    }
}
/// `f(b + q pi/2)` as `g(b)`, negated when the flag says so: `(g, negated)` for `q` quarter
/// turns (modulo 4; `cos(b + pi/2) = -sin(b)`, `sin(b - pi/2) = -cos(b)`).
pub(crate) fn quarter_turned(f: Trig, q: i64) -> (Trig, bool) {
    match (f, q.rem_euclid(4)) {
        (Trig::Cos, 0) => (Trig::Cos, false),
        (Trig::Cos, 1) => (Trig::Sin, true),
        (Trig::Cos, 2) => (Trig::Cos, true),
        (Trig::Cos, _) => (Trig::Sin, false),
        (Trig::Sin, 0) => (Trig::Sin, false),
        (Trig::Sin, 1) => (Trig::Cos, false),
        (Trig::Sin, 2) => (Trig::Sin, true),
        (Trig::Sin, _) => (Trig::Cos, true),
    }
}

/// `-e`, without a double negation.
fn negated(e: Expr) -> Expr {
    match e {
        Expr::Neg(x) => *x,
        e => Expr::Neg(Box::new(e)),
    }
}

/// `e` with each call `f(angle)` for which `map` returns `Some((g, b, neg))` replaced by
/// `g(b)`, negated when `neg`; the signs met are moved out of products and powers and kept on
/// the terms of sums (a sign may be left at the top).
fn walk_signed(e: Expr, map: &mut TrigMap) -> Expr {
    match e {
        Expr::Trig { f, angle } => match map(f, &angle) {
            Some((g, b, true)) => Expr::Neg(Box::new(Expr::Trig { f: g, angle: b })),
            Some((g, b, false)) => Expr::Trig { f: g, angle: b },
            None => Expr::Trig { f, angle },
        },
        Expr::Add(v) => Expr::Add(
            v.into_iter()
                .map(|x| match walk_signed(x, map) {
                    Expr::Neg(y) => negated(*y),
                    y => y,
                })
                .collect(),
        ),
        Expr::Mul(v) => {
            let mut neg = false;
            let parts = v
                .into_iter()
                .map(|x| match walk_signed(x, map) {
                    Expr::Neg(y) => {
                        neg = !neg;
                        *y
                    }
                    y => y,
                })
                .collect();
            if neg {
                Expr::Neg(Box::new(Expr::Mul(parts)))
            } else {
                Expr::Mul(parts)
            }
        }
        Expr::Neg(x) => negated(walk_signed(*x, map)),
        Expr::Pow(x, n) => match walk_signed(*x, map) {
            Expr::Neg(y) if n % 2 == 0 => Expr::Pow(y, n),
            Expr::Neg(y) => Expr::Neg(Box::new(Expr::Pow(y, n))),
            y => Expr::Pow(Box::new(y), n),
        },
        e => e,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift).
    struct Gen(u64);

    impl Gen {
        fn pick<T: Clone>(&mut self, v: &[T]) -> T {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            v[(self.0 % v.len() as u64) as usize].clone()
        }
    }

    fn random_angle(g: &mut Gen) -> Angle {
        let ks = [-2, -1, 0, 0, 1, 2].map(Small::from_integer);
        let halves = [
            Small::new(-1, 2),
            Small::zero(),
            Small::zero(),
            Small::new(1, 3),
        ];
        let mut terms = Vec::new();
        for name in ["a", "b", "theta1"] {
            let k = g.pick(&ks);
            if !k.is_zero() {
                terms.push((Sym::new(name), k));
            }
        }
        Angle::new(terms, g.pick(&halves), g.pick(&halves))
    }

    /// Placeholders read once per symbol are the placeholders read at every node (the route
    /// before, kept here): random sums, products, negations and powers of placeholders
    /// (`cos(q1)`, `sin(theta12)`), plain symbols and names that only look alike (`cos(`,
    /// `tan(q1)`, `cos(q1)x`), each repeated many times.
    #[test]
    fn placeholders_read_once_are_those_read_everywhere() {
        fn everywhere(e: Expr) -> Expr {
            match e {
                Expr::Sym(s) => match crate::scalar::parse_trig_placeholder(s.name()) {
                    Some((x, f)) => Expr::Trig {
                        f,
                        angle: Angle::of_symbol(Sym::new(x)),
                    },
                    None => Expr::Sym(s),
                },
                Expr::Add(v) => Expr::Add(v.into_iter().map(everywhere).collect()),
                Expr::Mul(v) => Expr::Mul(v.into_iter().map(everywhere).collect()),
                Expr::Neg(e) => Expr::Neg(Box::new(everywhere(*e))),
                Expr::Pow(e, n) => Expr::Pow(Box::new(everywhere(*e)), n),
                e => e,
            }
        }
        let names = [
            "cos(q1)",
            "sin(q1)",
            "cos(theta12)",
            "sin(a2)",
            "l1",
            "q1",
            "cos(",
            "tan(q1)",
            "cos(q1)x",
            "sin()",
        ];
        fn random(g: &mut Gen, names: &[&str], depth: u32) -> Expr {
            if depth == 0 || g.pick(&[0, 1, 2]) == 0 {
                return Expr::Sym(Sym::new(g.pick(names)));
            }
            let n = g.pick(&[1usize, 2, 3]);
            let v: Vec<Expr> = (0..n).map(|_| random(g, names, depth - 1)).collect();
            match g.pick(&[0, 1, 2, 3]) {
                0 => Expr::Add(v),
                1 => Expr::Mul(v),
                2 => Expr::Neg(Box::new(Expr::Add(v))),
                _ => Expr::Pow(Box::new(Expr::Mul(v)), 2),
            }
        }
        let mut g = Gen(0x9e37_79b9_7f4a_7c15);
        let mut calls_seen = 0;
        for _ in 0..300 {
            let e = random(&mut g, &names, 4);
            let (a, b) = (e.clone().with_placeholders_as_trig(), everywhere(e));
            let mut c = Vec::new();
            calls(&a, &mut c);
            calls_seen += c.len();
            assert_eq!(a, b);
        }
        assert!(calls_seen > 300, "{calls_seen}");
    }

    /// The calls of `e` (with the sign of each left out).
    fn calls(e: &Expr, out: &mut Vec<(Trig, Angle)>) {
        match e {
            Expr::Trig { f, angle } => out.push((*f, angle.clone())),
            Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| calls(x, out)),
            Expr::Neg(x) | Expr::Pow(x, _) => calls(x, out),
            _ => {}
        }
    }

    /// [`Expr::cheapest_offsets`] keeps each expression's value exactly and shows every call
    /// at an offset no costlier than any equal form of it found independently: on seeded random
    /// sums of signed products of a number, maybe a symbol, and one or two cosines or sines of
    /// symbolic angles plus `k pi/n` (n in 5, 7, 9, 10, 18), each call of the result is
    /// compared, in f64 at a point, with the eight calls `cos`, `sin` at its offset plus
    /// `j pi/2`: every one equal to it up to sign costs no less. The issue's case is rewritten
    /// as expected, and most expressions change.
    #[test]
    fn calls_at_their_cheapest_offsets_keep_the_value() {
        let cost = |e: &Expr| super::super::alt::full_cost(e).0;
        let q23 = |pi: Small| {
            let t = vec![
                (Sym::new("q2"), Small::one()),
                (Sym::new("q3"), -Small::one()),
            ];
            Angle::new(t, Small::zero(), pi)
        };
        let quarter = |f: Trig, pi: Small| {
            Expr::Mul(vec![
                Expr::Num(BigRational::new(1.into(), 4.into())),
                Expr::Trig { f, angle: q23(pi) },
            ])
        };
        let issue = quarter(Trig::Cos, Small::new(-4, 9)).cheapest_offsets(&cost);
        assert_eq!(issue, quarter(Trig::Sin, Small::new(1, 18)));
        let mut g = Gen(0x0ff5_e7c4_ea9e_0001);
        let point = [("a", 0.37), ("b", -1.21), ("theta1", 2.05), ("l", 1.3)];
        let (mut changed, mut checked) = (0, 0);
        for _ in 0..400 {
            let n = g.pick(&[5i64, 7, 9, 10, 18]);
            let ks: Vec<i64> = (1 - 2 * n..2 * n).collect();
            let mut terms = Vec::new();
            for _ in 0..g.pick(&[1, 2, 3, 4]) {
                let mut factors = vec![Expr::Num(BigRational::from_integer(
                    g.pick(&[1, 2, 3]).into(),
                ))];
                if g.pick(&[false, true]) {
                    factors.push(Expr::Sym(Sym::new("l")));
                }
                for _ in 0..g.pick(&[1, 2]) {
                    let mut angle = random_angle(&mut g);
                    if angle.terms.is_empty() {
                        angle.terms.push((Sym::new("a"), Small::one()));
                    }
                    angle.constant = Small::zero();
                    angle.pi = Small::new(g.pick(&ks), n);
                    angle.reduce_offset();
                    let f = g.pick(&[Trig::Cos, Trig::Sin]);
                    factors.push(Expr::Trig { f, angle });
                }
                let term = Expr::Mul(factors);
                terms.push(if g.pick(&[false, true]) {
                    Expr::Neg(Box::new(term))
                } else {
                    term
                });
            }
            let e = Expr::Add(terms);
            let c = e.clone().cheapest_offsets(&cost);
            assert_eq!(c.to_scalar(), e.to_scalar(), "{e:?}");
            changed += usize::from(c != e);
            let mut found = Vec::new();
            calls(&c, &mut found);
            for (f, angle) in found {
                let shown = Expr::Trig {
                    f,
                    angle: angle.clone(),
                };
                let v = shown.value_at(&point).expect("a value");
                for j in 0..4 {
                    for h in [Trig::Cos, Trig::Sin] {
                        let mut b = angle.clone();
                        b.pi += Small::new(j, 2);
                        b.reduce_offset();
                        let other = Expr::Trig { f: h, angle: b };
                        let w = other.value_at(&point).expect("a value");
                        if (w.abs() - v.abs()).abs() < 1e-12
                            && (w - v).abs().min((w + v).abs()) < 1e-12
                        {
                            checked += 1;
                            assert!(cost(&shown) <= cost(&other), "{shown:?} vs {other:?}");
                        }
                    }
                }
            }
        }
        assert!(
            changed > 100 && checked > 2000,
            "{changed} changed, {checked} checked"
        );
    }

    // The route before `plan` and `turn` (session 31), kept as the reference: each sum's and
    // product's turned operands built and their texts compared.
    /// [`sign_text`] of term `t` of a sum, or of `-t` (without a double negation, as [`negated`]
    /// makes it) when `neg`, with the separator before it (none before the first term, ` + ` or
    /// ` - ` before a later one): what the sum's text holds for it. Read off `t` without building
    /// `-t` ([`minus`] compares a term turned both ways).
    fn term_text_before(t: &Expr, neg: bool, first: bool) -> (usize, usize) {
        // The term `-x`: its minus sign, or ` - `, then `x` as a factor (a number as a term).
        let negative = |x: &Expr| {
            let (l, m) = sign_text(x, if matches!(x, Expr::Num(_)) { 1 } else { 2 });
            (l + if first { 1 } else { 3 }, m + 1)
        };
        match (t, neg) {
            (Expr::Neg(x), true) => term_text_before(x, false, first),
            (Expr::Neg(x), false) => negative(x),
            (t, true) => negative(t),
            (t, false) => {
                let (l, m) = sign_text(t, 1);
                (l + if first { 0 } else { 3 }, m)
            }
        }
    }

    /// [`sign_text`] of the product of `v` without its brackets: its separators and each
    /// factor's text as a factor. A sum over the factors, so that [`minus`] finds the text of the
    /// product with one factor replaced from the whole's.
    fn factors_text_before(v: &[Expr]) -> (usize, usize) {
        v.iter()
            .fold((v.len().saturating_sub(1), 0), |(len, minus), f| {
                let (l, m) = sign_text(f, 2);
                (len + l, minus + m)
            })
    }

    /// `-e` with its sign placed where it prints shortest ([`sign_text`]), then with the fewest
    /// minus signs: taken into a sum (each term turned, or its own sign cancelled inside it, a
    /// positive term moved first when the first would be negative) or into a product's sum
    /// factor, or kept in front. `-(1/4 (a - b))` is
    /// `1/4 (b - a)`, `-(-a + b)` is `a - b`, `-(c (-a + b))` is `c (a - b)`; `-1/4 (a + b)`
    /// stays (`1/4 (-a - b)` prints as long with one minus more), never a `-(-...)`.
    fn minus_before(e: Expr) -> Expr {
        let key = |e: &Expr| sign_text(e, 0);
        match e {
            Expr::Neg(x) => *x,
            Expr::Add(terms) => {
                let mut turned: Vec<Expr> = terms
                    .iter()
                    .map(|t| {
                        let inside = minus_before(t.clone());
                        // As a later term of the sum, where its own sign costs nothing; the term
                        // negated is built only when taken.
                        debug_assert_eq!(
                            term_text_before(t, true, false),
                            term_text_before(&negated(t.clone()), false, false)
                        );
                        if term_text_before(&inside, false, false)
                            < term_text_before(t, true, false)
                        {
                            inside
                        } else {
                            negated(t.clone())
                        }
                    })
                    .collect();
                // A positive term first, the others in their order (a Fourier sum keeps its
                // modes' order but one).
                if matches!(turned.first(), Some(Expr::Neg(_))) {
                    if let Some(p) = turned.iter().position(|t| !matches!(t, Expr::Neg(_))) {
                        let first = turned.remove(p);
                        turned.insert(0, first);
                    }
                }
                let inside = Expr::Add(turned);
                let outside = Expr::Neg(Box::new(Expr::Add(terms)));
                if key(&inside) < key(&outside) {
                    inside
                } else {
                    outside
                }
            }
            Expr::Mul(mut v) => {
                // The texts compared from the factors' ([`factors_text`]): the sign in front,
                // `-(...)`, or one sum factor turned, the product built once, for the one taken.
                let (len, neg) = factors_text_before(&v);
                let mut best: (Option<(usize, Expr)>, (usize, usize)) = (None, (1 + len, neg + 1));
                for (i, f) in v.iter().enumerate() {
                    if !matches!(f, Expr::Add(_)) {
                        continue;
                    }
                    let turned = minus_before(f.clone());
                    if matches!(turned, Expr::Neg(_)) {
                        continue;
                    }
                    let ((fl, fm), (tl, tm)) = (sign_text(f, 2), sign_text(&turned, 2));
                    let candidate = (len - fl + tl, neg - fm + tm);
                    if candidate < best.1 {
                        best = (Some((i, turned)), candidate);
                    }
                }
                let (turned, text) = best;
                let e = match turned {
                    Some((i, f)) => {
                        v[i] = f;
                        Expr::Mul(v)
                    }
                    None => Expr::Neg(Box::new(Expr::Mul(v))),
                };
                debug_assert_eq!(key(&e), text, "the product's text from its factors'");
                e
            }
            e => Expr::Neg(Box::new(e)),
        }
    }

    /// Random display expressions of every kind `minus` meets: sums (empty, of one term or
    /// more, terms signed), products (with a leading number, sum factors, even signed
    /// factors), negations (nested too), powers of sums and products, and leaves.
    fn random_expr(g: &mut Gen, depth: u32) -> Expr {
        let leaf = g.pick(&[0, 1, 2, 3, 4, 5]);
        if depth == 0 || g.pick(&[0, 1, 2, 3]) == 0 {
            let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
            return match leaf {
                0 => Expr::Num(g.pick(&[q(1, 1), q(1, 2), q(3, 1), q(0, 1)])),
                1 => Expr::Sqrt(g.pick(&[2, 3])),
                2 => Expr::Sym(Sym::new(g.pick(&["a", "l1"]))),
                _ => Expr::Trig {
                    f: g.pick(&[Trig::Cos, Trig::Sin]),
                    angle: random_angle(g),
                },
            };
        }
        let n = g.pick(&[0usize, 1, 2, 2, 3, 3, 4]);
        match g.pick(&[0, 0, 0, 1, 1, 1, 2, 3]) {
            0 => Expr::Add(
                (0..n)
                    .map(|_| match random_expr(g, depth - 1) {
                        t if g.pick(&[false, true]) => negated(t),
                        t => t,
                    })
                    .collect(),
            ),
            1 => {
                let mut v: Vec<Expr> = (0..n).map(|_| random_expr(g, depth - 1)).collect();
                if g.pick(&[false, true]) {
                    v.insert(0, Expr::Num(BigRational::new(1.into(), 4.into())));
                }
                Expr::Mul(v)
            }
            2 => Expr::Neg(Box::new(random_expr(g, depth - 1))),
            _ => Expr::Pow(Box::new(random_expr(g, depth - 1)), 2),
        }
    }

    /// Every sum and product in `e` (`e` first).
    fn sums_and_products<'a>(e: &'a Expr, out: &mut Vec<&'a Expr>) {
        match e {
            Expr::Add(v) | Expr::Mul(v) => {
                out.push(e);
                v.iter().for_each(|x| sums_and_products(x, out));
            }
            Expr::Neg(x) | Expr::Pow(x, _) => sums_and_products(x, out),
            _ => {}
        }
    }

    /// Whether `-e` was not simply left in front: the sign taken into a sum or a product.
    fn taken_in(e: &Expr, m: &Expr) -> bool {
        !matches!(m, Expr::Neg(x) if **x == *e) && !matches!(e, Expr::Neg(_))
    }

    /// `minus` planned from the operands' shapes and built once is the route before, which
    /// built every way: the same `Expr` on seeded random expressions of every kind and on each
    /// sum and product in them; and the shapes read in one walk are `sign_text` at every
    /// precedence. Most sums and many products take the sign in, terms and factors turned
    /// inside them at several depths.
    #[test]
    fn minus_planned_is_minus_built_every_way() {
        // A tie: the one-term sum of `(a) + (a)` (one-term sums, no brackets) with the sign
        // taken into its term prints `-(a + a)`, as with the sign in front: it stays in front.
        let a = || Expr::Add(vec![Expr::Sym(Sym::new("a"))]);
        let tie = Expr::Add(vec![Expr::Add(vec![a(), a()])]);
        assert_eq!(minus(tie.clone()), minus_before(tie.clone()));
        assert_eq!(minus(tie.clone()), Expr::Neg(Box::new(tie)));
        let mut g = Gen(0x51ed_2702_c0ff_ee31);
        let (mut checked, mut into_sums, mut into_products, mut deep) = (0, 0, 0, 0);
        for _ in 0..3000 {
            let e = random_expr(&mut g, 5);
            let mut parts = Vec::new();
            sums_and_products(&e, &mut parts);
            for x in std::iter::once(&e).chain(parts) {
                for prec in 0..4 {
                    assert_eq!(shape(x).at(prec), sign_text(x, prec), "{x:?} at {prec}");
                }
                let (new, old) = (minus(x.clone()), minus_before(x.clone()));
                assert_eq!(new, old, "-({x:?})");
                checked += 1;
                if taken_in(x, &new) {
                    match x {
                        Expr::Add(_) => into_sums += 1,
                        Expr::Mul(_) => into_products += 1,
                        _ => {}
                    }
                    let mut inner = Vec::new();
                    sums_and_products(&new, &mut inner);
                    deep += usize::from(inner.len() > 3);
                }
            }
        }
        assert!(
            checked > 10_000 && into_sums > 1000 && into_products > 300 && deep > 300,
            "{checked} checked, {into_sums} sums and {into_products} products taking the \
             sign, {deep} deep"
        );
    }

    /// The entries of the last column and the first row of pseudo-random DH chains of
    /// `joints` revolute joints in the Jaco-style arm's shape (twists pi/3, pi/6, pi/2,
    /// angles offset by `k pi/9` one time in two, symbolic lengths).
    fn chain_entries(seed: u64, joints: usize) -> Vec<Scalar> {
        let m = super::super::tests::chain_matrix(seed, joints, 4);
        let mut out: Vec<Scalar> = (0..3).map(|i| m[i][3].clone()).collect();
        out.extend((0..3).map(|k| m[0][k].clone()));
        out
    }

    /// On real closed forms (the translations and a rotation row of pseudo-random
    /// Jaco-style chains), `minus` gives what the route before gives on each sum and product
    /// in each form, and `scaled` by a negative number is still the form's multiple.
    #[test]
    fn minus_of_closed_forms_is_the_route_before() {
        let (mut forms, mut taken) = (0, 0);
        for seed in 0..6 {
            for x in chain_entries(seed, 3 + seed as usize % 2) {
                let Ok(e) = crate::closed_form(&x) else {
                    continue;
                };
                forms += 1;
                let mut parts = Vec::new();
                sums_and_products(&e, &mut parts);
                for p in parts {
                    let new = minus(p.clone());
                    assert_eq!(new, minus_before(p.clone()), "-({p:?})");
                    taken += usize::from(taken_in(p, &new));
                }
                for c in [-1, -3] {
                    let c = BigRational::from_integer(c.into());
                    let s = e.clone().scaled(&c);
                    assert_eq!(s.to_scalar(), x.clone() * Scalar::rational(c), "{e:?}");
                }
            }
        }
        assert!(
            forms >= 30 && taken > 100,
            "{forms} forms, {taken} taken in"
        );
    }

    #[test]
    fn angles_order_as_their_frequency_vectors() {
        // The display order must be the canonical form's: the constant as the entry `1`,
        // first in the vector.
        let mut g = Gen(0x2545_f491_4f6c_dd1d);
        for _ in 0..2000 {
            let (a, b) = (random_angle(&mut g), random_angle(&mut g));
            let old = (a.freq(), a.pi).cmp(&(b.freq(), b.pi));
            assert_eq!(a.cmp(&b), old, "{a:?} vs {b:?}");
            assert_eq!((a == b), old.is_eq());
            assert_eq!(Angle::from_freq(&a.freq(), a.pi), a);
            let lead = a.freq().first().map(|(_, k)| *k);
            assert_eq!(a.leading(), lead);
        }
    }

    #[test]
    fn the_constant_is_a_kind_of_symbol_not_a_name() {
        let one = Sym::one();
        assert!(one.is_one() && !one.is_pi());
        // Sorted by the text it prints as, before any symbol printing the same.
        assert!(one < Sym::new("a") && one < Sym::new("1") && Sym::new("0") < one);
        assert_ne!(one, Sym::new("1"));
        assert!(!Sym::new("1").is_one());
        assert!(Sym::new("pi").is_pi());
        // One word (a pointer to the interned name): a frequency entry `(Sym, Small)` is 24
        // bytes, where a `&str` symbol made it 32.
        assert_eq!(std::mem::size_of::<Sym>(), std::mem::size_of::<usize>());
    }

    #[test]
    fn an_angle_constant_is_a_field_and_evaluates_without_a_name() {
        let t = Scalar::sym("t");
        let x = (t.clone() + Scalar::int(1)).cos()
            * (t.clone() * small(&Small::new(1, 2)) - small(&Small::new(1, 3))).sin();
        let e = crate::closed_form(&x).expect("closed form");
        assert_eq!(e.to_scalar(), x);
        let mut angles = Vec::new();
        fn collect(e: &Expr, out: &mut Vec<Angle>) {
            match e {
                Expr::Trig { angle, .. } => out.push(angle.clone()),
                Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| collect(x, out)),
                Expr::Neg(x) | Expr::Pow(x, _) => collect(x, out),
                _ => {}
            }
        }
        collect(&e, &mut angles);
        assert!(!angles.is_empty());
        for a in &angles {
            assert!(a.terms.iter().all(|(s, _)| !s.is_one() && !s.is_pi()));
            assert!(!a.constant.is_zero(), "{a:?}");
        }
        // Numerically: the exact value, the display form, and an independent f64 formula.
        let tv = 0.7_f64;
        let want = (tv + 1.0).cos() * (tv / 2.0 - 1.0 / 3.0).sin();
        let asked = std::cell::RefCell::new(Vec::new());
        let exact = x
            .eval_symbols(&|s| {
                asked.borrow_mut().push(s.clone());
                Some(tv)
            })
            .expect("value");
        assert!(asked.borrow().iter().all(|s| s.name() == "t"));
        let shown = e.value_at(&[("t", tv)]).expect("value");
        assert!((exact - want).abs() < 1e-12 && (shown - want).abs() < 1e-12);
    }
}
