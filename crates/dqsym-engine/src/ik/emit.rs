//! Solver code: every branch of a derived [`IkSolution`] as Rust, C or Python (NumPy). The
//! formulas are the closed forms of the report, written as they are; the branch logic
//! (tolerances for singular and clamped radicands) is the one of [`super::candidates`].

use super::{Formula, IkSolution, TARGET_SYMBOLS};
use crate::emit::codegen::{
    float_literal, lower, CodegenOptions, Id, Node, Output, Program, STD_CONSTS,
};
use crate::emit::names::{self, comment_lines, Comment};
use crate::scalar::Trig;
use crate::{Scalar, ScalarError};

#[derive(Clone, Copy, PartialEq, Eq)]
enum Lang {
    Rust,
    C,
    Python,
}

/// A literal: through `std::f64::consts` in Rust where one matches (clippy's
/// `approx_constant`), else the shortest text that reads back exactly.
fn lit(v: f64, lang: Lang) -> String {
    match STD_CONSTS.iter().find(|(_, c)| *c == v) {
        Some((name, _)) if lang == Lang::Rust => format!("std::f64::consts::{name}"),
        _ => float_literal(v),
    }
}

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
    lang: Lang,
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

fn ctx(sol: &IkSolution, lang: Lang) -> Result<Ctx<'_>, ScalarError> {
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
    let mut k = 0;
    for (out, ids) in prog.outputs.iter().take(n_parts) {
        let (step, name) = out.name[1..].split_once('_').unwrap_or(("0", ""));
        let step: usize = step.parse().unwrap_or(0);
        let name = forms[step]
            .iter()
            .map(|(n, _)| *n)
            .find(|n| *n == name)
            .unwrap_or("v");
        parts[step].push((name, ids[0]));
        solve_level[step] = solve_level[step].max(level[ids[0]]);
        k += 1;
    }
    debug_assert_eq!(k, n_parts);
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
        lang,
        prog,
        temps,
        atoms,
        parts,
        solve_level,
        chain,
        degrees,
    })
}

impl Ctx<'_> {
    fn lit(&self) -> impl Fn(f64) -> String {
        let lang = self.lang;
        move |v| lit(v, lang)
    }

    fn local(&self, pad: &str, name: &str, value: &str, out: &mut String) {
        match self.lang {
            Lang::Rust => out.push_str(&format!("{pad}let {name} = {value};\n")),
            Lang::C => out.push_str(&format!("{pad}const double {name} = {value};\n")),
            Lang::Python => out.push_str(&format!("{pad}{name} = {value}\n")),
        }
    }

    /// What level `l` computes: sin/cos calls, locals, the roots of the steps solved there.
    fn level(&self, l: usize, ind: usize, out: &mut String) {
        let pad = " ".repeat(ind);
        let lit = self.lit();
        let p = &self.prog;
        if l == 0 {
            for (k, step) in self.sol.steps.iter().enumerate() {
                if matches!(step.formula, Formula::Atan2 { .. }) {
                    out.push_str(&match self.lang {
                        Lang::Rust => format!("{pad}let mut ik_m{k} = IkMemo::NEW;\n"),
                        Lang::C => format!("{pad}ik_memo ik_m{k} = ik_memo_new();\n"),
                        Lang::Python => format!("{pad}ik_m{k} = []\n"),
                    });
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
            match self.lang {
                Lang::Rust => out.push_str(&format!("{pad}let ({s}, {c}) = ({a}).sin_cos();\n")),
                Lang::C => out.push_str(&format!(
                    "{pad}const double {s} = sin({a}), {c} = cos({a});\n{pad}(void){s};\n{pad}(void){c};\n"
                )),
                Lang::Python => {
                    out.push_str(&format!("{pad}{s}, {c} = math.sin({a}), math.cos({a})\n"))
                }
            }
        }
        for (id, name) in &self.temps[l] {
            self.local(&pad, name, &p.definition(*id, &lit), out);
        }
        if l == 0 {
            self.chain_setup(&pad, out);
        }
        for (k, step) in self.sol.steps.iter().enumerate() {
            if self.solve_level[k] != l {
                continue;
            }
            let q = &step.variable;
            let comment = if self.lang == Lang::Python { "#" } else { "//" };
            out.push_str(&format!("{pad}{comment} {q}: {}\n", step.method));
            let mut args = Vec::new();
            for (n, id) in &self.parts[k] {
                let name = format!("ik_{q}_{n}");
                self.local(&pad, &name, &p.code(*id, &lit), out);
                args.push(name);
            }
            let f = match step.formula {
                Formula::Atan2 { .. } => "ik_atan2",
                Formula::Trig { .. } => "ik_trig",
                Formula::Quadratic { .. } => "ik_quadratic",
                Formula::Value { .. } => continue,
            };
            let f = if self.lang == Lang::Python {
                format!("_{f}")
            } else {
                f.to_string()
            };
            args.push(format!("ik_sg{k}"));
            if matches!(step.formula, Formula::Atan2 { .. }) {
                args.push(match self.lang {
                    Lang::Rust => format!("&mut ik_m{k}"),
                    Lang::C => format!("&ik_m{k}"),
                    Lang::Python => format!("ik_m{k}"),
                });
            }
            let call = format!("{f}({})", args.join(", "));
            match self.lang {
                Lang::Rust => out.push_str(&format!("{pad}let ik_r{k} = {call};\n")),
                Lang::C => out.push_str(&format!("{pad}const ik_roots ik_r{k} = {call};\n")),
                Lang::Python => out.push_str(&format!("{pad}ik_r{k} = {call}\n")),
            }
        }
    }

    /// The flags of the steps before `k` with roots (a value step has none).
    fn flags(&self, k: usize, field: &str) -> String {
        let or = if self.lang == Lang::Python {
            " or "
        } else {
            " || "
        };
        let v: Vec<String> = (0..k)
            .filter(|&i| !matches!(self.sol.steps[i].formula, Formula::Value { .. }))
            .map(|i| match self.lang {
                Lang::Python => format!("ik_r{i}[{}]", if field == "sg" { 1 } else { 2 }),
                _ => format!("ik_r{i}.{field}"),
            })
            .collect();
        if v.is_empty() {
            return match self.lang {
                Lang::Rust => "false".into(),
                Lang::C => "0".into(),
                Lang::Python => "False".into(),
            };
        }
        v.join(or)
    }

    /// The check's data at the top of the solver: the axes, the home pose, the robot's scale
    /// and each step's rounding `IK_ZERO_TOL L^d`.
    fn chain_setup(&self, pad: &str, out: &mut String) {
        let lit = self.lit();
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
        let axis = |i: usize, open: &str, close: &str| {
            let v: Vec<String> = self.chain[6 * i..6 * i + 6].iter().map(code).collect();
            format!("{open}{}, {}{close}", kind(i), v.join(", "))
        };
        let home = |r: usize, open: &str, close: &str| {
            let v: Vec<String> = self.chain[6 * n + 4 * r..6 * n + 4 * r + 4]
                .iter()
                .map(code)
                .collect();
            format!("{open}{}{close}", v.join(", "))
        };
        let (o, c) = match self.lang {
            Lang::C => ("{", "}"),
            _ => ("[", "]"),
        };
        let ax: Vec<String> = (0..n).map(|i| axis(i, o, c)).collect();
        let hm: Vec<String> = (0..3).map(|r| home(r, o, c)).collect();
        let (ax, hm) = (ax.join(", "), hm.join(", "));
        match self.lang {
            Lang::Rust => out.push_str(&format!(
                "{pad}let mut ik_ch = IkChain {{ ax: [{ax}], home: [{hm}], t: ik_target, len: 1.0 }};\n\
                 {pad}ik_ch.len = ik_scale(&ik_ch);\n"
            )),
            Lang::C => out.push_str(&format!(
                "{pad}ik_chain ik_ch = {{{{{ax}}}, {{{hm}}}, ik_target, 1.0}};\n\
                 {pad}ik_ch.len = ik_scale(&ik_ch);\n"
            )),
            Lang::Python => out.push_str(&format!(
                "{pad}ik_ax = [{ax}]\n{pad}ik_home = [{hm}]\n\
                 {pad}ik_len = _ik_scale(ik_ax, ik_home, T)\n"
            )),
        }
        let len = if self.lang == Lang::Python {
            "ik_len"
        } else {
            "ik_ch.len"
        };
        for (k, step) in self.sol.steps.iter().enumerate() {
            if matches!(step.formula, Formula::Value { .. }) {
                continue;
            }
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
        let smp: Vec<String> = (0..n)
            .filter(|&i| !matches!(self.sol.steps[i].formula, Formula::Value { .. }))
            .map(|i| match self.lang {
                Lang::Rust => format!("ik_r{i}.sampled(ik_i{i})"),
                Lang::C => format!("ik_i{i} >= ik_r{i}.smp"),
                Lang::Python => format!("ik_x{i}"),
            })
            .collect();
        let smp = if smp.is_empty() {
            match self.lang {
                Lang::Rust => "false".to_string(),
                Lang::C => "0".to_string(),
                Lang::Python => "False".to_string(),
            }
        } else if self.lang == Lang::Python {
            smp.join(" or ")
        } else {
            smp.join(" || ")
        };
        match self.lang {
            Lang::Rust => out.push_str(&format!(
                "{pad}if ik_out.n == IK_MAX {{\n{pad}    return;\n{pad}}}\n\
                 {pad}ik_push(ik_out, [{q}], {sg}, {ck}, {smp}, &ik_ch);\n"
            )),
            Lang::C => out.push_str(&format!(
                "{pad}if (ik_out->n == IK_MAX) return;\n{pad}{{\n\
                 {pad}    const double ik_q[IK_DOF] = {{{q}}};\n\
                 {pad}    ik_push(ik_out, ik_q, {sg}, {ck}, {smp}, &ik_ch);\n{pad}}}\n"
            )),
            Lang::Python => out.push_str(&format!(
                "{pad}_ik_push(ik_out, [{q}], {sg}, {ck}, {smp}, ik_ax, ik_home, T, ik_len)\n"
            )),
        }
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
        match self.lang {
            Lang::Rust => {
                if trig {
                    out.push_str(&format!("{pad}let ik_n{k} = ik_out.n;\n"));
                }
                out.push_str(&format!("{pad}for ik_i{k} in 0..ik_r{k}.n {{\n"));
                if trig {
                    out.push_str(&format!(
                        "{inner}if ik_r{k}.sampled(ik_i{k}) && ik_exact(ik_out, ik_n{k}) {{\n{inner}    continue;\n{inner}}}\n"
                    ));
                }
                out.push_str(&format!(
                    "{inner}let ({q}, s_{q}, c_{q}) = ik_r{k}.root(ik_i{k});\n"
                ));
            }
            Lang::C => {
                if trig {
                    out.push_str(&format!("{pad}const int ik_n{k} = ik_out->n;\n"));
                }
                out.push_str(&format!(
                    "{pad}for (int ik_i{k} = 0; ik_i{k} < ik_r{k}.n; ik_i{k}++) {{\n"
                ));
                if trig {
                    out.push_str(&format!(
                        "{inner}if (ik_i{k} >= ik_r{k}.smp && ik_exact(ik_out, ik_n{k})) continue;\n"
                    ));
                }
                out.push_str(&format!(
                    "{inner}double {q}, s_{q}, c_{q};\n{inner}ik_root(&ik_r{k}, ik_i{k}, &{q}, &s_{q}, &c_{q});\n{inner}(void)s_{q};\n{inner}(void)c_{q};\n"
                ));
            }
            Lang::Python => {
                if trig {
                    out.push_str(&format!("{pad}ik_n{k} = len(ik_out)\n"));
                }
                out.push_str(&format!(
                    "{pad}for {q}, s_{q}, c_{q}, ik_x{k} in ik_r{k}[0]:\n"
                ));
                if trig {
                    out.push_str(&format!(
                        "{inner}if ik_x{k} and any(not r[2] for r in ik_out[ik_n{k}:]):\n{inner}    continue\n"
                    ));
                }
            }
        }
        self.level(k + 1, ind + 4, out);
        self.body(k + 1, ind + 4, out);
        if self.lang != Lang::Python {
            out.push_str(&format!("{pad}}}\n"));
        }
    }
}

/// The helper functions the solver uses (blocks of the helper texts, kept when the name they
/// define is needed).
fn helpers(sol: &IkSolution, texts: &[&str]) -> String {
    let has = |f: fn(&Formula) -> bool| sol.steps.iter().any(|s| f(&s.formula));
    let atan2 = has(|f| matches!(f, Formula::Atan2 { .. }));
    let trig = has(|f| matches!(f, Formula::Trig { .. }));
    let quad = has(|f| matches!(f, Formula::Quadratic { .. }));
    let mut out = Vec::new();
    for t in texts {
        for block in t.split("\n\n\n").flat_map(|b| b.split("\n\n")) {
            let block = block.trim_matches('\n');
            if block.is_empty() {
                continue;
            }
            let keep =
                if block.contains("ik_radicand(rad") || block.contains("ik_radicand(double *rad") {
                    trig || quad
                } else if (block.contains("_atan2(") && !block.contains("_trig("))
                    || block.contains("IkMemo")
                    || block.contains("ik_memo")
                {
                    atan2
                } else if block.contains("_trig(") {
                    trig
                } else if block.contains("_quadratic(") {
                    quad
                } else {
                    true
                };
            if keep {
                out.push(block.to_string());
            }
        }
    }
    let sep = if texts.len() == 1 { "\n\n\n" } else { "\n\n" };
    format!("{}\n", out.join(sep))
}

/// The tolerances of [`super::check`] (where they are derived) as constants of the solver's
/// language, and the solver's shape (`IK_DOF`, `IK_POSITION_ONLY`) where its helpers need it.
fn tolerances(sol: &IkSolution, lang: Option<Lang>) -> String {
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
    let po = sol.position_only;
    let (f, i) = (float_literal, |v: usize| v.to_string());
    let consts: Vec<(&str, String, &str)> = vec![
        ("IK_ZERO_TOL", f(ZERO_TOL), "f64"),
        ("IK_REACH_TOL", f(REACH_TOL), "f64"),
        ("IK_CHECK_TOL", f(CHECK_TOL), "f64"),
        ("IK_REFINE_TOL", f(REFINE_TOL), "f64"),
        ("IK_POSE_TOL", f(POSE_TOL), "f64"),
        ("IK_REFINE_STEPS", i(REFINE_STEPS), "usize"),
    ];
    let mut s = String::new();
    let comment = match lang {
        Some(Lang::Python) => "#",
        _ => "//",
    };
    for l in text {
        if lang == Some(Lang::C) {
            s.push_str(&format!("/* {l} */\n"));
        } else {
            s.push_str(&format!("{comment} {l}\n"));
        }
    }
    for (name, v, ty) in consts {
        s.push_str(&match lang {
            Some(Lang::Rust) => format!("#[allow(dead_code)]\nconst {name}: {ty} = {v};\n"),
            Some(Lang::C) => format!("#define {name} {v}\n"),
            Some(Lang::Python) => format!("{name} = {v}\n"),
            None => format!("const {name} = {v};\n"),
        });
    }
    let n = sol.variables.len();
    s.push_str(&match lang {
        Some(Lang::Rust) => format!(
            "const IK_DOF: usize = {n};\n#[allow(dead_code)]\nconst IK_POSITION_ONLY: bool = {po};\n"
        ),
        Some(Lang::C) => format!("#define IK_POSITION_ONLY {}\n", u8::from(po)),
        Some(Lang::Python) => format!(
            "IK_EPS = {}\nIK_POSITION_ONLY = {}\n",
            f(f64::EPSILON),
            if po { "True" } else { "False" }
        ),
        None => format!("const IK_EPS = {};\n", f(f64::EPSILON)),
    });
    s
}

/// The numeric helpers of the IK page's JavaScript solver (`ik_cands`, `ik_push` with the
/// check, refinement and de-duplication of the other solvers) with their tolerances; the page
/// supplies the steps, the axes and the home pose.
pub fn ik_javascript_helpers(sol: &IkSolution) -> String {
    format!("{}{JS_HELPERS}", tolerances(sol, None))
}

/// The tolerances block of the C solvers (the general method's C solver states the same
/// constants as the family solvers).
pub(super) fn c_tolerances(sol: &IkSolution) -> String {
    tolerances(sol, Some(Lang::C))
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
    let sol = &*super::safe::solution(sol, names::Lang::Rust);
    let c = ctx(sol, Lang::Rust)?;
    let n = sol.variables.len();
    let max = max_solutions(sol);
    let params: String = sol.params.iter().map(|p| format!(", {p}: f64")).collect();
    let pnames: String = sol.params.iter().map(|p| format!(", {p}")).collect();
    let mut s = String::new();
    for l in doc_lines(sol, Comment::Slashes) {
        s.push_str(&format!("// {l}\n"));
    }
    s.push_str(&format!(
        "\n/// The most solutions the solver returns.\npub const IK_MAX: usize = {max};\n\n\
/// The solutions: `q[..n]` in joint order, with their flags.\n\
#[derive(Clone, Copy, Debug, PartialEq)]\npub struct IkSolutions {{\n    /// Joint vectors.\n    pub q: [[f64; {n}]; IK_MAX],\n    \
/// A singular set was met.\n    pub singular: [bool; IK_MAX],\n    /// The pose misses the target (the closest reach).\n    pub approximate: [bool; IK_MAX],\n    \
/// The residual where the solution was checked, else 0.\n    pub residual: [f64; IK_MAX],\n    \
/// How many are valid.\n    pub n: usize,\n}}\n\n\
impl Default for IkSolutions {{\n    fn default() -> Self {{\n        IkSolutions {{\n            q: [[0.0; {n}]; IK_MAX],\n            \
singular: [false; IK_MAX],\n            approximate: [false; IK_MAX],\n            residual: [0.0; IK_MAX],\n            n: 0,\n        }}\n    }}\n}}\n\n"
    ));
    let consts = tolerances(sol, Some(Lang::Rust));
    s.push_str(&helpers(sol, &[&consts, RUST_HELPERS]));
    s.push_str(&format!(
        "\n/// Every solution for the target pose `t` (row-major homogeneous matrix), written to\n\
/// `ik_out` (`ik_out.n` of them; the entries beyond are left as they were).\n\
#[allow(non_snake_case, unused_variables, clippy::too_many_arguments, clippy::excessive_precision, clippy::neg_multiply, clippy::double_parens, unused_parens)]\n\
pub fn ik_into(ik_out: &mut IkSolutions, ik_target: &[[f64; 4]; 4]{params}) {{\n"
    ));
    for (r, row) in TARGET_SYMBOLS.iter().enumerate() {
        for (col, name) in row.iter().enumerate() {
            s.push_str(&format!("    let {name} = ik_target[{r}][{col}];\n"));
        }
    }
    s.push_str("    ik_out.n = 0;\n");
    let mut body = String::new();
    c.level(0, 4, &mut body);
    c.body(0, 4, &mut body);
    s.push_str(&body);
    s.push_str("}\n\n");
    s.push_str(&format!(
        "/// Every solution for the target pose `t` (row-major homogeneous matrix).\n\
#[allow(non_snake_case, clippy::too_many_arguments)]\n\
pub fn ik(ik_target: &[[f64; 4]; 4]{params}) -> IkSolutions {{\n    let mut ik_out = IkSolutions::default();\n    \
ik_into(&mut ik_out, ik_target{pnames});\n    ik_out\n}}\n\n"
    ));
    s.push_str(&format!(
        "/// Every solution for the target given as a unit dual quaternion `(w, x, y, z)` +\n\
/// eps `(w, x, y, z)`.\n#[allow(non_snake_case, clippy::too_many_arguments)]\n\
pub fn ik_dq(ik_q: &[f64; 8]{params}) -> IkSolutions {{\n    ik(&ik_dq_matrix(ik_q){pnames})\n}}\n"
    ));
    Ok(s)
}

const RUST_HELPERS: &str = r#"/// The roots of one step: `n` joint values with their sines and cosines (known without a
/// call), and the flags (singular, checked); `n = 12` on a singular set of an atan2 (the
/// samples of `ik_any`), `n = 13` with the atan2 value first; roots from `smp` on are samples
/// beside a kept value.
#[derive(Clone, Copy)]
struct IkRoots {
    n: usize,
    q: [f64; 3],
    s: [f64; 3],
    c: [f64; 3],
    sg: bool,
    ck: bool,
    smp: usize,
}

impl IkRoots {
    const NONE: IkRoots = IkRoots { n: 0, q: [0.0; 3], s: [0.0; 3], c: [1.0; 3], sg: false, ck: false, smp: 99 };
    /// Root `i`: `(q, sin q, cos q)`.
    #[inline(always)]
    fn root(&self, i: usize) -> (f64, f64, f64) {
        if self.n >= 12 && i + 12 >= self.n {
            ik_any(i + 12 - self.n)
        } else {
            (self.q[i], self.s[i], self.c[i])
        }
    }
    /// Root `i` is a sample beside the kept atan2 value (dropped when it stays off the pose).
    #[inline(always)]
    #[allow(dead_code)]
    fn sampled(&self, i: usize) -> bool {
        i >= self.smp
    }
}

/// A joint free on a singular set: value `i` of twelve, k pi/6, k = -5..6, so that a later
/// joint can still reach.
#[cold]
#[inline(never)]
fn ik_any(i: usize) -> (f64, f64, f64) {
    let q = (i as f64 - 5.0) * std::f64::consts::FRAC_PI_6;
    let (s, c) = q.sin_cos();
    (q, s, c)
}

/// A step's last atan2 (`y`, `x` and the root `q`, `sin q`, `cos q`), reused by the next call
/// of the step: the same arguments give the same root, exactly negated ones the angle plus pi
/// with the sine and cosine negated (the wrist flip theta4 + pi, theta6 + pi of the sibling
/// branch).
#[derive(Clone, Copy)]
struct IkMemo {
    y: f64,
    x: f64,
    q: f64,
    s: f64,
    c: f64,
    ck: bool,
}

impl IkMemo {
    const NEW: IkMemo = IkMemo { y: f64::NAN, x: f64::NAN, q: 0.0, s: 0.0, c: 1.0, ck: false };
}

/// `atan2(y, x)`, its sine `y / h` and cosine `x / h`, for arguments rounded by `sg`: where
/// both are zero within it, any value (and atan2 itself where not exactly 0/0).
#[inline(always)]
fn ik_atan2(y: f64, x: f64, sg: f64, m: &mut IkMemo) -> IkRoots {
    if y == -m.y && x == -m.x {
        m.q = if m.q > 0.0 { m.q - std::f64::consts::PI } else { m.q + std::f64::consts::PI };
        m.s = -m.s;
        m.c = -m.c;
        m.y = y;
        m.x = x;
    } else if y != m.y || x != m.x {
        let h2 = y * y + x * x;
        if h2 <= sg * sg {
            return ik_atan2_singular(y, x, h2);
        }
        let h = h2.sqrt();
        let ck = sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2;
        *m = IkMemo { y, x, q: y.atan2(x), s: y / h, c: x / h, ck };
    }
    IkRoots { n: 1, q: [m.q, 0.0, 0.0], s: [m.s, 0.0, 0.0], c: [m.c, 1.0, 1.0], sg: false, ck: m.ck, smp: 99 }
}

#[cold]
#[inline(never)]
fn ik_atan2_singular(y: f64, x: f64, h2: f64) -> IkRoots {
    if h2 > 0.0 {
        let h = h2.sqrt();
        return IkRoots { n: 13, q: [y.atan2(x), 0.0, 0.0], s: [y / h, 0.0, 0.0], c: [x / h, 1.0, 1.0], sg: true, ck: true, smp: 1 };
    }
    IkRoots { n: 12, sg: true, ck: true, ..IkRoots::NONE }
}

/// A radicand `rad` of scale `n` rounded by `nu`: none out of reach (below -IK_REACH_TOL n),
/// a double root within `nu` of zero (singular), else itself (checked where its roots err by
/// more than IK_CHECK_TOL).
#[inline(always)]
fn ik_radicand(rad: f64, n: f64, nu: f64) -> Option<(f64, bool, bool)> {
    if rad < -IK_REACH_TOL * n - nu {
        None
    } else if rad <= nu {
        Some((0.0, true, true))
    } else {
        Some((rad, false, nu * nu > 4.0 * IK_CHECK_TOL * IK_CHECK_TOL * rad * n))
    }
}

/// `a cos q + b sin q = c` (parts rounded by `sg`): `q = atan2(b, a) +- atan2(r, c)`, `r =
/// sqrt(a^2 + b^2 - c^2)`, as `atan2(b c +- a r, a c -+ b r)`, whose sine and cosine are those
/// over `a^2 + b^2`. Where `b = 0` the roots are `+-q` (`atan2` is odd in `y`), where `a = 0`
/// they are `q` and `pi - q`.
#[inline(always)]
fn ik_trig(a: f64, b: f64, c: f64, sg: f64) -> IkRoots {
    let n = a * a + b * b;
    if n <= sg * sg {
        return if c.abs() <= sg { IkRoots { n: 1, sg: true, ck: true, ..IkRoots::NONE } } else { IkRoots::NONE };
    }
    let nu = 2.0 * sg * (a.abs() + b.abs() + c.abs()) + 4.0 * f64::EPSILON * n;
    let Some((rad, sg, ck)) = ik_radicand(n - c * c, n, nu) else {
        return IkRoots::NONE;
    };
    let r = rad.sqrt();
    // r^2 + c^2 = n, unless the radicand was clamped.
    let d = if sg { (n * (c * c + rad)).sqrt() } else { n };
    let (y0, x0, y1, x1) = (b * c + a * r, a * c - b * r, b * c - a * r, a * c + b * r);
    let q0 = y0.atan2(x0);
    let q1 = if b == 0.0 {
        -q0
    } else if a == 0.0 {
        std::f64::consts::PI.copysign(y0) - q0
    } else {
        y1.atan2(x1)
    };
    if sg {
        // Beside the double root, the pair of the radicand nu (sampled: kept where refinement
        // takes it onto the pose, which the double root may miss when the pose is only near).
        let w = nu.sqrt();
        let e = (n * (c * c + nu)).sqrt();
        let (y1, x1, y2, x2) = (b * c + a * w, a * c - b * w, b * c - a * w, a * c + b * w);
        return IkRoots { n: 3, q: [q0, y1.atan2(x1), y2.atan2(x2)], s: [y0 / d, y1 / e, y2 / e], c: [x0 / d, x1 / e, x2 / e], sg, ck, smp: 1 };
    }
    IkRoots { n: 2, q: [q0, q1, 0.0], s: [y0 / d, y1 / d, 0.0], c: [x0 / d, x1 / d, 1.0], sg, ck, smp: 99 }
}

/// Beside the double root of `ik_trig(...)`: a solution from `from` on reproduces the pose.
fn ik_exact(out: &IkSolutions, from: usize) -> bool {
    out.approximate[from..out.n].iter().any(|a| !a)
}

/// `q^2 + 2 beta q + gamma = 0` (`gamma` rounded by `sg`, `beta` by `sqrt(sg IK_ZERO_TOL)`):
/// up to two roots.
#[inline(always)]
fn ik_quadratic(beta: f64, gamma: f64, sg: f64) -> IkRoots {
    let s = beta.abs().max(gamma.abs().sqrt());
    let nu = sg + 2.0 * (sg * IK_ZERO_TOL).sqrt() * (2.0 * beta.abs() + s) + 4.0 * f64::EPSILON * (beta * beta + gamma.abs());
    let Some((rad, sg, ck)) = ik_radicand(beta * beta - gamma, (beta * beta).max(gamma.abs()), nu) else {
        return IkRoots::NONE;
    };
    let r = rad.sqrt();
    IkRoots { n: 2, q: [-beta + r, -beta - r, 0.0], sg, ck, ..IkRoots::NONE }
}

/// What the check of a solution needs: the joint axes in the home pose `[kind, w, p]` (kind 1:
/// prismatic), the home pose, the target and the robot's scale.
struct IkChain<'a> {
    ax: [[f64; 7]; IK_DOF],
    home: [[f64; 4]; 3],
    t: &'a [[f64; 4]; 4],
    len: f64,
}

/// The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
/// position or the target position.
fn ik_scale(ch: &IkChain) -> f64 {
    let n1 = |x: f64, y: f64, z: f64| x.abs() + y.abs() + z.abs();
    let mut l = n1(ch.home[0][3], ch.home[1][3], ch.home[2][3]).max(n1(ch.t[0][3], ch.t[1][3], ch.t[2][3]));
    for a in &ch.ax {
        l = l.max(n1(a[4], a[5], a[6]));
    }
    if l > 0.0 && l.is_finite() { l } else { 1.0 }
}

/// Writes a solution; one a step asks to check goes through `ik_checked`.
#[inline(always)]
fn ik_push(out: &mut IkSolutions, q: [f64; IK_DOF], sg: bool, ck: bool, smp: bool, ch: &IkChain) {
    if sg || ck {
        ik_checked(out, q, sg, smp, ch);
        return;
    }
    out.q[out.n] = q;
    out.singular[out.n] = false;
    out.approximate[out.n] = false;
    out.residual[out.n] = 0.0;
    out.n += 1;
}

/// A solution checked by forward kinematics: refined where its residual exceeds
/// IK_REFINE_TOL, flagged approximate where it stays above IK_POSE_TOL, dropped when it is a
/// sample off the pose or a singular duplicate.
#[cold]
#[inline(never)]
#[allow(clippy::needless_range_loop)]
fn ik_checked(out: &mut IkSolutions, mut q: [f64; IK_DOF], sg: bool, smp: bool, ch: &IkChain) {
    let mut res = ik_residual(ch, &q);
    if res > IK_REFINE_TOL {
        let mut r = q;
        let rr = ik_refine(ch, &mut r);
        if rr < res {
            q = r;
            res = rr;
        }
    }
    if smp && res > IK_POSE_TOL {
        return;
    }
    if sg {
        for i in 0..out.n {
            if out.singular[i] && ik_same(&out.q[i], &q) {
                return;
            }
        }
    }
    out.q[out.n] = q;
    out.singular[out.n] = sg;
    out.approximate[out.n] = res > IK_POSE_TOL || res.is_nan();
    out.residual[out.n] = res;
    out.n += 1;
}

/// Equal to a few units in the last place.
fn ik_same(a: &[f64; IK_DOF], b: &[f64; IK_DOF]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 4.0 * f64::EPSILON * x.abs().max(y.abs()).max(1.0))
}

/// `a b` for rigid motions as 3 x 4 blocks.
fn ik_compose(a: &[[f64; 4]; 3], b: &[[f64; 4]; 3]) -> [[f64; 4]; 3] {
    let mut m = [[0.0; 4]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + if c == 3 { a[r][3] } else { 0.0 };
        }
    }
    m
}

/// Joint motion at `q` about (along) a home axis: `R = c I + s [w]x + (1 - c) w w^T`, `t = (I
/// - R) p`.
#[allow(clippy::needless_range_loop)]
fn ik_motion(a: &[f64; 7], q: f64) -> [[f64; 4]; 3] {
    let w = [a[1], a[2], a[3]];
    if a[0] != 0.0 {
        return [[1.0, 0.0, 0.0, q * w[0]], [0.0, 1.0, 0.0, q * w[1]], [0.0, 0.0, 1.0, q * w[2]]];
    }
    let (s, c) = q.sin_cos();
    let k = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
    let mut m = [[0.0; 4]; 3];
    for r in 0..3 {
        for j in 0..3 {
            m[r][j] = if r == j { c } else { 0.0 } + s * k[r][j] + (1.0 - c) * w[r] * w[j];
        }
    }
    for r in 0..3 {
        m[r][3] = a[4 + r] - (m[r][0] * a[4] + m[r][1] * a[5] + m[r][2] * a[6]);
    }
    m
}

/// The pose `E1(q1) ... En(qn) M` and each joint's current axis `(w, p)`.
#[allow(clippy::needless_range_loop)]
fn ik_fk(ch: &IkChain, q: &[f64; IK_DOF], cur: &mut [[f64; 6]; IK_DOF]) -> [[f64; 4]; 3] {
    let mut p = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];
    for ((a, qi), cu) in ch.ax.iter().zip(q).zip(cur.iter_mut()) {
        for r in 0..3 {
            cu[r] = p[r][0] * a[1] + p[r][1] * a[2] + p[r][2] * a[3];
            cu[3 + r] = p[r][0] * a[4] + p[r][1] * a[5] + p[r][2] * a[6] + p[r][3];
        }
        p = ik_compose(&p, &ik_motion(a, *qi));
    }
    ik_compose(&p, &ch.home)
}

/// `T - F` (rotation entries, then positions over the scale; positions only for a
/// position-only solver); its length.
#[allow(clippy::needless_range_loop)]
fn ik_error(ch: &IkChain, f: &[[f64; 4]; 3], e: &mut [f64; 12]) -> usize {
    let mut k = 0;
    for r in 0..3 {
        for c in 0..4 {
            if c == 3 {
                e[k] = (ch.t[r][3] - f[r][3]) / ch.len;
                k += 1;
            } else if !IK_POSITION_ONLY {
                e[k] = ch.t[r][c] - f[r][c];
                k += 1;
            }
        }
    }
    k
}

/// The largest entry (NaN for a NaN).
fn ik_max_abs(e: &[f64]) -> f64 {
    e.iter().fold(0.0, |m: f64, x| if x.abs() > m || x.is_nan() { x.abs() } else { m })
}

/// The residual of `q`: the largest entry of `T - F(q)`, positions over the scale.
fn ik_residual(ch: &IkChain, q: &[f64; IK_DOF]) -> f64 {
    let mut cur = [[0.0; 6]; IK_DOF];
    let f = ik_fk(ch, q, &mut cur);
    let mut e = [0.0; 12];
    let k = ik_error(ch, &f, &mut e);
    ik_max_abs(&e[..k])
}

/// Damped Gauss-Newton on the pose residual from `q` (updated in place): at most
/// IK_REFINE_STEPS steps, each kept only when it lowers the residual (else the damping grows a
/// hundredfold). Returns the final residual.
#[allow(clippy::needless_range_loop)]
fn ik_refine(ch: &IkChain, q: &mut [f64; IK_DOF]) -> f64 {
    let mut cur = [[0.0; 6]; IK_DOF];
    let mut f = ik_fk(ch, q, &mut cur);
    let mut e = [0.0; 12];
    let m = ik_error(ch, &f, &mut e);
    let mut res = ik_max_abs(&e[..m]);
    let mut lambda = 1e-12;
    for _ in 0..IK_REFINE_STEPS {
        if res <= IK_CHECK_TOL * 1e-3 {
            break;
        }
        // Jacobian columns: d(R)/dqi = [wi]x R, d(t)/dqi = wi x (t - pi) (revolute), wi
        // (prismatic); the same entries and scaling as the residual.
        let mut jac = [[0.0; 12]; IK_DOF];
        for i in 0..IK_DOF {
            let w = [cur[i][0], cur[i][1], cur[i][2]];
            let cross = |v: [f64; 3]| [w[1] * v[2] - w[2] * v[1], w[2] * v[0] - w[0] * v[2], w[0] * v[1] - w[1] * v[0]];
            let pri = ch.ax[i][0] != 0.0;
            let dt = if pri { w } else { cross([f[0][3] - cur[i][3], f[1][3] - cur[i][4], f[2][3] - cur[i][5]]) };
            let mut dr = [[0.0; 3]; 3];
            if !pri {
                for c in 0..3 {
                    let v = cross([f[0][c], f[1][c], f[2][c]]);
                    for r in 0..3 {
                        dr[r][c] = v[r];
                    }
                }
            }
            let mut k = 0;
            for r in 0..3 {
                for c in 0..4 {
                    if c == 3 {
                        jac[i][k] = dt[r] / ch.len;
                        k += 1;
                    } else if !IK_POSITION_ONLY {
                        jac[i][k] = dr[r][c];
                        k += 1;
                    }
                }
            }
        }
        let mut a = [[0.0; IK_DOF]; IK_DOF];
        let mut g = [0.0; IK_DOF];
        let mut tr = 0.0;
        for i in 0..IK_DOF {
            for j in 0..IK_DOF {
                a[i][j] = (0..m).map(|k| jac[i][k] * jac[j][k]).sum();
            }
            g[i] = (0..m).map(|k| jac[i][k] * e[k]).sum();
            tr += a[i][i];
        }
        loop {
            let mut h = a;
            for i in 0..IK_DOF {
                h[i][i] += lambda * tr.max(f64::MIN_POSITIVE);
            }
            let mut d = g;
            if ik_cholesky(&mut h, &mut d) {
                let mut next = *q;
                for i in 0..IK_DOF {
                    next[i] += d[i];
                }
                let mut cur2 = [[0.0; 6]; IK_DOF];
                let f2 = ik_fk(ch, &next, &mut cur2);
                let mut e2 = [0.0; 12];
                ik_error(ch, &f2, &mut e2);
                let r2 = ik_max_abs(&e2[..m]);
                if r2 < res {
                    *q = next;
                    f = f2;
                    cur = cur2;
                    e = e2;
                    res = r2;
                    lambda = (lambda * 0.01).max(1e-15);
                    break;
                }
            }
            lambda *= 100.0;
            if lambda > 1.0 {
                return res;
            }
        }
    }
    res
}

/// Solves `h x = b` in place (`b` becomes `x`) for a symmetric positive definite `h`; false
/// when it is not.
#[allow(clippy::needless_range_loop)]
fn ik_cholesky(h: &mut [[f64; IK_DOF]; IK_DOF], b: &mut [f64; IK_DOF]) -> bool {
    for j in 0..IK_DOF {
        let mut d = h[j][j];
        for k in 0..j {
            d -= h[j][k] * h[j][k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        h[j][j] = d;
        for i in j + 1..IK_DOF {
            let mut s = h[i][j];
            for k in 0..j {
                s -= h[i][k] * h[j][k];
            }
            h[i][j] = s / d;
        }
    }
    for i in 0..IK_DOF {
        for k in 0..i {
            b[i] -= h[i][k] * b[k];
        }
        b[i] /= h[i][i];
    }
    for i in (0..IK_DOF).rev() {
        for k in i + 1..IK_DOF {
            b[i] -= h[k][i] * b[k];
        }
        b[i] /= h[i][i];
    }
    true
}

/// The homogeneous matrix of a unit dual quaternion (Appendix I).
fn ik_dq_matrix(q: &[f64; 8]) -> [[f64; 4]; 4] {
    let [w, x, y, z, a, b, c, d] = *q;
    // t = 2 q_eps q* (vector part)
    let tx = 2.0 * (-a * x + b * w - c * z + d * y);
    let ty = 2.0 * (-a * y + b * z + c * w - d * x);
    let tz = 2.0 * (-a * z - b * y + c * x + d * w);
    [
        [w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y), tx],
        [2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x), ty],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z, tz],
        [0.0, 0.0, 0.0, 1.0],
    ]
}
"#;

/// The solver as C99: `void ik(const double T[4][4], params..., ik_solutions *out)` and
/// `ik_dq`; no allocation.
///
/// # Errors
/// A closed form that fails.
pub fn ik_c(sol: &IkSolution) -> Result<String, ScalarError> {
    if sol.general.is_some() {
        return super::general::emit::ik_c(sol);
    }
    let sol = &*super::safe::solution(sol, names::Lang::C);
    let c = ctx(sol, Lang::C)?;
    let n = sol.variables.len();
    let max = max_solutions(sol);
    let params: String = sol.params.iter().map(|p| format!(", double {p}")).collect();
    let pnames: String = sol.params.iter().map(|p| format!(", {p}")).collect();
    let mut s = String::new();
    for l in doc_lines(sol, Comment::Block) {
        s.push_str(&format!("/* {l} */\n"));
    }
    s.push_str(&format!(
        "#include <float.h>\n#include <math.h>\n#ifndef M_PI\n#define M_PI 3.14159265358979323846\n#endif\n\n\
#define IK_MAX {max}\n#define IK_DOF {n}\n\ntypedef struct {{\n    double q[IK_MAX][IK_DOF];\n    int singular[IK_MAX];\n    int approximate[IK_MAX];\n    double residual[IK_MAX];\n    int n;\n}} ik_solutions;\n\n"
    ));
    let consts = tolerances(sol, Some(Lang::C));
    s.push_str(&helpers(sol, &[&consts, C_HELPERS]));
    s.push_str(&format!(
        "\nvoid ik(const double ik_target[4][4]{params}, ik_solutions *ik_out) {{\n"
    ));
    for (r, row) in TARGET_SYMBOLS.iter().enumerate() {
        for (col, name) in row.iter().enumerate() {
            s.push_str(&format!(
                "    const double {name} = ik_target[{r}][{col}];\n"
            ));
            s.push_str(&format!("    (void){name};\n"));
        }
    }
    for p in &sol.params {
        s.push_str(&format!("    (void){p};\n"));
    }
    s.push_str("    ik_out->n = 0;\n");
    let mut body = String::new();
    c.level(0, 4, &mut body);
    c.body(0, 4, &mut body);
    s.push_str(&body);
    s.push_str("}\n\n");
    s.push_str(&format!(
        "void ik_dq(const double ik_q[8]{params}, ik_solutions *ik_out) {{\n    double ik_target[4][4];\n    ik_dq_matrix(ik_q, ik_target);\n    ik((const double (*)[4])ik_target{pnames}, ik_out);\n}}\n"
    ));
    Ok(s)
}

const C_HELPERS: &str = r#"/* The roots of one step: n joint values with their sines and cosines, and the flags
   (singular, checked); n = 12 on a singular set of an atan2 (any value: k pi/6, k = -5..6),
   n = 13 with the atan2 value first. */
typedef struct {
    int n;
    double q[3], s[3], c[3];
    int sg, ck, smp;
} ik_roots;

static ik_roots ik_none(void) {
    ik_roots r = {0, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 0, 0, 99};
    return r;
}

static void ik_root(const ik_roots *r, int i, double *q, double *s, double *c) {
    if (r->n >= 12 && i + 12 >= r->n) {
        *q = (i + 12 - r->n - 5) * (M_PI / 6);
        *s = sin(*q);
        *c = cos(*q);
    } else {
        *q = r->q[i];
        *s = r->s[i];
        *c = r->c[i];
    }
}

/* A step's last atan2, reused by the next call of the step: the same arguments give the same
   root, exactly negated ones the angle plus pi with the sine and cosine negated. */
typedef struct {
    double y, x;
    ik_roots r;
} ik_memo;

static ik_memo ik_memo_new(void) {
    ik_memo m;
    m.y = m.x = NAN;
    m.r = ik_none();
    return m;
}

/* atan2(y, x) for arguments rounded by sg: where both are zero within it, any value (and
   atan2 itself where not exactly 0/0). */
static ik_roots ik_atan2(double y, double x, double sg, ik_memo *m) {
    ik_roots r = ik_none();
    double h2, h;
    if (m->r.n == 1 && y == m->y && x == m->x) return m->r;
    if (m->r.n == 1 && y == -m->y && x == -m->x) {
        const double q = m->r.q[0];
        m->r.q[0] = q > 0.0 ? q - M_PI : q + M_PI;
        m->r.s[0] = -m->r.s[0];
        m->r.c[0] = -m->r.c[0];
        m->y = y;
        m->x = x;
        return m->r;
    }
    h2 = y * y + x * x;
    if (h2 <= sg * sg) {
        r.sg = 1;
        r.ck = 1;
        r.n = 12;
        if (h2 > 0.0) {
            h = sqrt(h2);
            r.n = 13;
            r.smp = 1;
            r.q[0] = atan2(y, x);
            r.s[0] = y / h;
            r.c[0] = x / h;
        }
        return r;
    }
    h = sqrt(h2);
    r.n = 1;
    r.q[0] = atan2(y, x);
    r.s[0] = y / h;
    r.c[0] = x / h;
    r.ck = sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2;
    m->y = y;
    m->x = x;
    m->r = r;
    return r;
}

/* A radicand of scale n rounded by nu: 0 out of reach (below -IK_REACH_TOL n), a double root
   within nu of zero (singular), else itself (checked where its roots err by more than
   IK_CHECK_TOL). */
static int ik_radicand(double *rad, double n, double nu, int *sg, int *ck) {
    if (*rad < -IK_REACH_TOL * n - nu) return 0;
    if (*rad <= nu) {
        *sg = 1;
        *ck = 1;
        *rad = 0.0;
    } else {
        *ck = nu * nu > 4.0 * IK_CHECK_TOL * IK_CHECK_TOL * *rad * n;
    }
    return 1;
}

static ik_roots ik_trig(double a, double b, double c, double sg) {
    ik_roots r = ik_none();
    const double n = a * a + b * b;
    double rad, nu, w, d, y0, x0, y1, x1;
    if (n <= sg * sg) {
        if (fabs(c) <= sg) {
            r.n = 1;
            r.sg = 1;
            r.ck = 1;
        }
        return r;
    }
    rad = n - c * c;
    nu = 2.0 * sg * (fabs(a) + fabs(b) + fabs(c)) + 4.0 * DBL_EPSILON * n;
    if (!ik_radicand(&rad, n, nu, &r.sg, &r.ck)) return r;
    w = sqrt(rad);
    d = r.sg ? sqrt(n * (c * c + rad)) : n;
    y0 = b * c + a * w; x0 = a * c - b * w; y1 = b * c - a * w; x1 = a * c + b * w;
    r.n = 2;
    r.q[0] = atan2(y0, x0);
    r.q[1] = b == 0.0 ? -r.q[0] : a == 0.0 ? copysign(M_PI, y0) - r.q[0] : atan2(y1, x1);
    r.s[0] = y0 / d; r.s[1] = y1 / d;
    r.c[0] = x0 / d; r.c[1] = x1 / d;
    if (r.sg) {
        /* Beside the double root, the pair of the radicand nu (sampled: kept where refinement
           takes it onto the pose). */
        const double wn = sqrt(nu), e = sqrt(n * (c * c + nu));
        const double y2 = b * c + a * wn, x2 = a * c - b * wn, y3 = b * c - a * wn, x3 = a * c + b * wn;
        r.n = 3;
        r.smp = 1;
        r.q[1] = atan2(y2, x2); r.s[1] = y2 / e; r.c[1] = x2 / e;
        r.q[2] = atan2(y3, x3); r.s[2] = y3 / e; r.c[2] = x3 / e;
    }
    return r;
}

/* Beside the double root of ik_trig(...): a solution from `from` on reproduces the pose. */
static int ik_exact(const ik_solutions *out, int from) {
    int i;
    for (i = from; i < out->n; i++)
        if (!out->approximate[i]) return 1;
    return 0;
}

static ik_roots ik_quadratic(double beta, double gamma, double sg) {
    ik_roots r = ik_none();
    double rad = beta * beta - gamma, w;
    const double s = fmax(fabs(beta), sqrt(fabs(gamma)));
    const double nu = sg + 2.0 * sqrt(sg * IK_ZERO_TOL) * (2.0 * fabs(beta) + s) + 4.0 * DBL_EPSILON * (beta * beta + fabs(gamma));
    if (!ik_radicand(&rad, fmax(beta * beta, fabs(gamma)), nu, &r.sg, &r.ck)) return r;
    w = sqrt(rad);
    r.n = 2;
    r.q[0] = -beta + w; r.q[1] = -beta - w;
    return r;
}

/* What the check of a solution needs: the joint axes in the home pose {kind, w, p} (kind 1:
   prismatic), the home pose, the target and the robot's scale. */
typedef struct {
    double ax[IK_DOF][7];
    double home[3][4];
    const double (*t)[4];
    double len;
} ik_chain;

/* The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
   position or the target position. */
static double ik_scale(const ik_chain *ch) {
    double l = fmax(fabs(ch->home[0][3]) + fabs(ch->home[1][3]) + fabs(ch->home[2][3]),
                    fabs(ch->t[0][3]) + fabs(ch->t[1][3]) + fabs(ch->t[2][3]));
    int i;
    for (i = 0; i < IK_DOF; i++) l = fmax(l, fabs(ch->ax[i][4]) + fabs(ch->ax[i][5]) + fabs(ch->ax[i][6]));
    return l > 0.0 && l < HUGE_VAL ? l : 1.0;
}

/* a b for rigid motions as 3 x 4 blocks (m may not be a or b). */
static void ik_compose(const double a[3][4], const double b[3][4], double m[3][4]) {
    int r, c;
    for (r = 0; r < 3; r++)
        for (c = 0; c < 4; c++)
            m[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + (c == 3 ? a[r][3] : 0.0);
}

/* Joint motion at q about (along) a home axis: R = c I + s [w]x + (1 - c) w w^T,
   t = (I - R) p. */
static void ik_motion(const double a[7], double q, double m[3][4]) {
    const double w[3] = {a[1], a[2], a[3]};
    const double k[3][3] = {{0.0, -a[3], a[2]}, {a[3], 0.0, -a[1]}, {-a[2], a[1], 0.0}};
    const double s = sin(q), c = cos(q);
    int r, j;
    for (r = 0; r < 3; r++) {
        for (j = 0; j < 3; j++)
            m[r][j] = a[0] != 0.0 ? (r == j ? 1.0 : 0.0) : (r == j ? c : 0.0) + s * k[r][j] + (1.0 - c) * w[r] * w[j];
        m[r][3] = a[0] != 0.0 ? q * w[r] : a[4 + r] - (m[r][0] * a[4] + m[r][1] * a[5] + m[r][2] * a[6]);
    }
}

/* The pose E1(q1) ... En(qn) M (into f) and each joint's current axis (w, p). */
static void ik_fk(const ik_chain *ch, const double q[IK_DOF], double cur[IK_DOF][6], double f[3][4]) {
    double p[3][4] = {{1.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}}, e[3][4], m[3][4];
    int i, r, c;
    for (i = 0; i < IK_DOF; i++) {
        const double *a = ch->ax[i];
        for (r = 0; r < 3; r++) {
            cur[i][r] = p[r][0] * a[1] + p[r][1] * a[2] + p[r][2] * a[3];
            cur[i][3 + r] = p[r][0] * a[4] + p[r][1] * a[5] + p[r][2] * a[6] + p[r][3];
        }
        ik_motion(a, q[i], e);
        ik_compose((const double (*)[4])p, (const double (*)[4])e, m);
        for (r = 0; r < 3; r++)
            for (c = 0; c < 4; c++) p[r][c] = m[r][c];
    }
    ik_compose((const double (*)[4])p, ch->home, f);
}

/* T - F (rotation entries, then positions over the scale; positions only for a
   position-only solver); returns its length. */
static int ik_error(const ik_chain *ch, const double f[3][4], double e[12]) {
    int k = 0, r, c;
    for (r = 0; r < 3; r++)
        for (c = 0; c < 4; c++) {
            if (c == 3) e[k++] = (ch->t[r][3] - f[r][3]) / ch->len;
            else if (!IK_POSITION_ONLY) e[k++] = ch->t[r][c] - f[r][c];
        }
    return k;
}

static double ik_max_abs(const double *e, int m) {
    double x = 0.0;
    int k;
    for (k = 0; k < m; k++)
        if (fabs(e[k]) > x || e[k] != e[k]) x = fabs(e[k]);
    return x;
}

/* The residual of q: the largest entry of T - F(q), positions over the scale. */
static double ik_residual(const ik_chain *ch, const double q[IK_DOF]) {
    double cur[IK_DOF][6], f[3][4], e[12];
    int m;
    ik_fk(ch, q, cur, f);
    m = ik_error(ch, (const double (*)[4])f, e);
    return ik_max_abs(e, m);
}

/* Solves h x = b in place (b becomes x) for a symmetric positive definite h; 0 when it is
   not. */
static int ik_cholesky(double h[IK_DOF][IK_DOF], double b[IK_DOF]) {
    int i, j, k;
    for (j = 0; j < IK_DOF; j++) {
        double d = h[j][j];
        for (k = 0; k < j; k++) d -= h[j][k] * h[j][k];
        if (!(d > 0.0)) return 0;
        d = sqrt(d);
        h[j][j] = d;
        for (i = j + 1; i < IK_DOF; i++) {
            double s = h[i][j];
            for (k = 0; k < j; k++) s -= h[i][k] * h[j][k];
            h[i][j] = s / d;
        }
    }
    for (i = 0; i < IK_DOF; i++) {
        for (k = 0; k < i; k++) b[i] -= h[i][k] * b[k];
        b[i] /= h[i][i];
    }
    for (i = IK_DOF - 1; i >= 0; i--) {
        for (k = i + 1; k < IK_DOF; k++) b[i] -= h[k][i] * b[k];
        b[i] /= h[i][i];
    }
    return 1;
}

/* Damped Gauss-Newton on the pose residual from q (updated in place): at most
   IK_REFINE_STEPS steps, each kept only when it lowers the residual (else the damping grows a
   hundredfold). Returns the final residual. */
static double ik_refine(const ik_chain *ch, double q[IK_DOF]) {
    double cur[IK_DOF][6], f[3][4], e[12], jac[IK_DOF][12], a[IK_DOF][IK_DOF], g[IK_DOF];
    double lambda = 1e-12, res;
    int m, it, i, j, k, r, c;
    ik_fk(ch, q, cur, f);
    m = ik_error(ch, (const double (*)[4])f, e);
    res = ik_max_abs(e, m);
    for (it = 0; it < IK_REFINE_STEPS && res > IK_CHECK_TOL * 1e-3; it++) {
        double tr = 0.0;
        /* Jacobian columns: d(R)/dqi = [wi]x R, d(t)/dqi = wi x (t - pi) (revolute), wi
           (prismatic); the same entries and scaling as the residual. */
        for (i = 0; i < IK_DOF; i++) {
            const double *w = cur[i];
            const int pri = ch->ax[i][0] != 0.0;
            const double v[3] = {f[0][3] - cur[i][3], f[1][3] - cur[i][4], f[2][3] - cur[i][5]};
            double dt[3], dr[3][3];
            dt[0] = pri ? w[0] : w[1] * v[2] - w[2] * v[1];
            dt[1] = pri ? w[1] : w[2] * v[0] - w[0] * v[2];
            dt[2] = pri ? w[2] : w[0] * v[1] - w[1] * v[0];
            for (c = 0; c < 3; c++) {
                dr[0][c] = pri ? 0.0 : w[1] * f[2][c] - w[2] * f[1][c];
                dr[1][c] = pri ? 0.0 : w[2] * f[0][c] - w[0] * f[2][c];
                dr[2][c] = pri ? 0.0 : w[0] * f[1][c] - w[1] * f[0][c];
            }
            k = 0;
            for (r = 0; r < 3; r++)
                for (c = 0; c < 4; c++) {
                    if (c == 3) jac[i][k++] = dt[r] / ch->len;
                    else if (!IK_POSITION_ONLY) jac[i][k++] = dr[r][c];
                }
        }
        for (i = 0; i < IK_DOF; i++) {
            for (j = 0; j < IK_DOF; j++) {
                a[i][j] = 0.0;
                for (k = 0; k < m; k++) a[i][j] += jac[i][k] * jac[j][k];
            }
            g[i] = 0.0;
            for (k = 0; k < m; k++) g[i] += jac[i][k] * e[k];
            tr += a[i][i];
        }
        for (;;) {
            double h[IK_DOF][IK_DOF], d[IK_DOF];
            for (i = 0; i < IK_DOF; i++) {
                for (j = 0; j < IK_DOF; j++) h[i][j] = a[i][j];
                h[i][i] += lambda * (tr > DBL_MIN ? tr : DBL_MIN);
                d[i] = g[i];
            }
            if (ik_cholesky(h, d)) {
                double next[IK_DOF], cur2[IK_DOF][6], f2[3][4], e2[12], r2;
                for (i = 0; i < IK_DOF; i++) next[i] = q[i] + d[i];
                ik_fk(ch, next, cur2, f2);
                ik_error(ch, (const double (*)[4])f2, e2);
                r2 = ik_max_abs(e2, m);
                if (r2 < res) {
                    for (i = 0; i < IK_DOF; i++) q[i] = next[i];
                    for (i = 0; i < IK_DOF; i++)
                        for (j = 0; j < 6; j++) cur[i][j] = cur2[i][j];
                    for (r = 0; r < 3; r++)
                        for (c = 0; c < 4; c++) f[r][c] = f2[r][c];
                    for (k = 0; k < 12; k++) e[k] = e2[k];
                    res = r2;
                    lambda = lambda * 0.01 > 1e-15 ? lambda * 0.01 : 1e-15;
                    break;
                }
            }
            lambda *= 100.0;
            if (lambda > 1.0) return res;
        }
    }
    return res;
}

static int ik_same(const double *a, const double *b) {
    int i;
    for (i = 0; i < IK_DOF; i++) {
        const double s = fmax(fmax(fabs(a[i]), fabs(b[i])), 1.0);
        if (fabs(a[i] - b[i]) > 4.0 * DBL_EPSILON * s) return 0;
    }
    return 1;
}

/* Writes a solution; one a step asks to check is checked by forward kinematics: refined
   where its residual exceeds IK_REFINE_TOL, flagged approximate where it stays above
   IK_POSE_TOL, dropped when it is a sample off the pose or a singular duplicate. */
static void ik_push(ik_solutions *out, const double q0[IK_DOF], int sg, int ck, int smp, const ik_chain *ch) {
    double q[IK_DOF], res = 0.0;
    int i;
    for (i = 0; i < IK_DOF; i++) q[i] = q0[i];
    if (sg || ck) {
        res = ik_residual(ch, q);
        if (res > IK_REFINE_TOL) {
            double r[IK_DOF], rr;
            for (i = 0; i < IK_DOF; i++) r[i] = q[i];
            rr = ik_refine(ch, r);
            if (rr < res) {
                for (i = 0; i < IK_DOF; i++) q[i] = r[i];
                res = rr;
            }
        }
        if (smp && res > IK_POSE_TOL) return;
        if (sg)
            for (i = 0; i < out->n; i++)
                if (out->singular[i] && ik_same(out->q[i], q)) return;
    }
    for (i = 0; i < IK_DOF; i++) out->q[out->n][i] = q[i];
    out->singular[out->n] = sg;
    out->approximate[out->n] = !(res <= IK_POSE_TOL);
    out->residual[out->n] = res;
    out->n += 1;
}

static void ik_dq_matrix(const double q[8], double T[4][4]) {
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double a = q[4], b = q[5], c = q[6], d = q[7];
    T[0][0] = w * w + x * x - y * y - z * z; T[0][1] = 2 * (x * y - w * z); T[0][2] = 2 * (x * z + w * y);
    T[1][0] = 2 * (x * y + w * z); T[1][1] = w * w - x * x + y * y - z * z; T[1][2] = 2 * (y * z - w * x);
    T[2][0] = 2 * (x * z - w * y); T[2][1] = 2 * (y * z + w * x); T[2][2] = w * w - x * x - y * y + z * z;
    T[0][3] = 2 * (-a * x + b * w - c * z + d * y);
    T[1][3] = 2 * (-a * y + b * z + c * w - d * x);
    T[2][3] = 2 * (-a * z - b * y + c * x + d * w);
    T[3][0] = T[3][1] = T[3][2] = 0.0; T[3][3] = 1.0;
}
"#;

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
    let sol = &*super::safe::solution(sol, names::Lang::Python);
    let c = ctx(sol, Lang::Python)?;
    let kw = if sol.params.is_empty() {
        String::new()
    } else {
        format!(", *, {}", sol.params.join(", "))
    };
    let pass: String = sol.params.iter().map(|p| format!(", {p}={p}")).collect();
    let mut s = String::new();
    for l in doc_lines(sol, Comment::Python) {
        s.push_str(&format!("# {l}\n"));
    }
    s.push_str("import math\n\nimport numpy as np\n\n\n");
    let py = format!("{}\n\n{PY_HELPERS}", tolerances(sol, Some(Lang::Python)));
    s.push_str(&helpers(sol, &[&py]));
    s.push_str(&format!(
        "\n\ndef ik_full(T{kw}):\n    \"\"\"Every solution as (q, singular, approximate, residual).\"\"\"\n    T = np.asarray(T, dtype=float)\n"
    ));
    for (r, row) in TARGET_SYMBOLS.iter().enumerate() {
        for (col, name) in row.iter().enumerate() {
            s.push_str(&format!("    {name} = float(T[{r}, {col}])\n"));
        }
    }
    s.push_str("    ik_out = []\n");
    let mut body = String::new();
    c.level(0, 4, &mut body);
    c.body(0, 4, &mut body);
    s.push_str(&body);
    s.push_str("    return ik_out\n\n\n");
    s.push_str(&format!(
        "def ik(T{kw}):\n    \"\"\"Every solution: joint vectors in joint order ({}).\"\"\"\n    return [q for q, _, _, _ in ik_full(T{pass})]\n\n\n",
        sol.variables.join(", ")
    ));
    s.push_str(&format!(
        "def ik_dq(q{kw}):\n    \"\"\"ik for a unit dual quaternion (w, x, y, z) + eps (w, x, y, z).\"\"\"\n    return ik(_ik_dq_matrix(q){pass})\n"
    ));
    Ok(s)
}

const PY_HELPERS: &str = r#"def _ik_radicand(rad, n, nu):
    # A radicand of scale n rounded by nu: None out of reach (below -IK_REACH_TOL n), a double
    # root within nu of zero (singular), else itself (checked where its roots err by more than
    # IK_CHECK_TOL): (rad, singular, checked).
    if rad < -IK_REACH_TOL * n - nu:
        return None
    if rad <= nu:
        return 0.0, True, True
    return rad, False, nu * nu > 4.0 * IK_CHECK_TOL * IK_CHECK_TOL * rad * n


def _ik_any(first):
    # A joint free on a singular set: twelve values k pi/6, k = -5..6; sampled beside a kept
    # atan2 value when `first`.
    qs = [k * math.pi / 6 for k in range(-5, 7)]
    return [(q, math.sin(q), math.cos(q), first) for q in qs]


def _ik_atan2(y, x, sg, m):
    # The roots [(q, sin q, cos q, sampled)], singular, checked, for arguments rounded by sg.
    # m: the step's last [y, x, roots]: the same arguments give the same root, exactly negated
    # ones q + pi (the wrist flip).
    if m and len(m[2][0]) == 1 and y == m[0] and x == m[1]:
        return m[2]
    if m and len(m[2][0]) == 1 and y == -m[0] and x == -m[1]:
        q, s, c, _ = m[2][0][0]
        m[:] = [y, x, ([(q - math.pi if q > 0 else q + math.pi, -s, -c, False)], False, m[2][2])]
        return m[2]
    h2 = y * y + x * x
    if h2 <= sg * sg:
        if h2 > 0.0:
            h = math.sqrt(h2)
            return [(math.atan2(y, x), y / h, x / h, False)] + _ik_any(True), True, True
        return _ik_any(False), True, True
    h = math.sqrt(h2)
    ck = sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2
    m[:] = [y, x, ([(math.atan2(y, x), y / h, x / h, False)], False, ck)]
    return m[2]


def _ik_trig(a, b, c, sg):
    n = a * a + b * b
    if n <= sg * sg:
        return ([(0.0, 0.0, 1.0, False)] if abs(c) <= sg else []), True, True
    nu = 2.0 * sg * (abs(a) + abs(b) + abs(c)) + 4.0 * IK_EPS * n
    r = _ik_radicand(n - c * c, n, nu)
    if r is None:
        return [], False, False
    rad, sing, ck = r
    w = math.sqrt(rad)
    d = math.sqrt(n * (c * c + rad)) if sing else n
    y0, x0, y1, x1 = b * c + a * w, a * c - b * w, b * c - a * w, a * c + b * w
    q0 = math.atan2(y0, x0)
    if b == 0.0:
        q1 = -q0
    elif a == 0.0:
        q1 = math.copysign(math.pi, y0) - q0
    else:
        q1 = math.atan2(y1, x1)
    roots = [(q0, y0 / d, x0 / d, False), (q1, y1 / d, x1 / d, False)]
    if sing:
        # Beside the double root, the pair of the radicand nu (sampled: kept where refinement
        # takes it onto the pose).
        w, e = math.sqrt(nu), math.sqrt(n * (c * c + nu))
        y2, x2, y3, x3 = b * c + a * w, a * c - b * w, b * c - a * w, a * c + b * w
        roots = [roots[0], (math.atan2(y2, x2), y2 / e, x2 / e, True),
                 (math.atan2(y3, x3), y3 / e, x3 / e, True)]
    return roots, sing, ck


def _ik_quadratic(beta, gamma, sg):
    s = max(abs(beta), math.sqrt(abs(gamma)))
    nu = sg + 2.0 * math.sqrt(sg * IK_ZERO_TOL) * (2.0 * abs(beta) + s) + 4.0 * IK_EPS * (beta * beta + abs(gamma))
    r = _ik_radicand(beta * beta - gamma, max(beta * beta, abs(gamma)), nu)
    if r is None:
        return [], False, False
    rad, sing, ck = r
    w = math.sqrt(rad)
    return [(-beta + w, 0.0, 1.0, False), (-beta - w, 0.0, 1.0, False)], sing, ck


def _ik_scale(ax, home, T):
    # The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
    # position or the target position.
    s = max([abs(a[4]) + abs(a[5]) + abs(a[6]) for a in ax]
            + [sum(abs(home[r][3]) for r in range(3)), sum(abs(float(T[r][3])) for r in range(3))])
    return s if 0.0 < s < math.inf else 1.0


def _ik_fk(ax, home, q):
    # The pose E1(q1) ... En(qn) M (3 x 4) and each joint's current axis (w, p).
    p = np.eye(4)
    cur = []
    for a, qi in zip(ax, q):
        w = np.array(a[1:4])
        cur.append((p[:3, :3] @ w, p[:3, :3] @ np.array(a[4:7]) + p[:3, 3]))
        e = np.eye(4)
        if a[0] != 0.0:
            e[:3, 3] = qi * w
        else:
            s, c = math.sin(qi), math.cos(qi)
            k = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
            e[:3, :3] = c * np.eye(3) + s * k + (1.0 - c) * np.outer(w, w)
            e[:3, 3] = np.array(a[4:7]) - e[:3, :3] @ np.array(a[4:7])
        p = p @ e
    return (p @ np.vstack([home, [0.0, 0.0, 0.0, 1.0]]))[:3], cur


def _ik_error(f, T, n):
    # T - F: rotation entries, then positions over the scale (positions only for a
    # position-only solver).
    T = np.asarray(T, dtype=float)
    rows = []
    for r in range(3):
        for c in range(4):
            if c == 3:
                rows.append((T[r, 3] - f[r, 3]) / n)
            elif not IK_POSITION_ONLY:
                rows.append(T[r, c] - f[r, c])
    return np.array(rows)


def _ik_max_abs(e):
    return float(np.max(np.abs(e))) if not np.isnan(e).any() else math.nan


def _ik_refine(ax, home, T, n, q):
    # Damped Gauss-Newton on the pose residual from q: at most IK_REFINE_STEPS steps, each
    # kept only when it lowers the residual (else the damping grows a hundredfold); the joint
    # vector and its residual.
    q = list(q)
    f, cur = _ik_fk(ax, home, q)
    e = _ik_error(f, T, n)
    res = _ik_max_abs(e)
    lam = 1e-12
    for _ in range(IK_REFINE_STEPS):
        if res <= IK_CHECK_TOL * 1e-3:
            break
        cols = []
        for a, (w, p) in zip(ax, cur):
            if a[0] != 0.0:
                dr, dt = np.zeros((3, 3)), w
            else:
                dr, dt = np.cross(w, f[:, :3].T).T, np.cross(w, f[:, 3] - p)
            cols.append(_ik_error(np.hstack([-dr, -dt.reshape(3, 1)]), np.zeros((3, 4)), n))
        jac = np.array(cols).T
        a = jac.T @ jac
        g = jac.T @ e
        tr = max(float(np.trace(a)), 2.2250738585072014e-308)
        while True:
            ok = True
            try:
                d = np.linalg.solve(a + lam * tr * np.eye(len(q)), g)
                ok = bool(np.all(np.isfinite(d)))
            except np.linalg.LinAlgError:
                ok = False
            if ok:
                nxt = [x + float(y) for x, y in zip(q, d)]
                f2, cur2 = _ik_fk(ax, home, nxt)
                e2 = _ik_error(f2, T, n)
                r2 = _ik_max_abs(e2)
                if r2 < res:
                    q, f, cur, e, res = nxt, f2, cur2, e2, r2
                    lam = max(lam * 0.01, 1e-15)
                    break
            lam *= 100.0
            if lam > 1.0:
                return q, res
    return q, res


def _ik_push(out, q, sg, ck, smp, ax, home, T, n):
    # Writes a solution (q, singular, approximate, residual); one a step asks to check is
    # checked by forward kinematics: refined where its residual exceeds IK_REFINE_TOL, flagged
    # approximate where it stays above IK_POSE_TOL, dropped when it is a sample off the pose or
    # a singular duplicate.
    q = [float(x) for x in q]
    res = 0.0
    if sg or ck:
        f, _ = _ik_fk(ax, home, q)
        res = _ik_max_abs(_ik_error(f, T, n))
        if res > IK_REFINE_TOL:
            r, rr = _ik_refine(ax, home, T, n, q)
            if rr < res:
                q, res = [float(x) for x in r], rr
        if smp and res > IK_POSE_TOL:
            return
        if sg:
            for p, psg, _, _ in out:
                if psg and all(abs(x - y) <= 4 * IK_EPS * max(abs(x), abs(y), 1.0) for x, y in zip(p, q)):
                    return
    out.append((q, sg, not res <= IK_POSE_TOL, res))


def _ik_dq_matrix(q):
    w, x, y, z, a, b, c, d = (float(v) for v in q)
    return np.array([
        [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
         2 * (-a * x + b * w - c * z + d * y)],
        [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
         2 * (-a * y + b * z + c * w - d * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z,
         2 * (-a * z - b * y + c * x + d * w)],
        [0.0, 0.0, 0.0, 1.0],
    ])"#;

const JS_HELPERS: &str = r#"// The candidates of one step from its parts v (rounded by sg): [value, singular, checked,
// sampled] each.
function ik_cands(kind, v, sg) {
    const any = (first) => {
        const out = [];
        for (let k = -5; k <= 6; k++) out.push([k * Math.PI / 6, true, true, first]);
        return out;
    };
    const radicand = (rad, n, nu) => {
        if (rad < -IK_REACH_TOL * n - nu) return null;
        if (rad <= nu) return [0, true, true];
        return [rad, false, nu * nu > 4 * IK_CHECK_TOL * IK_CHECK_TOL * rad * n];
    };
    if (kind === "atan2") {
        const [y, x] = v, h2 = y * y + x * x;
        if (h2 <= sg * sg) {
            return (h2 > 0 ? [[Math.atan2(y, x), true, true, false]] : []).concat(any(h2 > 0));
        }
        return [[Math.atan2(y, x), false, sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2, false]];
    }
    if (kind === "value") return [[v[0], false, false, false]];
    if (kind === "trig") {
        const [a, b, c] = v, n = a * a + b * b;
        if (n <= sg * sg) return Math.abs(c) <= sg ? [[0, true, true, false]] : [];
        const nu = 2 * sg * (Math.abs(a) + Math.abs(b) + Math.abs(c)) + 4 * IK_EPS * n;
        const r = radicand(n - c * c, n, nu);
        if (r === null) return [];
        // atan2(b, a) +- atan2(w, c) as atan2(b c +- a w, a c -+ b w), as the solvers do.
        const w = Math.sqrt(r[0]);
        if (r[1]) {
            // Beside the double root, the pair of the radicand nu (sampled: kept where
            // refinement takes it onto the pose).
            const e = Math.sqrt(nu);
            return [[Math.atan2(b * c, a * c), true, true, false],
                [Math.atan2(b * c + a * e, a * c - b * e), true, true, true],
                [Math.atan2(b * c - a * e, a * c + b * e), true, true, true]];
        }
        return [[Math.atan2(b * c + a * w, a * c - b * w), r[1], r[2], false],
            [Math.atan2(b * c - a * w, a * c + b * w), r[1], r[2], false]];
    }
    const [b, g] = v, s = Math.max(Math.abs(b), Math.sqrt(Math.abs(g)));
    const nu = sg + 2 * Math.sqrt(sg * IK_ZERO_TOL) * (2 * Math.abs(b) + s) + 4 * IK_EPS * (b * b + Math.abs(g));
    const r = radicand(b * b - g, Math.max(b * b, Math.abs(g)), nu);
    if (r === null) return [];
    const w = Math.sqrt(r[0]);
    return [[-b + w, r[1], r[2], false], [-b - w, r[1], r[2], false]];
}

// The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
// position or the target position.
function ik_scale(ax, home, T) {
    const n1 = (v) => Math.abs(v[0]) + Math.abs(v[1]) + Math.abs(v[2]);
    let l = Math.max(n1(home.map((r) => r[3])), n1(T.map((r) => r[3])));
    for (const a of ax) l = Math.max(l, n1(a.slice(4)));
    return l > 0 && l < Infinity ? l : 1;
}

// The pose E1(q1) ... En(qn) M (3 x 4) and each joint's current axis [w, p].
function ik_fk(ax, home, q) {
    const compose = (a, b) => [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) =>
        a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + (c === 3 ? a[r][3] : 0)));
    let p = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]];
    const cur = [];
    ax.forEach((a, i) => {
        const w = [a[1], a[2], a[3]];
        cur.push([0, 1, 2].map((r) => p[r][0] * a[1] + p[r][1] * a[2] + p[r][2] * a[3])
            .concat([0, 1, 2].map((r) => p[r][0] * a[4] + p[r][1] * a[5] + p[r][2] * a[6] + p[r][3])));
        let m;
        if (a[0] !== 0) {
            m = [0, 1, 2].map((r) => [0, 1, 2].map((c) => (r === c ? 1 : 0)).concat([q[i] * w[r]]));
        } else {
            const s = Math.sin(q[i]), c = Math.cos(q[i]);
            const k = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]];
            m = [0, 1, 2].map((r) => [0, 1, 2].map((j) =>
                (r === j ? c : 0) + s * k[r][j] + (1 - c) * w[r] * w[j]));
            m.forEach((row, r) => row.push(a[4 + r] - (row[0] * a[4] + row[1] * a[5] + row[2] * a[6])));
        }
        p = compose(p, m);
    });
    return [compose(p, home), cur];
}

// T - F: rotation entries, then positions over the scale (positions only for a position-only
// solver).
function ik_error(f, T, len, po) {
    const e = [];
    for (let r = 0; r < 3; r++) for (let c = 0; c < 4; c++) {
        if (c === 3) e.push((T[r][3] - f[r][3]) / len);
        else if (!po) e.push(T[r][c] - f[r][c]);
    }
    return e;
}

function ik_max_abs(e) {
    return e.reduce((m, x) => (Math.abs(x) > m || Number.isNaN(x) ? Math.abs(x) : m), 0);
}

// Solves h x = b for a symmetric positive definite h (Cholesky); null when it is not.
function ik_cholesky(h, b) {
    const n = b.length, l = h.map((r) => r.slice()), x = b.slice();
    for (let j = 0; j < n; j++) {
        let d = l[j][j];
        for (let k = 0; k < j; k++) d -= l[j][k] * l[j][k];
        if (!(d > 0)) return null;
        d = Math.sqrt(d);
        l[j][j] = d;
        for (let i = j + 1; i < n; i++) {
            let s = l[i][j];
            for (let k = 0; k < j; k++) s -= l[i][k] * l[j][k];
            l[i][j] = s / d;
        }
    }
    for (let i = 0; i < n; i++) {
        for (let k = 0; k < i; k++) x[i] -= l[i][k] * x[k];
        x[i] /= l[i][i];
    }
    for (let i = n - 1; i >= 0; i--) {
        for (let k = i + 1; k < n; k++) x[i] -= l[k][i] * x[k];
        x[i] /= l[i][i];
    }
    return x;
}

// Damped Gauss-Newton on the pose residual from q: at most IK_REFINE_STEPS steps, each kept
// only when it lowers the residual (else the damping grows a hundredfold); [q, residual].
function ik_refine(ax, home, T, len, po, q) {
    let [f, cur] = ik_fk(ax, home, q), e = ik_error(f, T, len, po), res = ik_max_abs(e);
    let lambda = 1e-12;
    for (let it = 0; it < IK_REFINE_STEPS && res > IK_CHECK_TOL * 1e-3; it++) {
        // Jacobian columns: d(R)/dqi = [wi]x R, d(t)/dqi = wi x (t - pi) (revolute), wi
        // (prismatic); the same entries and scaling as the residual.
        const cols = ax.map((a, i) => {
            const w = cur[i].slice(0, 3), p = cur[i].slice(3);
            const cross = (v) => [w[1] * v[2] - w[2] * v[1], w[2] * v[0] - w[0] * v[2], w[0] * v[1] - w[1] * v[0]];
            const zero = [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]];
            const d = zero.map((row) => row.slice());
            const dt = a[0] !== 0 ? w : cross([0, 1, 2].map((r) => f[r][3] - p[r]));
            for (let c = 0; c < 3; c++) {
                const v = a[0] !== 0 ? [0, 0, 0] : cross([f[0][c], f[1][c], f[2][c]]);
                for (let r = 0; r < 3; r++) d[r][c] = -v[r];
            }
            for (let r = 0; r < 3; r++) d[r][3] = -dt[r];
            return ik_error(d, zero, len, po);
        });
        const n = q.length, m = e.length;
        const A = [], g = [];
        let tr = 0;
        for (let i = 0; i < n; i++) {
            A.push([]);
            for (let j = 0; j < n; j++) {
                let s = 0;
                for (let k = 0; k < m; k++) s += cols[i][k] * cols[j][k];
                A[i].push(s);
            }
            let s = 0;
            for (let k = 0; k < m; k++) s += cols[i][k] * e[k];
            g.push(s);
            tr += A[i][i];
        }
        for (;;) {
            const d = ik_cholesky(A.map((row, i) => row.map((x, j) =>
                x + (i === j ? lambda * Math.max(tr, Number.MIN_VALUE) : 0))), g);
            if (d !== null) {
                const next = q.map((x, i) => x + d[i]);
                const [f2, cur2] = ik_fk(ax, home, next), e2 = ik_error(f2, T, len, po);
                const r2 = ik_max_abs(e2);
                if (r2 < res) {
                    [q, f, cur, e, res] = [next, f2, cur2, e2, r2];
                    lambda = Math.max(lambda * 0.01, 1e-15);
                    break;
                }
            }
            lambda *= 100;
            if (lambda > 1) return [q, res];
        }
    }
    return [q, res];
}

// Adds a solution [q, singular, approximate, residual] to out; one a step asks to check is
// checked by forward kinematics: refined where its residual exceeds IK_REFINE_TOL, flagged
// approximate where it stays above IK_POSE_TOL, dropped when it is a sample off the pose or a
// singular duplicate.
function ik_push(out, q, sg, ck, smp, ax, home, T, len, po) {
    let res = 0;
    if (sg || ck) {
        res = ik_max_abs(ik_error(ik_fk(ax, home, q)[0], T, len, po));
        if (res > IK_REFINE_TOL) {
            const [r, rr] = ik_refine(ax, home, T, len, po, q);
            if (rr < res) [q, res] = [r, rr];
        }
        if (smp && res > IK_POSE_TOL) return;
        const same = (a, b) => a.every((x, i) =>
            Math.abs(x - b[i]) <= 4 * IK_EPS * Math.max(Math.abs(x), Math.abs(b[i]), 1));
        if (sg && out.some(([p, psg]) => psg && same(p, q))) return;
    }
    out.push([q, sg, !(res <= IK_POSE_TOL), res]);
}
"#;
