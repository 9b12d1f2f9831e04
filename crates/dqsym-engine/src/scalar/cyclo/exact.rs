//! The exact path: a group rewritten by dense linear algebra over `Q` in the power basis of
//! its field (the reference the fast path is checked against, and its fallback).

use super::super::atoms::Small;
use super::super::par::PerFork;
use super::super::{ScalarError, Term, Q};
use super::candidates::{candidates, Candidate, Col};
use super::field::{field, halves, mono, sparse_mul, Field, Sparse};
use super::level::{level_of, pi_exponent, primes_of, totient};
use super::{poisoned, terms_in_basis, Cache};
use num_rational::BigRational as Rat;
use num_traits::{One, Zero};
use std::collections::BTreeMap;
use std::sync::Arc;

/// A pivot row: its pivot index, the reduced vector, and the combination of columns it is.
pub(super) type PivotRow = (usize, Vec<Rat>, Vec<(usize, Rat)>);

/// A subspace of `Q^phi` spanned by columns added one at a time, in echelon form, with the
/// combination of columns each pivot row stands for.
pub(super) struct Span {
    pub(super) cols: usize,
    pub(super) rows: Vec<PivotRow>,
}

impl Span {
    pub(super) fn new() -> Span {
        Span {
            cols: 0,
            rows: Vec::new(),
        }
    }

    /// Reduces `v` against the pivots: the remainder, and the multiples of each pivot row
    /// taken away.
    pub(super) fn reduce(&self, mut v: Vec<Rat>) -> (Vec<Rat>, Vec<Rat>) {
        let mut lambdas = Vec::with_capacity(self.rows.len());
        for (p, row, _) in &self.rows {
            if v[*p].is_zero() {
                lambdas.push(Rat::zero());
                continue;
            }
            let l = &v[*p] / &row[*p];
            for (x, r) in v.iter_mut().zip(row) {
                if !r.is_zero() {
                    *x -= &l * r;
                }
            }
            lambdas.push(l);
        }
        (v, lambdas)
    }

    pub(super) fn independent(&self, v: &[Rat]) -> bool {
        self.reduce(v.to_vec()).0.iter().any(|x| !x.is_zero())
    }

    /// Adds a column; false when it depends on the others (it is then not recorded).
    pub(super) fn push(&mut self, v: Vec<Rat>) -> bool {
        let col = self.cols;
        let (rest, lambdas) = self.reduce(v);
        let Some(p) = rest.iter().position(|x| !x.is_zero()) else {
            return false;
        };
        let mut comb: BTreeMap<usize, Rat> = BTreeMap::new();
        comb.insert(col, Rat::one());
        for (l, (_, _, c)) in lambdas.iter().zip(&self.rows) {
            if l.is_zero() {
                continue;
            }
            for (j, x) in c {
                *comb.entry(*j).or_insert_with(Rat::zero) -= l * x;
            }
        }
        comb.retain(|_, x| !x.is_zero());
        self.rows.push((p, rest, comb.into_iter().collect()));
        self.cols += 1;
        true
    }

    /// The coefficients of `v` on the columns, or `None` when `v` is not in the span.
    pub(super) fn solve(&self, v: Vec<Rat>) -> Option<Vec<Rat>> {
        let (rest, lambdas) = self.reduce(v);
        if rest.iter().any(|x| !x.is_zero()) {
            return None;
        }
        let mut out = vec![Rat::zero(); self.cols];
        for (l, (_, _, c)) in lambdas.iter().zip(&self.rows) {
            if l.is_zero() {
                continue;
            }
            for (j, x) in c {
                out[*j] += l * x;
            }
        }
        Some(out)
    }
}

pub(super) struct Basis {
    pub(super) span: Span,
    pub(super) cols: Vec<Col>,
}
impl Basis {
    /// `R_M` (real) or `C_M` (complex, `4 | M`) inside `Q(zeta_W)`, with `sqrt(h)` (and
    /// `i sqrt(h)`) multiples for every square root of the field.
    /// `None` when the work budget runs out on the way (nothing is cached then).
    pub(super) fn new(f: &Field, m: u64, real: bool) -> Result<Basis, ScalarError> {
        let w = f.w;
        let mut span = Span::new();
        let mut cols = Vec::new();
        for Candidate { k, l, parts } in candidates(m, w, real) {
            let parts: Vec<Sparse> = parts.iter().map(halves).collect();
            super::super::charge((span.rows.len() * f.phi) as u64 + 1)?;
            if !span.independent(&f.reduce(&parts[0])?) {
                continue;
            }
            for (h, r) in &f.sqrts {
                for (imag, x) in parts.iter().enumerate() {
                    span.push(f.reduce(&sparse_mul(r, x, w))?);
                    cols.push(Col {
                        h: *h,
                        angle: Small::new(2 * k, l),
                        imag: imag == 1,
                    });
                }
            }
        }
        Ok(Basis { span, cols })
    }
}

pub(super) fn basis(f: &Field, m: u64, real: bool) -> Result<Arc<Basis>, ScalarError> {
    static CACHE: Cache<(u64, u64, bool), Basis> = PerFork::new();
    let cache = CACHE.get_or(Default::default);
    let key = (f.w, m, real);
    if let Some(b) = cache.lock().map_err(poisoned)?.get(&key) {
        return Ok(b.clone());
    }
    let b = Arc::new(Basis::new(f, m, real)?);
    cache.lock().map_err(poisoned)?.insert(key, b.clone());
    Ok(b)
}

/// The canonical terms of a group by exact dense linear algebra over `Q` (the reference the
/// fast path is checked against, and its fallback).
pub(super) fn canonical_group_exact(g: &[&Term]) -> Result<Vec<Term>, ScalarError> {
    let Some(first) = g.first() else {
        return Ok(Vec::new());
    };
    let real = first.mode.freq.is_empty();
    // Multiples of 24 only: K(zeta_M) for 24 | M are distinct fields, one for each smallest
    // field holding a value (K(zeta_15) = K(zeta_20) = K(zeta_120) since sqrt(-3) and i are
    // there), so the descent below ends at one M.
    let w = level_of(g.iter().copied())?;
    super::super::charge(g.len() as u64 * totient(w))?;
    let f = field(w)?;
    // y_s for each class s of square roots outside the field.
    let mut ys: BTreeMap<u64, Sparse> = BTreeMap::new();
    for t in g {
        let (s, h) = f.split(t.rad);
        let a = pi_exponent(&t.mode.pi, w);
        let q = t.coef.to_big();
        let half = &q / Rat::from_integer(2.into());
        let trig: Sparse = if real {
            if t.mode.is_unit() {
                mono(0, q)
            } else if !t.mode.sin {
                let mut s = mono(a, half.clone());
                *s.entry((w - a) % w).or_insert_with(Rat::zero) += half;
                s
            } else {
                // sin = -i (zeta^a - zeta^-a) / 2.
                let q4 = 3 * w / 4;
                let mut s = mono((a + q4) % w, half.clone());
                *s.entry((w - a + q4) % w).or_insert_with(Rat::zero) -= half;
                s
            }
        } else if !t.mode.sin {
            mono(a, q)
        } else {
            mono((a + 3 * w / 4) % w, q)
        };
        let x = sparse_mul(f.sqrt(h), &trig, w);
        let y = ys.entry(s).or_default();
        for (e, c) in x {
            *y.entry(e).or_insert_with(Rat::zero) += c;
        }
    }
    let ys: Vec<(u64, Vec<Rat>)> = ys
        .into_iter()
        .map(|(s, y)| Ok((s, f.reduce(&y)?)))
        .collect::<Result<_, ScalarError>>()?;
    let fits = |m: u64| -> Result<Option<Vec<Vec<Rat>>>, ScalarError> {
        let b = basis(&f, m, real)?;
        Ok(ys.iter().map(|(_, y)| b.span.solve(y.clone())).collect())
    };
    let mut m = w;
    let mut sol = fits(m)?.ok_or_else(|| {
        ScalarError::OutOfRange(format!("a value outside its cyclotomic field of order {w}"))
    })?;
    'descend: loop {
        for p in primes_of(m) {
            let n = m / p;
            if !n.is_multiple_of(24) {
                continue;
            }
            if let Some(s) = fits(n)? {
                m = n;
                sol = s;
                continue 'descend;
            }
        }
        break;
    }
    let b = basis(&f, m, real)?;
    let classes: Vec<u64> = ys.iter().map(|(s, _)| *s).collect();
    let sol = sol
        .into_iter()
        .map(|xs| xs.into_iter().map(Q::big).collect())
        .collect();
    terms_in_basis(first, real, &classes, sol, &b.cols)
}
