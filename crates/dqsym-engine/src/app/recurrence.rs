//! The forward kinematics of a long symbolic chain, exactly, as a recurrence over the joint
//! factors (the form `dqsym fk` takes when the expanded pose exceeds its term budget).
//!
//! Expanding the product of n DH links with every parameter symbolic is hopeless: the largest
//! DQ component of the product of the first k links has exactly k 4^k terms (4, 32, 192, 1,024,
//! 5,120, 24,576, 114,688 for k = 1..7, measured, and checked for k <= 5 by the test
//! `symbolic_chain_expansion_has_k_times_4_to_the_k_terms`), about 2.2e13 for k = 20. The
//! recurrence is linear in n instead: each line is a closed form over the joint parameters or
//! over the symbols of the lines before it.
//!
//! The entries, in the order of evaluation (i = 1..n is the joint, k = 0..7 the DQ component):
//!
//! - `L{i}[k]`: the joint factor L{i} at its symbolic variable (the last one times the tool
//!   motion of the chain, when it has one), in closed form over the robot's symbols.
//! - `dL{i}[k]` (with the Jacobian): d L{i} / d q_i, in closed form (revolute, prismatic, any
//!   convention: it is the derivative of the closed form).
//! - `Q{i}[k]`, i = 2..n: the prefix products `Q{i} = Q{i-1} L{i}` (Q{1} = L{1}), as
//!   expressions in the symbols `Q{i-1}_k` and `L{i}_k`.
//! - `dq[k]`: the pose, `Q{n}_k`.
//! - `P{i}[k]`, i = n-1 down to 2 (with the Jacobian): the suffix products
//!   `P{i} = L{i} P{i+1}` (P{n} = L{n}) in the symbols `L{i}_k` and `P{i+1}_k`.
//! - `T[i][j]` and `p[i]`: the matrix and the image of the point, in the symbols `Q{n}_k`;
//!   the matrix instead in the robot's symbols, factored from its polynomial in the cosines and
//!   sines (`Robot::forward_matrix_cos_sin`), when that fits the term budget (a 6R with every
//!   DH parameter symbolic: 1,595 monomials, where the Fourier form has about 300,000 terms).
//! - `J[k][i-1]` (with the Jacobian): component k of `Q{i-1} dL{i} P{i+1}` in the symbols
//!   `Q{i-1}_k`, `dL{i}_k` and `P{i+1}_k`, where Q{0} and P{n+1} are the identity (and are
//!   multiplied out), Q{1} is L{1} and P{n} is L{n}. By the product rule this is
//!   d (L{1} ... L{n}) / d q_i, exactly the column the expanded Jacobian would give.
//!
//! Entry `X[k]` is read by later entries as the symbol `X_k` (`Q2[3]` as `Q2_3`), except
//! that an entry whose value is a constant (the zeros of a planar link) is read as that
//! constant, so the zeros propagate instead of being multiplied at run time.

use super::fk::{FkOptions, ReportError};
use super::quantity::{MatrixFrom, Quantity, Section, SectionKind, Step};
use crate::scalar::{par_map, with_own_budget, FxHasher, SampledKey};

/// The work budget of the attempt at the matrix as a cos/sin polynomial (the generic 6R needs
/// about 52,000).
const COS_SIN_BUDGET: u64 = 500_000;

/// The largest entry of that polynomial, in monomials (the generic 6R's is 232).
const COS_SIN_MAX_TERMS: usize = 1_000;

/// The work budget of the closed forms of that matrix (RTB's Ball fits in it).
const COS_SIN_FORMS_BUDGET: u64 = 4_000_000;

/// The most bytes of plain text the closed forms of that matrix may take (RTB's Ball: 10 kB).
const MAX_COS_SIN_TEXT: usize = 40_000;
use crate::closed::turn;
use crate::kin::MadeJoints;
use crate::{closed::closed_form_cos_sin, DualQuat, Expr, Robot, Scalar, ScalarError};
use std::borrow::Cow;
use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

/// The forward kinematics of `robot` as a recurrence (see the module documentation): every
/// entry in the order of evaluation, named as in the report (`L1[0]`, `Q2[3]`, `dq[0]`,
/// `T[0][3]`, `J[7][19]`, ...). Entry `X[k]` appears in later entries as the symbol `X_k`.
/// The point and the Jacobian follow `o.point` and `o.jacobian`; `o.max_terms` and the format
/// are ignored ([`fk_report`](crate::fk_report) prints this when the expansion exceeds
/// `max_terms`).
///
/// # Errors
/// When an exact operation fails (a size limit or the work budget, say), or a symbol of the
/// robot or the point has the name of an entry's symbol (`Q2_3`).
pub fn fk_recurrence(robot: &Robot, o: &FkOptions) -> Result<Vec<(Quantity, Expr)>, ReportError> {
    Ok(recurrence_sections(robot, None, o)?
        .into_iter()
        .flat_map(|s| s.rows)
        .collect())
}

/// The entries whose value is a constant (the zeros of a planar link, say), by symbol: later
/// entries read the constant instead of the symbol, so the zeros propagate.
type Known = RefCell<HashMap<String, Scalar>>;

/// The DQ of the symbols of step `step` of joint `joint` (`Q2_0` .. `Q2_7`), or of their
/// constant values.
fn syms(known: &Known, step: Step, joint: usize) -> DualQuat<Scalar> {
    let known = known.borrow();
    let c = |k: usize| {
        let name = Quantity::Step { step, joint, k }.symbol();
        known
            .get(&name)
            .cloned()
            .unwrap_or_else(|| Scalar::sym(&name))
    };
    DualQuat::from_components([c(0), c(1), c(2), c(3), c(4), c(5), c(6), c(7)])
}

/// The sections of the recurrence before their closed forms.
type Staged = Vec<(SectionKind, Vec<(Quantity, Scalar)>)>;

/// Records the constant entries of `rows` in `known`.
fn learn(known: &Known, rows: &[(Quantity, Scalar)]) {
    for (name, x) in rows {
        if x.symbols().is_empty() && x.as_error().is_none() {
            known.borrow_mut().insert(name.symbol(), x.clone());
        }
    }
}

/// The entries of [`fk_recurrence`] in titled sections, every closed form computed in
/// parallel. `made`, the robot's joint factors when the caller made them already, are used
/// where they would be made again, charged as making them is ([`MadeJoints::again`]).
pub(crate) fn recurrence_sections(
    robot: &Robot,
    made: Option<&MadeJoints>,
    o: &FkOptions,
) -> Result<Vec<Section>, ReportError> {
    recurrence_sections_printed(robot, made, o).map(|(sections, _)| sections)
}

/// [`recurrence_sections`], and when the matrix is the one in cosines and sines, the plain
/// text of its rows (shorthand, no decimals: [`CosSinTexts`]).
pub(crate) fn recurrence_sections_printed(
    robot: &Robot,
    made: Option<&MadeJoints>,
    o: &FkOptions,
) -> Result<(Vec<Section>, Option<CosSinTexts>), ReportError> {
    let joints = || made.map_or_else(|| Cow::Owned(robot.joint_dqs()), |m| m.again(robot));
    // The base frame is folded into the first factor and the tool frame into the last.
    let factors = robot.pose_factors_of(joints().into_owned());
    let has_tool = robot.chain.tool != DualQuat::identity();
    let has_base = robot.chain.base != DualQuat::identity();
    let n = factors.len();
    // The variable each joint factor is differentiated by (a URDF mimic joint's is the
    // variable of the joint it follows); a chain without joints has none.
    let joint_var: Vec<Option<String>> = (0..robot.joint_values.len().min(n))
        .map(|i| robot.joint_variables(i).into_iter().next())
        .collect();
    // The prefix product Q{i} and suffix product P{i} as symbols; Q{1} is L{1}, P{n} is L{n},
    // Q{0} and P{n+1} the identity.
    let known = Known::default();
    let l = |i: usize| syms(&known, Step::Factor, i);
    let q = |i: usize| match i {
        0 => DualQuat::identity(),
        1 => l(1),
        _ => syms(&known, Step::Prefix, i),
    };
    let p = |i: usize| {
        if i > n {
            DualQuat::identity()
        } else if i == n {
            l(n)
        } else {
            syms(&known, Step::Suffix, i)
        }
    };
    let comps =
        |name: &dyn Fn(usize) -> Quantity, d: &DualQuat<Scalar>| -> Vec<(Quantity, Scalar)> {
            d.components()
                .into_iter()
                .enumerate()
                .map(|(k, c)| (name(k), c))
                .collect()
        };
    let step = |step: Step, joint: usize| move |k: usize| Quantity::Step { step, joint, k };

    let mut sections: Staged = Vec::new();
    let links: Vec<(Quantity, Scalar)> = factors
        .iter()
        .enumerate()
        .flat_map(|(i, f)| comps(&step(Step::Factor, i + 1), f))
        .collect();
    learn(&known, &links);
    sections.push((
        SectionKind::Factors {
            base: has_base,
            tool: has_tool,
        },
        links,
    ));
    if o.jacobian {
        let derivs: Vec<(Quantity, Scalar)> = factors
            .iter()
            .zip(&joint_var)
            .enumerate()
            .filter_map(|(i, (f, v))| Some((i, f, v.as_ref()?)))
            .flat_map(|(i, f, v)| {
                f.components()
                    .iter()
                    .enumerate()
                    .map(|(k, c)| (step(Step::FactorDerivative, i + 1)(k), c.diff(v)))
                    .collect::<Vec<_>>()
            })
            .collect();
        learn(&known, &derivs);
        sections.push((SectionKind::FactorDerivatives, derivs));
    }
    let mut steps: Vec<(Quantity, Scalar)> = Vec::new();
    for i in 2..=n {
        let rows = comps(&step(Step::Prefix, i), &(q(i - 1) * l(i)));
        learn(&known, &rows);
        steps.extend(rows);
    }
    sections.push((SectionKind::PrefixProducts, steps));
    sections.push((
        SectionKind::Pose { last_q: true },
        comps(&Quantity::Dq, &q(n)),
    ));
    if o.jacobian {
        let mut suffix: Vec<(Quantity, Scalar)> = Vec::new();
        for i in (2..n).rev() {
            let rows = comps(&step(Step::Suffix, i), &(l(i) * p(i + 1)));
            learn(&known, &rows);
            suffix.extend(rows);
        }
        sections.push((SectionKind::SuffixProducts, suffix));
    }
    let last = q(n);
    let cos_sin_forms = cos_sin_matrix(robot, &joints, made.and_then(MadeJoints::matrices), o);
    let (m, from, t_forms, texts) = match cos_sin_forms {
        Some((m, forms, texts)) => (m, MatrixFrom::CosSin, Some(forms), Some(texts)),
        None => (last.to_matrix(), MatrixFrom::LastQ, None, None),
    };
    let mut t = Vec::new();
    for i in 0..3 {
        for j in 0..4 {
            t.push((Quantity::T(i, j), m.rows[i][j].clone()));
        }
    }
    sections.push((SectionKind::Matrix(from), t));
    if let Some(pt) = &o.point {
        let img = last.transform_point(pt);
        let ps = img
            .into_iter()
            .enumerate()
            .map(|(k, c)| (Quantity::Point(k), c))
            .collect();
        sections.push((SectionKind::Point, ps));
    }
    if o.jacobian {
        // Column v is the sum over the joints that move with v (one, except for mimic joints).
        let columns: Vec<[Scalar; 8]> = robot
            .variables
            .iter()
            .map(|v| {
                let mut col = DualQuat::from_components(std::array::from_fn(|_| Scalar::int(0)));
                for (i, jv) in joint_var.iter().enumerate() {
                    if jv.as_ref() == Some(v) {
                        let i = i + 1;
                        col = col + q(i - 1) * syms(&known, Step::FactorDerivative, i) * p(i + 1);
                    }
                }
                col.components()
            })
            .collect();
        let mut jac = Vec::new();
        for k in 0..8 {
            for (j, c) in columns.iter().enumerate() {
                jac.push((Quantity::J { row: k, col: j }, c[k].clone()));
            }
        }
        sections.push((SectionKind::Jacobian { recurrence: true }, jac));
    }

    check_names(robot, &joints, o, &sections)?;
    Ok((with_closed_forms(sections, t_forms)?, texts))
}

/// The plain text (shorthand, no decimals) of each row of the matrix made in cosines and
/// sines, in order: printed to measure it ([`MAX_COS_SIN_TEXT`]), and kept for the report,
/// which prints these rows as they are (the symbolic 6R printed them twice, 1.85 M
/// instructions).
pub(crate) type CosSinTexts = Vec<String>;

/// The matrix as a polynomial in the cosines and sines of the joint matrices, with the closed
/// forms of its rows 0..2, when that fits (see the module docs); `None` past a budget or the
/// size of text. The joint factors' matrices are those `kept` where it has them (made by the
/// expansion given up, [`crate::kin::JointMatrices`]). With the forms, their text
/// ([`CosSinTexts`]).
#[allow(clippy::type_complexity)]
fn cos_sin_matrix<'a>(
    robot: &Robot,
    joints: &dyn Fn() -> Cow<'a, [DualQuat<Scalar>]>,
    kept: Option<&crate::kin::JointMatrices>,
    o: &FkOptions,
) -> Option<(
    crate::Matrix4<Scalar>,
    Vec<Result<Expr, ScalarError>>,
    CosSinTexts,
)> {
    // The matrix in the robot's own symbols when it fits as a polynomial in the cosines and
    // sines (a generic 6R: 1,595 monomials), else in the last Q's symbols.
    // An attempt with its own small budget: a long chain stops early and costs little.
    let cos_sin = with_own_budget(COS_SIN_BUDGET, || {
        robot.forward_matrix_cos_sin_of(&joints(), kept, o.max_terms.min(COS_SIN_MAX_TERMS))
    });
    // Its closed forms are kept when they are short (a numeric 10-joint chain can give 20 kB
    // per entry); else the matrix is read from the last Q.
    // They are part of the attempt: made with a budget of their own, and given up when it
    // runs out.
    cos_sin.and_then(|m| {
        let cells: Vec<&Scalar> = m.rows[..3].iter().flatten().collect();
        let forms = with_own_budget(COS_SIN_FORMS_BUDGET, || cos_sin_forms(robot, &cells));
        if forms.iter().any(Result::is_err) {
            return None;
        }
        let po = crate::print::PlainOptions {
            shorthand: true,
            decimals: false,
        };
        // Every form is one here (an error returned above).
        let texts: CosSinTexts = forms
            .iter()
            .map(|e| {
                e.as_ref()
                    .map_or_else(|_| String::new(), |e| crate::print::plain(e, &po))
            })
            .collect();
        let len: usize = texts.iter().map(String::len).sum();
        (len <= MAX_COS_SIN_TEXT).then_some((m, forms, texts))
    })
}

/// The closed forms of a matrix's entries in cosines and sines (`closed_form_cos_sin`). An
/// entry that is a quarter turn of an earlier one in the first joint's angle (the second row
/// of `Rz(q1) M`: `closed/turn.rs`) takes that one's form turned, checked, not a search of its
/// own (one whose check fails is searched); the others are searched in parallel. On the fully
/// symbolic 6R the second row's four entries.
fn cos_sin_forms(robot: &Robot, cells: &[&Scalar]) -> Vec<Result<Expr, ScalarError>> {
    let (_, turns) = super::fk::pose_turns(robot);
    let turned = turn::turned_placeholder_entries(cells, &turns, 8);
    let order: Vec<usize> = (0..cells.len()).filter(|&k| turned[k].is_none()).collect();
    let made = par_map(&order, |&k| crate::closed_form(cells[k]));
    let mut forms: Vec<Option<Result<Expr, ScalarError>>> = vec![None; cells.len()];
    for (k, f) in order.into_iter().zip(made) {
        forms[k] = Some(f);
    }
    for k in 0..cells.len() {
        let Some(t) = &turned[k] else {
            continue;
        };
        let from = match &forms[t.from] {
            Some(Ok(e)) => turn::turned_placeholder_form(e, t, cells[k]),
            _ => None,
        };
        forms[k] = Some(from.map_or_else(|| crate::closed_form(cells[k]), Ok));
    }
    forms
        .into_iter()
        .map(|f| {
            f.expect("every entry's form is made")
                .map(Expr::with_placeholders_as_trig)
        })
        .collect()
}

/// Refuses a robot or point symbol named like an entry's symbol.
fn check_names<'a>(
    robot: &Robot,
    joints: &dyn Fn() -> Cow<'a, [DualQuat<Scalar>]>,
    o: &FkOptions,
    sections: &Staged,
) -> Result<(), ReportError> {
    // A robot symbol named like an entry (`Q2_3`) would be read as that entry.
    // (One set of the entries' symbols: a scan of every entry per robot symbol was quadratic
    // in the joints.)
    let point_syms = o.point.iter().flatten().flat_map(|c| c.symbols());
    let robot_syms = robot
        .variables
        .iter()
        .cloned()
        .chain(robot.parameters_of(&joints()));
    let entries: std::collections::HashSet<String> = sections
        .iter()
        .flat_map(|(_, rows)| rows)
        .map(|(name, _)| name.symbol())
        .collect();
    for s in robot_syms.chain(point_syms.map(|s| s.name().to_string())) {
        if entries.contains(&s) {
            return Err(ReportError::NameClash(s));
        }
    }
    Ok(())
}

/// The sections with every entry in closed form: the matrix's `t_forms` when they were made
/// already, the others each shape's once ([`shared_closed_forms`]).
fn with_closed_forms(
    sections: Staged,
    t_forms: Option<Vec<Result<Expr, ScalarError>>>,
) -> Result<Vec<Section>, ReportError> {
    // The matrix's closed forms, when already made, are not made again.
    let have_t = t_forms.is_some();
    let done = |t: &SectionKind| matches!(t, SectionKind::Matrix(_)) && have_t;
    let all: Vec<&Scalar> = sections
        .iter()
        .filter(|(t, _)| !done(t))
        .flat_map(|(_, rows)| rows.iter().map(|(_, x)| x))
        .collect();
    let mut forms = shared_closed_forms(&all).into_iter();
    let mut t_forms = t_forms.into_iter().flatten();
    sections
        .into_iter()
        .map(|(kind, rows)| {
            // `forms` holds one closed form per entry, in the same order.
            let source: &mut dyn Iterator<Item = Result<Expr, ScalarError>> = if done(&kind) {
                &mut t_forms
            } else {
                &mut forms
            };
            let rows = rows
                .into_iter()
                .zip(source)
                .map(|((name, _), e)| Ok((name, e?)))
                .collect::<Result<Vec<_>, ScalarError>>()?;
            Ok(Section { kind, rows })
        })
        .collect()
}

/// The placeholder names of [`shape`]: sorted like their index below 10^6 (`~1000000` sorts
/// before `~999999`, and then `rename_syms_monotone`'s check refuses the shape, as the route
/// before did), and no robot symbol (those are identifiers) starts with `~`. Written as
/// `format!("~{k:06}")` writes it, without the formatting machinery.
fn placeholder(k: usize) -> String {
    let mut digits = [b'0'; 20];
    let (mut n, mut start) = (k, digits.len());
    loop {
        start -= 1;
        digits[start] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    let mut s = String::with_capacity(8);
    s.push('~');
    for &d in &digits[start.min(digits.len() - 6)..] {
        s.push(char::from(d));
    }
    s
}

/// An entry renamed to placeholders, and the symbols renamed: the `k`th to placeholder `k`.
type Shape = (Scalar, Vec<crate::Sym>);

/// The symbols a [`shape`] renames, in order (by name, as [`Scalar::symbols`] sorts them).
/// `None` for an entry with `pi` as a symbol, or a cos/sin placeholder, whose order with
/// respect to the placeholders a renaming could change (the constant of an angle is no
/// symbol of [`Scalar::symbols`], and keeps its place before every name).
fn shape_symbols(x: &Scalar) -> Option<Vec<crate::Sym>> {
    let symbols = x.symbols();
    let special = |s: &crate::Sym| {
        let n = s.name();
        s.is_pi() || n.starts_with('~') || crate::scalar::parse_trig_placeholder(n).is_some()
    };
    if symbols.iter().any(special) {
        return None;
    }
    debug_assert!(symbols.windows(2).all(|w| w[0].name() < w[1].name()));
    Some(symbols)
}

/// The shape of an entry: its symbols (`symbols`, [`shape_symbols`]) renamed in order to
/// placeholders (`holders[k]` is the symbol of `placeholder(k)`). Entries of one shape (the
/// joint factors of equal links, the prefix products past the first few, the Jacobian
/// columns of the middle joints) share one closed form.
fn shape(x: &Scalar, symbols: Vec<crate::Sym>, holders: &[crate::Sym]) -> Option<Shape> {
    let to = holders.get(..symbols.len())?;
    Some((x.rename_syms_monotone(&symbols, to)?, symbols))
}

/// `e` with the placeholders renamed back to `symbols` (placeholder `k` to `symbols[k]`).
fn unshape(e: Expr, symbols: &[crate::Sym]) -> Expr {
    let back = |s: crate::Sym| -> crate::Sym {
        match s
            .name()
            .strip_prefix('~')
            .and_then(|k| k.parse::<usize>().ok())
        {
            Some(k) if k < symbols.len() => symbols[k].clone(),
            _ => s,
        }
    };
    match e {
        Expr::Sym(s) => Expr::Sym(back(s)),
        Expr::Trig { f, mut angle } => {
            angle.terms = angle.terms.into_iter().map(|(s, k)| (back(s), k)).collect();
            Expr::Trig { f, angle }
        }
        Expr::Add(v) => Expr::Add(v.into_iter().map(|e| unshape(e, symbols)).collect()),
        Expr::Mul(v) => Expr::Mul(v.into_iter().map(|e| unshape(e, symbols)).collect()),
        Expr::Neg(e) => Expr::Neg(Box::new(unshape(*e, symbols))),
        Expr::Pow(e, n) => Expr::Pow(Box::new(unshape(*e, symbols)), n),
        e => e,
    }
}

/// The closed form of every entry, each shape's once (in parallel, in order of first
/// appearance, so the result does not depend on the threads). The renaming keeps the order of
/// the symbols, and closed forms only compare symbols, so an entry's form is its shape's form
/// renamed back, of the same value (checked exactly in debug builds).
fn shared_closed_forms(all: &[&Scalar]) -> Vec<Result<Expr, ScalarError>> {
    let symbols: Vec<(&Scalar, Option<Vec<crate::Sym>>)> = par_map(all, |x| (*x, shape_symbols(x)));
    // The placeholders interned once for every entry.
    let most = symbols
        .iter()
        .filter_map(|(_, s)| s.as_ref().map(Vec::len))
        .max();
    let holders: Vec<crate::Sym> = (0..most.unwrap_or(0))
        .map(|k| crate::Sym::new(&placeholder(k)))
        .collect();
    let shapes: Vec<Option<Shape>> = par_map(&symbols, |(x, s)| {
        s.as_ref().and_then(|s| shape(x, s.clone(), &holders))
    });
    // Keyed by a few terms of each shape (`SampledKey`, compared in full), hashed by FxHash:
    // std's SipHash of every term of every entry was 2.3 M instructions of a fully symbolic
    // 6R's report. Only looked up, never iterated: the order is the entries'.
    let mut index: HashMap<SampledKey, usize, BuildHasherDefault<FxHasher>> = HashMap::default();
    let mut distinct: Vec<&Scalar> = Vec::new();
    let keys: Vec<usize> = all
        .iter()
        .zip(&shapes)
        .map(|(x, sh)| {
            let key = sh.as_ref().map_or(*x, |(k, _)| k);
            *index.entry(SampledKey(key)).or_insert_with(|| {
                distinct.push(key);
                distinct.len() - 1
            })
        })
        .collect();
    // `closed_form_cos_sin` is `closed_form` on every entry without cos/sin placeholders.
    let forms = par_map(&distinct, |x| closed_form_cos_sin(x));
    keys.iter()
        .zip(shapes.iter().zip(all))
        .map(|(&k, (sh, x))| {
            let e = forms[k].clone()?;
            Ok(match sh {
                None => e,
                Some((_, symbols)) => {
                    let e = unshape(e, symbols);
                    // A limit reached by the check itself (the budget is shared) proves
                    // nothing either way. Only debug builds expand the form to check it
                    // (release builds spent 3.6% of a symbolic 6R's report on a value
                    // they threw away).
                    if cfg!(debug_assertions) {
                        let d = e.to_scalar() - *x;
                        debug_assert!(
                            d.as_error().is_some() || d.is_zero_value(),
                            "a shared closed form differs from its entry"
                        );
                    }
                    e
                }
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kin::{dh_link, mdh_link};
    use crate::scalar::{trig_placeholder, Trig};
    use crate::Sym;

    /// The shape as first made (kept as the reference): the names as strings, sorted, each
    /// placeholder formatted, renamed by name.
    fn shape_before(x: &Scalar) -> Option<(Scalar, Vec<(String, String)>)> {
        let symbols = x.symbols();
        let special = |s: &Sym| {
            let n = s.name();
            s.is_pi() || n.starts_with('~') || crate::scalar::parse_trig_placeholder(n).is_some()
        };
        if symbols.iter().any(special) {
            return None;
        }
        let mut names: Vec<String> = symbols.iter().map(|s| s.name().to_string()).collect();
        names.sort();
        names.dedup();
        let map: Vec<(String, String)> = names
            .into_iter()
            .enumerate()
            .map(|(k, n)| (n, format!("~{k:06}")))
            .collect();
        Some((x.rename_symbols_monotone(&map)?, map))
    }

    /// The renaming back as first made: each symbol interned again from its name.
    fn unshape_before(e: Expr, map: &[(String, String)]) -> Expr {
        let back = |s: Sym| -> Sym {
            match s
                .name()
                .strip_prefix('~')
                .and_then(|k| k.parse::<usize>().ok())
            {
                Some(k) if k < map.len() => Sym::new(&map[k].0),
                _ => s,
            }
        };
        match e {
            Expr::Sym(s) => Expr::Sym(back(s)),
            Expr::Trig { f, mut angle } => {
                angle.terms = angle.terms.into_iter().map(|(s, k)| (back(s), k)).collect();
                Expr::Trig { f, angle }
            }
            Expr::Add(v) => Expr::Add(v.into_iter().map(|e| unshape_before(e, map)).collect()),
            Expr::Mul(v) => Expr::Mul(v.into_iter().map(|e| unshape_before(e, map)).collect()),
            Expr::Neg(e) => Expr::Neg(Box::new(unshape_before(*e, map))),
            Expr::Pow(e, n) => Expr::Pow(Box::new(unshape_before(*e, map)), n),
            e => e,
        }
    }

    /// The closed forms of a matrix in cosines and sines (`cos_sin_forms`) on random chains
    /// and a fully symbolic 4R: each has the value of the entry's own search
    /// (`closed_form_cos_sin`), the entries turned from others (the second row) among them,
    /// none of whose checks fails (a failed one would be searched, unseen).
    #[test]
    fn the_cos_sin_forms_turned_from_others_are_their_entries() {
        let mut next = crate::testing::xorshift_below(0x7e57_0035);
        let mut robots: Vec<Robot> = (0..10)
            .map(|_| crate::kin::random_test_chain(&mut next, 5))
            .collect();
        let mut r4 = crate::kin::random_test_chain(&mut next, 4);
        let s = |name: &str, i: usize| Scalar::sym(&format!("{name}{i}"));
        r4.chain = crate::kin::Chain::new(
            (1..=4)
                .map(|i| {
                    crate::kin::Joint::revolute_dh(
                        Scalar::int(0),
                        s("d", i),
                        s("a", i),
                        s("alpha", i),
                    )
                })
                .collect(),
        );
        r4.variables = (1..=4).map(|i| format!("theta{i}")).collect();
        r4.joint_values = (1..=4).map(|i| s("theta", i)).collect();
        robots.push(r4);
        let (mut turned, mut matrices) = (0, 0);
        for robot in &robots {
            let _in = crate::Context::new().with_threads(1).enter();
            let Some(m) = robot.forward_matrix_cos_sin(20_000) else {
                continue;
            };
            matrices += 1;
            let cells: Vec<&Scalar> = m.rows[..3].iter().flatten().collect();
            turn::counts::COUNTS.with(|c| c.set((0, 0)));
            let forms = cos_sin_forms(robot, &cells);
            let (made, failed) = turn::counts::COUNTS.with(|c| c.get());
            assert_eq!(failed, 0, "{:?}", robot.chain);
            turned += made;
            if robot.variables[0] == "theta1" {
                assert_eq!(made, 4, "the symbolic 4R's second row");
            }
            for (x, f) in cells.iter().zip(&forms) {
                let own = closed_form_cos_sin(x).expect("a form");
                let f = f.as_ref().expect("a form");
                assert_eq!(f.to_scalar(), own.to_scalar(), "{x}");
            }
        }
        // The 4R's second row (the last robot's four), and rows of random DH chains (an MDH
        // chain's first twist, or a prismatic first joint, leaves its rows unrelated).
        assert!(
            matrices >= 8 && turned >= 8,
            "{matrices} matrices, {turned} turned"
        );
    }

    #[test]
    fn placeholders_are_written_as_format_writes_them() {
        for k in [
            0,
            1,
            9,
            10,
            99,
            12_345,
            999_999,
            1_000_000,
            31_415_926,
            usize::MAX,
        ] {
            assert_eq!(placeholder(k), format!("~{k:06}"));
        }
    }

    /// The entries of a few chains (joint factors of DH and modified-DH links with symbolic
    /// and numeric parameters, their derivatives, prefix products of factors and of the
    /// recurrence's symbols, cos/sin placeholders and `pi`, which have no shape): each shape,
    /// its symbols and each shared closed form renamed back are those of the route before.
    #[test]
    fn shapes_and_their_forms_renamed_back_are_those_of_the_route_before() {
        let s = |n: String| Scalar::sym(&n);
        let half_pi =
            Scalar::pi() * Scalar::rational(num_rational::BigRational::new(1.into(), 2.into()));
        let mut entries: Vec<Scalar> = Vec::new();
        let mut links = Vec::new();
        for i in 1..=3 {
            let (t, d, a, al) = (
                s(format!("theta{i}")),
                s(format!("d{i}")),
                s(format!("a{i}")),
                s(format!("alpha{i}")),
            );
            links.push(dh_link(&t, &d, &a, &al));
            links.push(dh_link(&t, &Scalar::int(0), &a, &half_pi));
            links.push(mdh_link(&t, &d, &Scalar::int(3), &al));
        }
        for l in &links {
            for c in l.components() {
                entries.push(c.diff("theta2"));
                entries.push(c.diff("theta1"));
                entries.push(c);
            }
        }
        for (x, y) in [(0, 3), (3, 7), (1, 5), (2, 8)] {
            entries.extend((links[x].clone() * links[y].clone()).components());
        }
        let syms =
            |p: &str| DualQuat::from_components(std::array::from_fn(|k| s(format!("{p}_{k}"))));
        entries.extend((syms("Q2") * syms("L3") * syms("P4")).components());
        entries.extend((syms("Q3") * syms("L4")).components());
        entries.push(trig_placeholder("theta1", Trig::Cos) * Scalar::sym("a1") + Scalar::sym("d2"));
        entries.push(Scalar::sym("b") * Scalar::pi() + Scalar::sym("a"));

        // The route of `shared_closed_forms`.
        let symbols: Vec<Option<Vec<Sym>>> = entries.iter().map(shape_symbols).collect();
        let most = symbols.iter().flatten().map(Vec::len).max().unwrap_or(0);
        let holders: Vec<Sym> = (0..most).map(|k| Sym::new(&placeholder(k))).collect();
        let (mut shaped, mut unshaped) = (0, 0);
        for (x, sy) in entries.iter().zip(symbols) {
            let now = sy.and_then(|sy| shape(x, sy, &holders));
            let before = shape_before(x);
            assert_eq!(now.is_some(), before.is_some(), "{x}");
            let (Some((k, sy)), Some((k0, map))) = (now, before) else {
                unshaped += 1;
                continue;
            };
            shaped += 1;
            assert_eq!(k, k0);
            let names: Vec<&str> = sy.iter().map(Sym::name).collect();
            let names0: Vec<&str> = map.iter().map(|(n, _)| n.as_str()).collect();
            assert_eq!(names, names0);
            if k.terms().map_or(0, <[_]>::len) <= 64 {
                let e = closed_form_cos_sin(&k).expect("closed form");
                assert_eq!(unshape(e.clone(), &sy), unshape_before(e, &map));
            }
        }
        assert!(shaped > 100 && unshaped >= 2, "{shaped} {unshaped}");
    }
}
