//! Solver code: every branch of a derived [`IkSolution`] as Rust, C or Python (NumPy). The
//! formulas are the closed forms of the report, written as they are; the branch logic
//! (tolerances for singular and clamped radicands) is the one of [`super::candidates`].

use super::{Formula, IkSolution, TARGET_SYMBOLS};
use crate::closed::{Angle, Expr};
use crate::ScalarError;
use num_traits::{One, ToPrimitive, Zero};

#[derive(Clone, Copy, PartialEq, Eq)]
enum Lang {
    Rust,
    C,
    Python,
}

fn lit(v: f64, lang: Lang) -> String {
    let s = format!("{v:?}");
    match lang {
        Lang::Rust | Lang::C | Lang::Python => {
            if s.contains('.') || s.contains('e') {
                s
            } else {
                format!("{s}.0")
            }
        }
    }
}

fn angle_code(a: &Angle, lang: Lang) -> String {
    let mut parts = Vec::new();
    for (s, k) in &a.terms {
        let k = k.to_f64().unwrap_or(f64::NAN);
        let name = if s.is_unit() {
            lit(1.0, lang)
        } else {
            s.name().to_string()
        };
        parts.push(if k == 1.0 {
            name
        } else {
            format!("{}*{name}", lit(k, lang))
        });
    }
    if !a.pi.is_zero() {
        let k = a.pi.to_f64().unwrap_or(f64::NAN);
        let pi = match lang {
            Lang::Rust => "std::f64::consts::PI",
            Lang::C => "M_PI",
            Lang::Python => "math.pi",
        };
        parts.push(format!("{}*{pi}", lit(k, lang)));
    }
    if parts.is_empty() {
        return lit(0.0, lang);
    }
    format!("({})", parts.join(" + "))
}

fn code(e: &Expr, lang: Lang, bound: &[&str]) -> String {
    match e {
        Expr::Num(q) => {
            let v = q.to_f64().unwrap_or(f64::NAN);
            lit(v, lang)
        }
        Expr::Sqrt(n) => lit((*n as f64).sqrt(), lang),
        Expr::Sym(s) => match (s.name(), lang) {
            ("pi", Lang::Rust) => "std::f64::consts::PI".into(),
            ("pi", Lang::C) => "M_PI".into(),
            ("pi", Lang::Python) => "math.pi".into(),
            (n, _) => n.to_string(),
        },
        Expr::Trig { f, angle } => {
            let f = f.name();
            // A solved joint's cosine and sine are locals (one sin_cos per joint).
            if angle.pi.is_zero() && angle.terms.len() == 1 && angle.terms[0].1.is_one() {
                let n = angle.terms[0].0.name();
                if bound.contains(&n) {
                    return format!("{}_{n}", &f[..1]);
                }
            }
            let a = angle_code(angle, lang);
            match lang {
                Lang::Rust => format!("{a}.{f}()"),
                Lang::C => format!("{f}{a}"),
                Lang::Python => format!("math.{f}{a}"),
            }
        }
        Expr::Add(v) => {
            let mut s = String::from("(");
            for (i, t) in v.iter().enumerate() {
                match t {
                    Expr::Neg(inner) => {
                        s.push_str(if i == 0 { "-" } else { " - " });
                        s.push_str(&code(inner, lang, bound));
                    }
                    t => {
                        if i > 0 {
                            s.push_str(" + ");
                        }
                        s.push_str(&code(t, lang, bound));
                    }
                }
            }
            s.push(')');
            s
        }
        Expr::Mul(v) => {
            let f: Vec<String> = v.iter().map(|t| code(t, lang, bound)).collect();
            format!("({})", f.join("*"))
        }
        Expr::Neg(x) => format!("(-{})", code(x, lang, bound)),
        Expr::Pow(x, n) => {
            let b = code(x, lang, bound);
            match lang {
                Lang::Rust => format!("{b}.powi({n})"),
                Lang::C => format!("pow({b}, {n})"),
                Lang::Python => format!("{b}**{n}"),
            }
        }
    }
}

/// Whether the closed form is the constant 1 (to skip a multiplication in code).
#[allow(dead_code)]
fn is_one(e: &Expr) -> bool {
    matches!(e, Expr::Num(q) if q.is_one())
}

struct Ctx<'a> {
    sol: &'a IkSolution,
    /// The joints whose `c_q`, `s_q` locals exist, per step.
    bound: Vec<Vec<&'a str>>,
    lang: Lang,
    parts: &'a [Vec<(&'static str, Expr)>],
}

/// The regular branches, times 12 for the representatives of a singular set (see `ik_atan2`).
fn max_solutions(sol: &IkSolution) -> usize {
    12 * sol
        .steps
        .iter()
        .map(|s| s.formula.branches())
        .product::<usize>()
}

impl Ctx<'_> {
    /// `c_q`, `s_q` of a revolute joint just bound.
    fn trig_locals(&self, k: usize, ind: usize, out: &mut String) {
        let step = &self.sol.steps[k];
        if matches!(
            step.formula,
            Formula::Value { .. } | Formula::Quadratic { .. }
        ) {
            return;
        }
        let q = &step.variable;
        let pad = " ".repeat(ind);
        match self.lang {
            Lang::Rust => out.push_str(&format!("{pad}let (s_{q}, c_{q}) = {q}.sin_cos();\n")),
            Lang::C => out.push_str(&format!(
                "{pad}const double s_{q} = sin({q}), c_{q} = cos({q});\n{pad}(void)s_{q};\n{pad}(void)c_{q};\n"
            )),
            Lang::Python => out.push_str(&format!(
                "{pad}s_{q}, c_{q} = math.sin({q}), math.cos({q})\n"
            )),
        }
    }

    /// The body of the branch loops, from step `k` on, at indentation `ind`.
    fn body(&self, k: usize, ind: usize, out: &mut String) {
        let pad = " ".repeat(ind);
        let Some(step) = self.sol.steps.get(k) else {
            let q = self.sol.variables.join(", ");
            let sg: Vec<String> = (0..k).map(|i| format!("ik_sg{i}")).collect();
            let ap: Vec<String> = (0..k).map(|i| format!("ik_ap{i}")).collect();
            match self.lang {
                Lang::Rust => {
                    out.push_str(&format!(
                        "{pad}if ik_out.n == IK_MAX {{\n{pad}    return ik_out;\n{pad}}}\n"
                    ));
                    out.push_str(&format!("{pad}ik_out.q[ik_out.n] = [{q}];\n"));
                    out.push_str(&format!(
                        "{pad}ik_out.singular[ik_out.n] = {};\n",
                        sg.join(" || ")
                    ));
                    out.push_str(&format!(
                        "{pad}ik_out.approximate[ik_out.n] = {};\n",
                        ap.join(" || ")
                    ));
                    out.push_str(&format!("{pad}ik_out.n += 1;\n"));
                }
                Lang::C => {
                    out.push_str(&format!("{pad}if (ik_out->n == IK_MAX) return;\n"));
                    for (i, v) in self.sol.variables.iter().enumerate() {
                        out.push_str(&format!("{pad}ik_out->q[ik_out->n][{i}] = {v};\n"));
                    }
                    out.push_str(&format!(
                        "{pad}ik_out->singular[ik_out->n] = {};\n",
                        sg.join(" || ")
                    ));
                    out.push_str(&format!(
                        "{pad}ik_out->approximate[ik_out->n] = {};\n",
                        ap.join(" || ")
                    ));
                    out.push_str(&format!("{pad}ik_out->n += 1;\n"));
                }
                Lang::Python => {
                    out.push_str(&format!(
                        "{pad}ik_out.append(([{q}], {}, {}))\n",
                        sg.join(" or "),
                        ap.join(" or ")
                    ));
                }
            }
            return;
        };
        let q = &step.variable;
        let comment = match self.lang {
            Lang::Python => "#",
            _ => "//",
        };
        out.push_str(&format!("{pad}{comment} {q}: {}\n", step.method));
        let tmp = |n: &str| format!("ik_{q}_{n}");
        for (n, e) in &self.parts[k] {
            let c = code(e, self.lang, &self.bound[k]);
            match self.lang {
                Lang::Rust => out.push_str(&format!("{pad}let {} = {c};\n", tmp(n))),
                Lang::C => out.push_str(&format!("{pad}const double {} = {c};\n", tmp(n))),
                Lang::Python => out.push_str(&format!("{pad}{} = {c}\n", tmp(n))),
            }
        }
        let args: Vec<String> = self.parts[k].iter().map(|(n, _)| tmp(n)).collect();
        let args = args.join(", ");
        match (&step.formula, self.lang) {
            (Formula::Atan2 { .. }, Lang::Rust) => {
                out.push_str(&format!(
                    "{pad}let (ik_n{k}, ik_c{k}) = ik_atan2({args});\n"
                ));
                out.push_str(&format!(
                    "{pad}for &({q}, ik_sg{k}) in &ik_c{k}[..ik_n{k}] {{\n"
                ));
                let p2 = " ".repeat(ind + 4);
                out.push_str(&format!("{p2}let ik_ap{k} = false;\n"));
                self.trig_locals(k, ind + 4, out);
                self.body(k + 1, ind + 4, out);
                out.push_str(&format!("{pad}}}\n"));
            }
            (Formula::Value { .. }, Lang::Rust) => {
                out.push_str(&format!("{pad}let {q} = {args};\n"));
                out.push_str(&format!(
                    "{pad}let (ik_sg{k}, ik_ap{k}) = (false, false);\n"
                ));
                self.trig_locals(k, ind, out);
                self.body(k + 1, ind, out);
            }
            (Formula::Trig { .. } | Formula::Quadratic { .. }, Lang::Rust) => {
                let f = if matches!(step.formula, Formula::Trig { .. }) {
                    "ik_trig"
                } else {
                    "ik_quadratic"
                };
                out.push_str(&format!("{pad}let (ik_n{k}, ik_c{k}) = {f}({args});\n"));
                out.push_str(&format!(
                    "{pad}for &({q}, ik_sg{k}, ik_ap{k}) in &ik_c{k}[..ik_n{k}] {{\n"
                ));
                self.trig_locals(k, ind + 4, out);
                self.body(k + 1, ind + 4, out);
                out.push_str(&format!("{pad}}}\n"));
            }
            (Formula::Atan2 { .. }, Lang::C) => {
                out.push_str(&format!(
                    "{pad}double ik_v{k}[12]; int ik_s{k};\n{pad}const int ik_n{k} = ik_atan2({args}, ik_v{k}, &ik_s{k});\n"
                ));
                out.push_str(&format!(
                    "{pad}for (int ik_i{k} = 0; ik_i{k} < ik_n{k}; ik_i{k}++) {{\n"
                ));
                let p2 = " ".repeat(ind + 4);
                out.push_str(&format!(
                    "{p2}const double {q} = ik_v{k}[ik_i{k}];\n{p2}const int ik_sg{k} = ik_s{k}, ik_ap{k} = 0;\n"
                ));
                self.trig_locals(k, ind + 4, out);
                self.body(k + 1, ind + 4, out);
                out.push_str(&format!("{pad}}}\n"));
            }
            (Formula::Value { .. }, Lang::C) => {
                out.push_str(&format!("{pad}const double {q} = {args};\n"));
                out.push_str(&format!("{pad}const int ik_sg{k} = 0, ik_ap{k} = 0;\n"));
                self.trig_locals(k, ind, out);
                self.body(k + 1, ind, out);
            }
            (Formula::Trig { .. } | Formula::Quadratic { .. }, Lang::C) => {
                let f = if matches!(step.formula, Formula::Trig { .. }) {
                    "ik_trig"
                } else {
                    "ik_quadratic"
                };
                out.push_str(&format!(
                    "{pad}double ik_v{k}[2]; int ik_s{k}[2], ik_a{k}[2];\n{pad}const int ik_n{k} = {f}({args}, ik_v{k}, ik_s{k}, ik_a{k});\n"
                ));
                out.push_str(&format!(
                    "{pad}for (int ik_i{k} = 0; ik_i{k} < ik_n{k}; ik_i{k}++) {{\n"
                ));
                let p2 = " ".repeat(ind + 4);
                out.push_str(&format!(
                    "{p2}const double {q} = ik_v{k}[ik_i{k}];\n{p2}const int ik_sg{k} = ik_s{k}[ik_i{k}], ik_ap{k} = ik_a{k}[ik_i{k}];\n"
                ));
                self.trig_locals(k, ind + 4, out);
                self.body(k + 1, ind + 4, out);
                out.push_str(&format!("{pad}}}\n"));
            }
            (Formula::Atan2 { .. }, Lang::Python) => {
                out.push_str(&format!("{pad}for {q}, ik_sg{k} in _ik_atan2({args}):\n"));
                out.push_str(&format!("{pad}    ik_ap{k} = False\n"));
                self.trig_locals(k, ind + 4, out);
                self.body(k + 1, ind + 4, out);
            }
            (Formula::Value { .. }, Lang::Python) => {
                out.push_str(&format!("{pad}{q} = {args}\n"));
                out.push_str(&format!("{pad}ik_sg{k}, ik_ap{k} = False, False\n"));
                self.trig_locals(k, ind, out);
                self.body(k + 1, ind, out);
            }
            (Formula::Trig { .. } | Formula::Quadratic { .. }, Lang::Python) => {
                let f = if matches!(step.formula, Formula::Trig { .. }) {
                    "_ik_trig"
                } else {
                    "_ik_quadratic"
                };
                out.push_str(&format!(
                    "{pad}for {q}, ik_sg{k}, ik_ap{k} in {f}({args}):\n"
                ));
                self.trig_locals(k, ind + 4, out);
                self.body(k + 1, ind + 4, out);
            }
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
                } else if block.contains("_atan2(") && !block.contains("_trig(") {
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

fn ctx(sol: &IkSolution, lang: Lang) -> Result<Ctx<'_>, ScalarError> {
    let parts = sol.forms().map_err(ScalarError::Unbound)?;
    let mut bound = Vec::new();
    let mut now: Vec<&str> = Vec::new();
    for st in &sol.steps {
        bound.push(now.clone());
        if !matches!(
            st.formula,
            Formula::Value { .. } | Formula::Quadratic { .. }
        ) {
            now.push(st.variable.as_str());
        }
    }
    Ok(Ctx {
        sol,
        bound,
        lang,
        parts,
    })
}

fn doc_lines(sol: &IkSolution) -> Vec<String> {
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
    v
}

/// The solver as Rust: `ik(t: &[[f64; 4]; 4], params...) -> IkSolutions` and `ik_dq(dq: &[f64;
/// 8], params...)`; no allocation.
///
/// # Errors
/// A closed form that fails.
pub fn ik_rust(sol: &IkSolution) -> Result<String, ScalarError> {
    let c = ctx(sol, Lang::Rust)?;
    let n = sol.variables.len();
    let max = max_solutions(sol);
    let params: String = sol.params.iter().map(|p| format!(", {p}: f64")).collect();
    let pnames: String = sol.params.iter().map(|p| format!(", {p}")).collect();
    let mut s = String::new();
    for l in doc_lines(sol) {
        s.push_str(&format!("// {l}\n"));
    }
    s.push_str(&format!(
        "\n/// The most solutions the solver returns.\npub const IK_MAX: usize = {max};\n\n\
/// The solutions: `q[..n]` in joint order, with their flags.\n\
#[derive(Clone, Copy, Debug, PartialEq)]\npub struct IkSolutions {{\n    /// Joint vectors.\n    pub q: [[f64; {n}]; IK_MAX],\n    \
/// A singular set was met.\n    pub singular: [bool; IK_MAX],\n    /// A radicand was clamped.\n    pub approximate: [bool; IK_MAX],\n    \
/// How many are valid.\n    pub n: usize,\n}}\n\n"
    ));
    s.push_str(&helpers(sol, &[RUST_RADICAND, RUST_HELPERS]));
    s.push_str(&format!(
        "\n/// Every solution for the target pose `t` (row-major homogeneous matrix).\n\
#[allow(non_snake_case, unused_variables, clippy::too_many_arguments, clippy::excessive_precision, clippy::neg_multiply, clippy::double_parens, unused_parens)]\n\
pub fn ik(ik_target: &[[f64; 4]; 4]{params}) -> IkSolutions {{\n"
    ));
    for (r, row) in TARGET_SYMBOLS.iter().enumerate() {
        for (col, name) in row.iter().enumerate() {
            s.push_str(&format!("    let {name} = ik_target[{r}][{col}];\n"));
        }
    }
    s.push_str(&format!(
        "    let mut ik_out = IkSolutions {{\n        q: [[0.0; {n}]; IK_MAX],\n        singular: [false; IK_MAX],\n        approximate: [false; IK_MAX],\n        n: 0,\n    }};\n"
    ));
    let mut body = String::new();
    c.body(0, 4, &mut body);
    s.push_str(&body);
    s.push_str("    ik_out\n}\n\n");
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

const RUST_HELPERS: &str = r#"#[inline(always)]
/// `atan2(y, x)`; where `x = y = 0` (a singular set: any value) twelve values k pi/6,
/// k = -5..6, so that a later joint can still reach.
fn ik_atan2(y: f64, x: f64) -> (usize, [(f64, bool); 12]) {
    if y.hypot(x) < 1e-10 {
        (12, std::array::from_fn(|k| ((k as f64 - 5.0) * std::f64::consts::FRAC_PI_6, true)))
    } else {
        (1, [(y.atan2(x), false); 12])
    }
}

/// `a cos q + b sin q = c`: up to two roots `(q, singular, approximate)`.
#[inline(always)]
fn ik_trig(a: f64, b: f64, c: f64) -> (usize, [(f64, bool, bool); 2]) {
    let n = a * a + b * b;
    if n < 1e-20 {
        return if c.abs() < 1e-9 {
            (1, [(0.0, true, false), (0.0, true, false)])
        } else {
            (0, [(0.0, false, false); 2])
        };
    }
    let Some((rad, sg, ap)) = ik_radicand(n - c * c, n) else {
        return (0, [(0.0, false, false); 2]);
    };
    let phi = b.atan2(a);
    let w = rad.sqrt().atan2(c);
    (2, [(phi + w, sg, ap), (phi - w, sg, ap)])
}

/// `q^2 + 2 beta q + gamma = 0`: up to two roots.
#[inline(always)]
fn ik_quadratic(beta: f64, gamma: f64) -> (usize, [(f64, bool, bool); 2]) {
    let scale = (beta * beta).max(gamma.abs()).max(1.0);
    let Some((rad, sg, ap)) = ik_radicand(beta * beta - gamma, scale) else {
        return (0, [(0.0, false, false); 2]);
    };
    let r = rad.sqrt();
    (2, [(-beta + r, sg, ap), (-beta - r, sg, ap)])
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
    let c = ctx(sol, Lang::C)?;
    let n = sol.variables.len();
    let max = max_solutions(sol);
    let params: String = sol.params.iter().map(|p| format!(", double {p}")).collect();
    let pnames: String = sol.params.iter().map(|p| format!(", {p}")).collect();
    let mut s = String::new();
    for l in doc_lines(sol) {
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

const C_HELPERS: &str = r#"static int ik_atan2(double y, double x, double v[12], int *sg) {
    if (hypot(y, x) < 1e-10) {
        *sg = 1;
        for (int k = 0; k < 12; k++) v[k] = (k - 5) * (M_PI / 6);
        return 12;
    }
    *sg = 0;
    v[0] = atan2(y, x);
    return 1;
}

static int ik_trig(double a, double b, double c, double v[2], int sg[2], int ap[2]) {
    const double n = a * a + b * b;
    if (n < 1e-20) {
        v[0] = 0.0; sg[0] = 1; ap[0] = 0;
        return fabs(c) < 1e-9 ? 1 : 0;
    }
    double rad = n - c * c;
    int s = 0, p = 0;
    if (!ik_radicand(&rad, n, &s, &p)) return 0;
    const double phi = atan2(b, a), w = atan2(sqrt(rad), c);
    v[0] = phi + w; v[1] = phi - w;
    sg[0] = sg[1] = s; ap[0] = ap[1] = p;
    return 2;
}

static int ik_quadratic(double beta, double gamma, double v[2], int sg[2], int ap[2]) {
    double rad = beta * beta - gamma;
    double scale = fmax(fmax(beta * beta, fabs(gamma)), 1.0);
    int s = 0, p = 0;
    if (!ik_radicand(&rad, scale, &s, &p)) return 0;
    const double r = sqrt(rad);
    v[0] = -beta + r; v[1] = -beta - r;
    sg[0] = sg[1] = s; ap[0] = ap[1] = p;
    return 2;
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
    let c = ctx(sol, Lang::Python)?;
    let kw = if sol.params.is_empty() {
        String::new()
    } else {
        format!(", *, {}", sol.params.join(", "))
    };
    let pass: String = sol.params.iter().map(|p| format!(", {p}={p}")).collect();
    let mut s = String::new();
    for l in doc_lines(sol) {
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


def _ik_atan2(y, x):
    if math.hypot(y, x) < 1e-10:
        return [(k * math.pi / 6, True) for k in range(-5, 7)]
    return [(math.atan2(y, x), False)]


def _ik_trig(a, b, c):
    n = a * a + b * b
    if n < 1e-20:
        return [(0.0, True, False)] if abs(c) < 1e-9 else []
    r = _ik_radicand(n - c * c, n)
    if r is None:
        return []
    rad, sg, ap = r
    phi = math.atan2(b, a)
    w = math.atan2(math.sqrt(rad), c)
    return [(phi + w, sg, ap), (phi - w, sg, ap)]


def _ik_quadratic(beta, gamma):
    scale = max(beta * beta, abs(gamma), 1.0)
    r = _ik_radicand(beta * beta - gamma, scale)
    if r is None:
        return []
    rad, sg, ap = r
    r = math.sqrt(rad)
    return [(-beta + r, sg, ap), (-beta - r, sg, ap)]


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
