//! The canonical form of cos and sin at rational multiples of pi: exact arithmetic in
//! cyclotomic fields.
//!
//! Every term of a scalar is `q sqrt(d) m t` (see `atoms.rs`). For the terms that share a
//! monomial `m` and a frequency vector `f` (a *group*), the sum of the `q sqrt(d) t` is:
//! - for an empty `f`, a real number `c` in `K(zeta_W)`, where `K` is the field of all square
//!   roots of rationals and `W` a multiple of 4 read from the pi offsets;
//! - otherwise `Re(z e^{i phi})` with `phi` the symbolic angle and `z` in `K(zeta_W)`
//!   (`cos(phi + a)` stands for `z = e^{ia}`, `sin(phi + a)` for `z = -i e^{ia}`).
//!
//! When a group holds a mode with a pi offset (a constant `cos(3 pi/7)`, a symbolic
//! `cos(x + pi/5)`; multiples of pi/12 never stay as offsets), [`canonicalize`] rewrites it as
//! the unique expansion of its value in a fixed basis:
//! - `M`, the smallest multiple of 24 dividing `W` with `c` (or `z`) in `K(zeta_M)`, found by
//!   removing one prime of `W` at a time. `K(zeta_M)` contains `i` and `zeta_3` through the
//!   square roots (`i = sqrt(-3)/sqrt(3)`), so fields are only told apart at multiples of 24:
//!   there `K(zeta_M) = K(zeta_N)` only for `M = N`, and the fields holding a value are the
//!   multiples of one smallest;
//! - for real `c`, the basis `R_M` of `K(zeta_M)^+` over `K`: cosines `cos(2 pi k / M)` at
//!   angles in `[0, pi/2)`, taken greedily when independent of the ones before (over `K`), in
//!   the order (the field they need, the denominator of the angle over pi, the angle):
//!   `cos(pi/7)`, `cos(2 pi/7)` for sevenths, with `cos(3 pi/7) = 1/2 - cos(pi/7) + cos(2 pi/7)`; `{1}` for `M = 24` (and
//!   fifths, eighths, tenths and twelfths, whose constants are square roots);
//! - for complex `z`, the basis `C_M` of `K(zeta_M)` over `K(i)`: `e^{i theta}`,
//!   `theta` a multiple of `2 pi / M` in `(-pi/4, pi/4]`, taken greedily in the same order
//!   (`|theta|` then positive first for the angle). A coefficient `a + b i` of `e^{i theta}`
//!   prints as `a cos(phi + theta) - b sin(phi + theta)`.
//!
//! `{q sqrt(d) b}` (`d` square-free, `b` in the basis) is a basis of the field over `Q`, so two
//! equal values give the same terms. The computation is in `Q(zeta_W)` (vectors over `Q` in the
//! power basis modulo the cyclotomic polynomial) for the square roots that live there (Gauss
//! sums); the others are carried along as independent factors. The degree `phi(W)` is bounded
//! by the context's limit ([`Context::with_max_cyclotomic_degree`](super::Context), 768 by
//! default): past it, or when the work budget runs out on the way, the result is an error
//! value, never a group left in a non-canonical form.
//!
//! The canonical form of a group is a function of its value, so a canonical group is its own
//! canonical form, and only a group's terms with a pi offset decide whether it is canonical
//! (see [`Settled`]): a sum of two canonical scalars rewrites only the groups whose offset
//! terms come from both ([`Settled::Sum`]); a product rewrites only the groups that are not
//! one factor's group with offsets times an offset-free group of the other, alone
//! (`product.rs`), and a product by a nonzero constant of the square-root field times a
//! monomial, or a negation, none ([`Settled::All`]). A group of one term is rewritten from
//! its mode's canonical form, made once per thread, times its constant ([`canonical_term`]:
//! the same argument), and a group whose value the fast path rewrote on this thread before
//! is that canonical form relabelled onto its frequency vector and monomial
//! ([`rewritten_before`]). Every group passed through is still held to the degree limit
//! entered now. Debug builds check every group passed through, and every group found
//! rewritten before, against the rewrite from scratch.
//!
//! The parts, one concern each: `level.rs` the level `W` of a group and its degree check;
//! `field.rs` `Q(zeta_W)` (reductions, square roots, the field cache); `candidates.rs` the
//! columns a basis may take and their order; `exact.rs` the dense exact path (the reference);
//! `fast.rs` the basis found modulo a prime and checked, and a group's coordinates from its
//! units'; `product.rs` which groups of a product are canonical already; this file the
//! rewriting of a term vector's groups and which of them pass through; `props.rs` the
//! randomized laws.

use super::atoms::{freq_cmp, rad_mul, Freq, Mode, MonoRc, Small};
use super::par::{this_fork, PerFork};
use super::{FxHasher, ScalarError, Term, Q};
use num_traits::{Signed, Zero};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};
use std::rc::Rc;
use std::sync::{Arc, Mutex};

mod candidates;
mod exact;
mod fast;
mod field;
mod level;
mod product;
#[cfg(test)]
mod props;

use candidates::Col;
use level::level_of;
pub(crate) use level::levels_within_limit;
pub(crate) use product::{settled_groups, ProductTrace};

/// A process-wide cache, made again in a forked child ([`PerFork`]).
type Cache<K, V> = PerFork<Mutex<HashMap<K, Arc<V>>>>;

fn poisoned<T>(_: T) -> ScalarError {
    ScalarError::OutOfRange("cyclotomic cache poisoned".into())
}

/// The key of a group: the frequency vector and the monomial its terms share.
pub(crate) type GroupKey<'a> = (&'a [(super::Sym, Small)], &'a MonoRc);

/// The derived order of group keys (the frequency vector, then the monomial), without its
/// costs: see [`freq_cmp`]; one shared monomial is equal to itself at once. Every sort and
/// search of group keys goes through it.
pub(crate) fn key_cmp(a: &GroupKey, b: &GroupKey) -> Ordering {
    freq_cmp(a.0, b.0).then_with(|| {
        if Arc::ptr_eq(a.1, b.1) {
            Ordering::Equal
        } else {
            a.1.cmp(b.1)
        }
    })
}

/// A group key hashed by the addresses of its symbols, for [`group_ids`]: equal keys
/// ([`key_cmp`]) hash alike, since a symbol is equal exactly to the one at its address
/// (names are interned, `Sym::addr`) and a coefficient's reduced numerator and denominator
/// are its value's. Equality is [`key_cmp`]'s.
struct HashedKey<'a>(GroupKey<'a>);

impl std::hash::Hash for HashedKey<'_> {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        let (freq, mono) = self.0;
        h.write_usize(freq.len());
        for (s, k) in freq {
            h.write_usize(s.addr());
            h.write_i64(*k.numer());
            h.write_i64(*k.denom());
        }
        h.write_usize(mono.len());
        for (s, e) in mono.iter() {
            h.write_usize(s.addr());
            h.write_u32(*e);
        }
    }
}

impl PartialEq for HashedKey<'_> {
    fn eq(&self, other: &Self) -> bool {
        key_cmp(&self.0, &other.0).is_eq()
    }
}

impl Eq for HashedKey<'_> {}

/// The distinct group keys of `terms`, in the order in which they first appear, the group
/// of each term (its key's index there), and whether each group holds a term with a pi
/// offset: one hash lookup a term, where sorting every term's key compared each term's
/// frequency vector and monomial some `log n` times (the group keys of `canonicalize` and
/// of a product's trace were 3% of the Jaco-style arm's `fk --jacobian`). The numbering is
/// not the key order: a caller that needs it sorts the keys, one each.
fn group_ids(terms: &[Term]) -> (Vec<GroupKey<'_>>, Vec<u32>, Vec<bool>) {
    let mut index: HashMap<HashedKey, u32, BuildHasherDefault<FxHasher>> =
        HashMap::with_capacity_and_hasher(terms.len(), Default::default());
    let mut keys: Vec<GroupKey> = Vec::new();
    let mut offset: Vec<bool> = Vec::new();
    let ids = terms
        .iter()
        .map(|t| {
            let k: GroupKey = (&*t.mode.freq, &t.mono);
            let g = *index.entry(HashedKey(k)).or_insert_with(|| {
                keys.push(k);
                offset.push(false);
                // Fewer groups than terms, and a term vector past `u32::MAX` terms is over
                // every term limit long before.
                (keys.len() - 1) as u32
            });
            offset[g as usize] |= !t.mode.pi.is_zero();
            g
        })
        .collect();
    (keys, ids, offset)
}

/// A group's key that owns its parts (a product names its settled groups before its terms
/// are sorted and merged).
pub(crate) type OwnedKey = (Freq, MonoRc);

/// Which groups of a term vector are known to be canonical already, so that
/// [`canonicalize`] passes them through.
///
/// What makes a group canonical: its canonical form is the expansion of its value in the
/// basis `B_M` of its smallest level `M` (a function of the value alone), and the first
/// column of every `B_M` is `1` (`cos 0`, `e^{i 0}`), whose coordinates are exactly the
/// group's terms without a pi offset (`q sqrt(r)`, `q sqrt(r) cos(phi)`, `q sqrt(r)
/// sin(phi)`). Adding a value of `K(i)` (`K` for a real group) changes no smallest level (every
/// `K(zeta_M)`, `24 | M`, holds `K(i)`), so it changes only those coordinates: a group is
/// canonical exactly when its terms *with* a pi offset are a canonical group on their own,
/// whatever its terms without one. Hence only the terms with a pi offset are traced below.
pub(crate) enum Settled<'a> {
    /// None: every group holding a pi offset is rewritten.
    Nothing,
    /// Every group (a canonical scalar negated, or times a nonzero constant of the
    /// square-root field times a monomial: see `arith::mul`; or with some groups written
    /// without an offset: see `Term::push_at_twelfths`); only the degree limit is checked.
    All,
    /// The terms of the sum of two canonical scalars, `origin[i]` telling where term `i`
    /// came from (bit 1 the left operand, bit 2 the right one), with the keys of the terms
    /// with a pi offset that cancelled. A group whose terms with a pi offset all come from one
    /// operand, none cancelled, has the offset terms of that operand's group, which are
    /// canonical on their own (that group less its `1` column): the group is canonical.
    Sum {
        /// Where each term came from.
        origin: &'a [u8],
        /// The keys of the terms with a pi offset of both operands that cancelled.
        cancelled: &'a [GroupKey<'a>],
    },
    /// The groups known to be canonical, sorted (a product's: see `arith::mul`).
    Groups(&'a [OwnedKey]),
}

/// Rewrites the groups of terms holding a pi offset in their canonical basis (see the module
/// docs); a field past the context's degree limit, or the work budget running out, is an
/// error. `None` when every such group is [`Settled`] (the terms are canonical as they are).
///
/// The degree limit holds for the groups passed through too: a value built under a higher
/// limit than the one entered now may hold a group past it, and the result is then the
/// degree error a rewrite from scratch gives, never the group passed through unchecked.
pub(crate) fn canonicalize(
    terms: &[Term],
    settled: &Settled,
) -> Result<Option<Vec<Term>>, ScalarError> {
    let offset = |t: &&Term| !t.mode.pi.is_zero();
    // One check of all offsets together when their level fits: each group's level divides
    // it, and `phi(d) <= phi(n)` when `d | n`. (A rewrite checks its own group.)
    let fits = match settled {
        Settled::Nothing => true,
        _ => level_of(terms.iter().filter(offset)).is_ok(),
    };
    if fits && matches!(settled, Settled::All) {
        return Ok(None);
    }
    if let (true, Settled::Sum { origin, cancelled }) = (fits, settled) {
        // Every term with a pi offset from one operand, none cancelled: every group is that
        // operand's, without sorting the groups out.
        let from = terms
            .iter()
            .zip(origin.iter())
            .filter(|(t, _)| !t.mode.pi.is_zero())
            .fold(0, |f, (_, o)| f | o);
        if from != 3 && cancelled.is_empty() {
            if cfg!(debug_assertions) {
                debug_check_canonical(terms);
            }
            return Ok(None);
        }
    }
    let (keys, at) = groups_of(terms);
    // For each group, the operands its terms with a pi offset came from (see
    // `Settled::Sum`).
    let mut from = vec![0u8; keys.len()];
    if let Settled::Sum { origin, .. } = settled {
        for ((t, k), o) in terms.iter().zip(&at).zip(origin.iter()) {
            if let (Some(k), false) = (k, t.mode.pi.is_zero()) {
                from[*k] |= o;
            }
        }
    }
    if !fits {
        // Group by group, in key order, as a rewrite from scratch meets them.
        let mut groups: Vec<Vec<&Term>> = vec![Vec::new(); keys.len()];
        for (t, k) in terms.iter().zip(&at) {
            if let Some(k) = k {
                groups[*k].push(t);
            }
        }
        for g in groups {
            level_of(g.into_iter())?;
        }
    }
    let redo: Vec<bool> = match settled {
        Settled::Nothing => vec![true; keys.len()],
        Settled::All => return Ok(None),
        Settled::Sum { cancelled, .. } => keys
            .iter()
            .zip(&from)
            .map(|(k, f)| *f == 3 || cancelled.contains(k))
            .collect(),
        Settled::Groups(known) => keys
            .iter()
            .map(|k| {
                known
                    .binary_search_by(|(f, m)| key_cmp(&(&**f, m), k))
                    .is_err()
            })
            .collect(),
    };
    if cfg!(debug_assertions) {
        debug_check_settled(terms, &at, &redo);
    }
    if !redo.contains(&true) {
        return Ok(None);
    }
    let mut groups: Vec<Vec<&Term>> = vec![Vec::new(); keys.len()];
    let mut out: Vec<Term> = Vec::with_capacity(terms.len());
    for (t, k) in terms.iter().zip(&at) {
        match k {
            Some(k) if redo[*k] => groups[*k].push(t),
            _ => out.push(t.clone()),
        }
    }
    for g in groups {
        if !g.is_empty() {
            out.extend(canonical_group(&g)?);
        }
    }
    Ok(Some(out))
}

/// The keys of the groups of `terms` (sorted) that hold a term with a pi offset, and each
/// term's group among them (`None` for a term of a group without an offset).
///
/// The groups are found by hashing ([`group_ids`]), and only the keys of those with an
/// offset sorted, each once: they are distinct, so an unstable sort gives the one order.
/// (The stable sort of every term's key it replaced, itself faster than sorting the keys of
/// the terms with an offset and searching every term's key among them, was 1.1% of the
/// Jaco-style arm's `fk --jacobian`.)
fn groups_of(terms: &[Term]) -> (Vec<GroupKey<'_>>, Vec<Option<usize>>) {
    let (all, ids, offset) = group_ids(terms);
    let mut kept: Vec<usize> = (0..all.len()).filter(|&g| offset[g]).collect();
    kept.sort_unstable_by(|&a, &b| key_cmp(&all[a], &all[b]));
    let mut position = vec![None; all.len()];
    for (p, &g) in kept.iter().enumerate() {
        position[g] = Some(p);
    }
    let keys = kept.iter().map(|&g| all[g]).collect();
    let at = ids.iter().map(|&g| position[g as usize]).collect();
    (keys, at)
}

/// Debug builds: every group passed through as settled is its own canonical form (checked
/// on a budget of its own, so the check neither fails for lack of the caller's budget nor
/// spends it).
fn debug_check_settled(terms: &[Term], at: &[Option<usize>], redo: &[bool]) {
    for (k, _) in redo.iter().enumerate().filter(|(_, r)| !**r) {
        let g: Vec<&Term> = terms
            .iter()
            .zip(at)
            .filter(|(_, a)| **a == Some(k))
            .map(|(t, _)| t)
            .collect();
        let again = super::with_own_budget(u64::MAX / 4, || canonical_group(&g));
        if let Ok(mut again) = again {
            again.sort_by(Term::key_cmp);
            let mut g: Vec<Term> = g.into_iter().cloned().collect();
            g.sort_by(Term::key_cmp);
            assert_eq!(again, g, "a settled group is not canonical");
        }
    }
}

/// Debug builds: `terms` (sorted, merged) are canonical as they are.
pub(crate) fn debug_check_canonical(terms: &[Term]) {
    let again = super::with_own_budget(u64::MAX / 4, || {
        canonicalize(terms, &Settled::Nothing)
            .and_then(|t| t.map(super::canonical_terms).transpose())
    });
    if let Ok(Some(again)) = again {
        assert_eq!(again, terms, "terms taken as canonical are not");
    }
}

fn canonical_group(g: &[&Term]) -> Result<Vec<Term>, ScalarError> {
    if let [t] = g {
        return canonical_term(t);
    }
    rewritten_group(g)
}

/// A group rewritten in its canonical basis, through the fast bases when their checks pass;
/// a group whose value was rewritten on this thread before is its remembered canonical form
/// relabelled ([`rewritten_before`]).
fn rewritten_group(g: &[&Term]) -> Result<Vec<Term>, ScalarError> {
    if g.is_empty() {
        return Ok(Vec::new());
    }
    let hash = value_hash(g);
    if let Some(out) = rewritten_before(g, hash)? {
        return Ok(out);
    }
    let w = level_of(g.iter().copied())?;
    match fast::canonical_group_fast_at(g, w)? {
        Some(out) => {
            let template: TermTemplate = out
                .iter()
                .map(|u| (u.mode.sin, u.mode.pi, u.rad, u.coef.clone()))
                .collect();
            let kept = Rewrite {
                value: GroupValue::of(g),
                template,
                level: w,
                degree: level::level_primes(w).0,
            };
            REWRITTEN.with(|c| {
                let mut c = c.borrow_mut();
                let known = this_fork(&mut c);
                if known.len() >= REWRITTEN_KEPT {
                    known.clear();
                }
                known.entry(hash).or_default().push(kept);
            });
            Ok(out)
        }
        None => exact::canonical_group_exact(g),
    }
}

/// A group's value apart from its labels (the frequency vector and the monomial its terms
/// share): whether it is real (no symbolic angle), and each term's sine flag, pi offset
/// (numerator, denominator: reduced, so equal offsets have equal words), radicand and
/// coefficient, in the group's order (the terms' order, by sine flag, offset, radicand).
#[derive(Clone, PartialEq, Eq, Debug)]
struct GroupValue(bool, Vec<(bool, i64, i64, u64, Q)>);

impl GroupValue {
    fn of(g: &[&Term]) -> GroupValue {
        let terms = g
            .iter()
            .map(|t| {
                let pi = t.mode.pi;
                (t.mode.sin, *pi.numer(), *pi.denom(), t.rad, t.coef.clone())
            })
            .collect();
        GroupValue(group_is_real(g), terms)
    }

    /// Whether `g`'s value is this one: [`GroupValue::of`] compared without being built.
    fn is_of(&self, g: &[&Term]) -> bool {
        self.0 == group_is_real(g)
            && self.1.len() == g.len()
            && self.1.iter().zip(g).all(|((sin, n, d, rad, coef), t)| {
                let pi = t.mode.pi;
                (*sin, *n, *d, *rad) == (t.mode.sin, *pi.numer(), *pi.denom(), t.rad)
                    && *coef == t.coef
            })
    }
}

/// Whether the group `g` is real (its terms have no symbolic angle).
fn group_is_real(g: &[&Term]) -> bool {
    g.first().is_some_and(|t| t.mode.freq.is_empty())
}

/// The hash of `g`'s [`GroupValue`], read from the terms without building it (a cache hit
/// then allocates nothing): equal values hash equal, since both hash the same fields in
/// the same order.
fn value_hash(g: &[&Term]) -> u64 {
    let mut h = FxHasher::default();
    group_is_real(g).hash(&mut h);
    g.len().hash(&mut h);
    for t in g {
        let pi = t.mode.pi;
        (t.mode.sin, *pi.numer(), *pi.denom(), t.rad).hash(&mut h);
        t.coef.hash(&mut h);
    }
    h.finish()
}

/// A group the fast path rewrote: its value, its canonical form, and its level `W` and the
/// degree `phi(W)` (both functions of the value: `W` of its pi offsets), kept so a hit
/// neither walks the group for its level nor looks the degree up.
struct Rewrite {
    value: GroupValue,
    template: TermTemplate,
    level: u64,
    degree: u64,
}

/// The most hashes [`REWRITTEN`] keeps on one thread (emptied when full): a bound on its
/// memory in a long-lived process. A group found there or rewritten again gives the same
/// terms and charges the same work, so the bound changes only how fast it is.
const REWRITTEN_KEPT: usize = 1 << 12;

/// The groups rewritten, by the [`value_hash`] of their values (the groups of one hash, in
/// the order they were met: distinct values almost always have distinct hashes).
type Rewritten = HashMap<u64, Vec<Rewrite>, BuildHasherDefault<FxHasher>>;

thread_local! {
    /// The canonical forms of the groups the fast path rewrote on this thread, by value
    /// ([`rewritten_before`]), with the fork count they were made at ([`PerFork`]).
    static REWRITTEN: RefCell<(u64, Rewritten)> = RefCell::new((0, Rewritten::default()));
}

/// The canonical form of the group `g` (whose [`value_hash`] is `hash`) when the fast path
/// rewrote a group of the same value on this thread before: its terms on `g`'s frequency
/// vector and monomial. `None` otherwise.
///
/// Why that is `g`'s canonical form: a group's canonical form is the expansion of its value
/// in the basis of its smallest level (see the module docs), and the value of `sum q sqrt(r)
/// m trig(phi + p)` is fixed by the terms' `(sin, p, r, q)` and whether `phi` is present:
/// `phi` and `m` only label it, and the fast path reads nothing else of them
/// (`terms_in_basis` copies the first term's frequency vector and monomial into every term
/// but, for a real group, the mode `1`). The degree limit is checked on `g`'s level as the
/// fast path checks it first, and the work charged is the fast path's when its bases and
/// units are made already, as they are once it rewrote a group of this value in this
/// process (they are kept per process, made again only in a forked child, as this cache).
///
/// The level is the one remembered: `level_of` reads only the pi offsets' denominators,
/// part of the value. It passes the limit as `level_of` would: `level_of` accepts a level
/// `W` (at most its factoring bound, as this one, accepted before) exactly when `phi(W)` is
/// within the limit, its other test (`W <= 2 limit^2`) then holding since `phi(W) >=
/// sqrt(W / 2)`; past the limit (entered lower since), `level_of` gives its error.
fn rewritten_before(g: &[&Term], hash: u64) -> Result<Option<Vec<Term>>, ScalarError> {
    let Some((template, w, degree)) = REWRITTEN.with(|c| {
        let mut c = c.borrow_mut();
        let known = this_fork(&mut c).get(&hash)?;
        let r = known.iter().find(|r| r.value.is_of(g))?;
        Some((r.template.clone(), r.level, r.degree))
    }) else {
        return Ok(None);
    };
    if degree > super::ctx::max_cyclotomic_degree() {
        level_of(g.iter().copied())?;
    }
    fast::charge_group(g.len(), degree)?;
    let first = g[0];
    let real = group_is_real(g);
    let out: Vec<Term> = template
        .iter()
        .map(|(sin, pi, rad, coef)| Term {
            mode: template_mode(real, *sin, *pi, &first.mode.freq),
            mono: first.mono.clone(),
            rad: *rad,
            coef: coef.clone(),
        })
        .collect();
    if cfg!(debug_assertions) {
        assert_eq!(level_of(g.iter().copied()), Ok(w), "a remembered level");
        let again = super::with_own_budget(u64::MAX / 4, || fast::canonical_group_fast(g));
        if let Ok(Some(again)) = again {
            assert_eq!(again, out, "a group found rewritten before differs");
        }
    }
    Ok(Some(out))
}

/// The mode of a template's term (sine or cosine, offset) on the frequency vector `freq`:
/// the mode `1` for a real group's cosine without an offset (as `terms_in_basis` writes it).
fn template_mode(real: bool, sin: bool, pi: Small, freq: &Freq) -> Mode {
    if real && !sin && pi.is_zero() {
        Mode::unit()
    } else {
        Mode {
            sin,
            freq: freq.clone(),
            pi,
        }
    }
}

/// The canonical form of a one-term mode `cos(phi + p)` or `sin(phi + p)` (`phi` present or
/// not), coefficient 1, radicand 1: the modes (sine or cosine, offset) and their constants;
/// or of a group of one value ([`REWRITTEN`]).
type TermTemplate = Rc<[(bool, Small, u64, Q)]>;

/// The canonical form of a group of one term `q sqrt(r) m trig(phi + p)` (a constant at a
/// pi offset, `cos(x + 5 pi/9)` built alone: an angle evaluated, a mode of a product), from
/// the canonical form of `trig(phi + p)` alone, made once per thread for each `(sin,
/// constant or not, p)`, times `q sqrt(r) m` (the frequency vector and the monomial copied
/// into each term, the radicands multiplied).
///
/// Why that is the group's canonical form: the canonical form of a group is the expansion
/// of its value in the basis `{sqrt(d) b}` (`d` square-free, `b` the columns of its
/// smallest level's basis) over `Q`, a function of the value alone; the value of the group
/// is `q sqrt(r)` times that of `trig(phi + p)` (the monomial and `phi` only label it), and
/// the smallest level of a value is that of its product by a nonzero element `q sqrt(r)` of
/// the square-root field `K` (the fields are `K(zeta_M)`). Multiplying the expansion
/// `sum c_j sqrt(d_j) b_j` by `q sqrt(r)` gives `sum q c_j k_j sqrt(d'_j) b_j` (`sqrt(r
/// d_j) = k_j sqrt(d'_j)`), whose pairs `(d'_j, b_j)` are distinct because `d -> r d`
/// modulo squares is one to one: that is the expansion of the product (the argument of
/// `arith::mul` for a canonical scalar times such a constant, [`Settled::All`]). The degree
/// limit is checked on the term's level as a rewrite checks it, and the work charged is the
/// fast path's for one term (the template's own rewrite charges as any).
pub(crate) fn canonical_term(t: &Term) -> Result<Vec<Term>, ScalarError> {
    // Keyed by the offset's numerator and denominator: `Ratio`'s own `Hash` walks its
    // continued fraction (a division a step) at every lookup. An offset written unreduced
    // would only miss, its template made again from the same value.
    type Templates = HashMap<(bool, bool, i64, i64), TermTemplate, BuildHasherDefault<FxHasher>>;
    thread_local! {
        // With the fork count it was filled at: a forked child empties it ([`PerFork`]).
        static TEMPLATES: RefCell<(u64, Templates)> = RefCell::new((0, Templates::default()));
    }
    let real = t.mode.freq.is_empty();
    let key = (t.mode.sin, real, *t.mode.pi.numer(), *t.mode.pi.denom());
    let known = TEMPLATES.with(|c| this_fork(&mut c.borrow_mut()).get(&key).cloned());
    let template = match known {
        Some(template) => {
            let w = level_of(std::iter::once(t))?;
            super::charge(level::level_primes(w).0 / 128 + 1)?;
            template
        }
        None => {
            let unit = Term {
                mode: t.mode.clone(),
                mono: super::atoms::empty_mono(),
                rad: 1,
                coef: Q::ONE,
            };
            let template: TermTemplate = rewritten_group(&[&unit])?
                .into_iter()
                .map(|u| (u.mode.sin, u.mode.pi, u.rad, u.coef))
                .collect();
            TEMPLATES.with(|c| this_fork(&mut c.borrow_mut()).insert(key, template.clone()));
            template
        }
    };
    template
        .iter()
        .map(|(sin, pi, r, c)| {
            let mode = template_mode(real, *sin, *pi, &t.mode.freq);
            t.times_root(mode, *r, c)
                .ok_or_else(|| ScalarError::OutOfRange("radicand too large".into()))
        })
        .collect()
}

/// The terms of a group from its coordinates: for each class `s` of square roots outside the
/// field, `x_j sqrt(s) b_j` over the basis columns `b_j`.
fn terms_in_basis(
    first: &Term,
    real: bool,
    classes: &[u64],
    sol: Vec<Vec<Q>>,
    cols: &[Col],
) -> Result<Vec<Term>, ScalarError> {
    let mut out = Vec::new();
    for (s, xs) in classes.iter().zip(sol) {
        for (col, x) in cols.iter().zip(xs) {
            if x.is_zero() {
                continue;
            }
            let (rad, k) = rad_mul(*s, col.h)
                .ok_or_else(|| ScalarError::OutOfRange("radicand too large".into()))?;
            // The common case multiplies by one: skipped, since a product of big rationals
            // reduces its result by gcds (11% of the Jaco-style arm's `fk --jacobian`).
            let mut coef = if k == 1 { x } else { &x * &Q::from_u64(k) };
            let mode = if col.angle.is_zero() && real {
                Mode::unit()
            } else {
                let two = Small::from_integer(2);
                let pi = if col.angle.is_negative() {
                    col.angle + two
                } else {
                    col.angle
                };
                if col.imag {
                    coef = -coef;
                }
                Mode {
                    sin: col.imag,
                    freq: first.mode.freq.clone(),
                    pi,
                }
            };
            out.push(Term {
                mode,
                mono: first.mono.clone(),
                rad,
                coef,
            });
        }
    }
    Ok(out)
}
