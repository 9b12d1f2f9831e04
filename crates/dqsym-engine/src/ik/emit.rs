//! Solver code: every branch of a derived [`IkSolution`] as Rust, C or Python (NumPy). The
//! formulas are the closed forms of the report, written as they are; the branch logic
//! (tolerances for singular and clamped radicands) is the one of [`super::candidates`].
//!
//! The logic is written once, here; every statement is written through the language's
//! [`SolverSyntax`] (`emit/syntax.rs`, implemented beside each language's fk writer), and the
//! numeric helpers the solver calls are the language's `emit/runtime/ik_helpers.*`.

use super::{Formula, IkSolution, TARGET_SYMBOLS};
use crate::emit::codegen::{lower, CodegenOptions, Id, Node, Output, Program};
use crate::emit::helpers::StepKind;
use crate::emit::names::{self, comment_lines, Comment};
use crate::emit::syntax::{solver_syntax, syntax, SolverFile, SolverSyntax, Syntax};
use crate::scalar::Trig;
use crate::{Scalar, ScalarError};

/// The regular branches, times 13 for the representatives of a singular set and the kept
/// atan2 value beside them (see `ik_any`).
fn max_solutions(sol: &IkSolution) -> usize {
    13 * sol
        .steps
        .iter()
        .map(|s| match s.formula {
            // A double root with the pair beside it (see `ik_trig`).
            Formula::Trig { .. } => 3,
            _ => s.formula.branches(),
        })
        .product::<usize>()
}

/// The solver's plan: every step's parts lowered into one DAG (shared subexpressions are one
/// node), each node placed at the shallowest loop level where what it reads is known.
/// Level 0 is the function's top; level `k + 1` the body of step `k`'s loop, after its joint
/// (and the joint's sine and cosine, known from the roots without a call) is bound. A node
/// read more than once, or read at a deeper level, is a local computed once at its own level;
/// a step's roots are computed at the level of its parts (PUMA's theta3 once, not once per
/// theta1), its loop stays at its place.
struct Ctx<'a> {
    sol: &'a IkSolution,
    /// The language the solver is written in.
    w: &'a dyn SolverSyntax,
    prog: Program,
    /// Per level: the locals (node, name) and the atoms computed by a sin/cos call.
    temps: Vec<Vec<(Id, String)>>,
    atoms: Vec<Vec<usize>>,
    /// Per step: its parts' nodes, the level its roots are computed at.
    parts: Vec<Vec<(&'static str, Id)>>,
    solve_level: Vec<usize>,
    /// The nodes of the axes (direction, point: six per joint) and of the home pose's top
    /// three rows, for the check of a solution by forward kinematics.
    chain: Vec<Id>,
    /// Each step's degree in lengths (its parts' rounding is `IK_ZERO_TOL L^d`).
    degrees: Vec<i32>,
}

fn ctx<'a>(sol: &'a IkSolution, w: &'a dyn SolverSyntax) -> Result<Ctx<'a>, ScalarError> {
    let forms = sol.forms()?;
    let n = sol.steps.len();
    let fixed = TARGET_SYMBOLS.iter().flatten().count() + sol.params.len();
    let args: Vec<String> = TARGET_SYMBOLS
        .iter()
        .flatten()
        .map(|s| s.to_string())
        .chain(sol.params.iter().cloned())
        .chain(sol.steps.iter().map(|s| s.variable.clone()))
        .collect();
    let angled =
        |st: &super::IkStep| matches!(st.formula, Formula::Atan2 { .. } | Formula::Trig { .. });
    let (outputs, n_parts, n_trig) = solver_outputs(sol, forms)?;
    let degrees = sol.degrees()?.to_vec();
    let mut prog = lower(&outputs, &args, &CodegenOptions::default())
        .map_err(|e| ScalarError::Unbound(e.to_string()))?;
    let arg_level = |i: usize| if i < fixed { 0 } else { i - fixed + 1 };
    let sym_level = |name: &str| args.iter().position(|a| a == name).map_or(0, arg_level);
    // Atoms: a revolute joint's own angle is bound by its loop; any other is a call.
    let mut atom_level = Vec::new();
    let mut atoms = vec![Vec::new(); n + 1];
    for (i, atom) in prog.atoms.iter_mut().enumerate() {
        let a = &atom.angle;
        let own = (a.is_plain_sum() && a.terms.len() == 1)
            .then(|| a.terms[0].0.name().to_string())
            .filter(|v| sol.steps.iter().any(|s| &s.variable == v && angled(s)));
        let level = a
            .terms
            .iter()
            .map(|(s, _)| sym_level(s.name()))
            .max()
            .unwrap_or(0);
        match own {
            Some(v) => {
                atom.sin_name = format!("s_{v}");
                atom.cos_name = format!("c_{v}");
            }
            None => atoms[level].push(i),
        }
        atom_level.push(level);
    }
    let nodes = prog.nodes.clone();
    let mut level = vec![0usize; nodes.len()];
    for (id, node) in nodes.iter().enumerate() {
        level[id] = match node {
            Node::Arg(i) => arg_level(*i),
            Node::Const(_) => 0,
            Node::Sin(i) | Node::Cos(i) => atom_level[*i],
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => level[*a].max(level[*b]),
            Node::Neg(a) => level[*a],
        };
    }
    let compound = |id: Id| {
        matches!(
            nodes[id],
            Node::Add(..) | Node::Sub(..) | Node::Mul(..) | Node::Neg(_)
        )
    };
    let mut deeper = vec![false; nodes.len()];
    for (id, node) in nodes.iter().enumerate() {
        if prog.uses[id] == 0 {
            continue;
        }
        if let Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) = node {
            deeper[*a] |= level[*a] < level[id];
            deeper[*b] |= level[*b] < level[id];
        }
        if let Node::Neg(a) = node {
            deeper[*a] |= level[*a] < level[id];
        }
    }
    let mut parts = vec![Vec::new(); n];
    let mut solve_level = vec![0; n];
    // The parts are the first outputs, step by step in the order of `forms`.
    let part_of = forms
        .iter()
        .enumerate()
        .flat_map(|(k, f)| f.iter().map(move |(name, _)| (k, *name)));
    for ((step, name), (_, ids)) in part_of.zip(&prog.outputs[..n_parts]) {
        parts[step].push((name, ids[0]));
        solve_level[step] = solve_level[step].max(level[ids[0]]);
    }
    let mut temps = vec![Vec::new(); n + 1];
    let mut temp = std::collections::HashMap::new();
    for id in 0..nodes.len() {
        if compound(id) && prog.uses[id] > 0 && (prog.uses[id] > 1 || deeper[id]) {
            let name = format!("ik_t{}", temp.len());
            temps[level[id]].push((id, name.clone()));
            temp.insert(id, name);
        }
    }
    prog.temp = temp;
    let chain = prog.outputs[n_trig..]
        .iter()
        .map(|(_, ids)| ids[0])
        .collect();
    Ok(Ctx {
        sol,
        w,
        prog,
        temps,
        atoms,
        parts,
        solve_level,
        chain,
        degrees,
    })
}

/// The outputs the solver computes: every step's parts (`p{k}_{name}`), the sine of every
/// angled joint, then the axes and the home pose's top rows (for the check by forward
/// kinematics); with the number of parts and where the axes begin.
fn solver_outputs(
    sol: &IkSolution,
    forms: &[Vec<(&'static str, crate::Expr)>],
) -> Result<(Vec<Output>, usize, usize), ScalarError> {
    let angled =
        |st: &super::IkStep| matches!(st.formula, Formula::Atan2 { .. } | Formula::Trig { .. });
    let mut outputs: Vec<Output> = Vec::new();
    for (k, f) in forms.iter().enumerate() {
        for (name, e) in f {
            outputs.push(Output::scalar(&format!("p{k}_{name}"), "", e.clone()));
        }
    }
    // sin of every revolute joint, so that its angle's step is 1 (never 2 theta as an atom
    // when only double angles occur): the joint's sine and cosine are known from its roots.
    let n_parts = outputs.len();
    for st in sol.steps.iter().filter(|s| angled(s)) {
        outputs.push(Output::scalar(
            &format!("trig_{}", st.variable),
            "",
            crate::closed_form(&Scalar::sym(&st.variable).sin())?,
        ));
    }
    // The axes and the home pose, for the check by forward kinematics (level 0: parameters
    // only).
    let n_trig = outputs.len();
    outputs.extend(chain_outputs(sol)?);
    Ok((outputs, n_parts, n_trig))
}

/// The axes `(w, p)` (six entries each) and the home pose's top three rows as outputs, for
/// the check by forward kinematics (both methods' solvers).
pub(super) fn chain_outputs(sol: &IkSolution) -> Result<Vec<Output>, ScalarError> {
    let mut outputs = Vec::new();
    for (i, a) in sol.axes.iter().enumerate() {
        for (k, x) in a.dir.iter().chain(&a.point).enumerate() {
            outputs.push(Output::scalar(
                &format!("ik_ax{i}_{k}"),
                "",
                crate::closed_form(x)?,
            ));
        }
    }
    for (r, row) in sol.home.rows.iter().take(3).enumerate() {
        for (c, x) in row.iter().enumerate() {
            outputs.push(Output::scalar(
                &format!("ik_home{r}{c}"),
                "",
                crate::closed_form(x)?,
            ));
        }
    }
    Ok(outputs)
}

impl Ctx<'_> {
    /// A local at indentation `pad`.
    fn local(&self, pad: &str, name: &str, value: &str, out: &mut String) {
        out.push_str(&format!("{pad}{}\n", self.w.local(name, value)));
    }

    /// What level `l` computes: sin/cos calls, locals, the roots of the steps solved there.
    fn level(&self, l: usize, ind: usize, out: &mut String) {
        let pad = " ".repeat(ind);
        let lit = |v: f64| self.w.literal(v);
        let p = &self.prog;
        if l == 0 {
            for (k, step) in self.sol.steps.iter().enumerate() {
                if matches!(step.formula, Formula::Atan2 { .. }) {
                    out.push_str(&format!("{pad}{}\n", self.w.memo(k)));
                }
            }
        }
        for &i in &self.atoms[l] {
            let (su, cu) = (p.atom_used(i, Trig::Sin), p.atom_used(i, Trig::Cos));
            if !su && !cu {
                continue;
            }
            let a = p.angle_code(i, &lit);
            let (s, c) = (&p.atoms[i].sin_name, &p.atoms[i].cos_name);
            out.push_str(&self.w.sin_cos(&pad, s, c, &a));
        }
        for (id, name) in &self.temps[l] {
            self.local(&pad, name, &p.definition(*id, &lit), out);
        }
        if l == 0 {
            self.chain_setup(&pad, out);
        }
        for k in (0..self.sol.steps.len()).filter(|&k| self.solve_level[k] == l) {
            self.roots(k, &pad, out);
        }
    }

    /// Step `k`'s parts and the call of its helper for the roots.
    fn roots(&self, k: usize, pad: &str, out: &mut String) {
        let lit = |v: f64| self.w.literal(v);
        let step = &self.sol.steps[k];
        let q = &step.variable;
        let comment = self.w.inline_comment();
        out.push_str(&format!("{pad}{comment} {q}: {}\n", step.method));
        let mut args = Vec::new();
        for (n, id) in &self.parts[k] {
            let name = format!("ik_{q}_{n}");
            self.local(pad, &name, &self.prog.code(*id, &lit), out);
            args.push(name);
        }
        let Some(kind) = step_kind(&step.formula) else {
            return;
        };
        args.push(format!("ik_sg{k}"));
        if matches!(step.formula, Formula::Atan2 { .. }) {
            args.push(self.w.memo_arg(k));
        }
        let call = format!("{}({})", self.w.helper(kind.helper()), args.join(", "));
        out.push_str(&format!("{pad}{}\n", self.w.roots(k, &call)));
    }

    /// The steps before `k` with roots (a value step has none).
    fn rooted(&self, k: usize) -> impl Iterator<Item = usize> + '_ {
        (0..k).filter(|&i| !matches!(self.sol.steps[i].formula, Formula::Value { .. }))
    }

    /// The flags `field` of the steps before `k` with roots, or'ed.
    fn flags(&self, k: usize, field: &str) -> String {
        let v: Vec<String> = self.rooted(k).map(|i| self.w.flag(i, field)).collect();
        if v.is_empty() {
            return self.w.false_literal().into();
        }
        v.join(self.w.or())
    }

    /// The check's data at the top of the solver: the axes, the home pose, the robot's scale
    /// and each step's rounding `IK_ZERO_TOL L^d`.
    fn chain_setup(&self, pad: &str, out: &mut String) {
        let lit = |v: f64| self.w.literal(v);
        let code = |id: &Id| self.prog.code(*id, &lit);
        let n = self.sol.axes.len();
        let kind = |i: usize| {
            let k = self.sol.axes[i].kind == crate::kin::JointKind::Prismatic;
            if k {
                "1.0"
            } else {
                "0.0"
            }
        };
        let axis = |i: usize| {
            let v: Vec<String> = self.chain[6 * i..6 * i + 6].iter().map(code).collect();
            self.w.list(&format!("{}, {}", kind(i), v.join(", ")))
        };
        let home = |r: usize| {
            let v: Vec<String> = self.chain[6 * n + 4 * r..6 * n + 4 * r + 4]
                .iter()
                .map(code)
                .collect();
            self.w.list(&v.join(", "))
        };
        let ax: Vec<String> = (0..n).map(axis).collect();
        let hm: Vec<String> = (0..3).map(home).collect();
        out.push_str(&self.w.chain(pad, &ax.join(", "), &hm.join(", ")));
        let len = self.w.scale();
        for k in self.rooted(self.sol.steps.len()) {
            let mut v = "IK_ZERO_TOL".to_string();
            for _ in 0..self.degrees[k] {
                v.push_str(&format!(" * {len}"));
            }
            self.local(pad, &format!("ik_sg{k}"), &v, out);
        }
    }

    /// A complete solution: written through the push helper with its flags (singular,
    /// checked, sampled beside a kept atan2 value).
    fn leaf(&self, pad: &str, out: &mut String) {
        let n = self.sol.steps.len();
        let q = self.sol.variables.join(", ");
        let (sg, ck) = (self.flags(n, "sg"), self.flags(n, "ck"));
        let smp: Vec<String> = self.rooted(n).map(|i| self.w.sampled(i)).collect();
        let smp = if smp.is_empty() {
            self.w.false_literal().to_string()
        } else {
            smp.join(self.w.or())
        };
        out.push_str(&self.w.push(pad, &q, &sg, &ck, &smp));
    }

    /// The loops from step `k` on, at indentation `ind`.
    fn body(&self, k: usize, ind: usize, out: &mut String) {
        let pad = " ".repeat(ind);
        let Some(step) = self.sol.steps.get(k) else {
            self.leaf(&pad, out);
            return;
        };
        let q = &step.variable;
        if let Formula::Value { .. } = step.formula {
            self.local(&pad, q, &format!("ik_{q}_v"), out);
            self.level(k + 1, ind, out);
            self.body(k + 1, ind, out);
            return;
        }
        let inner = " ".repeat(ind + 4);
        // A trig step's pair beside its double root is skipped where the double root already
        // gave a solution on the pose (it is there for poses only near the singular set).
        let trig = matches!(step.formula, Formula::Trig { .. });
        out.push_str(&self.w.loop_open(&pad, &inner, k, q, trig));
        self.level(k + 1, ind + 4, out);
        self.body(k + 1, ind + 4, out);
        out.push_str(&self.w.loop_close(&pad));
    }
}

/// The kind of step a formula is solved by (a value step has no roots to compute).
fn step_kind(f: &Formula) -> Option<StepKind> {
    match f {
        Formula::Atan2 { .. } => Some(StepKind::Atan2),
        Formula::Trig { .. } => Some(StepKind::Trig),
        Formula::Quadratic { .. } => Some(StepKind::Quadratic),
        Formula::Linear { .. } => Some(StepKind::Linear),
        Formula::Value { .. } => None,
    }
}

/// The kinds of step of `sol` with roots, each once (the helpers a solver needs follow from
/// them).
fn step_kinds(sol: &IkSolution) -> Vec<StepKind> {
    let mut kinds = Vec::new();
    for k in sol.steps.iter().filter_map(|s| step_kind(&s.formula)) {
        if !kinds.contains(&k) {
            kinds.push(k);
        }
    }
    kinds
}

/// The solver's helpers: the tolerance constants `consts`, then the language's runtime
/// helpers its steps use (declared in `emit/runtime/ik_helpers.*`, see `emit/helpers.rs`).
fn helpers(sol: &IkSolution, w: &dyn SolverSyntax, consts: &str) -> String {
    let kinds = step_kinds(sol);
    let mut out = vec![consts.trim_matches('\n')];
    out.extend(
        crate::emit::helpers::runtime(w.lang())
            .iter()
            .filter(|h| h.used_by(&kinds))
            .map(|h| h.text),
    );
    format!("{}\n", out.join(w.helper_separator()))
}

/// The tolerances of [`super::check`] (where they are derived) as constants of the solver's
/// language, and the solver's shape (`IK_DOF`, `IK_POSITION_ONLY`) where its helpers need it.
fn tolerances(sol: &IkSolution, w: &dyn Syntax) -> String {
    use super::check::{CHECK_TOL, POSE_TOL, REACH_TOL, REFINE_STEPS, REFINE_TOL, ZERO_TOL};
    let text = [
        "Tolerances (derived in dqsym's ik/check.rs), relative to the robot's scale L (the largest",
        "sum of absolute coordinates of an axis' point, the home or the target position):",
        "a step's parts are zero within IK_ZERO_TOL L^d (d their degree in lengths); a solution",
        "whose roots may err by more than IK_CHECK_TOL, or met a singular set, is checked by",
        "forward kinematics, refined (Gauss-Newton) where its residual exceeds IK_REFINE_TOL and",
        "flagged approximate where it stays above IK_POSE_TOL; radicands down to -IK_REACH_TOL",
        "(relative) are the closest reach.",
    ];
    let f = |v: f64| w.literal(v);
    let consts: Vec<(&str, String, &str)> = vec![
        ("IK_ZERO_TOL", f(ZERO_TOL), "f64"),
        ("IK_REACH_TOL", f(REACH_TOL), "f64"),
        ("IK_CHECK_TOL", f(CHECK_TOL), "f64"),
        ("IK_REFINE_TOL", f(REFINE_TOL), "f64"),
        ("IK_POSE_TOL", f(POSE_TOL), "f64"),
        ("IK_REFINE_STEPS", REFINE_STEPS.to_string(), "usize"),
    ];
    let mut s = String::new();
    for l in text {
        s.push_str(&w.comment_line(l));
    }
    for (name, v, ty) in consts {
        s.push_str(&w.constant(name, &v, ty));
    }
    s.push_str(&w.shape_constants(sol.variables.len(), sol.position_only));
    s
}

/// The numeric helpers of the IK page's JavaScript solver (`ik_cands`, `ik_push` with the
/// check, refinement and de-duplication of the other solvers) with their tolerances; the page
/// supplies the steps, the axes and the home pose.
pub fn ik_javascript_helpers(sol: &IkSolution) -> String {
    let js = crate::emit::javascript::JavaScript;
    format!("{}{}", tolerances(sol, &js), js.ik_runtime())
}

/// The tolerances block of `lang` (the general method's C solver states the same constants
/// as the family solvers).
pub(super) fn tolerances_of(sol: &IkSolution, lang: names::Lang) -> String {
    tolerances(sol, syntax(lang))
}

/// Each step's degree in lengths (see [`super::check`]), for the page's solver.
///
/// # Errors
/// A closed form that fails.
pub fn ik_step_degrees(sol: &IkSolution) -> Result<Vec<i32>, ScalarError> {
    Ok(sol.degrees()?.to_vec())
}

/// The solver's documentation, one comment line each, escaped for `syntax` (the robot's name
/// is text from outside: every line of it commented).
fn doc_lines(sol: &IkSolution, syntax: Comment) -> Vec<String> {
    let mut v = vec![
        format!(
            "Inverse kinematics of {}: every closed-form solution.",
            sol.robot
        ),
        format!("Family: {}.", sol.family),
        format!(
            "Joint vector order: {}; at most {} solutions.",
            sol.variables.join(", "),
            max_solutions(sol)
        ),
        "Flags: singular (a singular set was met: a double root, or a joint free on it, given as"
            .into(),
        "k pi/6, k = -5..6, so that a later joint can still reach; capped at IK_MAX);".into(),
        "approximate (the pose misses the target by more than IK_POSE_TOL after refinement: the"
            .into(),
        "closest reach), with the residual (0 where every step was well-conditioned).".into(),
        "Generated by dqsym ik.".into(),
    ];
    if sol.position_only {
        v.push("Only the position column of the target is used.".into());
    }
    v.iter().flat_map(|l| comment_lines(syntax, l)).collect()
}

/// The solver of `sol` in `lang`: its logic here, its statements and file through the
/// language's [`SolverSyntax`].
fn solver(sol: &IkSolution, lang: names::Lang) -> Result<String, ScalarError> {
    let w = solver_syntax(lang).expect("a language IK solvers are written in");
    let sol = &*super::safe::solution(sol, lang);
    let c = ctx(sol, w)?;
    let consts = tolerances(sol, syntax(lang));
    let mut body = String::new();
    c.level(0, 4, &mut body);
    c.body(0, 4, &mut body);
    Ok(w.file(&SolverFile {
        doc: doc_lines(sol, w.doc_syntax()),
        dof: sol.variables.len(),
        max: max_solutions(sol),
        params: &sol.params,
        variables: &sol.variables,
        target: &TARGET_SYMBOLS,
        helpers: helpers(sol, w, &consts),
        body,
    }))
}

/// The solver as Rust: `ik_into(out: &mut IkSolutions, t: &[[f64; 4]; 4], params...)` (no
/// allocation, nothing initialised beyond the solutions written), `ik(t, params...) ->
/// IkSolutions` and `ik_dq(dq: &[f64; 8], params...)`.
///
/// # Errors
/// A closed form that fails.
pub fn ik_rust(sol: &IkSolution) -> Result<String, ScalarError> {
    if sol.general.is_some() {
        return super::general::emit::ik_rust(sol);
    }
    solver(sol, names::Lang::Rust)
}

/// The solver as C99: `void ik(const double T[4][4], params..., ik_solutions *out)` and
/// `ik_dq`; no allocation.
///
/// # Errors
/// A closed form that fails.
pub fn ik_c(sol: &IkSolution) -> Result<String, ScalarError> {
    if sol.general.is_some() {
        return super::general::emit::ik_c(sol);
    }
    solver(sol, names::Lang::C)
}

/// The solver as Python: `ik(T, **params)` returns the joint vectors (lists of floats, joint
/// order); `ik_full` also the flags; `ik_dq(q, **params)` for a unit dual quaternion. Needs
/// only NumPy and `math`.
///
/// # Errors
/// A closed form that fails.
pub fn ik_python(sol: &IkSolution) -> Result<String, ScalarError> {
    if sol.general.is_some() {
        return super::general::emit::ik_python(sol);
    }
    solver(sol, names::Lang::Python)
}
