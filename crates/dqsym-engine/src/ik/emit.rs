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

/// The regular branches, times 12 for the representatives of a singular set (see `ik_any`).
fn max_solutions(sol: &IkSolution) -> usize {
    12 * sol
        .steps
        .iter()
        .map(|s| s.formula.branches())
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
    Ok(Ctx {
        sol,
        lang,
        prog,
        temps,
        atoms,
        parts,
        solve_level,
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

    /// The loops from step `k` on, at indentation `ind`.
    fn body(&self, k: usize, ind: usize, out: &mut String) {
        let pad = " ".repeat(ind);
        let Some(step) = self.sol.steps.get(k) else {
            let q = self.sol.variables.join(", ");
            let (sg, ap) = (self.flags(k, "sg"), self.flags(k, "ap"));
            match self.lang {
                Lang::Rust => {
                    out.push_str(&format!(
                        "{pad}if ik_out.n == IK_MAX {{\n{pad}    return;\n{pad}}}\n"
                    ));
                    out.push_str(&format!("{pad}ik_out.q[ik_out.n] = [{q}];\n"));
                    out.push_str(&format!("{pad}ik_out.singular[ik_out.n] = {sg};\n"));
                    out.push_str(&format!("{pad}ik_out.approximate[ik_out.n] = {ap};\n"));
                    out.push_str(&format!("{pad}ik_out.n += 1;\n"));
                }
                Lang::C => {
                    out.push_str(&format!("{pad}if (ik_out->n == IK_MAX) return;\n"));
                    for (i, v) in self.sol.variables.iter().enumerate() {
                        out.push_str(&format!("{pad}ik_out->q[ik_out->n][{i}] = {v};\n"));
                    }
                    out.push_str(&format!("{pad}ik_out->singular[ik_out->n] = {sg};\n"));
                    out.push_str(&format!("{pad}ik_out->approximate[ik_out->n] = {ap};\n"));
                    out.push_str(&format!("{pad}ik_out->n += 1;\n"));
                }
                Lang::Python => {
                    out.push_str(&format!("{pad}ik_out.append(([{q}], {sg}, {ap}))\n"));
                }
            }
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
        match self.lang {
            Lang::Rust => {
                out.push_str(&format!("{pad}for ik_i{k} in 0..ik_r{k}.n {{\n"));
                out.push_str(&format!(
                    "{inner}let ({q}, s_{q}, c_{q}) = ik_r{k}.root(ik_i{k});\n"
                ));
            }
            Lang::C => {
                out.push_str(&format!(
                    "{pad}for (int ik_i{k} = 0; ik_i{k} < ik_r{k}.n; ik_i{k}++) {{\n"
                ));
                out.push_str(&format!(
                    "{inner}double {q}, s_{q}, c_{q};\n{inner}ik_root(&ik_r{k}, ik_i{k}, &{q}, &s_{q}, &c_{q});\n{inner}(void)s_{q};\n{inner}(void)c_{q};\n"
                ));
            }
            Lang::Python => {
                out.push_str(&format!("{pad}for {q}, s_{q}, c_{q} in ik_r{k}[0]:\n"));
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
        "approximate (a slightly negative radicand clamped to 0: the closest reach).".into(),
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
/// A singular set was met.\n    pub singular: [bool; IK_MAX],\n    /// A radicand was clamped.\n    pub approximate: [bool; IK_MAX],\n    \
/// How many are valid.\n    pub n: usize,\n}}\n\n\
impl Default for IkSolutions {{\n    fn default() -> Self {{\n        IkSolutions {{\n            q: [[0.0; {n}]; IK_MAX],\n            \
singular: [false; IK_MAX],\n            approximate: [false; IK_MAX],\n            n: 0,\n        }}\n    }}\n}}\n\n"
    ));
    s.push_str(&helpers(sol, &[RUST_RADICAND, RUST_HELPERS]));
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

const RUST_RADICAND: &str = r#"/// A radicand of scale `n`: none below -1e-8 n, a double root within 1e-12 n of zero
/// (singular; approximate beyond rounding), else itself.
#[inline(always)]
fn ik_radicand(rad: f64, n: f64) -> Option<(f64, bool, bool)> {
    if rad < -1e-8 * n {
        None
    } else if rad <= 1e-12 * n {
        Some((0.0, true, rad.abs() > 1e-14 * n))
    } else {
        Some((rad, false, false))
    }
}
"#;

const RUST_HELPERS: &str = r#"/// The roots of one step: `n` joint values with their sines and cosines (known without a
/// call), and the flags; `n = 12` on a singular set of an atan2 (see `ik_any`).
#[derive(Clone, Copy)]
struct IkRoots {
    n: usize,
    q: [f64; 2],
    s: [f64; 2],
    c: [f64; 2],
    sg: bool,
    ap: bool,
}

impl IkRoots {
    const NONE: IkRoots = IkRoots { n: 0, q: [0.0; 2], s: [0.0; 2], c: [1.0; 2], sg: false, ap: false };
    /// Root `i`: `(q, sin q, cos q)`.
    #[inline(always)]
    fn root(&self, i: usize) -> (f64, f64, f64) {
        if self.n == 12 {
            ik_any(i)
        } else {
            (self.q[i], self.s[i], self.c[i])
        }
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
}

impl IkMemo {
    const NEW: IkMemo = IkMemo { y: f64::NAN, x: f64::NAN, q: 0.0, s: 0.0, c: 1.0 };
}

/// `atan2(y, x)`, its sine `y / h` and cosine `x / h`; where `x = y = 0` any value.
#[inline(always)]
fn ik_atan2(y: f64, x: f64, m: &mut IkMemo) -> IkRoots {
    if y == -m.y && x == -m.x {
        m.q = if m.q > 0.0 { m.q - std::f64::consts::PI } else { m.q + std::f64::consts::PI };
        m.s = -m.s;
        m.c = -m.c;
        m.y = y;
        m.x = x;
    } else if y != m.y || x != m.x {
        let h2 = y * y + x * x;
        if h2 < 1e-20 {
            return IkRoots { n: 12, sg: true, ..IkRoots::NONE };
        }
        let h = h2.sqrt();
        *m = IkMemo { y, x, q: y.atan2(x), s: y / h, c: x / h };
    }
    IkRoots { n: 1, q: [m.q, 0.0], s: [m.s, 0.0], c: [m.c, 1.0], sg: false, ap: false }
}

/// `a cos q + b sin q = c`: `q = atan2(b, a) +- atan2(r, c)`, `r = sqrt(a^2 + b^2 - c^2)`, as
/// `atan2(b c +- a r, a c -+ b r)`, whose sine and cosine are those over `a^2 + b^2`. Where
/// `b = 0` the roots are `+-q` (`atan2` is odd in `y`), where `a = 0` they are `q` and `pi - q`.
#[inline(always)]
fn ik_trig(a: f64, b: f64, c: f64) -> IkRoots {
    let n = a * a + b * b;
    if n < 1e-20 {
        return if c.abs() < 1e-9 { IkRoots { n: 1, sg: true, ..IkRoots::NONE } } else { IkRoots::NONE };
    }
    let Some((rad, sg, ap)) = ik_radicand(n - c * c, n) else {
        return IkRoots::NONE;
    };
    let r = rad.sqrt();
    // r^2 + c^2 = n, unless the radicand was clamped to 0.
    let d = if sg { (n * c * c).sqrt() } else { n };
    let (y0, x0, y1, x1) = (b * c + a * r, a * c - b * r, b * c - a * r, a * c + b * r);
    let q0 = y0.atan2(x0);
    let q1 = if b == 0.0 {
        -q0
    } else if a == 0.0 {
        std::f64::consts::PI.copysign(y0) - q0
    } else {
        y1.atan2(x1)
    };
    IkRoots { n: 2, q: [q0, q1], s: [y0 / d, y1 / d], c: [x0 / d, x1 / d], sg, ap }
}

/// `q^2 + 2 beta q + gamma = 0`: up to two roots.
#[inline(always)]
fn ik_quadratic(beta: f64, gamma: f64) -> IkRoots {
    let scale = (beta * beta).max(gamma.abs()).max(1.0);
    let Some((rad, sg, ap)) = ik_radicand(beta * beta - gamma, scale) else {
        return IkRoots::NONE;
    };
    let r = rad.sqrt();
    IkRoots { n: 2, q: [-beta + r, -beta - r], sg, ap, ..IkRoots::NONE }
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
        "#include <math.h>\n#ifndef M_PI\n#define M_PI 3.14159265358979323846\n#endif\n\n\
#define IK_MAX {max}\n#define IK_DOF {n}\n\ntypedef struct {{\n    double q[IK_MAX][IK_DOF];\n    int singular[IK_MAX];\n    int approximate[IK_MAX];\n    int n;\n}} ik_solutions;\n\n"
    ));
    s.push_str(&helpers(sol, &[C_RADICAND, C_HELPERS]));
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
        "void ik_dq(const double ik_q[8]{params}, ik_solutions *ik_out) {{\n    double ik_target[4][4];\n    ik_dq_matrix(ik_q, ik_target);\n    ik(ik_target{pnames}, ik_out);\n}}\n"
    ));
    Ok(s)
}

const C_RADICAND: &str = r#"static int ik_radicand(double *rad, double n, int *sg, int *ap) {
    if (*rad < -1e-8 * n) return 0;
    if (*rad <= 1e-12 * n) {
        *sg = 1;
        *ap = fabs(*rad) > 1e-14 * n;
        *rad = 0.0;
    }
    return 1;
}
"#;

const C_HELPERS: &str = r#"/* The roots of one step: n joint values with their sines and cosines, and the flags;
   n = 12 on a singular set of an atan2 (any value: k pi/6, k = -5..6). */
typedef struct {
    int n;
    double q[2], s[2], c[2];
    int sg, ap;
} ik_roots;

static ik_roots ik_none(void) {
    ik_roots r = {0, {0.0, 0.0}, {0.0, 0.0}, {1.0, 1.0}, 0, 0};
    return r;
}

static void ik_root(const ik_roots *r, int i, double *q, double *s, double *c) {
    if (r->n == 12) {
        *q = (i - 5) * (M_PI / 6);
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

static ik_roots ik_atan2(double y, double x, ik_memo *m) {
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
    ik_roots r = ik_none();
    const double h2 = y * y + x * x;
    if (h2 < 1e-20) {
        r.n = 12;
        r.sg = 1;
        return r;
    }
    const double h = sqrt(h2);
    r.n = 1;
    r.q[0] = atan2(y, x);
    r.s[0] = y / h;
    r.c[0] = x / h;
    m->y = y;
    m->x = x;
    m->r = r;
    return r;
}

static ik_roots ik_trig(double a, double b, double c) {
    ik_roots r = ik_none();
    const double n = a * a + b * b;
    if (n < 1e-20) {
        if (fabs(c) < 1e-9) {
            r.n = 1;
            r.sg = 1;
        }
        return r;
    }
    double rad = n - c * c;
    if (!ik_radicand(&rad, n, &r.sg, &r.ap)) return r;
    const double w = sqrt(rad);
    const double d = r.sg ? sqrt(n * c * c) : n;
    const double y0 = b * c + a * w, x0 = a * c - b * w, y1 = b * c - a * w, x1 = a * c + b * w;
    r.n = 2;
    r.q[0] = atan2(y0, x0);
    r.q[1] = b == 0.0 ? -r.q[0] : a == 0.0 ? copysign(M_PI, y0) - r.q[0] : atan2(y1, x1);
    r.s[0] = y0 / d; r.s[1] = y1 / d;
    r.c[0] = x0 / d; r.c[1] = x1 / d;
    return r;
}

static ik_roots ik_quadratic(double beta, double gamma) {
    ik_roots r = ik_none();
    double rad = beta * beta - gamma;
    const double scale = fmax(fmax(beta * beta, fabs(gamma)), 1.0);
    if (!ik_radicand(&rad, scale, &r.sg, &r.ap)) return r;
    const double w = sqrt(rad);
    r.n = 2;
    r.q[0] = -beta + w; r.q[1] = -beta - w;
    return r;
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
    s.push_str(&helpers(sol, &[PY_HELPERS]));
    s.push_str(&format!(
        "\n\ndef ik_full(T{kw}):\n    \"\"\"Every solution as (q, singular, approximate).\"\"\"\n    T = np.asarray(T, dtype=float)\n"
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
        "def ik(T{kw}):\n    \"\"\"Every solution: joint vectors in joint order ({}).\"\"\"\n    return [q for q, _, _ in ik_full(T{pass})]\n\n\n",
        sol.variables.join(", ")
    ));
    s.push_str(&format!(
        "def ik_dq(q{kw}):\n    \"\"\"ik for a unit dual quaternion (w, x, y, z) + eps (w, x, y, z).\"\"\"\n    return ik(_ik_dq_matrix(q){pass})\n"
    ));
    Ok(s)
}

const PY_HELPERS: &str = r#"def _ik_radicand(rad, n):
    if rad < -1e-8 * n:
        return None
    if rad <= 1e-12 * n:
        return 0.0, True, abs(rad) > 1e-14 * n
    return rad, False, False


def _ik_atan2(y, x, m):
    # The roots [(q, sin q, cos q)], singular, approximate. m: the step's last [y, x, roots]:
    # the same arguments give the same root, exactly negated ones q + pi (the wrist flip).
    if m and len(m[2][0]) == 1 and y == m[0] and x == m[1]:
        return m[2]
    if m and len(m[2][0]) == 1 and y == -m[0] and x == -m[1]:
        q, s, c = m[2][0][0]
        m[:] = [y, x, ([(q - math.pi if q > 0 else q + math.pi, -s, -c)], False, False)]
        return m[2]
    h2 = y * y + x * x
    if h2 < 1e-20:
        qs = [k * math.pi / 6 for k in range(-5, 7)]
        return [(q, math.sin(q), math.cos(q)) for q in qs], True, False
    h = math.sqrt(h2)
    m[:] = [y, x, ([(math.atan2(y, x), y / h, x / h)], False, False)]
    return m[2]


def _ik_trig(a, b, c):
    n = a * a + b * b
    if n < 1e-20:
        return ([(0.0, 0.0, 1.0)] if abs(c) < 1e-9 else []), True, False
    r = _ik_radicand(n - c * c, n)
    if r is None:
        return [], False, False
    rad, sg, ap = r
    w = math.sqrt(rad)
    d = math.sqrt(n * c * c) if sg else n
    y0, x0, y1, x1 = b * c + a * w, a * c - b * w, b * c - a * w, a * c + b * w
    q0 = math.atan2(y0, x0)
    if b == 0.0:
        q1 = -q0
    elif a == 0.0:
        q1 = math.copysign(math.pi, y0) - q0
    else:
        q1 = math.atan2(y1, x1)
    return [(q0, y0 / d, x0 / d), (q1, y1 / d, x1 / d)], sg, ap


def _ik_quadratic(beta, gamma):
    scale = max(beta * beta, abs(gamma), 1.0)
    r = _ik_radicand(beta * beta - gamma, scale)
    if r is None:
        return [], False, False
    rad, sg, ap = r
    w = math.sqrt(rad)
    return [(-beta + w, 0.0, 1.0), (-beta - w, 0.0, 1.0)], sg, ap


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
