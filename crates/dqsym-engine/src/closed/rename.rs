//! Entries that are others with their symbols permuted and signed: `x = s(y)`, where `s`
//! replaces each of some symbols by another, negated or not. The components of a quaternion
//! product are such renamings of each other: component `k` of `A B` is component 0 of
//! `A (B v)` for a unit `v` (`-i`, `-j`, `-k`), and the components of `B v` are those of `B`
//! permuted, with signs. A recurrence's prefix products and Jacobian columns
//! (`app/recurrence.rs`) are written in such components, so three of each four of their
//! entries take a renamed closed form, without a search of their own.
//!
//! The renaming of a polynomial is exact ([`SignedRenaming::scalar`]: each term renamed and
//! its sign taken), and the caller compares it with the entry exactly before using it. The
//! form renamed ([`SignedRenaming::form`]) has the value of the entry by construction; it is
//! checked like every derived form (exactly in debug builds, numerically in release builds,
//! [`SignedRenaming::agrees`]). Like a turned form, it is the renaming of the other's form,
//! not necessarily what a search of its own would give: the search's ties see the order of
//! the symbols and its costs the signs.

use super::expr::Expr;
use crate::scalar::{Sym, Term};
use crate::Scalar;

/// A permutation of some symbols, each taken with a sign: `from` becomes `to`, negated when
/// `neg`. Sorted by `from`; the symbols renamed are the symbols renamed to, so no two symbols
/// of a monomial become one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct SignedRenaming(Vec<(Sym, Sym, bool)>);

impl SignedRenaming {
    /// The renaming `from -> (to, negated)`; `None` unless it permutes its symbols (each
    /// renamed once, and the symbols renamed to are those renamed).
    pub(crate) fn new(mut map: Vec<(Sym, Sym, bool)>) -> Option<SignedRenaming> {
        map.sort_by(|a, b| a.0.cmp(&b.0));
        let mut to: Vec<&Sym> = map.iter().map(|(_, t, _)| t).collect();
        to.sort();
        let froms = map.iter().map(|(f, _, _)| f);
        let permutes =
            map.windows(2).all(|w| w[0].0 != w[1].0) && froms.zip(&to).all(|(f, t)| f == *t);
        permutes.then_some(SignedRenaming(map))
    }

    /// The symbol `s` is renamed to, and whether negated. A short renaming (a quarter turn's
    /// two placeholders, a product's last factor's eight) is scanned for the interned symbol,
    /// a longer one searched by name: `Sym`'s order compares texts, its equality addresses.
    fn get(&self, s: &Sym) -> Option<(&Sym, bool)> {
        let k = if self.0.len() <= 16 {
            self.0.iter().position(|(f, _, _)| f == s)
        } else {
            self.0.binary_search_by(|(f, _, _)| f.cmp(s)).ok()
        };
        k.map(|k| (&self.0[k].1, self.0[k].2))
    }

    /// `p` renamed: each monomial's symbols renamed, its coefficient negated for each
    /// negated symbol of odd degree. `None` for an error value or when a renamed symbol is
    /// in a trigonometric mode.
    pub(crate) fn scalar(&self, p: &Scalar) -> Option<Scalar> {
        let terms = p.terms().ok()?;
        let mut out: Vec<Term> = Vec::with_capacity(terms.len());
        for term in terms {
            if term.mode.freq.iter().any(|(s, _)| self.get(s).is_some()) {
                return None;
            }
            let mut neg = false;
            let mut changed = false;
            let mut mono: Vec<(Sym, u32)> = Vec::with_capacity(term.mono.len());
            for (y, e) in term.mono.iter() {
                match self.get(y) {
                    Some((t, n)) => {
                        neg ^= n && e % 2 == 1;
                        changed |= t != y;
                        mono.push((t.clone(), *e));
                    }
                    None => mono.push((y.clone(), *e)),
                }
            }
            let mut moved = term.clone();
            if changed {
                mono.sort_by(|a, b| a.0.cmp(&b.0));
                moved.mono = mono.into();
            }
            if neg {
                moved.coef = -moved.coef;
            }
            out.push(moved);
        }
        Some(Scalar::from_terms_settled(out))
    }

    /// A closed form renamed: each renamed symbol replaced (negated where the renaming
    /// negates it), the signs tidied as a turn tidies them (each product's sign placed where
    /// `minus` puts it), the symbols of each product and the terms of each sum of monomials
    /// sorted as the search writes them. `None` when a renamed symbol is in a call's angle.
    pub(crate) fn form(&self, e: Expr) -> Option<Expr> {
        let (e, _) = self.walk(e, true)?;
        Some(e)
    }

    /// [`SignedRenaming::form`] as a turn of the placeholders writes it (`turn.rs`): the
    /// sums' terms and the negations of products kept where the form had them.
    pub(crate) fn form_as_turned(&self, e: Expr) -> Option<Expr> {
        let (e, _) = self.walk(e, false)?;
        Some(e)
    }

    /// The renamed subtree and whether it changed; with `tidy`, each changed sum of
    /// monomials sorted and each changed negated product's sign placed again.
    fn walk(&self, e: Expr, tidy: bool) -> Option<(Expr, bool)> {
        Some(match e {
            Expr::Sym(y) => match self.get(&y) {
                Some((t, neg)) => {
                    let s = Expr::Sym(t.clone());
                    let changed = neg || *t != y;
                    (if neg { Expr::Neg(Box::new(s)) } else { s }, changed)
                }
                None => (Expr::Sym(y), false),
            },
            Expr::Trig { f, angle } => {
                if angle.terms.iter().any(|(s, _)| self.get(s).is_some()) {
                    return None;
                }
                (Expr::Trig { f, angle }, false)
            }
            Expr::Add(v) => {
                let (mut v, changed) = self.walk_all(v, tidy)?;
                if changed && tidy {
                    super::turn::sort_monomial_terms(&mut v);
                }
                (Expr::Add(v), changed)
            }
            Expr::Mul(v) => {
                let (v, changed) = self.walk_all(v, tidy)?;
                if !changed {
                    return Some((Expr::Mul(v), false));
                }
                (super::turn::signed_product(v), true)
            }
            // A renamed product's sign placed again (`-s1 (-c2 + s3)` is `s1 (c2 - s3)`).
            Expr::Neg(t) => match self.walk(*t, tidy)? {
                (Expr::Neg(y), ch) => (*y, ch),
                (y @ Expr::Mul(_), true) if tidy => (super::turn::signed(true, y), true),
                (y, ch) => (Expr::Neg(Box::new(y)), ch),
            },
            Expr::Pow(t, n) => {
                let (t, ch) = self.walk(*t, tidy)?;
                if !ch {
                    return Some((Expr::Pow(Box::new(t), n), false));
                }
                (super::turn::signed_power(t, n), true)
            }
            e => (e, false),
        })
    }

    fn walk_all(&self, v: Vec<Expr>, tidy: bool) -> Option<(Vec<Expr>, bool)> {
        let mut changed = false;
        let v = v
            .into_iter()
            .map(|t| {
                let (t, ch) = self.walk(t, tidy)?;
                changed |= ch;
                Some(t)
            })
            .collect::<Option<Vec<Expr>>>()?;
        Some((v, changed))
    }

    /// Whether `e` has the value of `from` renamed, at a fixed pseudo-random point (to a
    /// relative 1e-9 of the magnitudes, as `agrees_numerically` compares): `e` there against
    /// `from` at the point renamed (each renamed symbol given its image's value, signed).
    pub(crate) fn agrees(&self, e: &Expr, from: &Expr) -> bool {
        self.agrees_times(e, from, 1.0)
    }

    /// [`SignedRenaming::agrees`] of `e` with `c` times `from` renamed.
    pub(crate) fn agrees_times(&self, e: &Expr, from: &Expr, c: f64) -> bool {
        let seed = 0x9e37_79b9_7f4a_7c15u64;
        let (a, scale_a) = e.eval_f64(&|s| super::point_value(s, seed));
        let (b, scale_b) = from.eval_f64(&|s| match self.get(s) {
            Some((t, neg)) => {
                let v = super::point_value(t, seed);
                if neg {
                    -v
                } else {
                    v
                }
            }
            None => super::point_value(s, seed),
        });
        let scale = scale_a.max(scale_b * c.abs()).max(1.0);
        a.is_finite() && b.is_finite() && (a - c * b).abs() <= 1e-9 * scale
    }

    /// The form of `x`, an entry equal to this renaming of an entry whose form is `from`
    /// (the caller compared the scalars exactly): `from` renamed, checked exactly in debug
    /// builds (so in every test) and numerically in release builds. `None` when it cannot be
    /// renamed or its check fails.
    pub(crate) fn renamed_form(&self, from: &Expr, x: &Scalar) -> Option<Expr> {
        let e = self.form(from.clone())?;
        let good = if cfg!(debug_assertions) {
            e.to_scalar() == *x
        } else {
            self.agrees(&e, from)
        };
        #[cfg(test)]
        super::turn::counts::count(good);
        good.then_some(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random polynomial in `syms` (products of up to three symbols, squares among them,
    /// integer coefficients), with a cosine of another symbol in some terms.
    fn random_poly(next: &mut impl FnMut(u64) -> u64, syms: &[Scalar]) -> Scalar {
        let mut p = Scalar::int(0);
        for _ in 0..1 + next(12) {
            let mut t = Scalar::int(next(9) as i64 - 4);
            for _ in 0..next(4) {
                t = t * syms[next(syms.len() as u64) as usize].clone();
            }
            if next(5) == 0 {
                t = t * Scalar::sym("u").cos();
            }
            p = p + t;
        }
        p
    }

    /// A random signed permutation of `names`.
    fn random_renaming(next: &mut impl FnMut(u64) -> u64, names: &[&str]) -> SignedRenaming {
        let mut to: Vec<&str> = names.to_vec();
        for i in (1..to.len()).rev() {
            to.swap(i, next(i as u64 + 1) as usize);
        }
        let map = names
            .iter()
            .zip(to)
            .map(|(f, t)| (Sym::new(f), Sym::new(t), next(2) == 0))
            .collect();
        SignedRenaming::new(map).expect("a permutation")
    }

    /// `p` with each symbol of `r` replaced by its signed image, all at once (through
    /// names of their own first), by `Scalar::subs`: the reference.
    fn substituted(p: &Scalar, r: &SignedRenaming) -> Scalar {
        let mut x = p.clone();
        for (k, (f, _, _)) in r.0.iter().enumerate() {
            x = x.subs(f.name(), &Scalar::sym(&format!("tmp{k}")));
        }
        for (k, (_, t, neg)) in r.0.iter().enumerate() {
            let to = if *neg {
                -Scalar::sym(t.name())
            } else {
                Scalar::sym(t.name())
            };
            x = x.subs(&format!("tmp{k}"), &to);
        }
        x
    }

    #[test]
    fn a_renaming_permutes_its_symbols() {
        let s = |n: &str| Sym::new(n);
        assert!(
            SignedRenaming::new(vec![(s("a"), s("b"), true), (s("b"), s("a"), false)]).is_some()
        );
        // `a -> b` alone would merge `a b` into `b^2`.
        assert!(SignedRenaming::new(vec![(s("a"), s("b"), false)]).is_none());
        assert!(
            SignedRenaming::new(vec![(s("a"), s("a"), false), (s("a"), s("b"), false)]).is_none()
        );
    }

    /// The renamed scalar, term by term, is the substitution of the signed symbols; and the
    /// renamed closed form has its value, exactly, and agrees numerically with the form it
    /// came from (`agrees`), which a renaming of another sign does not.
    #[test]
    fn a_renamed_scalar_and_its_renamed_form_are_the_substitution() {
        let names = ["a", "b", "c", "d", "e"];
        let syms: Vec<Scalar> = names.iter().map(|n| Scalar::sym(n)).collect();
        let mut next = crate::testing::xorshift_below(0x5eed_0032);
        let (mut forms, mut changed) = (0, 0);
        for _ in 0..150 {
            let p = random_poly(&mut next, &syms);
            let r = random_renaming(&mut next, &names);
            let x = r.scalar(&p).expect("no renamed symbol in a call");
            assert_eq!(x, substituted(&p, &r), "{p}");
            let e = crate::closed_form(&p).expect("a form");
            let f = r.form(e.clone()).expect("no renamed symbol in a call");
            assert_eq!(f.to_scalar(), x, "{p}: {e:?}");
            assert!(r.agrees(&f, &e), "{p}: {e:?}");
            assert!(r.renamed_form(&e, &x).is_some());
            forms += 1;
            // The same symbols, the first one's sign turned: another value, unless that
            // symbol's degree is even in every term.
            let mut other = r.0.clone();
            other[0].2 = !other[0].2;
            let other = SignedRenaming::new(other).expect("a permutation");
            if other.scalar(&p) != Some(x.clone()) {
                changed += 1;
                assert!(!other.agrees(&f, &e), "{p}: {e:?}");
            }
        }
        assert!(forms == 150 && changed >= 50, "{changed}");
        // A renamed symbol inside a call: neither the scalar nor its form is renamed.
        let p = Scalar::sym("a").cos() * Scalar::sym("b");
        let r = random_renaming(&mut next, &["a", "b"]);
        assert!(r.scalar(&p).is_none());
        assert!(r.form(crate::closed_form(&p).expect("a form")).is_none());
    }

    #[test]
    fn sums_of_monomials_renamed_are_sorted_as_the_search_writes_them() {
        let s = |n: &str| Sym::new(n);
        let r = SignedRenaming::new(vec![
            (s("P_0"), s("P_1"), false),
            (s("P_1"), s("P_0"), true),
        ])
        .expect("a permutation");
        let p = Scalar::sym("P_0") * Scalar::sym("d_0") - Scalar::sym("P_1") * Scalar::sym("d_1");
        let x = r.scalar(&p).expect("renamed");
        let f = r
            .form(crate::closed_form(&p).expect("a form"))
            .expect("renamed");
        let own = crate::closed_form(&x).expect("a form");
        assert_eq!(f, own);
    }
}
