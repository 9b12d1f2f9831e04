//! The forward-kinematics report of a robot (`dqsym fk`): the unit DQ, the 4x4 matrix, the image
//! of a point and the 8 x n Jacobian, each entry in closed form, in one of three text formats.
//!
//! Entry names are the same in every format: `dq[k]` (k = 0..7, the components
//! (w, x, y, z, w_e, x_e, y_e, z_e) of q = r + eps q_e with q_e = t r / 2), `T[i][j]`
//! (i = 0..2, j = 0..3), `p[i]` and `J[i][j]` (i = 0..7, j = 0..n-1). A recurrence (see
//! [`fk_report`]) adds the names of its steps, `L{i}[k]`, `dL{i}[k]`, `Q{i}[k]` and `P{i}[k]`,
//! each read by later entries as the symbol `L{i}_k`, ...
//!
//! Entries and sections are data ([`Quantity`], [`SectionKind`]); every name, LaTeX letter,
//! generated output and title is written by `app/quantity.rs`, and no reader here parses one
//! back.

use super::quantity::{Family, Letters, MatrixFrom, Quantity, Section, SectionKind};
use super::recurrence::{recurrence_sections_printed, CosSinTexts};
use crate::closed::turn::{self, turned_entries, Turn, Turned};
use crate::emit::names::{line_comment, Comment, Lang};
use crate::emit::syntax::syntax;
use crate::emit::{
    arguments, count_ops, generated_ops, latex_aligned, product_table, rotation_chain_ops, sympy,
    sympy_decimals, CodegenError, CodegenOptions, Counted, LatexOptions, Output,
};
use crate::kin::{dq_jacobian, MadeJoints, Robot};
use crate::kin::{JointGeometry, JointKind};
use crate::print::{legend, plain, plain_len_bound, Format, PlainOptions};
use crate::scalar::{join, par_map, with_own_budget};
use crate::scalar::{FxHasher, ProportionalKey, SampledKey, Small, Sym, Q};
use std::collections::hash_map::Entry as MapEntry;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

type FxMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;
use crate::{
    closed::{
        closed_form_of_derivative, decimal_form, report_form, report_form_prepared, CommonOffsets,
        Hint,
    },
    Context, DualQuat, Expr, Scalar, ScalarError,
};

/// What the report contains.
#[derive(Clone, Debug)]
pub struct FkOptions {
    /// The text format. Every [`Format`] is a report: plain text and LaTeX with a comment
    /// header and one section per part, SymPy one `NAME = EXPR` line per entry, Rust, C and
    /// NumPy one generated function. The operation counts of the generated code are
    /// [`fk_ops`].
    pub format: Format,
    /// Plain text and LaTeX: `c12` rather than `cos(theta1 + theta2)` (and a legend); the
    /// other formats do not read it.
    pub shorthand: bool,
    /// A point of the last link (home pose for screw robots, last frame for DH) to transform.
    pub point: Option<[Scalar; 3]>,
    /// Add the 8 x n Jacobian of the DQ components.
    pub jacobian: bool,
    /// The most terms an expanded entry may have; beyond it the pose is reported as a
    /// recurrence over the joint factors (see [`fk_report`]).
    pub max_terms: usize,
}

impl Default for FkOptions {
    fn default() -> Self {
        FkOptions {
            format: Format::Plain,
            shorthand: true,
            point: None,
            jacobian: false,
            max_terms: 20_000,
        }
    }
}

/// Why a report could not be written.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// An exact operation failed (a size limit, say).
    #[error(transparent)]
    Scalar(#[from] ScalarError),
    /// Code generation refused the outputs.
    #[error(transparent)]
    Codegen(#[from] CodegenError),
    /// A task Jacobian needs the expanded pose, which exceeds the term limit.
    #[error("task Jacobians need the expanded pose, which exceeds {0} terms per entry (raise --term-limit)")]
    TaskTooLarge(usize),
    /// A symbol of the robot is also the name a recurrence gives one of its entries.
    #[error("symbol `{0}` is also an entry of the recurrence; rename it")]
    NameClash(String),
}

/// The report, or why it could not be made.
///
/// When the expanded pose exceeds `max_terms` terms per entry (a long chain with every
/// parameter symbolic grows exponentially: k 4^k terms after k DH links), the report is exact
/// but a recurrence over the joint factors, linear in the number of joints (see
/// [`fk_recurrence`](crate::app::fk_recurrence) for its entries): the joint factors `L{i}[k]` and,
/// with the Jacobian, their derivatives `dL{i}[k]` in closed form; the prefix products
/// `Q{i}[k]` of `Q{i} = Q{i-1} L{i}` in the symbols `Q{i-1}_k` and `L{i}_k`; `dq[k]` (the last
/// Q); with the Jacobian, the suffix products `P{i}[k]` of `P{i} = L{i} P{i+1}`; `T[i][j]` and
/// `p[i]` in the symbols of the last Q; and `J[k][i-1]`, component k of `Q{i-1} dL{i} P{i+1}`.
/// Entry `X[k]` is the symbol `X_k` of the entries after it (or its value, when that is a
/// constant such as the zeros of a planar link), in every format: SymPy lines stay
/// `NAME = EXPR` with these additional names, and the code formats compute the recurrence as
/// straight-line code, its entries as locals.
pub fn fk_report(robot: &Robot, o: &FkOptions) -> Result<String, ReportError> {
    fk_report_and_entries(robot, o).map(|(text, _)| text)
}

/// [`fk_report`], and the entries it printed: for a caller that ends right after printing
/// and need not drop them (the `dqsym` binary: dropping the PUMA 560's entries, many of them
/// made on the helper thread and freed across threads, took ~0.1 ms of its `fk --jacobian`).
///
/// # Errors
/// As [`fk_report`].
pub fn fk_report_and_entries(
    robot: &Robot,
    o: &FkOptions,
) -> Result<(String, FkEntries), ReportError> {
    // The joint factors once, for the expansions, the header's parameters and the recurrence.
    let joints = robot.made_joints();
    let params = robot.parameters_of(joints.dqs());
    let (entries, texts) = entries_of(robot, joints, o)?;
    let text = if entries.recurrence {
        let notes = [format!(
            "the expanded pose exceeds {} terms per entry: it is given exactly, as a recurrence over the joint factors (entry X[k] is the symbol X_k of later entries)",
            o.max_terms
        )];
        render_printed(robot, &params, &entries.sections, o, &notes, texts)?
    } else {
        render(robot, &params, &entries.sections, o, &[])?
    };
    Ok((text, entries))
}

/// The operation counts of the code [`fk_report`] generates for `robot` (`dqsym ops ROBOT`):
/// the numeric product of the joints' dual quaternions, then the generated function's
/// multiplications, additions, negations and sin/cos calls, for the dual quaternion alone and
/// for every output (`o.point`, `o.jacobian`). `o.format` and `o.shorthand` are not read.
///
/// # Errors
/// As [`fk_report`].
pub fn fk_ops(robot: &Robot, o: &FkOptions) -> Result<String, ReportError> {
    let entries = fk_entries(robot, o)?;
    Ok(code(robot, &entries.sections, Generated::Ops)?)
}

/// The entries of [`fk_report`] before any formatting (`o.format` and `o.shorthand` are not
/// read), for callers
/// that take closed forms rather than text (the Python package).
#[derive(Clone, Debug)]
pub struct FkEntries {
    /// The sections of `(entry, closed form)` rows: `dq[k]`, `T[i][j]`, `p[i]`, `J[i][j]`, and
    /// for a recurrence `L{i}[k]`, `Q{i}[k]`, ... ([`Quantity::name`]).
    pub sections: Vec<Section>,
    /// Whether the pose is a recurrence over the joint factors (a stage exceeded
    /// `o.max_terms`): entry `X[k]` is then the symbol `X_k` of the entries after it.
    pub recurrence: bool,
}

impl FkEntries {
    /// Every entry in order, named as in the report (`dq[3]`, `T[1][2]`, `Q2[3]`).
    pub fn named_rows(&self) -> Vec<(String, Expr)> {
        self.rows().map(|(q, e)| (q.name(), e.clone())).collect()
    }

    /// Every entry in order.
    pub fn rows(&self) -> impl Iterator<Item = &(Quantity, Expr)> {
        self.sections.iter().flat_map(|s| &s.rows)
    }
}

/// The closed forms of [`fk_report`], section by section.
///
/// # Errors
/// As [`fk_report`].
pub fn fk_entries(robot: &Robot, o: &FkOptions) -> Result<FkEntries, ReportError> {
    entries_of(robot, robot.made_joints(), o).map(|(entries, _)| entries)
}

/// [`fk_entries`] from the robot's joint factors `joints` ([`Robot::made_joints`]): the
/// recurrence takes them as the expansion leaves them (it moves them out only for the DQ
/// product, past the matrix product that gives a fully symbolic chain up). With the entries,
/// the text of a recurrence's matrix in cosines and sines, printed already ([`CosSinTexts`]).
fn entries_of(
    robot: &Robot,
    mut joints: MadeJoints,
    o: &FkOptions,
) -> Result<(FkEntries, Option<CosSinTexts>), ReportError> {
    // Any stage past the term limit (the DQ, the matrix, the point, the Jacobian, a closed
    // form) switches to the recurrence, whose every entry is small.
    // The expansion is an attempt with a budget of its own (what is left of the caller's), so
    // that running out of it, or a report longer than `MAX_EXPANDED_TEXT`, leaves the whole
    // budget to the recurrence.
    let left = Context::current()
        .work_budget()
        .saturating_sub(crate::scalar::work_used());
    let expanded = with_own_budget(left, || expanded_entries(robot, &mut joints, o));
    match expanded {
        // Every size limit: too many terms, term pairs (a product of the constant frames of
        // a URDF with angles off the pi/12 grid), digits or symbols in one angle (a long chain
        // of collinear axes), or work.
        Some(Err(ReportError::Scalar(
            ScalarError::TooLarge { .. }
            | ScalarError::TooManyPairs { .. }
            | ScalarError::TooManyDigits { .. }
            | ScalarError::AngleSymbols { .. }
            | ScalarError::Budget { .. },
        )))
        | None => recurrence_entries(robot, &joints, o),
        Some(r) => r.map(|sections| {
            let entries = FkEntries {
                sections,
                recurrence: false,
            };
            (entries, None)
        }),
    }
}

/// The most bytes the entries of an expanded report may take in plain text before the
/// recurrence, linear in the number of joints, is printed instead (a numeric 10-joint chain
/// whose expansion fits the term limit can print 650 kB; its recurrence about 50 kB).
const MAX_EXPANDED_TEXT: usize = 100_000;

/// Whether the plain text of the closed forms of `sections` is longer than `max` bytes. The
/// text is only written when a bound of its length ([`plain_len_bound`], a few times the
/// length) exceeds `max`: a report well within `max` is not printed twice.
pub(super) fn text_exceeds(sections: &[Section], max: usize) -> bool {
    let rows = || sections.iter().flat_map(|s| &s.rows);
    let po = PlainOptions {
        shorthand: true,
        decimals: false,
    };
    let length = || rows().map(|(_, e)| plain(e, &po).len()).sum::<usize>();
    let bound: usize = rows().map(|(_, e)| plain_len_bound(e)).sum();
    if bound > max {
        // Printed row by row until past `max` (a symbolic chain's pose prints megabytes).
        let mut total = 0;
        return rows().any(|(_, e)| {
            total += plain(e, &po).len();
            total > max
        });
    }
    debug_assert!(length() <= bound, "plain_len_bound is not a bound");
    false
}

fn recurrence_entries(
    robot: &Robot,
    joints: &MadeJoints,
    o: &FkOptions,
) -> Result<(FkEntries, Option<CosSinTexts>), ReportError> {
    let (sections, texts) = recurrence_sections_printed(robot, Some(joints), o)?;
    let entries = FkEntries {
        sections,
        recurrence: true,
    };
    Ok((entries, texts))
}

/// The sections of a report.
type Sections = Vec<Section>;

/// The expanded entries, or `None` when the DQ or the matrix exceeds `o.max_terms` terms.
/// `joints` are moved out only when the DQ product is begun.
fn expanded_entries(
    robot: &Robot,
    joints: &mut MadeJoints,
    o: &FkOptions,
) -> Option<Result<Sections, ReportError>> {
    // The matrix (the product of the joint factors' matrices), then its entries in closed
    // form; the DQ product, then its components. Then the point and the Jacobian, every
    // distinct entry once, in parallel. `closed_form` is a pure function of its input, so
    // neither the threads nor the sharing of equal entries change the output.
    // Each expansion stops as soon as an entry exceeds the limit, before its closed forms.
    // The matrix goes first: it grows faster, on numeric chains (3^k modes against 2^k) and
    // on symbolic ones (a fully symbolic 5R: 6,688 terms against the DQ's 5,120), and
    // predicts its overflow from its growth, and when it is abandoned the DQ is never made.
    // They run one after the other, not side by side: the DQ product beside an abandoned
    // matrix noticed the stop only between two factors, after a product thrown away (whole
    // `fk --jacobian` processes, callgrind, one thread / two: generic 6R 573 M / 2,224 M
    // instructions, of which 1,640 M in that DQ product; a 20-joint symbolic chain 75 / 149 ms
    // CPU; the PUMA 560 51 M / 49 M instructions, both expansions small).
    // The pose's text is summed as its closed forms are found, and the rest given up once it
    // is past `MAX_EXPANDED_TEXT` (see `pose_text_exceeds`). The matrix's closed forms come
    // before the DQ product: when they alone print past the limit, the report is the
    // recurrence whatever the DQ adds, and the DQ is never multiplied out (a fully symbolic
    // 4R: two matrix entries of 59 kB each, where the DQ product and the closed forms of its
    // components cost 160 M instructions). Its large entries' closed forms are found as the
    // last product makes them, largest first, so that the entries after the limit are never
    // made either (the 4R's other ten; on the offset-free route all sixteen are made and
    // shifted back first, then shown largest first: more work, the same decision). Neither
    // order changes what is decided: the sum only grows.
    let text = PoseText::default();
    let stop = AtomicBool::new(false);
    let (dq_turns, t_turns) = pose_turns(robot);
    // Both products multiply the joint factors without their constant angle offsets where
    // that gives the same entries and decisions (`OffsetFree`), the offsets put back once
    // per entry: the partial products then carry no cyclotomic phases.
    let free = robot.offset_free(joints.dqs());
    // The matrix product, with the closed forms of its large entries found as it makes them.
    let product = |factors| {
        let mut t_forms: Vec<Option<PoseForm>> = (0..12).map(|_| None).collect();
        let mut seen = |i: usize, j: usize, x: &Scalar| {
            if i == 3 || x.len() < EARLY_FORM_TERMS {
                return true;
            }
            let f = report_form(x, None);
            text.add(&f);
            t_forms[4 * i + j] = Some((f, None));
            !text.exceeded()
        };
        // Offset-free, the product as multiplied is kept beside it (`made`) for the hints.
        let (m, made) = match free
            .as_ref()
            .and_then(|f| robot.forward_matrix_offset_free(f, o.max_terms, &stop, &mut seen))
        {
            Some(m) => m.map(|(m, made)| (m, Some(made)))?,
            None => (
                robot.forward_matrix_until(factors, o.max_terms, &stop, &mut seen)?,
                None,
            ),
        };
        Some((m, t_forms, made))
    };
    // The closed forms of the matrix's other entries (`pose_forms` is a `par_map`), each told
    // the offset-free entry it was shifted back from (`hint_of`).
    type Made = (
        crate::Matrix4<Scalar>,
        Vec<Option<PoseForm>>,
        Option<crate::Matrix4<Scalar>>,
    );
    let matrix_forms = |(m, found, made): Made| {
        let cells = matrix_cells(&m);
        let made_cells = made.as_ref().map(matrix_cells);
        let (forms, _) = pose_forms(&cells, found, &text, &t_turns, |x| {
            let hint = hint_of(x, &cells, free.as_ref(), made_cells.as_deref());
            (report_form(x, hint), None)
        });
        if text.exceeded() {
            stop.store(true, Ordering::Relaxed);
        }
        (m, forms)
    };
    let dq_product = |joints| {
        if text.exceeded() {
            return None;
        }
        match free
            .as_ref()
            .and_then(|f| robot.forward_within_offset_free(f, o.max_terms, &stop))
        {
            Some(q) => q.map(|(q, made)| (q, Some(made))),
            None => robot
                .forward_within_until(joints, o.max_terms, &stop)
                .map(|q| (q, None)),
        }
    };
    // The DQ product on the helper while this thread begins the matrix's closed forms; the
    // helper takes the closed forms left once the product is done. Before, the product (2.6 M
    // instructions of the PUMA 560's 36 M, 1.7 M of it the product of its two halves) ran
    // alone between two parallel stages. It is not begun once the matrix's text is past the
    // limit (one thread: the closed forms come first, as before), and stops between two
    // factors once it is. It is not made beside the matrix product: a matrix abandoned for its
    // size (a fully symbolic 6R) would leave the DQ product's work thrown away (two threads:
    // 202 M instructions instead of 188 M). Unless the matrix stays small
    // (`FactorMatrices::small`: neither its size nor the text of its entries' closed forms
    // abandons it, as on the PUMA 560): then the DQ product is begun beside the matrix
    // product, which ran alone while the helper waited (PUMA 560 `fk --jacobian`, SCHED_FIFO
    // runs: wall minimum 4.31 -> 4.26 ms, median 4.54 -> 4.49 ms).
    // Their matrices are kept in `joints` for the recurrence that follows a pose given up.
    let factors = robot.factor_matrices(
        joints.dqs(),
        EARLY_FORM_TERMS.min(o.max_terms),
        joints.matrices(),
    );
    let (matrix, q) = if factors.small() {
        let joints = joints.take();
        join(|| product(factors).map(matrix_forms), || dq_product(joints))
    } else {
        let made = product(factors)?;
        let joints = joints.take();
        let (matrix, q) = join(|| matrix_forms(made), || dq_product(joints));
        (Some(matrix), q)
    };
    let (m, t_forms) = matrix?;
    if text.exceeded() {
        return None;
    }
    let (q, made) = q?;
    let comps = q.components();
    let comp_refs: Vec<&Scalar> = comps.iter().collect();
    let made_refs: Option<Vec<&Scalar>> = made.as_ref().map(|m| m.iter().collect());
    let none = (0..comp_refs.len()).map(|_| None).collect();
    // The point's image and the Jacobian (derivatives of the DQ's components) on the helper
    // while this thread begins the DQ's closed forms, as above; not made once the pose's text
    // is past the limit.
    let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
    let ((forms, dq_turned), (img, jac)) = join(
        || {
            pose_forms(&comp_refs, none, &text, &dq_turns, |x| {
                let hint = hint_of(x, &comp_refs, free.as_ref(), made_refs.as_deref());
                let (e, p) = report_form_prepared(x, hint);
                (e, Some(p))
            })
        },
        || {
            if text.exceeded() {
                return (None, None);
            }
            (
                o.point.as_ref().map(|p| q.transform_point(p)),
                o.jacobian.then(|| dq_jacobian(&q, &vars)),
            )
        },
    );
    drop(made_refs);
    drop(made);
    if text.exceeded() {
        return None;
    }
    let (dq_forms, prepared): (Vec<_>, Vec<_>) = forms.into_iter().flatten().unzip();
    let t_forms: Vec<_> = t_forms.into_iter().flatten().map(|(e, _)| e).collect();
    // One offset per angle across the report (`closed/common.rs`), chosen from the pose's
    // entries and shown in every entry.
    let common = CommonOffsets::from_forms(dq_forms.iter().chain(&t_forms).flatten());
    // The pose's rows are rows of the report as they stand: when their text alone is past
    // `MAX_EXPANDED_TEXT`, the report is the recurrence whatever the Jacobian and the point
    // add, so their closed forms (most of the work on a fully symbolic chain) are never made.
    let pose_entries = dq_forms.len() + t_forms.len();
    if !text.all_within(pose_entries, 0) && pose_text_exceeds(&dq_forms, &t_forms, &common) {
        return None;
    }
    let (sections, rest_bound) = match expanded_sections(
        &q, &vars, img, jac, dq_forms, prepared, &dq_turned, t_forms, m,
    ) {
        Ok(made) => made,
        Err(e) => return Some(Err(e)),
    };
    let sections: Sections = sections
        .into_iter()
        .map(|s| Section {
            kind: s.kind,
            rows: s
                .rows
                .into_iter()
                .map(|(n, e)| (n, common.apply(e)))
                .collect(),
        })
        .collect();
    // A report longer than `MAX_EXPANDED_TEXT` is the recurrence. When every row is final
    // before the offsets were chosen, the sum of the bounds found with the closed forms
    // (in parallel) says so, or not, without bounding every row again.
    let within = rest_bound.is_some_and(|more| text.all_within(pose_entries, more));
    if !within && text_exceeds(&sections, MAX_EXPANDED_TEXT) {
        return None;
    }
    Some(Ok(sections))
}

/// What the closed form of the pose entry `x` is told of it (`closed::report_form_prepared`):
/// when the pose was multiplied offset-free (`free`) and `made` holds the entries as
/// multiplied, in the order of `entries` (the same pose's entries, shifted back), the one at
/// `x`'s place, found by its address (`pose_forms` shows its closures the entries
/// themselves); else none, which changes nothing but the work.
fn hint_of<'a>(
    x: &Scalar,
    entries: &[&Scalar],
    free: Option<&'a crate::kin::OffsetFree>,
    made: Option<&[&'a Scalar]>,
) -> Option<Hint<'a>> {
    #[cfg(test)]
    if tests::NO_HINTS.with(std::cell::Cell::get) {
        return None;
    }
    let k = entries.iter().position(|e| std::ptr::eq(*e, x))?;
    let hint = free?.hint(made?.get(k)?);
    #[cfg(test)]
    tests::HINTS_GIVEN.with(|n| n.set(n.get() + 1));
    Some(hint)
}

/// A pose entry's closed form (and, for a DQ component, its prepared form).
type PoseForm = (Result<Expr, ScalarError>, Option<crate::closed::Prepared>);

/// The matrix entries of at least this many terms whose closed forms are found as the
/// matrix product makes them (one after the other); the others' are found after it, in
/// parallel. Either way they are the same closed forms: only the work stopped early differs.
const EARLY_FORM_TERMS: usize = 512;

/// The closed forms `form` of the pose's `entries`, in their order, those of `found` kept
/// (and counted in `text` already), the others counted in `text`; once `text` is past
/// [`MAX_EXPANDED_TEXT`] the entries not yet begun are `None`. The entries are begun largest
/// first (by terms): the longest texts are found first, so the limit is passed after as few
/// closed forms as the entries allow.
///
/// An entry that is a turn of an earlier one (`turned_entries` with `turns`: a rational
/// multiple of it with a joint angle turned, the second row of `Rz(q1) M`) takes that one's
/// form turned (`turn::turned_form`), not a search of its own; the entries so made are
/// returned beside the forms. One whose turned form is not found (an error, a form past the
/// text limit, a failed check) is searched after all.
///
/// What it changes: a turned row is its partner's form turned, not its own search's, and the
/// search is no function of the turn (its costs see signs, its ties the order of the atoms).
/// Measured on the `fk --jacobian` reports of the 61 robot files and `benches/support/`
/// (3,256 rows; with the Jacobian's rows turned alike, `expanded_sections`, the recurrence's
/// matrix, `recurrence::cos_sin_forms`, and the forms in the joints' angles,
/// `closed::report_form_prepared`): 421 rows change, 274 print shorter (4,614 characters in
/// all), 62 as long, 85 longer (1,934 characters; a 7-joint arm's `dq[7]` by 93, where its own
/// search found a grouping the search of its partner did not). Instructions (callgrind, one
/// thread, session 31), the turns alone: Jaco-style arm 115.6 M -> 78.3 M, PUMA 560 21.1 M ->
/// 16.6 M.
fn pose_forms(
    entries: &[&Scalar],
    found: Vec<Option<PoseForm>>,
    text: &PoseText,
    turns: &[Turn],
    form: impl Fn(&Scalar) -> PoseForm + Sync,
) -> (Vec<Option<PoseForm>>, Vec<Option<Turned>>) {
    let mut turned = turned_entries(entries, turns, TURNED_TERMS);
    let mut order: Vec<usize> = (0..entries.len())
        .filter(|&k| found[k].is_none() && turned[k].is_none())
        .collect();
    order.sort_by_key(|&k| std::cmp::Reverse(entries[k].len()));
    let made = par_map(&order, |&k| {
        if text.exceeded() {
            return None;
        }
        let f = form(entries[k]);
        text.add(&f.0);
        Some(f)
    });
    let mut forms = found;
    for (k, f) in order.into_iter().zip(made) {
        forms[k] = f;
    }
    for k in 0..entries.len() {
        let Some(t) = &turned[k] else {
            continue;
        };
        if forms[k].is_some() {
            // Found before (as the matrix product made it).
            turned[k] = None;
            continue;
        }
        if text.exceeded() {
            continue;
        }
        let from = match &forms[t.from] {
            Some((Ok(e), _)) => turn::turned_form(e, t, entries[k]),
            _ => None,
        };
        let f = match from {
            Some(e) => (Ok(e), None),
            None => {
                turned[k] = None;
                form(entries[k])
            }
        };
        text.add(&f.0);
        forms[k] = Some(f);
    }
    (forms, turned)
}

/// The fewest terms a pose entry must have to be looked at as a turn of another
/// ([`turned_entries`]): below it, its own search costs about what the turn does.
const TURNED_TERMS: usize = 8;

/// The turns [`pose_forms`] tries, for the dual quaternion's components (half angles: a
/// turn by pi) and for the matrix's entries (a quarter turn): the first joint's and the last
/// joint's, when revolute and their values plain symbols (`Rz(q1)` first: the matrix's second
/// row is a turn of its first; the last joint's turn relates its first two columns), and the
/// twist that ends a DH chain or begins a modified-DH one when it is a plain symbol (`M
/// Rx(alpha)`: the third column is a turn of the second).
pub(super) fn pose_turns(robot: &Robot) -> (Vec<Turn>, Vec<Turn>) {
    // The symbol of joint `i`, when it is revolute and its value is one.
    let angle = |i: usize| {
        let joint = robot.chain.joints.get(i)?;
        let value = robot.joint_values.get(i)?;
        (joint.kind == JointKind::Revolute)
            .then(|| value.as_plain_symbol())
            .flatten()
    };
    let mut syms: Vec<Sym> = angle(0).into_iter().collect();
    let n = robot.chain.joints.len();
    let last = n.checked_sub(1).and_then(angle);
    if let Some(l) = last.filter(|l| !syms.contains(l)) {
        syms.push(l);
    }
    // The twist that begins or ends the product, when it is a plain symbol: the last DH
    // joint's `Rx(alpha)` (no tool frame after it) turns the matrix's columns 1 and 2 into
    // each other, the first modified-DH joint's (no base frame before it) its rows 1 and 2.
    let twist = |i: usize, dh: bool| match &robot.chain.joints.get(i)?.geometry {
        JointGeometry::Dh { alpha, .. } if dh => alpha.as_plain_symbol(),
        JointGeometry::Mdh { alpha, .. } if !dh => alpha.as_plain_symbol(),
        _ => None,
    };
    let ends = [
        robot.base_frames.is_empty().then(|| twist(0, false)),
        robot
            .tool_frames
            .is_empty()
            .then(|| n.checked_sub(1).and_then(|l| twist(l, true))),
    ];
    for t in ends.into_iter().flatten().flatten() {
        if !syms.contains(&t) && !robot.variables.iter().any(|v| v == t.name()) {
            syms.push(t);
        }
    }
    let dq = syms
        .iter()
        .map(|s| (s.clone(), Small::from_integer(1)))
        .collect();
    let t = syms.into_iter().map(|s| (s, Small::new(1, 2))).collect();
    (dq, t)
}

/// The plain text of the pose's closed forms found so far, counted as they are found (by
/// every thread), of the entries whose text is final before the report's common offsets are
/// chosen ([`CommonOffsets::fixes`]: every entry of a chain without offsets). Once it is past
/// [`MAX_EXPANDED_TEXT`], [`pose_text_exceeds`] would say so for the whole pose (the other
/// entries only add text), so the closed forms not yet begun are never made: a fully symbolic
/// 4R spent 330 M of its 534 M instructions on the closed forms of a pose thrown away for the
/// recurrence. When the sum stays below, every form is made and the decision is
/// `pose_text_exceeds`'s, as before.
#[derive(Default)]
struct PoseText {
    /// The sum of [`plain_len_bound`] over the entries counted.
    bound: AtomicUsize,
    /// The exact length of the entries printed: a lower bound of the text of those counted.
    bytes: AtomicUsize,
    /// The number of entries counted.
    counted: AtomicUsize,
}

impl PoseText {
    fn add(&self, e: &Result<Expr, ScalarError>) {
        let (Some(bound), Ok(e)) = (final_bound(e), e) else {
            return;
        };
        self.counted.fetch_add(1, Ordering::Relaxed);
        // Printed only once the bounds say the text may be past the limit: the PUMA's pose
        // is never printed here.
        if self.bound.fetch_add(bound, Ordering::Relaxed) + bound <= MAX_EXPANDED_TEXT {
            return;
        }
        let po = PlainOptions {
            shorthand: true,
            decimals: false,
        };
        self.bytes.fetch_add(plain(e, &po).len(), Ordering::Relaxed);
    }

    fn exceeded(&self) -> bool {
        self.bytes.load(Ordering::Relaxed) > MAX_EXPANDED_TEXT
    }

    /// Whether all `n` entries of the pose were counted (none an error, every one's text final
    /// before the report's offsets are chosen) and the sum of their bounds and `more` is
    /// within [`MAX_EXPANDED_TEXT`]: then [`pose_text_exceeds`] (`more` 0), or
    /// [`text_exceeds`] of the report whose other rows' bounds sum to `more`, is false, and is
    /// not asked (it clones or bounds every entry again; the PUMA 560's).
    fn all_within(&self, n: usize, more: usize) -> bool {
        self.counted.load(Ordering::Relaxed) == n
            && self.bound.load(Ordering::Relaxed).saturating_add(more) <= MAX_EXPANDED_TEXT
    }
}

/// Whether the pose's rows (the DQ's and the matrix's closed forms, shown at the report's
/// common offsets) alone print more than [`MAX_EXPANDED_TEXT`] bytes, which makes the report
/// a recurrence whatever follows them. An entry that is an error leaves the decision to the
/// report (`false`).
fn pose_text_exceeds(
    dq_forms: &[Result<Expr, ScalarError>],
    t_forms: &[Result<Expr, ScalarError>],
    common: &CommonOffsets,
) -> bool {
    // Only the rows' text counts: the entries are named as the pose section names them.
    let names = (0..dq_forms.len())
        .map(Quantity::Dq)
        .chain((0..t_forms.len()).map(|k| Quantity::T(k / 4, k % 4)));
    let Ok(rows) = dq_forms
        .iter()
        .chain(t_forms)
        .zip(names)
        .map(|(e, n)| e.clone().map(|e| (n, common.apply(e))))
        .collect::<Result<Vec<_>, _>>()
    else {
        return false;
    };
    let pose = Section {
        kind: SectionKind::Pose { last_q: false },
        rows,
    };
    text_exceeds(&[pose], MAX_EXPANDED_TEXT)
}

/// `sections` as a robot whose file wrote decimals reads them (`0.425 c2`), exactly: the
/// denominators pulled out of sums put back ([`decimal_form`]); unchanged for other robots.
/// The report and Python's `Robot` both show entries so.
pub fn in_decimals(robot: &Robot, sections: &mut [Section]) {
    if robot.decimals.is_empty() {
        return;
    }
    for s in sections {
        for (_, e) in &mut s.rows {
            *e = decimal_form(e, &robot.decimals);
        }
    }
}

/// The report from the expanded DQ and matrix and their closed forms. `img` is the point's
/// image (when the report has a point) and `jac` the Jacobian of `q` in `vars` (when it has
/// one). With it, the sum of [`final_bound`] over the rows after the pose's, when every one
/// has one.
#[allow(clippy::too_many_arguments)]
fn expanded_sections(
    q: &DualQuat<Scalar>,
    vars: &[&str],
    img: Option<[Scalar; 3]>,
    jac: Option<Vec<Vec<Scalar>>>,
    dq_forms: Vec<Result<Expr, ScalarError>>,
    prepared: Vec<Option<crate::closed::Prepared>>,
    dq_turned: &[Option<Turned>],
    t_forms: Vec<Result<Expr, ScalarError>>,
    m: crate::Matrix4<Scalar>,
) -> Result<(Sections, Option<usize>), ReportError> {
    let comps = q.components();
    let cells = matrix_cells(&m);
    // Each entry with, for a Jacobian entry, the DQ component it is the derivative of and the
    // variable: its closed form starts from that component's regrouped monomials.
    type Entry<'a> = (Quantity, &'a Scalar, Option<(usize, &'a str)>);
    let mut rest: Vec<Entry> = Vec::new();
    if let Some(img) = &img {
        for (k, c) in img.iter().enumerate() {
            rest.push((Quantity::Point(k), c, None));
        }
    }
    if let Some(jac) = &jac {
        for (i, row) in jac.iter().enumerate() {
            for (k, x) in row.iter().enumerate() {
                rest.push((Quantity::J { row: i, col: k }, x, Some((i, vars[k]))));
            }
        }
    }
    // Entries often repeat (a Jacobian column of two joints that always appear together,
    // say, or equal to a DQ component): each distinct scalar is put in closed form once.
    // Keyed by a few terms of each entry (`SampledKey`), sized once: hashing and rehashing
    // every term of every entry was 4% of the PUMA 560's report.
    let mut known: FxMap<SampledKey, &Result<Expr, ScalarError>> = FxMap::default();
    if !rest.is_empty() {
        known.reserve(comps.len() + cells.len());
        for (x, e) in comps.iter().zip(&dq_forms) {
            known.entry(SampledKey(x)).or_insert(e);
        }
        for (x, e) in cells.iter().zip(&t_forms) {
            known.entry(SampledKey(x)).or_insert(e);
        }
    }
    // Each row's source, found in one lookup per row (hashing and comparing a repeated
    // entry's terms again for its source was 1% of the PUMA 560's report): a pose entry's
    // form, or the index of a class of entries to put in closed form, with the factor the
    // row is of it. A class holds the rows that are rational multiples of each other
    // (`ProportionalKey`: equal canonical forms up to a rational factor, exactly, whatever
    // the chain: the Jaco-style arm's entries in `q2 - q3` and `q3 - q2`); its first row is
    // put in closed form and the others take that form times their factor (`Expr::scaled`).
    // Rows proportional to a pose entry but not equal to it are searched as before: taking
    // the pose's forms times their factor changed 147 rows of the robots in examples/ and
    // tests/data/, 45 of them printed longer than before (mdh's J[4][0]: 183 -> 306
    // characters, the pose's search having kept the Fourier sum), where rows taking an
    // earlier row's form changed 42 rows, none longer. Measured again after those (140 rows
    // change, 55 longer, 74 shorter), no gate read off the row or the pose's form before the
    // row's search keeps only the rows no longer: 23 of the 55 have a higher cost key, the
    // other 32 the key of the row's own form, an equal-cost factorization or sign placement
    // printing 1 to 6 characters longer, beside rows of the same terms and key printing
    // shorter (51 such rows; franka_panda's J[1][0] 447 -> 450, its J[0][0] 453 -> 444;
    // puma_like's J[0][0] 287 -> 288, its J[0][5] 289 -> 287). Taking every such row would
    // save 2.6% of the PUMA 560's instructions and 3.4% of the Jaco-style arm's.
    let mut index: FxMap<ProportionalKey, usize> = FxMap::default();
    index.reserve(rest.len());
    let mut distinct: Vec<(&Scalar, Option<(usize, &str)>)> = Vec::new();
    type Source<'a> = Result<&'a Result<Expr, ScalarError>, usize>;
    // A row of a component that is a turn of another (`pose_forms`) is the same turn of that
    // component's row in the same column (a turn of a joint angle commutes with the
    // derivative in every variable): a distinct row so is not searched but turned from its
    // partner's form, when that is a pose entry's or a searched row's. Rows of the Jacobian
    // come after the point's, in order.
    let jac_start = rest
        .iter()
        .position(|(q, _, _)| matches!(q, Quantity::J { .. }))
        .unwrap_or(rest.len());
    let mut distinct_turn: Vec<Option<(usize, &Turned)>> = Vec::new();
    let mut sources: Vec<(Source, Q)> = Vec::with_capacity(rest.len());
    for (q, x, from) in &rest {
        if let Some(e) = known.get(&SampledKey(x)) {
            sources.push((Ok(*e), Q::ONE));
            continue;
        }
        let key = ProportionalKey(x);
        let source = match index.entry(key) {
            MapEntry::Occupied(o) => (Err(*o.get()), key.factor(o.key())),
            MapEntry::Vacant(v) => {
                let turn = match (q, from) {
                    (Quantity::J { col, .. }, Some((i, _))) => {
                        dq_turned.get(*i).and_then(Option::as_ref).and_then(|t| {
                            let partner = jac_start + t.from * vars.len() + col;
                            match sources.get(partner)?.0 {
                                Ok(_) => Some((partner, t)),
                                Err(j) if distinct_turn[j].is_none() => Some((partner, t)),
                                Err(_) => None,
                            }
                        })
                    }
                    _ => None,
                };
                distinct.push((x, *from));
                distinct_turn.push(turn);
                v.insert(distinct.len() - 1);
                (Err(distinct.len() - 1), Q::ONE)
            }
        };
        sources.push(source);
    }
    let search = |k: usize| match distinct[k] {
        (x, Some((i, var))) => match &prepared[i] {
            Some(p) => closed_form_of_derivative(p, var, x),
            None => report_form(x, None),
        },
        (x, None) => report_form(x, None),
    };
    // Begun largest first (by terms), so that the last closed forms to end, when one thread
    // may wait for the other, are small ones.
    let mut order: Vec<usize> = (0..distinct.len())
        .filter(|&k| distinct_turn[k].is_none())
        .collect();
    order.sort_by_key(|&k| std::cmp::Reverse(distinct[k].0.len()));
    let made = par_map(&order, |&k| {
        let form = search(k);
        let bound = final_bound(&form);
        (form, bound)
    });
    // Each distinct entry's form (taken by its last row, below) and its text's bound.
    let mut forms: Vec<Option<Result<Expr, ScalarError>>> = vec![None; distinct.len()];
    let mut bounds: Vec<Option<usize>> = vec![None; distinct.len()];
    for (k, (f, b)) in order.into_iter().zip(made) {
        forms[k] = Some(f);
        bounds[k] = b;
    }
    // The turned rows, from their partners' forms (made above: a partner's class is never a
    // turned one), each searched when its turn is not found.
    for k in 0..distinct.len() {
        let Some((partner, t)) = distinct_turn[k] else {
            continue;
        };
        let (source, c) = &sources[partner];
        let base = match source {
            Ok(Ok(e)) => Some(e.clone()),
            Ok(Err(_)) => None,
            Err(j) => forms[*j].as_ref().and_then(|f| f.as_ref().ok()).cloned(),
        };
        let base = base.map(|e| if c.is_one() { e } else { e.scaled(&c.to_big()) });
        let form = match base.and_then(|e| turn::turned_form(&e, t, distinct[k].0)) {
            Some(e) => Ok(e),
            None => search(k),
        };
        bounds[k] = final_bound(&form);
        forms[k] = Some(form);
    }
    // Each row's form: a pose entry's, or a distinct entry's, moved into its last row and
    // cloned into the others. The pose's own rows take its forms after these, moved too
    // (cloning the PUMA 560's 68 rows and dropping the originals took ~0.1 ms after the last
    // parallel stage).
    let mut uses = vec![0usize; forms.len()];
    for &i in sources.iter().filter_map(|(s, _)| s.as_ref().err()) {
        uses[i] += 1;
    }
    // Each row's form and the bound of its text, when final (see `final_bound`); a multiple's
    // bound is its own form's.
    let (rest_forms, row_bounds): (Vec<Result<Expr, ScalarError>>, Vec<Option<usize>>) = sources
        .into_iter()
        .map(|(source, c)| {
            let (form, bound) = match source {
                Ok(e) => (e.clone(), final_bound(e)),
                Err(i) => {
                    uses[i] -= 1;
                    let form = if uses[i] == 0 {
                        forms[i].take()
                    } else {
                        forms[i].clone()
                    };
                    let form = form.expect("a distinct entry's form is taken by its last row only");
                    (form, bounds[i])
                }
            };
            if c.is_one() {
                return (form, bound);
            }
            let c = c.to_big();
            let form = form.map(|e| e.scaled(&c));
            let bound = final_bound(&form);
            (form, bound)
        })
        .unzip();
    // The bound of the rows' text, when every row's is final.
    let rest_bound: Option<usize> = row_bounds.into_iter().sum();
    drop(known);
    let mut sections: Vec<Section> = vec![
        Section {
            kind: SectionKind::Pose { last_q: false },
            rows: dq_forms
                .into_iter()
                .enumerate()
                .map(|(k, e)| Ok((Quantity::Dq(k), e?)))
                .collect::<Result<_, ScalarError>>()?,
        },
        Section {
            kind: SectionKind::Matrix(MatrixFrom::Expanded),
            rows: t_forms
                .into_iter()
                .enumerate()
                .map(|(c, e)| Ok((Quantity::T(c / 4, c % 4), e?)))
                .collect::<Result<_, ScalarError>>()?,
        },
    ];
    for ((q, _, _), form) in rest.iter().zip(rest_forms) {
        let kind = match q {
            Quantity::Point(_) => SectionKind::Point,
            _ => SectionKind::Jacobian { recurrence: false },
        };
        if sections.last().map(|s| &s.kind) != Some(&kind) {
            sections.push(Section {
                kind,
                rows: Vec::new(),
            });
        }
        let row = (*q, form?);
        if let Some(s) = sections.last_mut() {
            s.rows.push(row);
        }
    }
    Ok((sections, rest_bound))
}

/// [`plain_len_bound`] of a closed form whose text is final before the report's offsets are
/// chosen ([`CommonOffsets::fixes`]); `None` for an error or another form.
fn final_bound(e: &Result<Expr, ScalarError>) -> Option<usize> {
    e.as_ref()
        .ok()
        .filter(|e| CommonOffsets::fixes(e))
        .map(plain_len_bound)
}

/// Rows 0..2 of a matrix, row by row.
fn matrix_cells(m: &crate::Matrix4<Scalar>) -> Vec<&Scalar> {
    m.rows[..3].iter().flatten().collect()
}

/// The sections in `o.format` (plain and LaTeX with `o.shorthand`), after `notes` (comment
/// lines in plain and LaTeX); `params` are the robot's [`Robot::parameters`].
pub(super) fn render(
    robot: &Robot,
    params: &[String],
    sections: &[Section],
    o: &FkOptions,
    notes: &[String],
) -> Result<String, ReportError> {
    render_printed(robot, params, sections, o, notes, None)
}

/// [`render`], the rows of a matrix in cosines and sines taken from `texts` (their plain
/// text, shorthand and without decimals, [`CosSinTexts`]) where the report prints them so:
/// the same closed forms, printed the same way.
fn render_printed(
    robot: &Robot,
    params: &[String],
    sections: &[Section],
    o: &FkOptions,
    notes: &[String],
    texts: Option<CosSinTexts>,
) -> Result<String, ReportError> {
    let shorthand = o.shorthand;
    // A robot whose file wrote decimals reads in decimals (`0.425 c2`), exactly: the
    // denominators pulled out of sums put back, decimal fractions printed as decimals.
    let decimals = !robot.decimals.is_empty();
    // Copied only to be changed (a copy of a symbolic chain's entries cost a tenth of its
    // report).
    let mut copy;
    let sections = if decimals {
        copy = sections.to_vec();
        in_decimals(robot, &mut copy);
        &copy[..]
    } else {
        sections
    };
    Ok(match o.format {
        Format::Rust => code(robot, sections, Generated::Code(Lang::Rust))?,
        Format::C => code(robot, sections, Generated::Code(Lang::C))?,
        Format::Python => code(robot, sections, Generated::Code(Lang::Python))?,
        Format::Sympy => sections
            .iter()
            .flat_map(|s| {
                s.rows.iter().map(|(n, e)| {
                    let text = if decimals {
                        sympy_decimals(e)
                    } else {
                        sympy(e)
                    };
                    format!("{} = {text}\n", n.name())
                })
            })
            .collect(),
        Format::Plain => {
            let po = PlainOptions {
                shorthand,
                decimals,
            };
            let mut out = header(robot, params, Comment::Hash, "#");
            for n in notes {
                out.push_str(&line_comment(Comment::Hash, "#", n));
            }
            // The rows printed on the threads the closed forms were found on (printing was a
            // tenth of the PUMA 560's report, all of it after the last closed form). A matrix
            // in cosines and sines was printed already, in this report's options when
            // shorthand and without decimals (`sections` are then the entries themselves).
            let mut printed = texts.filter(|_| shorthand && !decimals).map(Vec::into_iter);
            let mut rows: Vec<(&(Quantity, Expr), Option<String>)> = Vec::new();
            for s in sections {
                let cos_sin = s.kind == SectionKind::Matrix(MatrixFrom::CosSin);
                for row in &s.rows {
                    let text = printed
                        .as_mut()
                        .filter(|_| cos_sin)
                        .and_then(Iterator::next);
                    rows.push((row, text));
                }
            }
            let lines = par_map(&rows, |((n, e), text)| match text {
                Some(text) => format!("{} = {text}\n", n.name()),
                None => format!("{} = {}\n", n.name(), plain(e, &po)),
            });
            let all: Vec<&Expr> = sections
                .iter()
                .flat_map(|s| s.rows.iter().map(|(_, e)| e))
                .collect();
            let leg = legend(&all);
            let legend_line =
                (shorthand && !leg.is_empty()).then(|| format!("# where {}\n", leg.join(", ")));
            let titles: Vec<String> = sections
                .iter()
                .map(|s| format!("# {}\n", s.kind.title()))
                .collect();
            // The report's size reserved once: a growing `String` copies itself into fresh
            // pages at every doubling (the PUMA 560's 18 kB report went through 8, 16 and 32 kB).
            out.reserve(
                lines
                    .iter()
                    .chain(&titles)
                    .chain(&legend_line)
                    .map(String::len)
                    .sum(),
            );
            let mut lines = lines.into_iter();
            for (s, title) in sections.iter().zip(&titles) {
                out.push_str(title);
                for line in lines.by_ref().take(s.rows.len()) {
                    out.push_str(&line);
                }
            }
            if let Some(line) = legend_line {
                out.push_str(&line);
            }
            out
        }
        Format::Latex => {
            let lo = LatexOptions {
                shorthand,
                decimals,
                ..LatexOptions::default()
            };
            let letters = Letters::avoiding(robot.variables.iter().chain(params).cloned());
            let mut out = header(robot, params, Comment::Latex, "% #");
            for n in notes {
                out.push_str(&line_comment(Comment::Latex, "%", n));
            }
            for s in sections {
                out.push_str(&format!("% {}\n", s.kind.title()));
                let rows: Vec<(String, Expr)> = s
                    .rows
                    .iter()
                    .map(|(n, e)| (n.latex(&letters), e.clone()))
                    .collect();
                out.push_str(&latex_aligned(&rows, &lo));
                out.push('\n');
            }
            out
        }
    })
}

/// What [`code`] writes: a function in one language, or the operation counts of the Rust one.
#[derive(Clone, Copy)]
enum Generated {
    Code(Lang),
    Ops,
}

/// The report's sections as one generated function: `dq` (8), `t` (3 x 4), `p` (3) and `j`
/// (8 x n), arguments the joint variables in joint order, then the parameters alphabetically.
/// The entries of a recurrence (`L1[k]`, `Q2[k]`, ...) are intermediate outputs: locals the
/// function computes in order, each read by the later ones as the symbol `L1_k`, `Q2_k`.
fn code(robot: &Robot, sections: &[Section], f: Generated) -> Result<String, CodegenError> {
    let n = robot.variables.len();
    // Consecutive entries of one family (`T` of `T[1][2]`) make one output.
    let mut groups: Vec<(Family, Vec<Expr>)> = Vec::new();
    for (q, e) in sections.iter().flat_map(|s| &s.rows) {
        let family = q.family();
        match groups.last_mut() {
            Some((b, v)) if *b == family => v.push(e.clone()),
            _ => groups.push((family, vec![e.clone()])),
        }
    }
    // The outputs up to the DQ's, for the counts of the DQ alone.
    let dq_end = groups
        .iter()
        .position(|(f, _)| *f == Family::Dq)
        .map_or(groups.len(), |i| i + 1);
    let outputs: Vec<Output> = groups
        .into_iter()
        .map(|(family, v)| family.output(v, n))
        .collect();
    let joints: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
    let args = arguments(&outputs, &joints);
    let name = snake(&robot.name);
    let form = if outputs.iter().any(|o| o.intermediate) {
        "its closed form, a recurrence over the joint factors"
    } else {
        "its closed form"
    };
    let doc = format!(
        "Forward kinematics of {} (generated by dqsym from {form}).",
        robot.name
    );
    let o = CodegenOptions::default();
    match f {
        Generated::Ops => {
            let mut out = header(robot, &robot.parameters(), Comment::Hash, "#");
            let n = robot.variables.len();
            let dq = count_ops(|| {
                let mk = |k: f64| Counted(k);
                let q = |a: f64| {
                    DualQuat::from_components([
                        mk(a),
                        mk(0.1),
                        mk(0.2),
                        mk(0.3),
                        mk(0.4),
                        mk(0.5),
                        mk(0.6),
                        mk(0.7),
                    ])
                };
                q(1.0) * q(0.5)
            })
            .1;
            out.push_str(&format!(
                "chain of {n} joint DQs, multiplied numerically: {} products of {} mult, {} add = {} mult, {} add\n",
                n.saturating_sub(1),
                dq.mul,
                dq.add,
                dq.mul * n.saturating_sub(1),
                dq.add * n.saturating_sub(1)
            ));
            for (label, outs) in [
                ("generated code, DQ only", &outputs[..dq_end]),
                ("generated code, all outputs", &outputs[..]),
            ] {
                let c = generated_ops(outs, &args, &o)?;
                out.push_str(&format!(
                    "{label}: {} mult, {} add, {} neg, {} sin/cos calls\n",
                    c.mul, c.add, c.neg, c.trig
                ));
            }
            Ok(out)
        }
        Generated::Code(lang) => syntax(lang).function(&name, &doc, &outputs, &args, &o),
    }
}

/// `PUMA 560` -> `puma_560_fk`.
fn snake(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    while s.contains("__") {
        s = s.replace("__", "_");
    }
    let s = s.trim_matches('_');
    // An empty name gives `robot_fk`, not `robot__fk` (rustc's snake-case lint rejects a
    // double underscore).
    let s = if s.is_empty() {
        "robot".to_string()
    } else if s.starts_with(|c: char| c.is_ascii_digit()) {
        format!("robot_{s}")
    } else {
        s.to_string()
    };
    format!("{s}_fk")
}

/// The report's first comment: the robot's name (every line of it commented, control
/// characters escaped), its joints and parameters `params`; `prefix` is `#`, or `% #` in
/// LaTeX.
fn header(robot: &Robot, params: &[String], syntax: Comment, prefix: &str) -> String {
    let text = format!(
        "{} ({} joint{}: {}; parameters: {})",
        robot.name,
        robot.variables.len(),
        if robot.variables.len() == 1 { "" } else { "s" },
        robot.variables.join(", "),
        if params.is_empty() {
            "none".to_string()
        } else {
            params.join(", ")
        }
    );
    line_comment(syntax, prefix, &text)
}

/// Tables 1 and 2 of the paper, counted by running each product (with the corrections of
/// ERRATA items 10 and 11), and the sec 7 chain of 3x3 rotations.
pub fn ops_tables() -> String {
    let mut out =
        String::from("# operations of one product, counted by running it (ERRATA 10, 11)\n");
    for (name, c) in product_table() {
        out.push_str(&format!(
            "{name}: {} mult, {} add, total {}\n",
            c.mul,
            c.add,
            c.mul + c.add
        ));
    }
    for n in [3usize, 6] {
        let c = rotation_chain_ops(n);
        out.push_str(&format!(
            "chain of {n} 3x3 rotations (orientation only): {} mult, {} add\n",
            c.mul, c.add
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::recurrence::recurrence_sections;
    use crate::kin::{random_test_chain, LARGEST_FIRST};
    use crate::Ring;

    thread_local! {
        /// Set by a test: no pose entry is told its offset-free entry (`hint_of`).
        pub(super) static NO_HINTS: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
        /// The pose entries told their offset-free entry on this thread.
        pub(super) static HINTS_GIVEN: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    }

    /// On random chains (3 to 6 joints, offsets of fifths of pi on some: the offset-free
    /// route), `fk`'s entries and decision with each pose entry told its offset-free entry
    /// (`hint_of`, `closed::offsets::Hint`) are those without (the route before), and some
    /// entries were told.
    #[test]
    fn fk_prints_as_without_the_offset_free_entries_told() {
        let mut next = crate::testing::xorshift_below(0x41e7_0f4e);
        let run = |robot: &Robot, hints: bool| {
            std::thread::scope(|s| {
                s.spawn(|| {
                    NO_HINTS.with(|f| f.set(!hints));
                    HINTS_GIVEN.with(|n| n.set(0));
                    let _in = crate::Context::new().with_threads(1).enter();
                    let o = FkOptions {
                        jacobian: true,
                        ..FkOptions::default()
                    };
                    let r = fk_entries(robot, &o).map(|e| (e.recurrence, e.named_rows()));
                    (format!("{r:?}"), HINTS_GIVEN.with(std::cell::Cell::get))
                })
                .join()
                .expect("the entries")
            })
        };
        let (mut told, mut robots) = (0, 0);
        for _ in 0..16 {
            let robot = random_test_chain(&mut next, 6);
            let (with, given) = run(&robot, true);
            let (without, none) = run(&robot, false);
            assert_eq!(none, 0);
            assert!(with == without, "{:?}", robot.chain);
            told += given;
            robots += usize::from(given > 0);
        }
        assert!(
            robots >= 3 && told >= 30,
            "{told} entries told, on {robots} chains"
        );
    }

    /// `fk`'s entries and decision (expanded or recurrence) on a thread of its own, with
    /// the matrix products' entries made largest first (`largest_first`, the order before
    /// `early_first`) or not.
    fn entries_in_order(robot: &Robot, o: &FkOptions, largest_first: bool) -> String {
        std::thread::scope(|s| {
            s.spawn(|| {
                LARGEST_FIRST.with(|f| f.set(largest_first));
                let _in = crate::Context::new().with_threads(1).enter();
                let r = fk_entries(robot, o).map(|e| (e.recurrence, e.named_rows()));
                format!("{r:?}")
            })
            .join()
            .expect("the entries")
        })
    }

    /// The entries of a random chain's pose: the DQ's components and the matrix's rows 0..2.
    fn pose_entries(next: &mut impl FnMut(u64) -> u64) -> (Vec<Scalar>, Vec<Sym>) {
        let robot = random_test_chain(next, 5);
        let q = robot.forward();
        let m = robot.forward_matrix();
        let mut entries: Vec<Scalar> = q.components().to_vec();
        entries.extend(m.rows[..3].iter().flatten().cloned());
        let vars = robot.variables.iter().map(|v| Sym::new(v)).collect();
        (entries, vars)
    }

    /// The turn of a scalar term by term (`turn::turned_scalar`) is the scalar shift of its
    /// angles (the canonical rewrite), on the entries of random chains (offsets of ninths,
    /// tenths and eighteenths of pi on some joints, prismatic joints, symbolic twists) turned
    /// by half and quarter turns of each variable, and by a turn that is not one (pi/3: no
    /// form term by term).
    #[test]
    fn a_scalar_turned_term_by_term_is_its_angles_shifted() {
        let mut next = crate::testing::xorshift_below(0x7e57_0031);
        let (mut turned, mut moved) = (0, 0);
        for _ in 0..12 {
            let (entries, vars) = pose_entries(&mut next);
            for x in &entries {
                for v in &vars {
                    for t in [Small::from_integer(1), Small::new(1, 2), Small::new(-3, 2)] {
                        let turn = (v.clone(), t);
                        let Some(y) = turn::turned_scalar(x, &turn) else {
                            continue;
                        };
                        let shifted = x.shift_angles(std::slice::from_ref(&turn));
                        assert_eq!(Some(&y), shifted.as_ref(), "{x} turned by {turn:?}");
                        turned += 1;
                        moved += usize::from(y != *x);
                    }
                    let third = (v.clone(), Small::new(1, 3));
                    let moves = x.shift_angles(std::slice::from_ref(&third)) != Some(x.clone());
                    assert!(!moves || turn::turned_scalar(x, &third).is_none());
                }
            }
        }
        assert!(
            turned > 1_000 && moved > 500,
            "{turned} turned, {moved} moved"
        );
    }

    /// A closed form turned (`turn::turned`) is the closed form of its scalar turned, exactly, on
    /// the closed forms of random chains' entries; an angle the turn does not take to a
    /// quarter turn (half a variable turned by a quarter) leaves no form.
    #[test]
    fn a_form_turned_is_the_form_of_the_turned_scalar() {
        let mut next = crate::testing::xorshift_below(0x7e57_0032);
        let mut checked = 0;
        for _ in 0..6 {
            let (entries, vars) = pose_entries(&mut next);
            for x in entries.iter().filter(|x| x.len() <= 64) {
                let Ok(e) = crate::closed_form(x) else {
                    continue;
                };
                for v in &vars {
                    for t in [
                        Small::from_integer(1),
                        Small::new(1, 2),
                        Small::from_integer(-1),
                    ] {
                        let turn = (v.clone(), t);
                        let Some(y) = x.shift_angles(std::slice::from_ref(&turn)) else {
                            continue;
                        };
                        match turn::turned(e.clone(), &turn) {
                            Some(f) => {
                                assert_eq!(f.to_scalar(), y, "{e:?} turned by {turn:?}");
                                checked += 1;
                            }
                            // Only half angles turned by a quarter turn have no form.
                            None => assert!(t.denom() % 2 == 0, "{e:?} by {turn:?}"),
                        }
                    }
                }
            }
        }
        assert!(checked > 300, "{checked} forms turned");
    }

    /// Among entries, each turned one is found with its source and factor, and only those:
    /// the entries of random chains with copies of some entries turned (the scalar shift of
    /// their angles) and scaled put among them; every pair found holds exactly, and every copy
    /// that is no multiple of an earlier entry is found.
    #[test]
    fn the_turned_entries_found_are_turns_of_their_sources() {
        let mut next = crate::testing::xorshift_below(0x7e57_0033);
        let (mut found, mut copies) = (0, 0);
        for _ in 0..20 {
            let (mut entries, vars) = pose_entries(&mut next);
            let turns = [
                (vars[0].clone(), Small::from_integer(1)),
                (vars[0].clone(), Small::new(1, 2)),
                (vars[vars.len() - 1].clone(), Small::from_integer(1)),
            ];
            let n = entries.len();
            for k in 0..10 {
                let x = entries[next(n as u64) as usize].clone();
                let turn = &turns[next(3) as usize];
                if x.len() < 2 || turn::turned_scalar(&x, turn).is_none() {
                    continue;
                }
                let y = x.shift_angles(std::slice::from_ref(turn)).expect("a turn");
                entries.push(&y * &Scalar::from_ratio(-(k as i64) - 1, 3));
            }
            let refs: Vec<&Scalar> = entries.iter().collect();
            let out = turn::turned_entries(&refs, &turns, 2);
            for (b, t) in out.iter().enumerate() {
                let Some(t) = t else {
                    continue;
                };
                assert!(t.from < b);
                let y = entries[t.from]
                    .shift_angles(std::slice::from_ref(&t.turn))
                    .expect("a turn");
                assert_eq!(entries[b], &y * &Scalar::rational(t.factor.to_big()));
                found += 1;
            }
            for b in n..entries.len() {
                let key = ProportionalKey(&entries[b]);
                if !entries[..b].iter().any(|x| ProportionalKey(x) == key) {
                    assert!(out[b].is_some(), "copy {b} not found");
                    copies += 1;
                }
            }
        }
        assert!(
            found >= 60 && copies >= 15,
            "{found} found, {copies} copies"
        );
    }

    /// Every row of `fk --jacobian` on random chains (3 to 6 joints; offsets, prismatic
    /// joints, symbolic twists) and on the Jaco-style arm's chain is its entry exactly: the
    /// rows turned from others (`closed/turn.rs`: the second half of the DQ's components and
    /// their Jacobian rows, the matrix's second row and the first two columns' pairs) among
    /// them, none of whose checks fails (a failed one would be searched, unseen).
    #[test]
    fn every_row_and_every_turned_row_is_its_entry() {
        let mut next = crate::testing::xorshift_below(0x7e57_0034);
        let mut robots: Vec<Robot> = (0..8).map(|_| random_test_chain(&mut next, 6)).collect();
        // The Jaco-style arm (tests/data/jaco_style.toml): a random chain's shell, its
        // joints replaced.
        let mut jaco = random_test_chain(&mut next, 6);
        let pi = |n: i64, d: i64| Scalar::pi() * Scalar::from_ratio(n, d);
        let sym = |name: &str| Scalar::sym(name);
        let table = [
            (pi(0, 1), sym("d1"), Scalar::int(0), pi(1, 2)),
            (pi(5, 9), Scalar::int(0), sym("a2"), pi(1, 1)),
            (pi(0, 1), sym("d3"), Scalar::int(0), pi(1, 2)),
            (pi(0, 1), sym("d4"), Scalar::int(0), pi(1, 3)),
            (pi(0, 1), sym("d5"), Scalar::int(0), pi(1, 3)),
            (pi(0, 1), sym("d6"), Scalar::int(0), pi(1, 1)),
        ];
        jaco.chain = crate::kin::Chain::new(
            table
                .into_iter()
                .map(|(theta, d, a, alpha)| crate::kin::Joint::revolute_dh(theta, d, a, alpha))
                .collect(),
        );
        jaco.variables = (1..=6).map(|i| format!("q{i}")).collect();
        jaco.joint_values = (1..=6).map(|i| sym(&format!("q{i}"))).collect();
        jaco.convention = crate::kin::Convention::Dh;
        robots.push(jaco);
        // Fully symbolic 3R chains, DH and modified DH: the twist that ends the first (its
        // third column a turn of its second) and begins the second (its third row a turn of
        // its second) is a turn too.
        let twisted = robots.len();
        for mdh in [false, true] {
            robots.push(crate::kin::symbolic_test_chain(&mut next, 3, mdh, "q"));
        }
        let mut turned_rows = 0;
        for (k, robot) in robots.iter().enumerate() {
            let _in = crate::Context::new().with_threads(1).enter();
            crate::closed::turn::counts::COUNTS.with(|c| c.set((0, 0)));
            let o = FkOptions {
                jacobian: true,
                ..FkOptions::default()
            };
            let entries = fk_entries(robot, &o).expect("a report");
            let (made, failed) = crate::closed::turn::counts::COUNTS.with(|c| c.get());
            assert_eq!(failed, 0, "{:?}", robot.chain);
            turned_rows += made;
            if k >= twisted {
                // The twist's turned entries: by name, those whose form would differ without
                // it (the third column of a DH chain, the third row of a modified-DH one).
                let twist = pose_turns(robot)
                    .1
                    .iter()
                    .filter(|(t, _)| t.name().starts_with("alpha"))
                    .count();
                assert_eq!(twist, 1, "{:?}", robot.chain);
                // 24 each; 20 without the twist's turns (the DH chain, measured).
                assert!(made >= 24, "{made} rows turned of {:?}", robot.chain);
            }
            if entries.recurrence {
                continue;
            }
            let q = robot.forward();
            let comps = q.components();
            let m = robot.forward_matrix();
            let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
            let jac = dq_jacobian(&q, &vars);
            for (quantity, e) in entries.rows() {
                let x = match *quantity {
                    Quantity::Dq(k) => &comps[k],
                    Quantity::T(i, j) => &m.rows[i][j],
                    Quantity::J { row, col } => &jac[row][col],
                    _ => continue,
                };
                assert_eq!(
                    e.to_scalar(),
                    *x,
                    "{} of {:?}",
                    quantity.name(),
                    robot.chain
                );
            }
        }
        assert!(turned_rows >= 100, "{turned_rows} rows turned");
    }

    /// On random chains (3 to 8 joints; symbolic, numeric and mixed parameters; offsets;
    /// prismatic joints) under term limits below and above the binary's 5,000, `fk` decides
    /// and prints as it did with the products' entries made largest first.
    #[test]
    fn fk_decides_as_with_the_largest_entries_first() {
        let mut next = crate::testing::xorshift_below(2929);
        let mut recurrences = 0;
        for _ in 0..10 {
            let robot = random_test_chain(&mut next, 8);
            for max_terms in [300, 5_000] {
                let o = FkOptions {
                    jacobian: true,
                    max_terms,
                    ..FkOptions::default()
                };
                let new = entries_in_order(&robot, &o, false);
                let old = entries_in_order(&robot, &o, true);
                assert!(new == old, "{:?} at {max_terms}", robot.chain);
                recurrences += usize::from(new.starts_with("Ok((true"));
            }
        }
        // 12 of the 20 reports are recurrences (10 chains, two limits).
        assert!(recurrences >= 8, "{recurrences} recurrences");
    }

    /// A recurrence's report prints the matrix in cosines and sines from the text kept when
    /// it was measured (`CosSinTexts`) as it prints it without, in every format and with or
    /// without the shorthand, on random chains and the fully symbolic 6R (whose matrix is
    /// made so); a robot read in decimals prints its own text.
    #[test]
    fn the_matrix_text_kept_is_the_matrix_printed() {
        let mut next = crate::testing::xorshift_below(3535);
        let mut robots: Vec<Robot> = (0..8).map(|_| random_test_chain(&mut next, 6)).collect();
        // A fully symbolic 6R (tests/data/generic_6r.toml): a random chain's shell, its joints
        // replaced.
        let mut r6 = random_test_chain(&mut next, 6);
        let s = |name: &str, i: usize| Scalar::sym(&format!("{name}{i}"));
        r6.chain = crate::kin::Chain::new(
            (1..=6)
                .map(|i| {
                    let (d, a, alpha) = (s("d", i), s("a", i), s("alpha", i));
                    crate::kin::Joint::revolute_dh(Scalar::int(0), d, a, alpha)
                })
                .collect(),
        );
        r6.variables = (1..=6).map(|i| format!("theta{i}")).collect();
        r6.joint_values = (1..=6).map(|i| s("theta", i)).collect();
        r6.convention = crate::kin::Convention::Dh;
        robots.push(r6);
        let mut kept = 0;
        for robot in &robots {
            let _in = crate::Context::new().with_threads(1).enter();
            let o = FkOptions {
                jacobian: true,
                max_terms: 300,
                ..FkOptions::default()
            };
            let Ok((entries, texts)) = entries_of(robot, robot.made_joints(), &o) else {
                continue;
            };
            kept += usize::from(texts.is_some());
            let params = robot.parameters();
            for format in [Format::Plain, Format::Latex, Format::Sympy] {
                for shorthand in [true, false] {
                    let o = FkOptions {
                        format,
                        shorthand,
                        ..o.clone()
                    };
                    let mut decimal = robot.clone();
                    decimal.decimals = vec![num_rational::BigRational::new(17.into(), 40.into())];
                    for r in [robot, &decimal] {
                        let s = &entries.sections;
                        let with = render_printed(r, &params, s, &o, &[], texts.clone());
                        assert_eq!(with, render(r, &params, s, &o, &[]));
                    }
                }
            }
        }
        assert!(kept >= 3, "{kept}");
    }

    /// The recurrence from the joint factors `fk` made (and their matrices kept) gives what it
    /// gives making them itself, and charges the same work, under no budget and under budgets
    /// that run out around the first place it would make them (the pose's factors: `units`
    /// and one unit either side) and later. Not reached here: a budget that refuses the third
    /// use (the names' check, after the products; the second, the matrix in cosines and sines,
    /// runs on a budget of its own), which `joint_factors_kept_are_charged_as_made` covers for
    /// `MadeJoints::again` itself (and `joint_matrices_kept_are_charged_as_made` for the
    /// matrices).
    #[test]
    fn the_recurrence_from_the_factors_made_is_the_recurrence() {
        let mut next = crate::testing::xorshift_below(4141);
        let mut errors = 0;
        for _ in 0..6 {
            let robot = random_test_chain(&mut next, 7);
            let o = FkOptions {
                jacobian: true,
                ..FkOptions::default()
            };
            // Made on warm caches, as the recurrence would make them again (see
            // `MadeJoints::again`: on cold ones the charge may be the caches' misses more).
            // Their matrices kept as the expansion keeps them (`JointMatrices`: those of the
            // factors a matrix product reached), on warm caches too.
            let made = {
                let _in = crate::Context::new().with_threads(1).enter();
                let _ = robot.joint_dqs();
                let made = robot.made_joints();
                let _ = robot.forward_matrix_cos_sin_of(made.dqs(), None, 1_000);
                let _ = robot.forward_matrix_cos_sin_of(made.dqs(), made.matrices(), 1_000);
                made
            };
            let units = made.units_for_tests();
            let run = |budget: Option<u64>, from_made: bool| {
                let mut ctx = crate::Context::new().with_threads(1);
                if let Some(b) = budget {
                    ctx = ctx.with_work_budget(b);
                }
                let _in = ctx.enter();
                let r = recurrence_sections(&robot, from_made.then_some(&made), &o);
                let used = crate::scalar::work_used();
                (format!("{r:?}"), used)
            };
            // Once first, so that the per-thread caches charged on a miss (closed forms,
            // cyclotomic templates) are as full for every run compared.
            let _ = run(None, false);
            let whole = run(None, false);
            let from_made = run(None, true);
            assert!(from_made.0 == whole.0, "{:?}", robot.chain);
            assert!(from_made.1 == whole.1, "{:?}", robot.chain);
            let w = whole.1;
            for b in [
                units - 1,
                units,
                units + 1,
                2 * units,
                3 * units - 1,
                w / 2,
                w - 1,
                w,
            ] {
                let old = run(Some(b), false);
                let new = run(Some(b), true);
                // The same result; where both run out of the budget, the work counted when
                // they stop may differ by a few units (a debug build's run met 95,729 against
                // 95,725 at a budget of 95,700; the runs compared start from different cache
                // states, which charge on a miss, and a debug build's exact re-checks fill
                // caches of their own), so two budget errors are compared by kind and limit.
                let budget = |r: &str| {
                    r.starts_with("Err(Scalar(Budget") && r.contains(&format!("limit: {b} "))
                };
                assert!(
                    new == old || (budget(&old.0) && budget(&new.0)),
                    "{:?} at {b}: {} / {}",
                    robot.chain,
                    old.0,
                    new.0
                );
                errors += usize::from(old.0.starts_with("Err"));
            }
        }
        // 36 of the 48 runs under a budget end in an error (6 chains, 8 budgets).
        assert!(errors >= 24, "{errors} errors");
    }
}
