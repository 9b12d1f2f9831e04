//! Offsets absorbed into the symbols: a scalar whose modes carry pi offsets outside the
//! multiples of pi/12 (`cos(q2 + 5 pi/9)`, the joint offset of a Kinova arm) is written in
//! shifted symbols `y_s = x_s + o_s`, one rational multiple of pi `o_s` per symbol, chosen so
//! that the scalar in `y` has no such offset left. Its closed form is then found on the
//! path every offset-free scalar takes (angle sums regrouped, factored, products and powers),
//! and every angle of it is shifted back (`cos(y2 + y3)` prints `cos(q2 + q3 + 5*pi/9)`).
//!
//! How the offsets are found, for the terms that share a monomial and a frequency vector `f`
//! (a group, whose value is `Re(z e^{i f.x})`): the group's phase class `d_f` is the multiple
//! `d` of `pi / N` (`N = lcm(12, the offsets' denominators)`), taken modulo `1/12`, for
//! which the group shifted by `-d` has no offset; a group with no such `d` (a sum of two
//! unrelated phases) means no shift exists. When `N` has no prime factor but 2 and 3 (ninths,
//! eighths: the Kinova arms' offsets), `d_f` is the class modulo `1/12` that all the group's
//! offsets share, read off them ([`phase_class_of_offsets`] proves it); otherwise each
//! candidate is tried exactly, one small canonicalization each. The offsets must then satisfy `f . o = d_f (mod 1/12)` for every group: each
//! symbol's candidates are the multiples of `pi / (N a)` (`a` the lcm of its coefficients'
//! numerators) over one period; scaled to integers modulo one common modulus, the
//! congruences are solved in echelon form (`congruence.rs`), which lists the solutions in
//! lexicographic order without a search (the first [`MAX_SOLUTIONS`] are compared, every
//! value listed charged to the Context), and counts them without listing them (a product
//! over the echelon form's steps) when deciding whether they are fewer than that.
//!
//! Which solution is shown (`5 pi/9` or `-4 pi/9`, or `1/18 pi` with the cosine turned into
//! a sine): among every solution (when there are fewer than [`MAX_SOLUTIONS`]; else with the symbols whose
//! first offset is a multiple of their own pi/12 steps kept at 0), the one for which the
//! shifted scalar has the fewest cosine and sine parts, then the smallest denominator, then
//! the fewest nonzero offsets (no `q1 - pi` for a sign), then the fewest negative parts (`cos(t + 5*pi/9)`, not `-cos(t - 4*pi/9)`), then the smallest
//! sum of `|o_s|`, then the fewest negative offsets. The shifted scalar is computed exactly and must have no offset left on a
//! symbolic mode; the closed form built from it is checked against the input like every
//! other. Across an `fk` report the offsets shown are then made to agree (`common.rs`).

use super::expr::{Angle, Expr};
use crate::scalar::{Small, Sym, Term};
use crate::Scalar;
use num_integer::Integer;
use num_traits::{Signed, ToPrimitive, Zero};

/// The most terms a scalar may have for offsets to be looked for.
const MAX_TERMS: usize = 20_000;

/// The most candidates one symbol's offset may have before narrowing.
const MAX_CANDIDATES: i64 = 1024;

/// One offset per symbol (a multiple of pi), absorbed into it: `y_s = x_s + o_s`.
#[derive(Clone, Debug)]
pub(crate) struct Shift(Vec<(Sym, Small)>);

/// What the maker of a scalar `x` knows of it: `x` is `y` with every symbol `s` of `shifts`
/// replaced by `s + o` (`y.shift_angles(shifts)`, as an offset-free product's entry is
/// shifted back: `kin/robot.rs`, `OffsetFree`), `y` made under the limits of the context
/// that `x`'s closed form is searched in (as `fk` makes both: the term, digit, angle and
/// degree limits that [`Shift::apply`] checks its result's terms against then pass on `y`'s,
/// as they did when `y` was made). When [`find`] gives `x` that shift, or one that `y` does
/// not tell from it, [`Shift::apply`] of `x` is `y` (see [`Shift::apply_hinted`]), which is
/// then not made again.
#[derive(Clone, Copy)]
pub(crate) struct Hint<'a> {
    /// Each shifted symbol (once) and its offset, a multiple of pi (`OffsetFree`'s shifts).
    pub(crate) shifts: &'a [(Sym, Small)],
    /// `x` before its symbols were shifted.
    pub(crate) y: &'a Scalar,
}

/// A group of terms sharing a monomial and a symbolic frequency vector.
struct Group<'a> {
    /// The frequency vector without the constant entry.
    freq: Vec<(Sym, Small)>,
    terms: Vec<&'a Term>,
}

/// `p` modulo 2, in `[0, 2)`: for `p = a / b` (lowest terms, `b > 0`) the numerator `a mod
/// 2 b` over `b`, in lowest terms as it stands (it differs from `a` by a multiple of `b`, so
/// its gcd with `b` is 1); in `Small` when `2 b` leaves a machine word.
fn reduce2(p: Small) -> Small {
    match p.denom().checked_mul(2) {
        Some(period) => Small::new_raw(p.numer().rem_euclid(period), *p.denom()),
        None => {
            let two = Small::from_integer(2);
            p - (p / two).floor() * two
        }
    }
}

/// The group's terms with their offsets lowered by `d`, canonical.
fn shifted_group(g: &Group, d: Small) -> Scalar {
    Scalar::from_terms(
        g.terms
            .iter()
            .map(|t| {
                let mut t = (*t).clone();
                t.mode.pi = reduce2(t.mode.pi - d);
                t
            })
            .collect(),
    )
}

fn no_offset(s: &Scalar) -> bool {
    s.terms().is_ok_and(|t| {
        t.iter()
            .all(|t| t.mode.pi.is_zero() || t.mode.freq.is_empty())
    })
}

/// A group's phase class (see the module docs), found by trying each candidate `j pi / n`,
/// `0 < j < n / 12`, on the group shifted by it (one canonicalization each): `0` for a group
/// without offsets, `None` when no candidate leaves it without one.
fn phase_class_by_search(g: &Group, n: i64) -> Option<Small> {
    if g.terms.iter().all(|t| t.mode.pi.is_zero()) {
        return Some(Small::zero());
    }
    let step = Small::new(1, n);
    let freq = g.terms.first().map(|t| t.mode.freq.to_vec())?;
    (1..n / 12)
        .map(|j| step * Small::from_integer(j))
        .filter(|&d| offsets_among_columns(g, &freq, d))
        .find(|&d| no_offset(&shifted_group(g, d)))
}

/// Whether every offset of the group's terms is one of the offsets of the canonical
/// `cos(phi + d pi)` (`phi` the group's angle, `freq`): true for the group's phase class `d`,
/// so [`phase_class_by_search`] canonicalizes the shifted group only for the candidates that
/// pass (one small canonicalization of a single term each, from its per-thread template, in
/// place of one of the whole group; the offsets in sevenths and thirteenths of the stress
/// run spent most of their work budget here). True when that form is an error value.
///
/// Why: the shifted group has no offset exactly when `z e^{-i pi d}` is some `k` in `K(i)`
/// (`z` the group's amplitude, `K` the square-root field: see `scalar/cyclo`'s module docs,
/// whose basis has the column `1` for `K(i)`). Then the group's value is `Re(k e^{i (phi + d
/// pi)}) = a cos(phi + d pi) - b sin(phi + d pi)` with `k = a + b i`, `a`, `b` in `K`. Its
/// canonical form is the expansion of that value in the columns of the basis, and an
/// expansion is linear over `K` (the coordinates over `K(i)` are, and each coordinate's terms
/// `q sqrt(r)` keep its column): so the group's terms lie on the columns of `cos(phi + d pi)`
/// and `sin(phi + d pi) = Re(-i e^{i (phi + d pi)})`, which are the same columns (`-i` is in
/// `K(i)`). A column `e^{i theta}` gives terms of offset `theta` (mod 2) alone.
fn offsets_among_columns(g: &Group, freq: &[(Sym, Small)], d: Small) -> bool {
    let unit = Scalar::trig_of_parts(false, freq.to_vec(), d);
    let Ok(columns) = unit.terms() else {
        return true;
    };
    g.terms
        .iter()
        .all(|t| columns.iter().any(|c| c.mode.pi == t.mode.pi))
}

/// Whether `n` (a multiple of 12) has no prime factor but 2 and 3: then [`phase_class_of_offsets`]
/// gives every group's phase class without a canonicalization.
fn graded_level(n: i64) -> bool {
    let mut m = n;
    for p in [2, 3] {
        while m % p == 0 {
            m /= p;
        }
    }
    m == 1
}

/// A group's phase class read off its terms' offsets, when `n` (the lcm of 12 and every
/// offset's denominator) is a [`graded_level`]: the class `p mod 1/12` shared by every term's
/// offset `p` (an offset-free term has class 0); `None` when two terms differ in it, or when
/// it is 0 and some offset is not (as [`phase_class_by_search`], which tries no candidate 0).
///
/// Why this is [`phase_class_by_search`]'s answer, without trying candidates. Let `K` be the
/// field of the square roots of all rationals (it holds `i`, and `zeta_24`): `K` is the union
/// of fields with Galois groups `(Z/2)^k`, so the roots of unity in it are the 24th roots (a
/// root of order `m` in `K` has `(Z/m)^*` of exponent 2, so `m | 24`). A group (one monomial,
/// one frequency vector `f`, value `Re(z e^{i f.x})`, `z` in `K(zeta_2n)`) shifted by `-d`
/// canonicalizes without an offset exactly when `z e^{-i pi d}` lies in `K`: the canonical
/// basis of a value of `K` is `{1}`, and the value's expansion is unique (`scalar/cyclo`'s
/// module docs). So the classes that work are one coset of `1/12`: two of them, `d` and
/// `d'`, give `e^{i pi (d - d')}` in `K` (`z != 0`: a canonical group is the expansion of its
/// value in a basis, and is not empty), a 24th root of unity, `d - d'` a multiple of `1/12`.
/// With `2n = 2^a 3^b`, `[K(zeta_2n) : K] = 2n/24` (`(Z/2n)^*` modulo its squares has order
/// 8), the minimal polynomial of `zeta_2n` over `K` is `t^(2n/24) - zeta_24`, and `K(zeta_2n)`
/// is the direct sum over `j mod 2n/24` of the lines `K zeta_2n^j`: the values
/// `K e^{i pi p}` with `p n = j (mod n/12)`, i.e. one line per class `p mod 1/12`. The
/// canonical basis of a group has at most one column per line (two roots of unity on one
/// line are proportional over `K`; the basis is independent), and a column's terms are the
/// nonzero coordinate of the group's value on it. So the value's component on the line of
/// class `c` is nonzero exactly when some term has class `c`, and `z` lies on one line (of
/// class `d`: `z e^{-i pi d}` in `K`) exactly when every term has class `d`. (For other `n`,
/// the lines are not independent: `1 + zeta_5 + ... + zeta_5^4 = 0`, so a value on one line
/// may be written on several, and the classes are searched.) Checked against
/// [`phase_class_by_search`] in debug builds, and by the tests below.
fn phase_class_of_offsets(g: &Group, n: i64) -> Option<Small> {
    let classes = n / 12;
    let class = |p: Small| (p.numer() * (n / p.denom())).rem_euclid(classes);
    let mut terms = g.terms.iter().map(|t| t.mode.pi);
    let first = class(terms.next()?);
    if terms.any(|p| class(p) != first) {
        return None;
    }
    if first == 0 {
        return g
            .terms
            .iter()
            .all(|t| t.mode.pi.is_zero())
            .then(Small::zero);
    }
    Some(Small::new(first, n))
}

/// `N`, the lcm of 12 and the denominators of the terms' offsets (over pi).
fn level(terms: &[Term]) -> i64 {
    terms.iter().fold(12, |n: i64, t| n.lcm(t.mode.pi.denom()))
}

/// Whether a term's mode holds a symbol (not only the constant `1`).
fn symbolic(t: &Term) -> bool {
    t.mode.freq.iter().any(|(s, _)| !s.is_one())
}

/// A group's key for [`groups_of`]: its frequency vector and monomial, equal as the derived
/// `Eq` of the pair says (a symbol by its interned address, a coefficient by value). Hashed by
/// the symbols' addresses (one per name: names are interned for the process) and the
/// coefficients' numerators and denominators, which agrees with `Eq` because every `Small` of
/// a canonical term is reduced (as `Mode`'s hash assumes). A map ordered by the pair's derived
/// `Ord` was a third of `find`'s own work on the Jaco-style arm (`Ratio::cmp` by divisions,
/// names compared for every step of every search).
#[derive(PartialEq, Eq)]
struct GroupKey<'a>(&'a [(Sym, Small)], &'a [(Sym, u32)]);

impl std::hash::Hash for GroupKey<'_> {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        h.write_usize(self.0.len());
        for (s, k) in self.0 {
            h.write_usize(s.addr());
            h.write_i64(*k.numer());
            h.write_i64(*k.denom());
        }
        h.write_usize(self.1.len());
        for (s, e) in self.1 {
            h.write_usize(s.addr());
            h.write_u32(*e);
        }
    }
}

/// The groups of the symbolic terms, by (frequency vector, monomial), in the order their
/// first terms come.
fn groups_of(terms: &[Term]) -> Vec<Group<'_>> {
    let mut index: super::FxMap<GroupKey, usize> = Default::default();
    let mut groups: Vec<Group> = Vec::new();
    for t in terms.iter().filter(|t| symbolic(t)) {
        let k = GroupKey(&t.mode.freq, &t.mono);
        let i = *index.entry(k).or_insert_with(|| {
            groups.push(Group {
                freq: t
                    .mode
                    .freq
                    .iter()
                    .filter(|(s, _)| !s.is_one())
                    .cloned()
                    .collect(),
                terms: Vec::new(),
            });
            groups.len() - 1
        });
        groups[i].terms.push(t);
    }
    groups
}

/// The shift that leaves `x` without offsets outside the multiples of pi/12 on its symbolic
/// modes, when `x` has such offsets and one exists (see the module docs).
pub(crate) fn find(x: &Scalar) -> Option<Shift> {
    let terms = x.terms().ok()?;
    // The gate every offset-free scalar (the PUMA's) fails at once.
    if !terms.iter().any(|t| !t.mode.pi.is_zero() && symbolic(t)) {
        return None;
    }
    if terms.len() > MAX_TERMS {
        return None;
    }
    let n = level(terms);
    if n > 100_000 {
        return None;
    }
    let groups = groups_of(terms);
    crate::scalar::charge(groups.len() as u64).ok()?;
    // Each group's phase class d_f (mod 1/12).
    let graded = graded_level(n);
    let mut phase: Vec<Small> = Vec::with_capacity(groups.len());
    for g in &groups {
        let d = if graded {
            let d = phase_class_of_offsets(g, n);
            debug_assert_eq!(d, phase_class_by_search(g, n), "a graded level's class");
            d
        } else {
            phase_class_by_search(g, n)
        };
        phase.push(d?);
    }
    let mut syms: Vec<Sym> = groups
        .iter()
        .flat_map(|g| g.freq.iter().map(|(s, _)| s.clone()))
        .collect();
    syms.sort();
    syms.dedup();
    let rows: Vec<Vec<(usize, Small)>> = groups
        .iter()
        .map(|g| {
            g.freq
                .iter()
                .map(|(s, k)| (syms.binary_search(s).unwrap_or(0), *k))
                .collect()
        })
        .collect();
    let targets: Vec<(Small, Small)> = phase.iter().map(|d| (*d, Small::new(1, 12))).collect();
    let congruences = Congruences::of(&rows, &targets);
    let free = vec![None; syms.len()];
    // The system with every symbol free: solved here for a first solution, and again by
    // `representatives` (counted, then listed), built once.
    let everything = system(&syms, &congruences.rows, &congruences.targets, n, &free)?;
    let mut base: Option<Vec<Small>> = None;
    solve(&everything, &free, false, &mut |node| match node {
        Offered::Solution(o) => {
            base = Some(o.to_vec());
            false
        }
        Offered::Prefix { .. } => false,
    })?;
    let base = base?;
    let offsets = representatives(&groups, &syms, &rows, &congruences, n, &everything, base)?;
    let shift = Shift(
        syms.into_iter()
            .zip(offsets)
            .filter(|(_, o)| !o.is_zero())
            .collect(),
    );
    (!shift.0.is_empty()).then_some(shift)
}

/// The congruences `row . o = target` (modulo the target's modulus) of [`system`], one per
/// distinct pair of a group's row and target: the groups of one frequency vector and phase
/// class (other monomials) give one congruence, and [`system`] makes its integer row once
/// (the Jaco-style arm's 96-term dual-quaternion components: 48 groups, 16 congruences; its
/// 84-term pose entries: 48 and 48). Its solutions are those of every group's congruence (a
/// repeated congruence says nothing more), and the system is the same as the one of every
/// group's up to its rows' order and repeats: its modulus, scale and units are lcms over the
/// set of rows (so every bound `system` checks is met or missed alike), and the elimination
/// (`congruence.rs`) sorts its integer rows and drops the repeated ones before anything else,
/// so it eliminates, charges and walks the same rows either way.
struct Congruences {
    rows: Vec<Vec<(usize, Small)>>,
    targets: Vec<(Small, Small)>,
}

impl Congruences {
    /// The distinct pairs of `rows[g]` and `targets[g]`, compared by their numerators and
    /// denominators (in lowest terms, as canonical terms' coefficients and phase classes are;
    /// two pairs equal but written otherwise would both be kept, which changes nothing).
    fn of(rows: &[Vec<(usize, Small)>], targets: &[(Small, Small)]) -> Congruences {
        let raw = |q: &Small| (*q.numer(), *q.denom());
        let order = |x: &usize, y: &usize| {
            let (tx, ty) = (&targets[*x], &targets[*y]);
            (raw(&tx.0), raw(&tx.1))
                .cmp(&(raw(&ty.0), raw(&ty.1)))
                .then_with(|| {
                    let entry = |(s, k): &(usize, Small)| (*s, raw(k));
                    rows[*x].iter().map(entry).cmp(rows[*y].iter().map(entry))
                })
        };
        let mut kept: Vec<usize> = (0..rows.len()).collect();
        kept.sort_unstable_by(order);
        kept.dedup_by(|x, y| order(x, y).is_eq());
        Congruences {
            rows: kept.iter().map(|g| rows[*g].clone()).collect(),
            targets: kept.iter().map(|g| targets[*g]).collect(),
        }
    }
}

/// Whether `v` is a multiple of `m`.
fn multiple(v: Small, m: Small) -> bool {
    (v / m).is_integer()
}

/// What [`solve`] shows its visitor: as `congruence::Node`, in offsets.
enum Offered<'o> {
    /// A solution: the visitor returns false to stop.
    Solution(&'o [Small]),
    /// The offsets of the first `set` free symbols (`System::free`) fixed, before their
    /// extensions (the other free symbols' offsets are stale), with the number of solutions
    /// among those when they may be skipped: the visitor returns true to skip them.
    Prefix {
        o: &'o [Small],
        set: usize,
        count: Option<u128>,
    },
}

/// Offsets (multiples of pi, one per symbol) with `rows[g] . o = targets[g].0` modulo
/// `targets[g].1` for every group, each free symbol's over the multiples of `1/(n a)` in one
/// period `[0, 2 D)` (`a` the lcm of its coefficients' numerators, `D` of their
/// denominators), the `fixed` ones at their value: passed to `found` in lexicographic order
/// (by symbol, then value) until it returns false; with `prefixes`, the prefixes too (see
/// `congruence::walk`). Every phase is scaled to an integer residue modulo one common
/// modulus (`sys`, made by [`system`] from the same `fixed`) and the system solved by
/// `congruence.rs`, which lists the solutions without a search. `Some(true)` when every
/// solution was passed or skipped; `None` past the work budget.
fn solve(
    sys: &System,
    fixed: &[Option<Small>],
    prefixes: bool,
    found: &mut dyn FnMut(Offered) -> bool,
) -> Option<bool> {
    let System { free, ranges, .. } = sys;
    let mut o: Vec<Small> = fixed
        .iter()
        .map(|v| v.unwrap_or_else(Small::zero))
        .collect();
    // Each free symbol's offsets `unit * v`, made once per value met: the solutions repeat
    // a few values (a product in `Small` reduces by gcds; 6% of the Jaco-style arm's
    // `fk --jacobian` made them afresh for every solution).
    let mut values: Vec<Vec<Option<Small>>> = ranges
        .iter()
        .map(|c| vec![None; usize::try_from(*c).unwrap_or(0)])
        .collect();
    let mut set = |z: &[i64], o: &mut [Small]| {
        for (((s, unit, _), v), known) in free.iter().zip(z).zip(&mut values) {
            let slot = usize::try_from(*v).ok().and_then(|i| known.get_mut(i));
            o[*s] = match slot {
                Some(Some(x)) => *x,
                Some(slot) => *slot.insert(*unit * Small::from_integer(*v)),
                None => *unit * Small::from_integer(*v),
            };
        }
    };
    let Ok(echelon) = sys.echelon() else {
        return None;
    };
    let result = echelon.walk(ranges, prefixes, &mut |node| {
        use super::congruence::Node;
        match node {
            Node::Solution(z) => {
                set(z, &mut o);
                found(Offered::Solution(&o))
            }
            Node::Prefix(z, count) => {
                set(z, &mut o);
                found(Offered::Prefix {
                    o: &o,
                    set: z.len(),
                    count,
                })
            }
        }
    });
    match result {
        Ok(()) => Some(true),
        Err(super::congruence::Stop::Work(_)) => None,
        Err(_) => Some(false),
    }
}

/// Whether [`solve`] on the same system has fewer than `bound` solutions, decided by
/// counting them without listing them (`congruence::count`) when the count is known, by
/// listing up to `bound` of them otherwise; `None` as [`solve`].
fn fewer_solutions_than(sys: &System, bound: usize) -> Option<bool> {
    let echelon = sys.echelon().ok()?;
    if let Some(c) = echelon.count(&sys.ranges) {
        return Some(c < bound as u128);
    }
    // Listed as `congruence::solutions` listed them, after eliminating the system afresh.
    echelon.recharge().ok()?;
    let mut seen = 0usize;
    let result = echelon.walk(&sys.ranges, false, &mut |node| match node {
        super::congruence::Node::Solution(_) => {
            seen += 1;
            seen < bound
        }
        super::congruence::Node::Prefix(..) => false,
    });
    match result {
        Ok(()) => Some(true),
        Err(super::congruence::Stop::Work(_)) => None,
        Err(_) => Some(false),
    }
}

/// The system of [`solve`] in integers (see `congruence.rs`): each free symbol's index, unit
/// `1/(n a)` and number of candidates; the rows and right-hand sides modulo one modulus; the
/// candidates' ranges; its echelon form once made ([`System::echelon`]).
struct System {
    free: Vec<(usize, Small, i64)>,
    a: Vec<Vec<i64>>,
    b: Vec<i64>,
    modulus: i64,
    ranges: Vec<i64>,
    echelon: std::cell::OnceCell<super::congruence::Echelon>,
}

impl System {
    /// The system in echelon form, for one more use: eliminated at the first call, and at
    /// each later one its elimination's work charged again (`congruence::Echelon::recharge`),
    /// so that the work budget sees what eliminating it afresh for each use (as every use did
    /// before: [`find`]'s first solution and [`fewer_solutions_than`]'s count eliminated the
    /// same system twice, about 9% of `find` on the Jaco-style arm) charged.
    fn echelon(&self) -> Result<&super::congruence::Echelon, super::congruence::Stop> {
        if let Some(e) = self.echelon.get() {
            e.recharge()?;
            return Ok(e);
        }
        let e = super::congruence::echelon(&self.a, &self.b, self.modulus, self.ranges.len())?;
        Ok(self.echelon.get_or_init(|| e))
    }
}

/// One row of [`system`] before its scaling to integers: each free symbol's coefficient as a
/// fraction `(numerator, denominator)` in lowest terms, the right-hand side, the modulus.
type FractionRow = (Vec<(i64, i64)>, Small, Small);

/// The integer system of [`solve`]; `None` past the bounds (too many candidates, numbers too
/// large).
fn system(
    syms: &[Sym],
    rows: &[Vec<(usize, Small)>],
    targets: &[(Small, Small)],
    n: i64,
    fixed: &[Option<Small>],
) -> Option<System> {
    // Each free symbol's unit `1/(n a)` and number of candidates.
    let mut free: Vec<(usize, Small, i64)> = Vec::new();
    for (s, fixed_s) in fixed.iter().enumerate().take(syms.len()) {
        if fixed_s.is_some() {
            continue;
        }
        let (mut num, mut den) = (1i64, 1i64);
        for r in rows {
            // A multiple already (a coefficient met before, or 1) leaves it without a gcd.
            if let Some((_, k)) = r.iter().find(|(x, _)| *x == s) {
                let kn = k.numer().abs();
                if kn == 0 || num % kn != 0 {
                    num = num.lcm(&kn);
                }
                if den % k.denom() != 0 {
                    den = den.lcm(k.denom());
                }
            }
        }
        let count = n.checked_mul(num)?.checked_mul(den)?.checked_mul(2)?;
        if count > MAX_CANDIDATES {
            return None;
        }
        free.push((s, Small::new(1, n.checked_mul(num)?), count));
    }
    let column: Vec<Option<usize>> = {
        let mut c = vec![None; syms.len()];
        for (j, (s, _, _)) in free.iter().enumerate() {
            c[*s] = Some(j);
        }
        c
    };
    // Each row as fractions `(numerator, denominator)` in lowest terms: coefficients of the
    // free symbols' integers, right-hand side (the fixed symbols moved to it), modulus. A
    // coefficient `k / (n a)` is reduced by one gcd in machine words (the same fraction as
    // `k * unit` in `Small`, which reduces by two: a product in `Small` was half of this
    // function's instructions on the Jaco-style arm).
    let mut rational: Vec<FractionRow> = Vec::with_capacity(rows.len());
    let mut lcm: i64 = 1;
    let mut take = |den: i64| -> Option<()> {
        if lcm % den != 0 {
            lcm = lcm.checked_mul(den / lcm.gcd(&den))?;
        }
        Some(())
    };
    for (r, (t, m)) in rows.iter().zip(targets) {
        let mut a = vec![(0, 1); free.len()];
        let mut rhs = *t;
        for (s, k) in r {
            match (column[*s], fixed[*s]) {
                (Some(j), _) => {
                    let den = k.denom().checked_mul(*free[j].1.denom())?;
                    let g = k.numer().gcd(&den);
                    a[j] = (k.numer() / g, den / g);
                    take(a[j].1)?;
                }
                (None, Some(v)) if !v.is_zero() => rhs -= *k * v,
                (None, _) => {}
            }
        }
        take(*rhs.denom())?;
        take(*m.denom())?;
        rational.push((a, rhs, *m));
    }
    if lcm > 1 << 40 {
        return None;
    }
    // One common modulus: each row scaled by `L` (integers), then by `M / (L m)`. A fraction
    // `p / q` times `L` is the integer `p (L / q)` (`q` divides `L`).
    let l = lcm;
    let times_l = |(p, q): (i64, i64)| i128::from(p) * i128::from(l / q);
    let mut modulus: i64 = 1;
    for (_, _, m) in &rational {
        let mg = i64::try_from(times_l((*m.numer(), *m.denom()))).ok()?;
        modulus = modulus.checked_mul(mg / modulus.gcd(&mg))?;
    }
    if modulus > 1 << 40 {
        return None;
    }
    let mut a: Vec<Vec<i64>> = Vec::with_capacity(rational.len());
    let mut b: Vec<i64> = Vec::with_capacity(rational.len());
    for (coef, rhs, m) in &rational {
        // `L m` fits in a machine word (checked above, as `mg`): the quotient in words is the
        // quotient in 128 bits, without the call to the 128-bit division routine.
        let scale = modulus / i64::try_from(times_l((*m.numer(), *m.denom()))).ok()?;
        // No product leaves i128 unnoticed: a numerator past ~2^47 gives no system. In machine
        // words when every product fits in one (the same integer, and the same remainder as
        // in 128 bits: `congruence::md`), else in 128 bits.
        let int = |(p, q): (i64, i64)| -> Option<i64> {
            if let Some(v) = p.checked_mul(l / q).and_then(|v| v.checked_mul(scale)) {
                return Some(v.rem_euclid(modulus));
            }
            let v = times_l((p, q)).checked_mul(i128::from(scale))?;
            Some(super::congruence::md(v, modulus))
        };
        a.push(coef.iter().map(|q| int(*q)).collect::<Option<_>>()?);
        b.push(int((*rhs.numer(), *rhs.denom()))?);
    }
    let ranges: Vec<i64> = free.iter().map(|(_, _, c)| *c).collect();
    Some(System {
        free,
        a,
        b,
        modulus,
        ranges,
        echelon: std::cell::OnceCell::new(),
    })
}

/// The value of terms of one frequency vector `F` (a group) as the complex amplitude `z` of
/// `e^{i F}`: `(re, im)` in f64.
pub(super) fn amplitude<'a>(terms: impl IntoIterator<Item = &'a Term>) -> Option<(f64, f64)> {
    let (mut re, mut im) = (0.0, 0.0);
    for t in terms {
        let c = t.coef.to_f64()? * (t.rad as f64).sqrt();
        let p = std::f64::consts::PI * t.mode.pi.numer().to_f64()? / t.mode.pi.denom().to_f64()?;
        // cos(F + p) = Re(e^{ip} e^{iF}), sin(F + p) = Re(-i e^{ip} e^{iF}).
        let (a, b) = if t.mode.sin {
            (p.sin(), -p.cos())
        } else {
            (p.cos(), p.sin())
        };
        re += c * a;
        im += c * b;
    }
    Some((re, im))
}

/// `sum k o[s]` over the row `r`, exactly (see [`dot_of_pairs`]).
fn dot(r: &[(usize, Small)], o: &[Small]) -> Small {
    dot_of_pairs(r.iter().map(|(s, k)| (*k, o[*s])))
}

/// `sum k o` over the pairs `(k, o)`, exactly: summed over a growing common denominator in
/// machine words and reduced once (the same value as the sum in `Small`, whose every step
/// reduces by gcds: the Jaco-style arm's offsets spent half their instructions there, scoring
/// each solution); in `Small` when a word would overflow.
fn dot_of_pairs(pairs: impl Iterator<Item = (Small, Small)> + Clone) -> Small {
    let fast = |pairs: &mut dyn Iterator<Item = (Small, Small)>| -> Option<Small> {
        let (mut num, mut den) = (0i64, 1i64);
        for (k, o) in pairs {
            let a = k.numer().checked_mul(*o.numer())?;
            let b = k.denom().checked_mul(*o.denom())?;
            if den % b == 0 {
                num = num.checked_add(a.checked_mul(den / b)?)?;
            } else {
                num = num.checked_mul(b)?.checked_add(a.checked_mul(den)?)?;
                den = den.checked_mul(b)?;
            }
        }
        let g = num.unsigned_abs().gcd(&den.unsigned_abs()) as i64;
        Some(Small::new_raw(num / g, den / g))
    };
    fast(&mut pairs.clone()).unwrap_or_else(|| pairs.map(|(k, o)| k * o).sum())
}

/// The least common multiple of the denominators of `xs`; `None` when it leaves a machine
/// word. A denominator that divides the multiple so far (1, the offset of most symbols, or
/// one met before) leaves it as it is without a gcd.
pub(super) fn common_denominator<'a>(mut xs: impl Iterator<Item = &'a Small>) -> Option<i64> {
    xs.try_fold(1i64, |den, x| {
        if den % x.denom() == 0 {
            Some(den)
        } else {
            den.checked_mul(x.denom() / den.gcd(x.denom()))
        }
    })
}

/// Rows of integer coefficients `(symbol, k)` over one common denominator: `(rows, den)`.
type IntegerRows = (Vec<Vec<(usize, i64)>>, i64);

/// The rows `freqs` with integer coefficients over one common denominator; `None` when that
/// denominator or a coefficient leaves a machine word.
fn integer_rows(freqs: &[&[(usize, Small)]]) -> Option<IntegerRows> {
    let den = common_denominator(freqs.iter().flat_map(|r| r.iter().map(|(_, k)| k)))?;
    let rows = freqs
        .iter()
        .map(|r| {
            r.iter()
                .map(|(s, k)| Some((*s, k.numer().checked_mul(den / k.denom())?)))
                .collect::<Option<Vec<_>>>()
        })
        .collect::<Option<Vec<_>>>()?;
    Some((rows, den))
}

/// The offsets `o` over their common denominator: the numerators into `out`, the denominator
/// returned; `None` when it leaves a machine word.
fn scale_offsets(o: &[Small], out: &mut Vec<i64>) -> Option<i64> {
    out.clear();
    let den = common_denominator(o.iter())?;
    for v in o {
        out.push(v.numer().checked_mul(den / v.denom())?);
    }
    Some(den)
}

/// The phase `f . o` of the `i`-th distinct vector `f` as `(numerator, denominator)`, for the
/// value `numerator / denominator` in f64: from the integer rows (`int_freqs`, see
/// [`integer_rows`]) and the scaled offsets (`scaled`, over `o_den`, see [`scale_offsets`])
/// when every number fits and is exact in an f64 (then the quotient is the correctly rounded
/// value of the phase, the same bits as the reduced fraction's), else reduced by [`dot`].
fn phase_of(
    f: &[(usize, Small)],
    int_freqs: Option<&IntegerRows>,
    i: usize,
    o: &[Small],
    scaled: &[i64],
    o_den: Option<i64>,
) -> (i64, i64) {
    const EXACT: u64 = 1 << 53;
    let fast = || -> Option<(i64, i64)> {
        let (rows, den) = int_freqs?;
        let den = den.checked_mul(o_den?)?;
        let mut num: i64 = 0;
        for (s, k) in &rows[i] {
            num = num.checked_add(k.checked_mul(scaled[*s])?)?;
        }
        (num.unsigned_abs() <= EXACT && den.unsigned_abs() <= EXACT).then_some((num, den))
    };
    fast().unwrap_or_else(|| {
        let f = dot(f, o);
        (*f.numer(), *f.denom())
    })
}

/// The offsets shown (see the module docs): a symbol whose offset in `base` is a multiple
/// of its own steps (each keeping every group's phase modulo 1/12) keeps none; the others
/// range over every solution with those fixed at 0, the best by (fewest cosine and sine
/// parts of the shifted scalar, smallest denominator, fewest negative parts, smallest
/// `|o|`, positive).
fn representatives(
    groups: &[Group],
    syms: &[Sym],
    rows: &[Vec<(usize, Small)>],
    congruences: &Congruences,
    n: i64,
    everything: &System,
    base: Vec<Small>,
) -> Option<Vec<Small>> {
    let amps: Vec<(f64, f64)> = groups
        .iter()
        .map(|g| amplitude(g.terms.iter().copied()).unwrap_or((0.0, 0.0)))
        .collect();
    // Groups of one frequency vector (and other monomials) share their phase: each distinct
    // vector's `e^{-i pi f}` is computed once per solution.
    let mut freqs: Vec<&[(usize, Small)]> = rows.iter().map(Vec::as_slice).collect();
    freqs.sort_unstable();
    freqs.dedup();
    let row_freq: Vec<usize> = rows
        .iter()
        .map(|r| freqs.binary_search(&r.as_slice()).unwrap_or(0))
        .collect();
    // Each symbol's half period `D` (the lcm of its coefficients' denominators).
    let halves: Vec<Small> = (0..syms.len())
        .map(|i| {
            Small::from_integer(
                rows.iter()
                    .filter_map(|r| r.iter().find(|(x, _)| *x == i))
                    .fold(1i64, |acc, (_, k)| acc.lcm(k.denom())),
            )
        })
        .collect();
    // Each distinct vector's phase for the solution being scored, made when a group first
    // asks for it (`stamp` says for which solution).
    let mut phases: Vec<(f64, f64)> = vec![(0.0, 0.0); freqs.len()];
    let mut stamp: Vec<usize> = vec![0; freqs.len()];
    let mut scored = 0usize;
    // `e^{i pi f}` by the exact phase `f`: the solutions compared share few phases (most
    // symbols are held at 0 or take a few values), and the cosine and sine were most of the
    // cost of scoring a solution. The same `f` gives the same bits, so the scores are those
    // computed afresh.
    let mut unit_circle: super::FxMap<(i64, i64), (f64, f64)> = Default::default();
    // The distinct vectors over one common denominator, and each solution's offsets over
    // theirs (`scaled`): a phase is then an integer sum over a known denominator, not a sum
    // of rationals reduced by a gcd (see `phase_of`).
    let int_freqs = integer_rows(&freqs);
    let mut scaled_o: Vec<i64> = Vec::with_capacity(syms.len());
    // The number of cosine and sine parts of the shifted scalar, and of negative ones, added
    // to `start`; `None` once the parts pass `bound` (the parts of the best solution so far:
    // the parts come first in the order of solutions, and they only grow group by group, so
    // such a solution is never taken, and the rest of its groups need not be looked at). Of
    // the groups `only` alone (in increasing order; listed once per run for the solutions,
    // not skipped group by group for each: see `listed`). With
    // `after`, the number of groups past each `g` among those that give a part whatever their
    // phase (see [`surely_a_part`]): `None` as soon as the parts so far and those pass
    // `bound`, which the parts at the end then do.
    let mut score = |o: &[Small],
                     start: (usize, usize),
                     bound: usize,
                     only: &[usize],
                     after: Option<&[usize]>|
     -> Option<(usize, usize)> {
        if let Some(after) = after {
            if start.0 + after.first().map_or(0, |a| *a) > bound {
                return None;
            }
        }
        scored += 1;
        let o_den = scale_offsets(o, &mut scaled_o);
        let (mut parts, mut neg) = start;
        for &g in only {
            let (i, (re, im)) = (&row_freq[g], &amps[g]);
            #[cfg(test)]
            tests::GROUPS_SCORED.with(|n| n.set(n.get() + 1));
            if stamp[*i] != scored {
                stamp[*i] = scored;
                let f = phase_of(freqs[*i], int_freqs.as_ref(), *i, o, &scaled_o, o_den);
                phases[*i] = *unit_circle.entry(f).or_insert_with(|| {
                    let f = f.0 as f64 / f.1 as f64;
                    (
                        (f * std::f64::consts::PI).cos(),
                        (f * std::f64::consts::PI).sin(),
                    )
                });
            }
            let (c, s) = phases[*i];
            // z e^{-i pi f}: the cosine part is its real part, the sine part minus its
            // imaginary part.
            let (a, b) = (re * c + im * s, -(im * c - re * s));
            let scale = re.abs() + im.abs();
            for v in [a, b] {
                if v.abs() > 1e-9 * scale.max(1e-300) {
                    parts += 1;
                    neg += usize::from(v < 0.0);
                }
            }
            if parts + after.map_or(0, |a| a[g + 1]) > bound {
                return None;
            }
        }
        Some((parts, neg))
    };
    let mut run =
        |sys: &System, fixed: &[Option<Small>], all: bool| -> Option<(bool, Option<Vec<Small>>)> {
            // Whether the solutions are fewer than the bound, counted first: when they are not,
            // none of the first run (`all`) is shown.
            // Counted without listing them when the count is known (the Jaco-style arm's pose
            // entries each have more than the bound: listing them to the bound was a ninth of
            // its `fk --jacobian`).
            if all && !fewer_solutions_than(sys, MAX_SOLUTIONS)? {
                return Some((false, None));
            }
            let mut best: Option<(Key, Vec<Small>)> = None;
            let mut seen = 0usize;
            // The solution being scored, centred into (-D, D] for a period 2 D: one buffer,
            // copied only when the solution is the best so far.
            let mut o: Vec<Small> = Vec::with_capacity(syms.len());
            let done = completions(rows, sys);
            // The parts, and negative parts, of the groups known from each prefix shown
            // (`known[set]`), and the
            // length of the first (the shortest: see `congruence::walk`).
            let mut known: Vec<(usize, usize)> = vec![(0, 0); sys.free.len() + 1];
            let mut first: Option<usize> = None;
            // The parts the groups not known from `set` free symbols have at least: one each
            // but those of a zero amplitude (see `completions`).
            let mut rest: Vec<usize> = vec![0; sys.free.len() + 1];
            for (d, (re, im)) in done.iter().zip(&amps) {
                if re.abs() + im.abs() > 0.0 {
                    rest[..*d].iter_mut().for_each(|r| *r += 1);
                }
            }
            // A solution's parts: those of the groups whose rows hold no free symbol (the
            // same for every solution of the run: their symbols are fixed), counted at the
            // first solution, and those of the others (`done[g] >= varying`), scored for each.
            // `after[g]`: how many of those from `g` on give a part whatever their phase (so
            // at least that many parts are still to come; a sum of counts, the same whatever
            // the order the groups are scored in).
            let cut = cuts();
            let mut constant: Option<(usize, usize)> = None;
            let varying = if cut { 1 } else { 0 };
            let mut after: Vec<usize> = vec![0; groups.len() + 1];
            for g in (0..groups.len()).rev() {
                let sure = done[g] >= varying && surely_a_part(amps[g]);
                after[g] = after[g + 1] + usize::from(sure);
            }
            // The groups scored for each solution (`done[g] >= varying`; `done[g]` is at most
            // the number of free symbols), and a buffer for those of a prefix or of the
            // constant ones (`lo <= done[g] <= hi`), in increasing order as they were met when
            // `score` went through every group and skipped the others.
            let listed: Vec<usize> = (0..groups.len()).filter(|g| done[*g] >= varying).collect();
            let mut some: Vec<usize> = Vec::with_capacity(groups.len());
            let among = |lo: usize, hi: usize, out: &mut Vec<usize>| {
                out.clear();
                out.extend((0..groups.len()).filter(|g| (lo..=hi).contains(&done[*g])));
            };
            let complete = solve(sys, fixed, true, &mut |node| {
                let (solution, prefix) = match node {
                    Offered::Solution(raw) => (raw, None),
                    Offered::Prefix { o: raw, set, count } => (raw, Some((set, count))),
                };
                o.clear();
                o.extend(
                    solution
                        .iter()
                        .zip(&halves)
                        .map(|(&v, &den)| centred(v, den)),
                );
                let bound = best.as_ref().map_or(usize::MAX, |(k, _)| k.0);
                if let Some((set, count)) = prefix {
                    let lo = if *first.get_or_insert(set) == set {
                        0
                    } else {
                        set
                    };
                    among(lo, set, &mut some);
                    let (parts, neg) = score(&o, (0, 0), usize::MAX, &some, None).unwrap_or((0, 0));
                    let before = if lo == 0 { (0, 0) } else { known[set - 1] };
                    known[set] = (before.0 + parts, before.1 + neg);
                    // A head no solution under the prefix is below (see `completions`): above
                    // the best's, none of them is taken, and the walk goes on as it would
                    // past them.
                    let set_offsets = sys.free[..set].iter().map(|(s, _, _)| o[*s]);
                    let den = set_offsets.clone().map(|v| *v.denom()).max().unwrap_or(1);
                    let nonzero = set_offsets.filter(|v| !v.is_zero()).count();
                    let head = (known[set].0 + rest[set], den, nonzero, known[set].1);
                    let skip = best
                        .as_ref()
                        .is_some_and(|(b, _)| head > (b.0, b.1, b.2, b.3))
                        && count.is_some_and(|c| c < (MAX_SOLUTIONS - seen) as u128);
                    if skip {
                        seen += count.map_or(0, |c| c as usize);
                    }
                    return skip;
                }
                seen += 1;
                // A solution whose largest denominator and number of nonzero offsets are past
                // the best's is taken (by `key_below`, which compares whole keys) only with
                // fewer parts than the best: its bound is one less, and with a best of no
                // parts it is not scored.
                let bound = match &best {
                    Some((k, _)) if cut => {
                        let den = o.iter().map(|v| *v.denom()).max().unwrap_or(1);
                        let nonzero = o.iter().filter(|v| !v.is_zero()).count();
                        if (den, nonzero) > (k.1, k.2) {
                            let Some(fewer) = bound.checked_sub(1) else {
                                return seen < MAX_SOLUTIONS;
                            };
                            fewer
                        } else {
                            bound
                        }
                    }
                    _ => bound,
                };
                let start = if cut {
                    *constant.get_or_insert_with(|| {
                        among(0, 0, &mut some);
                        score(&o, (0, 0), usize::MAX, &some, None).unwrap_or((0, 0))
                    })
                } else {
                    (0, 0)
                };
                let Some((parts, neg)) = score(&o, start, bound, &listed, cut.then_some(&after))
                else {
                    return seen < MAX_SOLUTIONS;
                };
                if let Some(key) = key_below(&o, parts, neg, best.as_ref().map(|(k, _)| k)) {
                    best = Some((key, o.clone()));
                }
                seen < MAX_SOLUTIONS
            })?;
            Some((complete, best.map(|(_, o)| o)))
        };
    // Every solution when they are few; else the symbols whose offset in `base` is a multiple
    // of their own steps keep none, and the others range over the solutions.
    let free = vec![None; syms.len()];
    if let (true, Some(o)) = run(everything, &free, true)? {
        return Some(o);
    }
    let fixed = held_at_zero(congruences, syms.len(), &base);
    let sys = system(syms, &congruences.rows, &congruences.targets, n, &fixed)?;
    run(&sys, &fixed, false)?.1
}

/// The symbols [`representatives`] holds at offset 0 when the solutions are too many: those
/// whose offset in `base` is a multiple of their own step, the rational lcm of `m / k` over
/// the congruences (modulus `m`) whose row holds the symbol (coefficient `k`), or that no row
/// holds; `None` for the others.
///
/// Each pair `(m, k)` is divided once per symbol (most congruences repeat a few: the Jaco-style
/// arm's 48 rows hold each symbol with the coefficients 1 and 2, and a quotient in `Small`
/// reduces by gcds): the same step, as the rational lcm (`lcm` of the numerators over `gcd`
/// of the denominators, in lowest terms) takes the larger power of each prime, so it is
/// idempotent, commutative and associative, and a repeated quotient leaves it as it is.
fn held_at_zero(congruences: &Congruences, syms: usize, base: &[Small]) -> Vec<Option<Small>> {
    // The pairs met, by their numerators and denominators (in lowest terms: a pair written
    // otherwise is only divided again).
    let mut seen: Vec<[i64; 4]> = Vec::new();
    (0..syms)
        .map(|i| {
            seen.clear();
            let mut step: Option<Small> = None;
            for (r, (_, m)) in congruences.rows.iter().zip(&congruences.targets) {
                if let Some((_, k)) = r.iter().find(|(x, _)| *x == i) {
                    let pair = [*m.numer(), *m.denom(), *k.numer(), *k.denom()];
                    if seen.contains(&pair) {
                        continue;
                    }
                    seen.push(pair);
                    let q = (*m / *k).abs();
                    step = Some(match step {
                        None => q,
                        Some(p) => Small::new(p.numer().lcm(q.numer()), p.denom().gcd(q.denom())),
                    });
                }
            }
            step.is_none_or(|st| multiple(base[i], st))
                .then(Small::zero)
        })
        .collect()
}

/// Each group's completion in the walk of `sys`: 1 + the position in `sys.free` of the last
/// free symbol its row holds (0 when it holds none), the number of free symbols set from
/// which its offsets, so its parts, are known.
///
/// Why skipping the solutions under a prefix whose head (below) is above the best's shows the
/// same offsets. A solution's parts and negative parts are sums over the groups of each
/// group's, which depend on that group's offsets alone (centred per symbol); a group of
/// amplitude `z != 0` has at least one part whatever its phase (the cosine and sine parts
/// `a`, `b` of `z e^{-i pi f}` have `|a| + |b| >= |z| >= (|Re z| + |Im z|) / sqrt 2`, so one
/// of them is above a quarter of the `scale` of `score`, far above its threshold `1e-9
/// scale`). So every solution under the prefix has at least the known groups' parts plus
/// one per other group of nonzero amplitude, at least the known groups' negative parts, a
/// largest denominator at least the set offsets' and at least as many nonzero offsets: its
/// [`Key`]'s head is at least `(parts, den, nonzero, neg)` so bounded in every entry, so
/// lexicographically, and above the best's: `score` returns `None` for it or `key_below`
/// does (the best only falls), leaving the best as it is. The walk skips only when the solutions skipped
/// stop short of [`MAX_SOLUTIONS`] (so the run stops after the same solution) and charges
/// them as listed (`congruence::walk`): the best, `complete` and the work charged are those
/// of the run that scores them all.
fn completions(rows: &[Vec<(usize, Small)>], sys: &System) -> Vec<usize> {
    let mut column: Vec<Option<usize>> = Vec::new();
    for (j, (s, _, _)) in sys.free.iter().enumerate() {
        if column.len() <= *s {
            column.resize(*s + 1, None);
        }
        column[*s] = Some(j + 1);
    }
    rows.iter()
        .map(|r| {
            r.iter()
                .filter_map(|(s, _)| column.get(*s).copied().flatten())
                .max()
                .unwrap_or(0)
        })
        .collect()
}

/// `v` moved by a multiple of the period `2 den` into `(-den, den]` (`den` a positive
/// integer): in machine words when they suffice (zero, the common case, at once), in `Small`
/// otherwise.
fn centred(v: Small, den: Small) -> Small {
    if v.is_zero() {
        return v;
    }
    let slow = || {
        let period = den * Small::from_integer(2);
        let v = v - (v / period).floor() * period;
        if v > den {
            v - period
        } else {
            v
        }
    };
    // v = a / b, period p: a mod (p b), over b, is v minus floor(v / p) p. It is in lowest
    // terms as it stands: `r` differs from `a` by a multiple of `b`, so `gcd(r, b) = gcd(a, b)
    // = 1` (`b > 0`), and no gcd is taken.
    let fast = || -> Option<Small> {
        let (a, b) = (*v.numer(), *v.denom());
        let half = den.to_integer().checked_mul(b)?;
        let r = a.rem_euclid(half.checked_mul(2)?);
        let r = if r > half { r - 2 * half } else { r };
        Some(Small::new_raw(r, b))
    };
    if den.is_integer() {
        fast().unwrap_or_else(slow)
    } else {
        slow()
    }
}

/// The order of solutions: parts, largest denominator, offsets, negative parts, sum of
/// `|o|`, negative offsets.
type Key = (usize, i64, usize, usize, Small, usize);

/// The [`Key`] of the offsets `o` whose shifted scalar has `parts` parts, `neg` of them
/// negative, when it is below `best` (every key is, without a best so far); `None` otherwise.
/// The sum of `|o|` (rational additions, each reduced by a gcd) and the negative offsets are only
/// computed when the key's first four parts do not already decide: a key whose head is above
/// `best`'s is above it whatever its tail (keys are compared lexicographically), one whose
/// head is below is below it, and only on equal heads is the tail compared.
fn key_below(o: &[Small], parts: usize, neg: usize, best: Option<&Key>) -> Option<Key> {
    let den = o.iter().map(|v| *v.denom()).max().unwrap_or(1);
    let nonzero = o.iter().filter(|v| !v.is_zero()).count();
    let head = (parts, den, nonzero, neg);
    if let Some(b) = best {
        if head > (b.0, b.1, b.2, b.3) {
            return None;
        }
    }
    let size: Small = o.iter().map(|v| v.abs()).sum();
    let negatives = o.iter().filter(|v| v.is_negative()).count();
    let key = (parts, den, nonzero, neg, size, negatives);
    best.is_none_or(|b| key < *b).then_some(key)
}

/// Whether a group of amplitude `(re, im)` gives at least one part in `representatives`'
/// score whatever its phase `f`: when `s = |re| + |im|` is finite and within `[1e-290,
/// 1e290]`. Why: the parts are `a = re c + im s'`, `b = re s' - im c` (`c`, `s'` the cosine
/// and sine of `pi f`, `c^2 + s'^2 = 1` to a few units of rounding), so `|a| + |b| >= sqrt(a^2 +
/// b^2) = |z| >= s / sqrt 2` exactly, and the larger of them is at least `s / (2 sqrt 2)`; the
/// products and sum that make each in f64 err by a few units of rounding of `s` (no product
/// overflows, none that matters underflows in that range), far below that, and it is far above
/// the threshold `1e-9 s` a part passes. (A zero amplitude, or one that is not finite, may give
/// none.)
fn surely_a_part((re, im): (f64, f64)) -> bool {
    let s = re.abs() + im.abs();
    s.is_finite() && (1e-290..=1e290).contains(&s)
}

/// Whether [`representatives`] cuts its scoring short (see there); false in the tests that
/// compare it with the scoring of every group of every solution.
fn cuts() -> bool {
    #[cfg(test)]
    if tests::UNCUT.with(std::cell::Cell::get) {
        return false;
    }
    true
}

/// The most solutions [`representatives`] compares.
const MAX_SOLUTIONS: usize = 4096;

impl Shift {
    /// `x` in the shifted symbols: each mode `trig(f.x + p)` becomes `trig(f.y + p - f.o)`;
    /// `None` when a symbolic mode keeps an offset (or `x` is an error value).
    ///
    /// A group (one monomial, one frequency vector `f`) moves as a whole, every term by the
    /// same `f.o`. When every moved term lands on a multiple of pi/12 (the shifts found for
    /// offsets of 2s and 3s: see `phase_class_of_offsets`), it is written at once without an
    /// offset (`Term::push_at_twelfths`), and the groups not moved are the canonical groups
    /// of `x` as they were: every group is then canonical once like terms are merged, and the
    /// terms are only sorted and merged (`Scalar::from_terms_settled`, checked against the
    /// rewrite from scratch in debug builds). Otherwise the moved terms are canonicalized.
    pub(crate) fn apply(&self, x: &Scalar) -> Option<Scalar> {
        let terms = x.terms().ok()?;
        let mut moved: Vec<Term> = Vec::with_capacity(terms.len() + terms.len() / 2);
        let mut settled = true;
        // The phase of the last frequency vector met: the terms come sorted by (sine, vector),
        // so the terms of one vector follow each other, and `f . o` (a lookup of each symbol
        // and a sum of rationals) is computed once for them. The same vector gives the same
        // phase, so each term moves as it did with its own.
        let mut last: Option<(&[(Sym, Small)], Small)> = None;
        for t in terms {
            let d = match last {
                Some((f, d)) if crate::scalar::atoms::freq_cmp(f, &t.mode.freq).is_eq() => d,
                _ => {
                    let d = self.phase(&t.mode.freq);
                    last = Some((&t.mode.freq, d));
                    d
                }
            };
            if d.is_zero() {
                moved.push(t.clone());
                continue;
            }
            let pi = reduce2(t.mode.pi - d);
            if !t.push_at_twelfths(pi, &mut moved) {
                settled = false;
                let mut t = t.clone();
                t.mode.pi = pi;
                moved.push(t);
            }
        }
        let y = if settled {
            Scalar::from_terms_settled(moved)
        } else {
            Scalar::from_terms(moved)
        };
        no_offset(&y).then_some(y)
    }

    /// [`Shift::apply`] of `x`, made from `hint`'s scalar `y` when the hint's shift and this
    /// one differ by a translation that moves every mode of `y` by a multiple of pi/2
    /// ([`Shift::translated`]): the hint's own shift (the same symbols with the same offsets),
    /// or `q3` shifted by `-5 pi/9` where the hint shifts `q2` by `5 pi/9`, in an entry of
    /// `q2 - q3` alone, or `-4 pi/9` for `5 pi/9` (the terms of odd `q2` negated; on the half
    /// angles of a dual quaternion's components, `cos(q2/2)` made `-sin(q2/2)`). Otherwise `x`
    /// is shifted as before.
    ///
    /// Why it is the same scalar: `x` is `y` with each symbol `s` of the hint replaced by
    /// `s + c_s` ([`Hint`]), and [`Shift::apply`] replaces each `s` of this shift by `s - o_s`
    /// in `x` (a mode `trig(f.x + p)` becomes `trig(f.y + p - f.o)`), so it gives the value
    /// of `y` with every mode `trig(f.y + p)` turned into `trig(f.y + p + f.(c - o))` (`c`,
    /// `o` zero for a symbol the hint, or this shift, leaves alone). When every `f.(c - o)` is
    /// an integer `k` (`pi` implied), that is the term times `(-1)^k`: `y` with the terms of
    /// odd `k` negated. The terms of one group (monomial, frequency vector) share `k`, so each
    /// group is kept or negated whole: the terms stay sorted and merged and every group
    /// canonical (as `-y` is: `Neg for &Scalar`), and a value has one canonical form, so it
    /// is `apply`'s scalar. A group moved by an odd multiple of pi/2 has its cosine and sine
    /// parts swapped (see [`Shift::translated`]), canonical when it has no offset, as `apply`
    /// writes it. `apply` returns the scalar when no symbolic mode of it keeps an offset, and
    /// so does this (the same test on the same scalar). The Jaco-style arm's 20 pose entries
    /// all take this route (`apply` was 3.6% of its `fk --jacobian`, callgrind, one thread;
    /// 0.04% now, for scalars searched inside the closed forms, which have no hint). Checked
    /// against `apply` in debug builds, and by the tests below.
    pub(crate) fn apply_hinted(&self, x: &Scalar, hint: Option<Hint>) -> Option<Scalar> {
        // Under a cancelled context `apply` may give an error value (and `None`): then as
        // before.
        let made = hint
            .filter(|_| crate::scalar::check_cancelled().is_ok())
            .and_then(|h| self.translated(&h));
        let Some(y) = made else {
            return self.apply(x);
        };
        let y = no_offset(&y).then_some(y);
        debug_assert_eq!(y, self.apply(x), "a hinted shift's scalar");
        y
    }

    /// The hint's `y` translated by `c - o` (the hint's offsets `c` less this shift's `o`),
    /// when every mode's phase `f.(c - o)` is a multiple of 1/2 (of pi), and of 1 on the
    /// terms with an offset: its terms turned by that phase, in place (see
    /// [`Shift::apply_hinted`]); `None` otherwise, and for an error value.
    fn translated(&self, h: &Hint) -> Option<Scalar> {
        // `c - o` over the symbols of either, zero entries left out: none when the shifts are
        // the same.
        let mut v: Vec<(Sym, Small)> = h.shifts.to_vec();
        for (s, o) in &self.0 {
            match v.iter_mut().find(|(t, _)| t == s) {
                Some((_, c)) => *c -= *o,
                None => v.push((s.clone(), -*o)),
            }
        }
        v.retain(|(_, d)| !d.is_zero());
        let terms = h.y.terms().ok()?;
        if v.is_empty() {
            #[cfg(test)]
            tests::HINTS_TAKEN.with(|n| {
                let mut c = n.get();
                c[0] += 1;
                n.set(c);
            });
            return Some(h.y.clone());
        }
        // Each term's phase in quarter turns (`2 f.(c - o)` modulo 4); the terms of one
        // frequency vector mostly follow each other (see `apply`), each run's phase computed
        // once.
        let mut last: Option<(&[(Sym, Small)], i64)> = None;
        let mut turns: Vec<u8> = Vec::with_capacity(terms.len());
        for t in terms {
            let turn = match last {
                Some((f, turn)) if crate::scalar::atoms::freq_cmp(f, &t.mode.freq).is_eq() => turn,
                _ => {
                    let d = dot_of_pairs(t.mode.freq.iter().filter_map(|(s, k)| {
                        v.iter().find(|(x, _)| x == s).map(|(_, d)| (*k, *d))
                    }));
                    let turn = super::turn::quarters(d)?;
                    last = Some((&t.mode.freq, turn));
                    turn
                }
            };
            // A quarter turn writes the term's cosine as a sine (and back), which leaves its
            // group canonical only without an offset (see below).
            if turn % 2 == 1 && !t.mode.pi.is_zero() {
                return None;
            }
            turns.push(turn as u8);
        }
        #[cfg(test)]
        tests::HINTS_TAKEN.with(|n| {
            let mut c = n.get();
            let most = turns.iter().map(|t| usize::from(t % 2 == 1) + 1).max();
            c[most.filter(|_| turns.iter().any(|t| *t != 0)).unwrap_or(0)] += 1;
            n.set(c);
        });
        if turns.iter().all(|t| *t == 0) {
            return Some(h.y.clone());
        }
        // `trig(a + k pi/2)`: `k = 2` negates the term; `k = 1` makes `cos a` into `-sin a`
        // and `sin a` into `cos a`, `k = 3` into `sin a` and `-cos a`. A group's terms share
        // `k`: negated, or with an odd `k` its cosine and sine parts swapped (one negated),
        // the value `Re(i^k z e^{i a})` of a group `Re(z e^{i a})` without an offset, written
        // in the same columns (`cos a`, `sin a` over the square-root field), as
        // `Term::push_at_twelfths` writes a term moved by `k/2`: canonical once sorted, and no
        // two terms meet (the swap is one-to-one on each group's keys).
        let quarter = turns.iter().any(|t| t % 2 == 1);
        let turned: Vec<Term> = terms
            .iter()
            .zip(turns)
            .map(|(t, turn)| super::turn::quarter_turned_term(t, i64::from(turn)))
            .collect();
        Some(if quarter {
            Scalar::from_terms_settled(turned)
        } else {
            Scalar::from_sorted_settled(turned)
        })
    }

    /// `f . o` for a frequency vector, exactly (in machine words when they suffice:
    /// [`dot_of_pairs`]).
    fn phase(&self, freq: &[(Sym, Small)]) -> Small {
        dot_of_pairs(
            freq.iter()
                .filter_map(|(s, k)| self.0.iter().find(|(x, _)| x == s).map(|(_, o)| (*k, *o))),
        )
    }

    /// The expression `e` (in the shifted symbols) in the original ones: every angle gets its
    /// offset back.
    pub(crate) fn unshift(&self, e: Expr) -> Expr {
        match e {
            Expr::Trig { f, angle } => {
                let d = self.phase(&angle.terms);
                if d.is_zero() {
                    return Expr::Trig { f, angle };
                }
                let mut a = Angle::new(angle.terms, angle.constant, angle.pi + d);
                a.reduce_offset();
                Expr::Trig { f, angle: a }
            }
            Expr::Add(v) => Expr::Add(v.into_iter().map(|e| self.unshift(e)).collect()),
            Expr::Mul(v) => Expr::Mul(v.into_iter().map(|e| self.unshift(e)).collect()),
            Expr::Neg(e) => Expr::Neg(Box::new(self.unshift(*e))),
            Expr::Pow(e, n) => Expr::Pow(Box::new(self.unshift(*e)), n),
            e => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    thread_local! {
        /// Set by a test to score every group of every solution (no cut of `representatives`).
        pub(super) static UNCUT: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
        /// The groups `representatives` scored, one per group per solution or prefix.
        pub(super) static GROUPS_SCORED: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
        /// The scalars `Shift::apply_hinted` made from a hint: kept as it was, some groups
        /// negated (none turned by a quarter), some groups turned by a quarter.
        pub(super) static HINTS_TAKEN: std::cell::Cell<[u64; 3]> =
            const { std::cell::Cell::new([0; 3]) };
    }

    /// `apply_hinted` against `apply` (the old route, kept as the reference): on seeded random
    /// offset-free sums `y` (products of cosines and sines of `s (k x + j y + m z) + i pi/12`,
    /// `s` a half or 1 as in a dual quaternion's components or a matrix's, `k`, `j`, `m` in
    /// -1, 0, 1, or `k x + n (y - z)` alone in some),
    /// shifted back by one or two symbols' offsets off the pi/12 grid as `OffsetFree` shifts
    /// them (`Scalar::shift_angles`), the same scalar (and `None` alike) wherever a shift is
    /// found; and `y` is taken as it is, with groups negated, and left for `apply`, each many
    /// times.
    #[test]
    fn a_hinted_shift_gives_the_shifted_scalar() {
        let mut next = crate::testing::xorshift_below(0x41e7_ed5a_11f7_0001);
        let syms = [Scalar::sym("x"), Scalar::sym("y"), Scalar::sym("z")];
        let l = Scalar::sym("l");
        let half = |k: i64| Scalar::rational(num_rational::BigRational::new(k.into(), 2.into()));
        let (mut compared, mut fell_back) = (0u64, 0u64);
        HINTS_TAKEN.with(|n| n.set([0; 3]));
        for round in 0..1000 {
            // Half angles on even rounds (a dual quaternion's components), whole ones on odd.
            let scale = if round % 2 == 0 {
                half(1)
            } else {
                Scalar::int(1)
            };
            let difference = next(3) == 0;
            let mut y = Scalar::int(0);
            for _ in 0..1 + next(5) {
                let mut p = Scalar::int(next(7) as i64 - 3);
                if next(2) == 0 {
                    p = p * l.clone();
                }
                for _ in 0..1 + next(2) {
                    let coef = |next: &mut dyn FnMut(u64) -> u64| next(3) as i64 - 1;
                    let angle = if difference {
                        let k = 1 + next(2) as i64;
                        Scalar::int(coef(&mut next)) * syms[0].clone()
                            + Scalar::int(k) * (syms[1].clone() - syms[2].clone())
                    } else {
                        Scalar::int(coef(&mut next)) * syms[0].clone()
                            + Scalar::int(coef(&mut next)) * syms[1].clone()
                            + Scalar::int(coef(&mut next)) * syms[2].clone()
                    };
                    let angle = scale.clone() * angle + parse_pi(next(24) as i64, 12);
                    p = p * if next(2) == 0 {
                        angle.cos()
                    } else {
                        angle.sin()
                    };
                }
                y = y + p;
            }
            let den = [9, 18, 5, 7, 8][next(5) as usize] as i64;
            let mut shifts: Vec<(Sym, Small)> = Vec::new();
            for s in ["x", "y", "z"] {
                if shifts.is_empty() || next(3) == 0 {
                    let c = Small::new(next(2 * den as u64) as i64 - den + 1, den);
                    if !(c * Small::from_integer(12)).is_integer() && next(2) == 0 {
                        shifts.push((Sym::new(s), c));
                    }
                }
            }
            if shifts.is_empty() {
                continue;
            }
            let Some(x) = y.shift_angles(&shifts) else {
                continue;
            };
            let Some(shift) = find(&x) else {
                continue;
            };
            let hint = Hint {
                shifts: &shifts,
                y: &y,
            };
            let before = HINTS_TAKEN.with(std::cell::Cell::get);
            assert_eq!(
                shift.apply_hinted(&x, Some(hint)),
                shift.apply(&x),
                "{y:?} shifted by {shifts:?}, then by {shift:?}"
            );
            compared += 1;
            fell_back += u64::from(HINTS_TAKEN.with(std::cell::Cell::get) == before);
        }
        let [kept, negated, quarter] = HINTS_TAKEN.with(std::cell::Cell::get);
        assert!(
            compared >= 400 && kept >= 30 && negated >= 30 && quarter >= 30 && fell_back >= 100,
            "{compared} compared: {kept} kept, {negated} negated, {quarter} turned by a \
             quarter, {fell_back} shifted"
        );
    }

    /// `held_at_zero` (each pair of a modulus and a coefficient divided once per symbol)
    /// against the step computed from every congruence (the old route, kept here), on seeded
    /// random congruences whose rows repeat a few coefficients, moduli of twelfths and sixths
    /// and offsets of ninths, tenths and eighteenths of pi (some of them multiples of the step).
    #[test]
    fn the_symbols_held_at_zero_are_those_of_every_congruences_step() {
        let mut next = crate::testing::xorshift_below(0x0ff5_e7a1_4e1d_0003);
        let old = |c: &Congruences, syms: usize, base: &[Small]| -> Vec<Option<Small>> {
            (0..syms)
                .map(|i| {
                    let mut step: Option<Small> = None;
                    for (r, (_, m)) in c.rows.iter().zip(&c.targets) {
                        if let Some((_, k)) = r.iter().find(|(x, _)| *x == i) {
                            let q = (*m / *k).abs();
                            step = Some(match step {
                                None => q,
                                Some(p) => {
                                    Small::new(p.numer().lcm(q.numer()), p.denom().gcd(q.denom()))
                                }
                            });
                        }
                    }
                    step.is_none_or(|st| multiple(base[i], st))
                        .then(Small::zero)
                })
                .collect()
        };
        let coefs = [(1, 1), (-1, 1), (2, 1), (-2, 1), (1, 2), (3, 2), (3, 1)];
        let (mut held, mut free) = (0, 0);
        for _ in 0..2000 {
            let syms = 1 + next(5) as usize;
            let mut rows = Vec::new();
            let mut targets = Vec::new();
            for _ in 0..1 + next(12) {
                let mut row: Vec<(usize, Small)> = Vec::new();
                for s in 0..syms {
                    if next(3) > 0 {
                        let (p, q) = coefs[next(coefs.len() as u64) as usize];
                        row.push((s, Small::new(p, q)));
                    }
                }
                rows.push(row);
                let m = if next(4) == 0 { 6 } else { 12 };
                targets.push((Small::zero(), Small::new(1, m)));
            }
            let c = Congruences { rows, targets };
            let base: Vec<Small> = (0..syms)
                .map(|_| {
                    let d = [9, 10, 18, 12, 4][next(5) as usize];
                    Small::new(next(2 * d) as i64, d as i64)
                })
                .collect();
            let want = old(&c, syms, &base);
            held += want.iter().filter(|v| v.is_some()).count();
            free += want.iter().filter(|v| v.is_none()).count();
            assert_eq!(held_at_zero(&c, syms, &base), want, "{:?} {base:?}", c.rows);
        }
        assert!(held > 500 && free > 500, "{held} held, {free} free");
    }

    /// A seeded random sum of products of one to three cosines and sines of `k x + o`
    /// (`k` of 1 and 2, over the symbols `x`, `y`, `z`), each times 1, `l` or `l^2`; each
    /// symbol's offset `o` a multiple of `pi / den` with one multiple of `pi / 12` added per
    /// factor, and for one draw in `stray` an offset of `pi / den` of its own (which may leave
    /// no shift).
    fn offset_products(next: &mut dyn FnMut(u64) -> u64, den: u64, stray: u64) -> Scalar {
        let syms = [Scalar::sym("x"), Scalar::sym("y"), Scalar::sym("z")];
        let base: Vec<i64> = (0..3).map(|_| next(2 * den) as i64).collect();
        let l = Scalar::sym("l");
        let mut e = Scalar::int(0);
        for _ in 0..1 + next(4) {
            let mut p = Scalar::int(next(7) as i64 - 3);
            for _ in 0..next(3) {
                p = p * l.clone();
            }
            for _ in 0..1 + next(3) {
                let s = next(3) as usize;
                let k = 1 + next(2) as i64;
                let o = if next(stray) == 0 {
                    parse_pi(next(2 * den) as i64, den as i64)
                } else {
                    parse_pi(k * base[s], den as i64) + parse_pi(next(24) as i64, 12)
                };
                let a = Scalar::int(k) * syms[s].clone() + o;
                p = p * if next(2) == 0 { a.cos() } else { a.sin() };
            }
            e = e + p;
        }
        e
    }

    /// `find` with `representatives`' cuts (the groups that hold no free symbol counted once
    /// per run, a solution left once its parts so far and the groups sure to give one more
    /// pass the bound, the bound lowered for a head past the best's in its denominator and
    /// nonzero offsets) against `find` scoring every group of every solution: the same shift
    /// and the same work charged, on seeded random products with offsets of fifths, sevenths,
    /// ninths, tenths and eighteenths of pi; and fewer groups scored.
    #[test]
    fn the_cut_scoring_chooses_the_shift_of_the_whole_scoring() {
        let mut next = crate::testing::xorshift_below(0x0ff5_e7a1_c075_0001);
        let run = |e: &Scalar, uncut: bool| {
            UNCUT.with(|u| u.set(uncut));
            GROUPS_SCORED.with(|n| n.set(0));
            let ctx = crate::Context::new();
            let guard = ctx.enter();
            let shift = find(e).map(|s| s.0);
            let used = guard.work_used();
            drop(guard);
            UNCUT.with(|u| u.set(false));
            (shift, used, GROUPS_SCORED.with(std::cell::Cell::get))
        };
        let (mut found, mut cut, mut whole) = (0, 0, 0);
        for round in 0..1000 {
            let den = [5, 7, 9, 10, 18][round % 5];
            let e = offset_products(&mut next, den, 8);
            // Once first: the work of a canonicalization depends on the per-thread caches.
            run(&e, false);
            let (whole_shift, whole_used, whole_scored) = run(&e, true);
            let (shift, used, scored) = run(&e, false);
            assert_eq!((&shift, used), (&whole_shift, whole_used), "{e}");
            found += usize::from(shift.is_some());
            cut += scored;
            whole += whole_scored;
        }
        assert!(found > 400, "{found} shifts found");
        assert!(
            cut * 4 < whole * 3,
            "{cut} groups scored, {whole} without the cuts"
        );
    }

    /// A phase from the integer rows (`phase_of`) is the phase `dot` sums in rationals, and
    /// its f64 quotient has the same bits as that of the reduced fraction (what `score` looked
    /// the cosine and sine up by), on rows of half and whole coefficients and offsets of
    /// several denominators, centred as `representatives` centres them.
    #[test]
    fn phases_over_one_denominator_are_the_reduced_phases() {
        let mut below = crate::testing::xorshift_below(0x0ff5_e7a1);
        let coefs = [(1, 1), (-1, 1), (1, 2), (-1, 2), (3, 2), (-3, 2), (2, 1)];
        for _ in 0..300 {
            let syms = 1 + below(6) as usize;
            let mut rows: Vec<Vec<(usize, Small)>> = Vec::new();
            for _ in 0..1 + below(8) {
                let mut row = Vec::new();
                for s in 0..syms {
                    if below(3) > 0 {
                        let (p, q) = coefs[below(coefs.len() as u64) as usize];
                        row.push((s, Small::new(p, q)));
                    }
                }
                rows.push(row);
            }
            let dens = [1, 12, 18, 36, 72, 7];
            let o: Vec<Small> = (0..syms)
                .map(|_| {
                    let d = dens[below(dens.len() as u64) as usize];
                    let v = Small::new(below(4 * d as u64) as i64, d);
                    centred(v, Small::from_integer(2))
                })
                .collect();
            let freqs: Vec<&[(usize, Small)]> = rows.iter().map(Vec::as_slice).collect();
            let ints = integer_rows(&freqs);
            let mut scaled = Vec::new();
            let o_den = scale_offsets(&o, &mut scaled);
            for (i, f) in freqs.iter().enumerate() {
                let (num, den) = phase_of(f, ints.as_ref(), i, &o, &scaled, o_den);
                let exact = dot(f, &o);
                assert_eq!(Small::new(num, den), exact);
                let reduced = *exact.numer() as f64 / *exact.denom() as f64;
                assert_eq!((num as f64 / den as f64).to_bits(), reduced.to_bits());
            }
        }
    }

    fn parse_pi(k: i64, n: i64) -> Scalar {
        Scalar::pi() * Scalar::rational(num_rational::BigRational::new(k.into(), n.into()))
    }

    #[test]
    fn a_joint_offset_of_five_ninths_of_pi_is_absorbed_into_its_symbol() {
        let (t, q, l1, l2) = (
            Scalar::sym("t"),
            Scalar::sym("q"),
            Scalar::sym("l1"),
            Scalar::sym("l2"),
        );
        let off = parse_pi(5, 9);
        let x = l1 * (t.clone() + off.clone()).cos() + l2 * (t + off + q).cos();
        let shift = find(&x).expect("a shift");
        assert_eq!(shift.0.len(), 1);
        assert_eq!(shift.0[0].0.name(), "t");
        assert_eq!(shift.0[0].1, Small::new(5, 9));
        let y = shift.apply(&x).expect("shifted");
        assert!(y
            .terms()
            .is_ok_and(|t| t.iter().all(|t| t.mode.pi.is_zero())));
    }

    /// `dot` against the sum in big rationals, on seeded random rows (small denominators, as
    /// phases have, and larger ones whose common denominator may pass a machine word before
    /// its reduction and take the `Small` path).
    #[test]
    fn dot_is_the_exact_sum_of_the_row_times_the_offsets() {
        use num_rational::BigRational;
        let mut next = crate::testing::xorshift_below(0x2545_f491_4f6c_dd1du64);
        let big = |q: Small| BigRational::new((*q.numer()).into(), (*q.denom()).into());
        for round in 0..2000 {
            let span = if round % 2 == 0 { 37 } else { 360 };
            let o: Vec<Small> = (0..6)
                .map(|_| Small::new(next(2 * span) as i64 - span as i64, 1 + next(span) as i64))
                .collect();
            let r: Vec<(usize, Small)> = (0..1 + next(3) as usize)
                .map(|_| {
                    let k = Small::new(next(25) as i64 - 12, 1 + next(span) as i64);
                    (next(6) as usize, k)
                })
                .collect();
            let want = r.iter().fold(BigRational::zero(), |acc, (s, k)| {
                acc + big(*k) * big(o[*s])
            });
            assert_eq!(big(dot(&r, &o)), want, "row {r:?}, offsets {o:?}");
        }
        // A product past a machine word before its reduction: `Small`'s path.
        let (k, o) = (Small::new(1 << 62, 3), Small::new(5, 1 << 61));
        assert_eq!(dot(&[(0, k)], &[o]), Small::new(10, 3));
    }

    /// `Shift::phase` (a frequency vector's `f . o` over the symbols the shift holds, in
    /// machine words) against the sum in `Small` term by term, and `reduce2` (modulo 2 in
    /// machine words) against `p - 2 floor(p / 2)`, on seeded random vectors, shifts and phases
    /// (denominators up to 360, and one past half a machine word: `Small`'s path).
    #[test]
    fn a_shifts_phase_and_its_reduction_modulo_two_are_the_rational_ones() {
        let mut next = crate::testing::xorshift_below(0x9d2c_5680_a5a5_0f0fu64);
        let syms: Vec<Sym> = ["x", "y", "z", "w"].into_iter().map(Sym::new).collect();
        let two = Small::from_integer(2);
        let modulo_two = |p: Small| p - (p / two).floor() * two;
        let random = |next: &mut dyn FnMut(u64) -> u64, span: u64| {
            let n = next(2 * span) as i64 - span as i64;
            Small::new(n, 1 + next(span) as i64)
        };
        let (mut held, mut moved) = (0, 0);
        for _ in 0..2000 {
            let mut shift = Vec::new();
            let mut freq: Vec<(Sym, Small)> = Vec::new();
            for s in &syms {
                if next(3) != 0 {
                    shift.push((s.clone(), random(&mut next, 360)));
                }
                if next(4) != 0 {
                    freq.push((s.clone(), random(&mut next, 6)));
                }
            }
            let shift = Shift(shift);
            let want = freq.iter().fold(Small::zero(), |acc, (s, k)| {
                let o = shift.0.iter().find(|(x, _)| x == s);
                acc + o.map_or(Small::zero(), |(_, o)| *k * *o)
            });
            let d = shift.phase(&freq);
            assert_eq!(d, want, "{freq:?} {shift:?}");
            held += usize::from(!d.is_zero());
            let p = random(&mut next, 360) + d;
            let r = reduce2(p);
            assert_eq!(r, modulo_two(p));
            assert!(r >= Small::zero() && r < two && r.denom() == p.denom());
            moved += usize::from(r != p);
        }
        assert!(held > 1000 && moved > 500, "{held} phases, {moved} moved");
        // A denominator past half a machine word: `Small`'s path.
        let wide = Small::new((1 << 62) + 4, (1 << 62) + 1);
        assert_eq!(reduce2(wide), wide);
    }

    /// `centred` against its definition in big rationals (the multiple of the period `2 den`
    /// that takes `v` into `(-den, den]`), on seeded random offsets and half periods.
    #[test]
    fn centred_offsets_lie_in_the_half_open_period_and_differ_by_whole_periods() {
        use num_rational::BigRational;
        let mut next = crate::testing::xorshift_below(0x1234_5678_9abc_def1u64);
        let big = |q: Small| BigRational::new((*q.numer()).into(), (*q.denom()).into());
        for _ in 0..3000 {
            let v = Small::new(next(2001) as i64 - 1000, 1 + next(72) as i64);
            let den = Small::from_integer(1 + next(6) as i64);
            let r = centred(v, den);
            assert!(
                *r.denom() > 0 && r.numer().gcd(r.denom()) == 1,
                "{v} centred in lowest terms: {r:?}"
            );
            let c = big(r);
            let (bv, bd) = (big(v), big(den));
            assert!(c > -bd.clone() && c <= bd, "{v} in ({den})");
            let turns = (bv - c) / (bd * BigRational::from_integer(2.into()));
            assert!(
                turns.is_integer(),
                "{v} and its centred value differ by whole periods"
            );
        }
    }

    /// `key_below` (the tail of a key computed only when its head ties) against the whole
    /// key compared with the best, on seeded random offsets, part counts and bests (some of
    /// them equal in their heads).
    #[test]
    fn a_key_is_below_the_best_as_the_whole_key_compares() {
        let mut next = crate::testing::xorshift_below(0x0ff5_e7a1_4e75_0002);
        let full = |o: &[Small], parts: usize, neg: usize| -> Key {
            let den = o.iter().map(|v| *v.denom()).max().unwrap_or(1);
            let size: Small = o.iter().map(|v| v.abs()).sum();
            let negatives = o.iter().filter(|v| v.is_negative()).count();
            let nonzero = o.iter().filter(|v| !v.is_zero()).count();
            (parts, den, nonzero, neg, size, negatives)
        };
        let (mut taken, mut tied) = (0, 0);
        for _ in 0..5000 {
            let syms = 1 + next(4) as usize;
            let mut offsets = || -> Vec<Small> {
                (0..syms)
                    .map(|_| match next(3) {
                        0 => Small::zero(),
                        _ => Small::new(next(19) as i64 - 9, [1, 3, 9][next(3) as usize]),
                    })
                    .collect()
            };
            let (o, b) = (offsets(), offsets());
            let (parts, neg) = (next(3) as usize, next(2) as usize);
            let best = full(&b, next(3) as usize, next(2) as usize);
            let key = full(&o, parts, neg);
            tied += usize::from((key.0, key.1, key.2, key.3) == (best.0, best.1, best.2, best.3));
            let want = (key < best).then_some(key);
            taken += usize::from(want.is_some());
            assert_eq!(
                key_below(&o, parts, neg, Some(&best)),
                want,
                "{o:?} {best:?}"
            );
            assert_eq!(key_below(&o, parts, neg, None), Some(key));
        }
        assert!(
            taken > 500 && tied > 100,
            "both ways met ({taken} taken, {tied} tied)"
        );
    }

    /// A seeded random sum over the level `den`: one to `most_modes` modes (`x` or `2 x`, with
    /// `-y`, none or `y`), each times 1 or `l`, of one to three terms at one base offset `k
    /// pi/den` apart by multiples of pi/12 (one phase class), but for one draw in `arms` at
    /// another offset of the level and, with `bare`, one more at none.
    fn graded_sum(
        next: &mut dyn FnMut(u64) -> u64,
        den: u64,
        most_modes: u64,
        arms: u64,
        bare: bool,
    ) -> Scalar {
        let (x, y, l) = (Scalar::sym("x"), Scalar::sym("y"), Scalar::sym("l"));
        let mut e = Scalar::int(0);
        for _ in 0..1 + next(most_modes) {
            let angle = Scalar::int(1 + next(2) as i64) * x.clone()
                + Scalar::int(next(3) as i64 - 1) * y.clone();
            let mono = if next(2) == 0 {
                Scalar::int(1)
            } else {
                l.clone()
            };
            let base = next(2 * den) as i64;
            for _ in 0..1 + next(3) {
                let p = match next(arms) {
                    0 => parse_pi(next(2 * den) as i64, den as i64),
                    1 if bare => parse_pi(0, 1),
                    _ => parse_pi(base, den as i64) + parse_pi(next(24) as i64, 12),
                };
                let a = angle.clone() + p;
                let f = if next(2) == 0 { a.cos() } else { a.sin() };
                e = e + Scalar::int(next(7) as i64 - 3) * mono.clone() * f;
            }
        }
        e
    }

    /// The groups a phase-class test met: with a class past zero, with none.
    #[derive(Debug, Default)]
    struct Classes {
        seen: usize,
        found: usize,
        none: usize,
    }

    impl Classes {
        fn count(&mut self, class: Option<Small>) {
            self.seen += 1;
            match class {
                Some(d) if !d.is_zero() => self.found += 1,
                Some(_) => {}
                None => self.none += 1,
            }
        }
    }

    /// The phase class read off the offsets is the one found by trying every candidate, on
    /// the groups of seeded random sums over levels of 2s and 3s (offsets of ninths,
    /// eighths, 36ths, 27ths, 16ths ...): terms of one class apart by multiples of pi/12 (one
    /// class), now and then a term of another class or without an offset (none), several
    /// monomials and frequency vectors per sum.
    #[test]
    fn the_phase_class_of_a_graded_level_is_the_one_its_offsets_share() {
        let mut next = crate::testing::xorshift_below(0x05ee_dc1a_55e5_u64);
        let dens = [9, 18, 36, 8, 16, 24, 27, 48, 72];
        let mut classes = Classes::default();
        for _ in 0..150 {
            let den = dens[next(dens.len() as u64) as usize];
            let e = graded_sum(&mut next, den, 3, 8, true);
            let Ok(terms) = e.terms() else {
                panic!("{e:?} an error");
            };
            let n = level(terms);
            assert!(graded_level(n), "{n}");
            for g in groups_of(terms) {
                let want = phase_class_by_search(&g, n);
                assert_eq!(phase_class_of_offsets(&g, n), want, "{e:?} at level {n}");
                classes.count(want);
            }
        }
        assert!(classes.found > 50 && classes.none > 20, "{classes:?}");
        assert!(
            graded_level(12) && graded_level(36 * 64) && !graded_level(60) && !graded_level(84)
        );
    }

    /// The integer system of [`system`] as its rationals give it (each coefficient `k` times
    /// the symbol's unit in `Small`, every entry scaled by the lcm `L` of the denominators and
    /// by `M / (L m)`): the reference the machine-word arithmetic of `system` must equal.
    fn system_in_rationals(
        rows: &[Vec<(usize, Small)>],
        targets: &[(Small, Small)],
        fixed: &[Option<Small>],
        free: &[(usize, Small, i64)],
    ) -> (Vec<Vec<i64>>, Vec<i64>, i64) {
        let column = |s: usize| free.iter().position(|(f, _, _)| *f == s);
        let mut rational: Vec<(Vec<Small>, Small, Small)> = Vec::new();
        for (r, (t, m)) in rows.iter().zip(targets) {
            let mut a = vec![Small::zero(); free.len()];
            let mut rhs = *t;
            for (s, k) in r {
                match (column(*s), fixed[*s]) {
                    (Some(j), _) => a[j] = *k * free[j].1,
                    (None, Some(v)) => rhs -= *k * v,
                    (None, None) => {}
                }
            }
            rational.push((a, rhs, *m));
        }
        let l = rational
            .iter()
            .flat_map(|(a, rhs, m)| a.iter().chain([rhs, m]))
            .fold(1i64, |l, q| l.lcm(q.denom()));
        let l = Small::from_integer(l);
        let modulus = rational
            .iter()
            .fold(1i64, |acc, (_, _, m)| acc.lcm(&(*m * l).to_integer()));
        let int = |q: Small, m: Small| {
            ((q * l).to_integer() * (modulus / (m * l).to_integer())).rem_euclid(modulus)
        };
        let a = rational
            .iter()
            .map(|(a, _, m)| a.iter().map(|q| int(*q, *m)).collect())
            .collect();
        let b = rational.iter().map(|(_, rhs, m)| int(*rhs, *m)).collect();
        (a, b, modulus)
    }

    /// `system` in machine words is the system its rationals give (`system_in_rationals`) on
    /// 2,000 random systems: 1 to 4 symbols, rows of coefficients `+-1..3` over 1, 2 or 3,
    /// phases over the level `n` (12, 36, 60, 72), moduli 1/12 and 1/4, symbols free, fixed
    /// at 0 or fixed at a multiple of pi/n; and it gives up (`None`) exactly where the
    /// candidates pass `MAX_CANDIDATES`.
    #[test]
    fn a_system_in_machine_words_is_the_system_of_its_rationals() {
        let mut next = crate::testing::xorshift_below(0x0ff5_e75e_u64);
        let syms: Vec<Sym> = ["a", "b", "c", "d"].into_iter().map(Sym::new).collect();
        let (mut built, mut too_many) = (0, 0);
        for _ in 0..2000 {
            let n = [12, 36, 60, 72][next(4) as usize];
            let count = 1 + next(4) as usize;
            let mut rows: Vec<Vec<(usize, Small)>> = Vec::new();
            for _ in 0..1 + next(8) {
                let mut row = Vec::new();
                for s in 0..count {
                    if next(4) != 0 {
                        let k = 1 + next(3) as i64;
                        let sign = if next(2) == 0 { 1 } else { -1 };
                        row.push((s, Small::new(sign * k, 1 + next(3) as i64)));
                    }
                }
                rows.push(row);
            }
            let targets: Vec<(Small, Small)> = rows
                .iter()
                .map(|_| {
                    let m = [Small::new(1, 12), Small::new(1, 4)][next(2) as usize];
                    (Small::new(next(2 * n as u64) as i64, n), m)
                })
                .collect();
            let fixed: Vec<Option<Small>> = (0..count)
                .map(|_| match next(4) {
                    0 => Some(Small::zero()),
                    1 => Some(Small::new(next(2 * n as u64) as i64, n)),
                    _ => None,
                })
                .collect();
            let Some(sys) = system(&syms[..count], &rows, &targets, n, &fixed) else {
                // Only the candidates' bound gives up on these (numbers stay far inside a word).
                let over = fixed.iter().enumerate().any(|(s, f)| {
                    let (num, den) = rows
                        .iter()
                        .filter_map(|r| r.iter().find(|(x, _)| *x == s))
                        .fold((1i64, 1i64), |(a, b), (_, k)| {
                            (a.lcm(&k.numer().abs()), b.lcm(k.denom()))
                        });
                    f.is_none() && 2 * n * num * den > MAX_CANDIDATES
                });
                assert!(over, "gave up on {rows:?} {targets:?} {fixed:?}");
                too_many += 1;
                continue;
            };
            built += 1;
            let free: Vec<usize> = (0..count).filter(|s| fixed[*s].is_none()).collect();
            assert_eq!(sys.free.iter().map(|f| f.0).collect::<Vec<_>>(), free);
            for (s, unit, c) in &sys.free {
                assert_eq!(
                    *c,
                    2 * n * (*unit.denom() / n) * {
                        rows.iter()
                            .filter_map(|r| r.iter().find(|(x, _)| x == s))
                            .fold(1i64, |d, (_, k)| d.lcm(k.denom()))
                    }
                );
                assert_eq!(*unit.numer(), 1);
            }
            let (a, b, modulus) = system_in_rationals(&rows, &targets, &fixed, &sys.free);
            assert_eq!((&sys.a, &sys.b, sys.modulus), (&a, &b, modulus), "{rows:?}");
            assert_eq!(sys.ranges, sys.free.iter().map(|f| f.2).collect::<Vec<_>>());
        }
        assert!(
            built > 1000 && too_many > 50,
            "{built} built, {too_many} over the bound"
        );
    }

    /// A shift applied with its moved groups written at once without an offset is the
    /// shifted terms canonicalized from scratch, on seeded random sums of Kinova-style offsets
    /// (ninths, eighths, 36ths: shifts onto multiples of pi/12), radicals, monomials and
    /// constants at pi offsets (groups not moved), wherever a shift is found.
    #[test]
    fn a_shift_applied_is_the_shifted_terms_canonicalized() {
        let mut next = crate::testing::xorshift_below(0x5e77_1ed0_0a55_u64);
        let (x, y, z, l) = (
            Scalar::sym("x"),
            Scalar::sym("y"),
            Scalar::sym("z"),
            Scalar::sym("l"),
        );
        let dens = [9, 18, 36, 8, 16, 72];
        let (mut applied, mut moved_terms) = (0, 0);
        for _ in 0..200 {
            let den = dens[next(dens.len() as u64) as usize] as i64;
            let offs: Vec<Scalar> = (0..3)
                .map(|_| parse_pi(next(2 * den as u64) as i64, den))
                .collect();
            let mut e = Scalar::int(0);
            for _ in 0..1 + next(5) {
                let (i, j) = (next(3) as i64, next(3) as i64 - 1);
                let angle = Scalar::int(1 + i) * (x.clone() + offs[0].clone())
                    + Scalar::int(j) * (y.clone() + offs[1].clone())
                    + Scalar::int(next(2) as i64) * (z.clone() + offs[2].clone())
                    + parse_pi(next(24) as i64, 12);
                let f = if next(2) == 0 {
                    angle.cos()
                } else {
                    angle.sin()
                };
                let c = Scalar::int(next(7) as i64 - 3)
                    * Scalar::int([1, 2, 3, 6][next(4) as usize]).sqrt();
                let mono = if next(2) == 0 {
                    Scalar::int(1)
                } else {
                    l.clone()
                };
                e = e + c * mono * f;
            }
            if next(3) == 0 {
                e = e + parse_pi(next(2 * den as u64) as i64, den).cos() * l.clone();
            }
            let Some(shift) = find(&e) else {
                continue;
            };
            let Ok(terms) = e.terms() else {
                panic!("{e:?} an error");
            };
            let plain: Vec<Term> = terms
                .iter()
                .map(|t| {
                    let mut t = t.clone();
                    t.mode.pi = reduce2(t.mode.pi - shift.phase(&t.mode.freq));
                    t
                })
                .collect();
            moved_terms += plain
                .iter()
                .zip(terms)
                .filter(|(a, b)| a.mode.pi != b.mode.pi)
                .count();
            let want = Scalar::from_terms(plain);
            assert!(no_offset(&want), "{e:?}: the shift leaves no offset");
            assert_eq!(shift.apply(&e), Some(want), "{e:?} shifted by {shift:?}");
            applied += 1;
        }
        assert!(
            applied > 60 && moved_terms > 300,
            "{applied} shifts, {moved_terms} terms moved"
        );
    }

    /// The phase class found by trying only the candidates whose columns hold the group's
    /// offsets is the one found by trying every candidate, on the groups of seeded random sums
    /// at levels with primes past 3 (fifths, sevenths, tenths, thirteenths: the search's
    /// levels), terms of one class and of several.
    #[test]
    fn the_phase_class_searched_among_fitting_columns_is_the_one_searched_among_all() {
        let mut next = crate::testing::xorshift_below(0x0c01_5ea2_c4ed_u64);
        let dens = [5, 7, 10, 13, 15, 14, 20];
        let mut classes = Classes::default();
        for _ in 0..60 {
            let den = dens[next(dens.len() as u64) as usize];
            let e = graded_sum(&mut next, den, 2, 6, false);
            let Ok(terms) = e.terms() else {
                continue;
            };
            let n = level(terms);
            for g in groups_of(terms) {
                let every = if g.terms.iter().all(|t| t.mode.pi.is_zero()) {
                    Some(Small::zero())
                } else {
                    (1..n / 12)
                        .map(|j| Small::new(j, n))
                        .find(|&d| no_offset(&shifted_group(&g, d)))
                };
                assert_eq!(phase_class_by_search(&g, n), every, "{e:?} at level {n}");
                classes.count(every);
            }
        }
        assert!(classes.found > 30 && classes.none > 5, "{classes:?}");
    }

    /// The system of the distinct congruences (`Congruences::of`) is the system of every
    /// group's, on 600 seeded random families of groups drawn from a few rows and phases (so
    /// most repeat), symbols free or fixed: the same units, ranges and modulus, the same set of
    /// integer rows, and the same solutions listed (the first 300), count and work charged by
    /// the elimination and walk.
    #[test]
    fn the_distinct_congruences_make_the_system_of_every_group() {
        let mut next = crate::testing::xorshift_below(0x000c_096e_5ce5_u64);
        let syms: Vec<Sym> = ["a", "b", "c", "d"].into_iter().map(Sym::new).collect();
        // What a system gives: its integer rows as a set, and what solving it lists,
        // counts and charges.
        let solved = |sys: &System, fixed: &[Option<Small>]| {
            let mut rows: Vec<Vec<i64>> = sys
                .a
                .iter()
                .zip(&sys.b)
                .map(|(r, c)| r.iter().chain([c]).copied().collect())
                .collect();
            rows.sort_unstable();
            rows.dedup();
            let ctx = crate::Context::new();
            let guard = ctx.enter();
            let mut listed: Vec<Vec<Small>> = Vec::new();
            let complete = solve(sys, fixed, false, &mut |node| {
                if let Offered::Solution(o) = node {
                    listed.push(o.to_vec());
                }
                listed.len() < 300
            });
            let fewer = fewer_solutions_than(sys, 50);
            (rows, listed, complete, fewer, guard.work_used())
        };
        let (mut merged, mut compared) = (0, 0);
        for _ in 0..600 {
            let n = [12, 36, 72][next(3) as usize];
            let count = 1 + next(4) as usize;
            let pool: Vec<Vec<(usize, Small)>> = (0..1 + next(4))
                .map(|_| {
                    let mut row = Vec::new();
                    for s in 0..count {
                        if next(3) != 0 {
                            let k = 1 + next(2) as i64;
                            let sign = if next(2) == 0 { 1 } else { -1 };
                            row.push((s, Small::new(sign * k, 1 + next(2) as i64)));
                        }
                    }
                    row
                })
                .collect();
            let phases: Vec<Small> = (0..1 + next(3))
                .map(|_| Small::new(next(n as u64 / 12) as i64, n))
                .collect();
            let groups = 1 + next(10) as usize;
            let rows: Vec<Vec<(usize, Small)>> = (0..groups)
                .map(|_| pool[next(pool.len() as u64) as usize].clone())
                .collect();
            let targets: Vec<(Small, Small)> = (0..groups)
                .map(|_| {
                    (
                        phases[next(phases.len() as u64) as usize],
                        Small::new(1, 12),
                    )
                })
                .collect();
            let fixed: Vec<Option<Small>> = (0..count)
                .map(|_| (next(4) == 0).then(Small::zero))
                .collect();
            let c = Congruences::of(&rows, &targets);
            merged += groups - c.rows.len();
            let every = system(&syms[..count], &rows, &targets, n, &fixed);
            let distinct = system(&syms[..count], &c.rows, &c.targets, n, &fixed);
            let (Some(every), Some(distinct)) = (every, distinct) else {
                assert!(
                    system(&syms[..count], &rows, &targets, n, &fixed).is_none()
                        && system(&syms[..count], &c.rows, &c.targets, n, &fixed).is_none()
                );
                continue;
            };
            assert_eq!(
                (&every.free, &every.ranges, every.modulus),
                (&distinct.free, &distinct.ranges, distinct.modulus),
                "{rows:?} {targets:?}"
            );
            assert_eq!(
                solved(&every, &fixed),
                solved(&distinct, &fixed),
                "{rows:?} {targets:?}"
            );
            compared += 1;
        }
        assert!(
            merged > 1000 && compared > 400,
            "{merged} merged, {compared} compared"
        );
    }

    /// `groups_of` (a hash map by the symbols' addresses and the coefficients' words) against
    /// the map ordered by the key pair's derived `Ord` it replaced (kept here): the same groups,
    /// frequency vectors and terms (by address) in the same order, on seeded random products
    /// with offsets (several monomials and frequency vectors a scalar, repeated across terms).
    #[test]
    fn the_hashed_groups_are_the_groups_of_the_ordered_map() {
        fn old(terms: &[Term]) -> Vec<Group<'_>> {
            type Key<'a> = (&'a [(Sym, Small)], &'a crate::scalar::MonoRc);
            let mut index: std::collections::BTreeMap<Key, usize> = Default::default();
            let mut groups: Vec<Group> = Vec::new();
            for t in terms.iter().filter(|t| symbolic(t)) {
                let i = *index.entry((&*t.mode.freq, &t.mono)).or_insert_with(|| {
                    groups.push(Group {
                        freq: t
                            .mode
                            .freq
                            .iter()
                            .filter(|(s, _)| !s.is_one())
                            .cloned()
                            .collect(),
                        terms: Vec::new(),
                    });
                    groups.len() - 1
                });
                groups[i].terms.push(t);
            }
            groups
        }
        // Each group's frequency vector and its terms' addresses.
        type Shape = Vec<(Vec<(Sym, Small)>, Vec<usize>)>;
        let shape = |g: &[Group]| -> Shape {
            g.iter()
                .map(|g| {
                    let at = g.terms.iter().map(|t| std::ptr::from_ref(*t) as usize);
                    (g.freq.clone(), at.collect())
                })
                .collect()
        };
        let mut next = crate::testing::xorshift_below(0x6a0c_5b1e_d00d_0001);
        let (mut groups, mut shared) = (0, 0);
        for _ in 0..300 {
            let den = [5, 7, 9, 18][next(4) as usize];
            let e = offset_products(&mut next, den, 4);
            let Ok(terms) = e.terms() else { continue };
            let want = old(terms);
            groups += want.len();
            shared += want.iter().filter(|g| g.terms.len() > 1).count();
            assert_eq!(shape(&groups_of(terms)), shape(&want), "{e:?}");
        }
        assert!(
            groups > 1000 && shared > 800,
            "{groups} groups, {shared} shared"
        );
    }

    #[test]
    fn unrelated_phases_in_one_mode_have_no_shift() {
        let x = Scalar::sym("x");
        let e = (x.clone() + parse_pi(1, 7)).cos() + (x + parse_pi(2, 7)).cos();
        assert!(find(&e).is_none());
    }
}
