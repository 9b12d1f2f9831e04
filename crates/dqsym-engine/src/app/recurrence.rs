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
//!
//! Closed forms are shared: entries equal up to an order-keeping renaming of their symbols
//! (`Q3[k]` and `Q4[k]`) have one search ([`shared_closed_forms`]); components 1..3 and 5..7
//! of a product (of `Q{i}`, `P{i}`, a Jacobian column) are component 0 or 4 with the symbols
//! of its last factor permuted and signed ([`component_hints`], `closed/rename.rs`), and take
//! that one's form renamed when their scalars agree exactly (on the fully symbolic 6R, 24 of
//! 47 searches); a joint factor's derivative `dL{i}[k]` is `L{i}[k]` with its variable turned
//! by pi, halved, and takes that form turned ([`derivative_hints`]: 8 more); the matrix in
//! cosines and sines takes the forms of rows and columns that are turns of others
//! (`closed/turn.rs`: its second row, and its third column when the last twist is a symbol).

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
use crate::closed::rename::SignedRenaming;
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
    // The symbols of `p(i)`, for `i <= n`.
    let p_family = |i: usize| {
        if i == n {
            (Step::Factor, n)
        } else {
            (Step::Suffix, i)
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
    // The entries derived from others: the derivatives of the joint factors (turned, see
    // `derivative_hints`) and the components of each product (renamed, `component_hints`).
    let mut derived = Derived::default();
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
        for (i, v) in joint_var.iter().enumerate() {
            if let Some(v) = v {
                derivative_hints(&mut derived, i + 1, v);
            }
        }
    }
    let mut steps: Vec<(Quantity, Scalar)> = Vec::new();
    for i in 2..=n {
        let rows = comps(&step(Step::Prefix, i), &(q(i - 1) * l(i)));
        learn(&known, &rows);
        component_hints(&mut derived, &step(Step::Prefix, i), &[(Step::Factor, i)]);
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
            component_hints(&mut derived, &step(Step::Suffix, i), &[p_family(i + 1)]);
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
        // Each term of column v ends in `P{i+1}`, or in `dL{n}` for the last joint.
        for (j, v) in robot.variables.iter().enumerate() {
            let lasts: Vec<(Step, usize)> = (1..=n)
                .filter(|&i| joint_var.get(i - 1).and_then(Option::as_ref) == Some(v))
                .map(|i| {
                    if i == n {
                        (Step::FactorDerivative, n)
                    } else {
                        p_family(i + 1)
                    }
                })
                .collect();
            component_hints(&mut derived, &|k| Quantity::J { row: k, col: j }, &lasts);
        }
        sections.push((SectionKind::Jacobian { recurrence: true }, jac));
    }

    check_names(robot, &joints, o, &sections)?;
    Ok((with_closed_forms(sections, t_forms, &derived)?, texts))
}

/// Entries that may be derived from others ([`Derivation`]): by entry, the entry it would be
/// derived from. A hint only: [`shared_closed_forms`] takes it when the derived scalar is the
/// entry, exactly.
type Derived = HashMap<Quantity, (Quantity, Derivation)>;

/// How an entry is another: its symbols permuted and signed (a component of a product from
/// its first), or its joint variable turned and scaled (a joint factor's derivative: `d L(q)
/// / d q = L(q + pi) / 2` for `L` a function of `q/2` through `cos` and `sin`, the half angle
/// turned by a quarter turn).
#[derive(Clone, Debug)]
enum Derivation {
    Renamed(SignedRenaming),
    Turned(turn::Turned),
}

impl Derivation {
    /// Whether `x` is `from` derived so, exactly.
    fn holds(&self, from: &Scalar, x: &Scalar) -> bool {
        match self {
            Derivation::Renamed(r) => r.scalar(from).as_ref() == Some(x),
            Derivation::Turned(t) => turn::turned_scalar(from, &t.turn)
                .is_some_and(|y| Scalar::from_q(t.factor.clone()) * y == *x),
        }
    }

    /// The form of `x` from `from`'s, checked (`None` when its check fails).
    fn form(&self, from: &Expr, x: &Scalar) -> Option<Expr> {
        match self {
            Derivation::Renamed(r) => r.renamed_form(from, x),
            // A call with a constant phase (`sin(q2/2 - 3*pi/5)`) turns into one whose own
            // search may write it at another phase, shorter (`cos(q2/2 - pi/10)`): such an
            // entry is searched.
            Derivation::Turned(_) if has_phase(from) => None,
            Derivation::Turned(t) => turn::turned_form(from, t, x).map(turn::signs_placed),
        }
    }
}

/// Whether a call of `e` has a constant multiple of pi in its angle.
fn has_phase(e: &Expr) -> bool {
    match e {
        Expr::Trig { angle, .. } => *angle.pi.numer() != 0,
        Expr::Add(v) | Expr::Mul(v) => v.iter().any(has_phase),
        Expr::Neg(x) | Expr::Pow(x, _) => has_phase(x),
        Expr::Num(_) | Expr::Sqrt(_) | Expr::Sym(_) => false,
    }
}

/// The hints of the joint factors' derivatives: `dL{i}[k]` is `L{i}[k]` with its joint's
/// variable `v` turned by pi, halved (a prismatic joint's, or one whose factor is no function
/// of `v/2`, is not: the check refuses it and it is searched).
fn derivative_hints(derived: &mut Derived, joint: usize, v: &str) {
    let half = crate::scalar::Q::new(1, 2);
    for k in 0..8 {
        let t = turn::Turned {
            from: 0,
            turn: (crate::Sym::new(v), crate::scalar::Small::from_integer(1)),
            factor: half.clone(),
        };
        derived.insert(
            Quantity::Step {
                step: Step::FactorDerivative,
                joint,
                k,
            },
            (
                Quantity::Step {
                    step: Step::Factor,
                    joint,
                    k,
                },
                Derivation::Turned(t),
            ),
        );
    }
}

/// The hints of a product's components `name(0..8)` whose terms end in factors with the
/// symbols of `lasts` (`(step, joint)`: `Q2_0`..`Q2_7`). Component `k` of a product `X` is
/// component 0 of `X v` with `v = -i, -j, -k` for `k = 1, 2, 3` (`w(X (-i)) = x(X)`), and
/// component `4 + k` is component 4 of it (the dual part is multiplied by `v` alike); `X v`
/// ends in `B v` where `X` ends in `B`, whose components are `B`'s permuted with signs
/// ([`UNIT_PRODUCTS`]). So component `k` is component 0 (or 4) with each last factor's
/// symbols renamed so.
fn component_hints(
    derived: &mut Derived,
    name: &dyn Fn(usize) -> Quantity,
    lasts: &[(Step, usize)],
) {
    if lasts.is_empty() {
        return;
    }
    let families: Vec<[crate::Sym; 8]> = lasts
        .iter()
        .map(|&(step, joint)| {
            std::array::from_fn(|c| crate::Sym::new(&Quantity::Step { step, joint, k: c }.symbol()))
        })
        .collect();
    for (k, images) in UNIT_PRODUCTS.iter().enumerate() {
        let mut map: Vec<(crate::Sym, crate::Sym, bool)> = Vec::with_capacity(8 * lasts.len());
        for b in &families {
            for (c, &(to, neg)) in images.iter().enumerate() {
                for part in [0, 4] {
                    map.push((b[part + c].clone(), b[part + to].clone(), neg));
                }
            }
        }
        let Some(r) = SignedRenaming::new(map) else {
            return;
        };
        derived.insert(name(k + 1), (name(0), Derivation::Renamed(r.clone())));
        derived.insert(name(k + 5), (name(4), Derivation::Renamed(r)));
    }
}

/// The components of `B v` for `v = -i, -j, -k`: component `c` (of the real part, and of
/// the dual part alike) is component `to` of `B`, negated when `neg` (`B (-i) = (B1, -B0,
/// -B3, B2)`). Checked against the product of dual quaternions by the test
/// `component_hints_are_the_products_by_units`.
const UNIT_PRODUCTS: [[(usize, bool); 4]; 3] = [
    [(1, false), (0, true), (3, true), (2, false)],
    [(2, false), (3, false), (0, true), (1, true)],
    [(3, false), (2, true), (1, false), (0, true)],
];

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

#[cfg(test)]
thread_local! {
    /// Tests: [`with_closed_forms`] on this thread takes no hint ([`component_hints`],
    /// [`derivative_hints`]): the reference the derived forms are compared with.
    static NO_HINTS: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Whether a test asked for the forms without hints ([`NO_HINTS`]).
fn no_hints_in_tests() -> bool {
    #[cfg(test)]
    return NO_HINTS.with(std::cell::Cell::get);
    #[cfg(not(test))]
    false
}

/// The sections with every entry in closed form: the matrix's `t_forms` when they were made
/// already, the others each shape's once ([`shared_closed_forms`]).
fn with_closed_forms(
    sections: Staged,
    t_forms: Option<Vec<Result<Expr, ScalarError>>>,
    derived: &Derived,
) -> Result<Vec<Section>, ReportError> {
    // The matrix's closed forms, when already made, are not made again.
    let have_t = t_forms.is_some();
    let done = |t: &SectionKind| matches!(t, SectionKind::Matrix(_)) && have_t;
    let rows: Vec<&(Quantity, Scalar)> = sections
        .iter()
        .filter(|(t, _)| !done(t))
        .flat_map(|(_, rows)| rows)
        .collect();
    let all: Vec<&Scalar> = rows.iter().map(|(_, x)| x).collect();
    let at: HashMap<Quantity, usize, BuildHasherDefault<FxHasher>> =
        rows.iter().enumerate().map(|(k, (q, _))| (*q, k)).collect();
    let hints: Vec<Option<(usize, &Derivation)>> = rows
        .iter()
        .map(|(q, _)| {
            if no_hints_in_tests() {
                return None;
            }
            let (from, r) = derived.get(q)?;
            Some((*at.get(from)?, r))
        })
        .collect();
    let mut forms = shared_closed_forms(&all, &hints).into_iter();
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
    map_syms(e, &|s: crate::Sym| -> crate::Sym {
        match s
            .name()
            .strip_prefix('~')
            .and_then(|k| k.parse::<usize>().ok())
        {
            Some(k) if k < symbols.len() => symbols[k].clone(),
            _ => s,
        }
    })
}

/// `e` with `symbols` (sorted by name) renamed to the placeholders of their places, as
/// [`shape`] renames an entry: the inverse of [`unshape`].
fn reshape(e: Expr, symbols: &[crate::Sym], holders: &[crate::Sym]) -> Expr {
    map_syms(e, &|s: crate::Sym| -> crate::Sym {
        match symbols.binary_search_by(|o| o.name().cmp(s.name())) {
            Ok(k) if k < holders.len() => holders[k].clone(),
            _ => s,
        }
    })
}

/// `e` with each symbol `s` (of a monomial or an angle) renamed to `f(s)`.
fn map_syms(e: Expr, f: &dyn Fn(crate::Sym) -> crate::Sym) -> Expr {
    match e {
        Expr::Sym(s) => Expr::Sym(f(s)),
        Expr::Trig { f: g, mut angle } => {
            angle.terms = angle.terms.into_iter().map(|(s, k)| (f(s), k)).collect();
            Expr::Trig { f: g, angle }
        }
        Expr::Add(v) => Expr::Add(v.into_iter().map(|e| map_syms(e, f)).collect()),
        Expr::Mul(v) => Expr::Mul(v.into_iter().map(|e| map_syms(e, f)).collect()),
        Expr::Neg(e) => Expr::Neg(Box::new(map_syms(*e, f))),
        Expr::Pow(e, n) => Expr::Pow(Box::new(map_syms(*e, f)), n),
        e => e,
    }
}

/// What a distinct entry's closed form is made from: its own search, or another entry's
/// form derived (`from`, an entry before `entry`: [`Derivation`]).
enum Slot<'a> {
    Search(&'a Scalar),
    Derived {
        entry: usize,
        from: usize,
        derivation: &'a Derivation,
    },
}

/// The closed form of every entry, each shape's once (in parallel, in order of first
/// appearance, so the result does not depend on the threads). The renaming keeps the order of
/// the symbols, and closed forms only compare symbols, so an entry's form is its shape's form
/// renamed back, of the same value (checked exactly in debug builds). An entry of a new shape
/// with a hint (`hints[k]`: an earlier entry and a [`Derivation`], see [`component_hints`] and
/// [`derivative_hints`]) whose derived scalar is the entry, exactly, takes that entry's form
/// derived, checked, instead of a search (the symbolic 6R's prefix products, Jacobian and
/// joint factors' derivatives: 32 of 47 searches).
fn shared_closed_forms(
    all: &[&Scalar],
    hints: &[Option<(usize, &Derivation)>],
) -> Vec<Result<Expr, ScalarError>> {
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
    let mut slots: Vec<Slot> = Vec::new();
    let derives = |k: usize| -> Option<(usize, &Derivation)> {
        let (from, r) = hints.get(k).copied().flatten()?;
        (from < k && r.holds(all[from], all[k])).then_some((from, r))
    };
    let keys: Vec<usize> = all
        .iter()
        .zip(&shapes)
        .enumerate()
        .map(|(k, (x, sh))| {
            let key = sh.as_ref().map_or(*x, |(s, _)| s);
            *index.entry(SampledKey(key)).or_insert_with(|| {
                slots.push(match derives(k) {
                    Some((from, derivation)) => Slot::Derived {
                        entry: k,
                        from,
                        derivation,
                    },
                    None => Slot::Search(key),
                });
                slots.len() - 1
            })
        })
        .collect();
    // `closed_form_cos_sin` is `closed_form` on every entry without cos/sin placeholders.
    let searched: Vec<(usize, &Scalar)> = slots
        .iter()
        .enumerate()
        .filter_map(|(k, s)| match s {
            Slot::Search(x) => Some((k, *x)),
            Slot::Derived { .. } => None,
        })
        .collect();
    let made = par_map(&searched, |(_, x)| closed_form_cos_sin(x));
    let mut forms: Vec<Option<Result<Expr, ScalarError>>> = vec![None; slots.len()];
    for ((k, _), f) in searched.iter().zip(made) {
        forms[*k] = Some(f);
    }
    // An entry's own form from its slot's (a shape's, in placeholders).
    let own = |forms: &[Option<Result<Expr, ScalarError>>], k: usize| {
        let e = forms[keys[k]]
            .clone()
            .expect("a slot's form is made before its uses")?;
        Ok(match &shapes[k] {
            None => e,
            Some((_, symbols)) => unshape(e, symbols),
        })
    };
    // The derived slots in order: each one's source is an earlier entry, of an earlier slot.
    for s in 0..slots.len() {
        let Slot::Derived {
            entry,
            from,
            derivation,
        } = slots[s]
        else {
            continue;
        };
        let x = all[entry];
        let e = own(&forms, from)
            .ok()
            .and_then(|f| derivation.form(&f, x))
            .map_or_else(|| closed_form_cos_sin(x), Ok);
        forms[s] = Some(e.map(|e| match &shapes[entry] {
            None => e,
            Some((_, symbols)) => reshape(e, symbols, &holders),
        }));
    }
    (0..all.len())
        .map(|k| {
            let e = own(&forms, k)?;
            // A limit reached by the check itself (the budget is shared) proves nothing
            // either way. Only debug builds expand the form to check it (release builds spent
            // 3.6% of a symbolic 6R's report on a value they threw away).
            if cfg!(debug_assertions) && shapes[k].is_some() {
                let d = e.to_scalar() - all[k];
                debug_assert!(
                    d.as_error().is_some() || d.is_zero_value(),
                    "a shared closed form differs from its entry"
                );
            }
            Ok(e)
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
        robots.push(crate::kin::symbolic_test_chain(
            &mut next, 4, false, "theta",
        ));
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
                // Its second row turned from its first in `theta1`, and its third column
                // from its second in the last twist `alpha4` (rows 0 and 2).
                assert_eq!(made, 6, "the symbolic 4R's second row and third column");
            }
            for (x, f) in cells.iter().zip(&forms) {
                let own = closed_form_cos_sin(x).expect("a form");
                let f = f.as_ref().expect("a form");
                assert_eq!(f.to_scalar(), own.to_scalar(), "{x}");
            }
        }
        // The 4R's six (the last robot's), and rows of random DH chains (an MDH
        // chain's first twist, or a prismatic first joint, leaves its rows unrelated).
        assert!(
            matrices >= 8 && turned >= 8,
            "{matrices} matrices, {turned} turned"
        );
    }

    /// `UNIT_PRODUCTS` is the product by `-i`, `-j`, `-k` of a dual quaternion in symbols;
    /// and each component of a product (of two and of three factors, and of a sum of two such
    /// with different last factors, a mimic joint's column) is its first or fourth renamed by
    /// the renaming `component_hints` gives.
    #[test]
    fn component_hints_are_the_products_by_units() {
        let dq = |step: Step, joint: usize| {
            DualQuat::from_components(std::array::from_fn(|k| {
                Scalar::sym(&Quantity::Step { step, joint, k }.symbol())
            }))
        };
        let b = dq(Step::Factor, 3);
        let bc = b.components();
        let units = [[0, -1, 0, 0], [0, 0, -1, 0], [0, 0, 0, -1]];
        for (images, v) in UNIT_PRODUCTS.iter().zip(units) {
            let [w, x, y, z] = v.map(Scalar::int);
            let bv = (b.clone() * DualQuat::from_real(crate::Quat::new(w, x, y, z))).components();
            for (c, &(to, neg)) in images.iter().enumerate() {
                for part in [0, 4] {
                    let want = bc[part + to].clone();
                    let want = if neg { -want } else { want };
                    assert_eq!(bv[part + c], want);
                }
            }
        }
        let (q2, l3, p4, p3) = (
            dq(Step::Prefix, 2),
            dq(Step::Factor, 3),
            dq(Step::Suffix, 4),
            dq(Step::Suffix, 3),
        );
        // Each product, and the steps and joints of its last factors.
        type Families = Vec<(Step, usize)>;
        let products: Vec<(DualQuat<Scalar>, Families)> = vec![
            (q2.clone() * l3.clone(), vec![(Step::Factor, 3)]),
            (
                q2.clone() * l3.clone() * p4.clone(),
                vec![(Step::Suffix, 4)],
            ),
            (
                q2.clone() * p4 + l3 * p3,
                vec![(Step::Suffix, 4), (Step::Suffix, 3)],
            ),
        ];
        for (x, lasts) in products {
            let x = x.components();
            let name = |k: usize| Quantity::Dq(k);
            let mut derived = Derived::default();
            component_hints(&mut derived, &name, &lasts);
            assert_eq!(derived.len(), 6);
            for k in [1, 2, 3, 5, 6, 7] {
                let (from, r) = &derived[&name(k)];
                let Quantity::Dq(from) = *from else {
                    panic!("{from:?}")
                };
                assert_eq!(from, if k < 4 { 0 } else { 4 });
                let Derivation::Renamed(r) = r else {
                    panic!("{r:?}")
                };
                assert_eq!(r.scalar(&x[from]).as_ref(), Some(&x[k]), "component {k}");
            }
        }
    }

    /// The recurrences of a symbolic 4R and of random chains (whose constants, the zeros of
    /// planar links, break some renamings: those entries are searched) with and without the
    /// renamed and turned forms: every row has the value of its entry's own form, exactly, the
    /// rows of the products of the symbolic chain are renamed (three of every four components
    /// of its prefix products and Jacobian columns) and its joint factors' derivatives turned
    /// (eight, the shapes of the first one's), at least 32, and no derived form is longer than
    /// its entry's own.
    #[test]
    fn renamed_rows_of_a_recurrence_are_their_entries() {
        let mut next = crate::testing::xorshift_below(0x7e57_0032);
        let mut robots: Vec<Robot> = (0..6)
            .map(|_| crate::kin::random_test_chain(&mut next, 5))
            .collect();
        robots.push(crate::kin::symbolic_test_chain(
            &mut next, 4, false, "theta",
        ));
        let o = FkOptions {
            jacobian: true,
            ..FkOptions::default()
        };
        let po = crate::print::PlainOptions {
            shorthand: false,
            decimals: false,
        };
        let mut total = 0;
        for robot in &robots {
            let _in = crate::Context::new().with_threads(1).enter();
            turn::counts::COUNTS.with(|c| c.set((0, 0)));
            let with = recurrence_sections(robot, None, &o).expect("a recurrence");
            let (made, failed) = turn::counts::COUNTS.with(|c| c.get());
            NO_HINTS.with(|h| h.set(true));
            let without = recurrence_sections(robot, None, &o).expect("a recurrence");
            NO_HINTS.with(|h| h.set(false));
            assert_eq!(failed, 0, "{:?}", robot.chain);
            total += made;
            if robot.variables[0] == "theta1" {
                // 38: 6 of its matrix turned, 24 renamed, 8 derivatives turned.
                assert!(
                    made >= 32,
                    "{made} renamed or turned rows of the symbolic 4R"
                );
            }
            for (a, b) in with.iter().zip(&without) {
                for ((qa, ea), (qb, eb)) in a.rows.iter().zip(&b.rows) {
                    assert_eq!(qa, qb);
                    assert_eq!(ea.to_scalar(), eb.to_scalar(), "{qa:?}");
                    let (la, lb) = (crate::print::plain(ea, &po), crate::print::plain(eb, &po));
                    assert!(la.len() <= lb.len(), "{qa:?}: {la} longer than {lb}");
                }
            }
        }
        assert!(total >= 40, "{total} renamed or turned rows");
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
