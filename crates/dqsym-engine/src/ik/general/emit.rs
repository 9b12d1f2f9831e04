//! The generated solvers of a general-method solution: the robot's exact axes and home pose
//! as expressions in its parameters, and the numeric core: `core.rs` verbatim in Rust, so that
//! the generated solver and the reference solver are the same algorithm, and its ports
//! `core.py` (Python, NumPy), `core.c` (C99) and `core.js` (the IK page's JavaScript). The
//! ports read the core's tolerances and tables as constants written here from `core.rs`
//! (`core_constants`), never as copies; the tests of `tests/it/ik_general_ports.rs` hold the
//! C and JavaScript ports to the reference solver's solution sets.

use super::super::check;
use super::super::IkSolution;
use crate::emit::codegen::{float_literal, lower, CodegenOptions, Output, STD_CONSTS};
use crate::emit::names::{self, comment_lines, Comment};
use crate::scalar::Trig;
use crate::ScalarError;

/// The numeric core, included in the generated solver.
const CORE: &str = include_str!("core.rs");

fn lit(v: f64) -> String {
    match STD_CONSTS.iter().find(|(_, c)| *c == v) {
        Some((name, _)) => format!("std::f64::consts::{name}"),
        None => float_literal(v),
    }
}

/// The numeric core in Python (NumPy).
const PY_CORE: &str = include_str!("core.py");

/// The numeric core in C99 (a port of `core.rs`).
const C_CORE: &str = include_str!("core.c");

/// The numeric core in JavaScript (a port of `core.rs`, for the IK page).
const JS_CORE: &str = include_str!("core.js");

/// The target language of [`chain_code`].
#[derive(Clone, Copy, PartialEq, Eq)]
enum Lang {
    Rust,
    Python,
    C,
}

/// The languages of the ports that read the core's constants ([`core_constant_code`]).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Port {
    C,
    Python,
    JavaScript,
}

/// A constant of the core by the name the ports read it by.
type Named<T> = (&'static str, T);

/// A table of the core by name: its rows (one for a vector).
type Table = Named<Vec<Vec<f64>>>;

/// The constants of `core.rs` the C, Python and JavaScript ports read, by name: the scalars as
/// literals, then the tables as rows (one row for a vector), from their one definition there.
fn core_constants() -> (Vec<Named<String>>, Vec<Table>) {
    use super::core as k;
    let f = float_literal;
    let scalars = vec![
        ("IK_GEN_MAX", k::GEN_MAX.to_string()),
        ("IK_GEN_REFINE_ITERS", k::REFINE_ITERS.to_string()),
        ("IK_GEN_PI", f(std::f64::consts::PI)),
        ("IK_GEN_TAU", f(std::f64::consts::TAU)),
        ("IK_GEN_NEAR_REAL", f(k::NEAR_REAL)),
        ("IK_GEN_SHIFT_GOOD", f(k::SHIFT_GOOD)),
        ("IK_GEN_SHIFT_SINGULAR", f(k::SHIFT_SINGULAR)),
        ("IK_GEN_SPURIOUS_TOL", f(k::SPURIOUS_TOL)),
        ("IK_GEN_SPURIOUS_RANK", f(k::SPURIOUS_RANK)),
        ("IK_GEN_INFINITE_ROOT", f(k::INFINITE_ROOT)),
        ("IK_GEN_RANK_TOL", f(k::RANK_TOL)),
        ("IK_GEN_EXACT_TOL", f(k::EXACT_TOL)),
        ("IK_GEN_DAMP_START", f(k::DAMP_START)),
        ("IK_GEN_DAMP_MIN", f(k::DAMP_MIN)),
        ("IK_GEN_DAMP_MAX", f(k::DAMP_MAX)),
        ("IK_GEN_SAME_TOL", f(k::SAME_TOL)),
        ("IK_GEN_MIN_POSITIVE", f(f64::MIN_POSITIVE)),
        ("IK_GEN_PRISM_FAR", f(k::PRISM_FAR)),
    ];
    let rows = |m: &[[f64; 3]; 3]| m.iter().map(|r| r.to_vec()).collect::<Vec<_>>();
    let tables = vec![
        ("IK_GEN_SAMPLE_S", vec![k::SAMPLE_S.to_vec()]),
        ("IK_GEN_SAMPLE_C", vec![k::SAMPLE_C.to_vec()]),
        ("IK_GEN_DFT", rows(&k::DFT)),
        ("IK_GEN_HALF", rows(&k::HALF)),
        ("IK_GEN_SHIFTS", vec![k::SHIFTS.to_vec()]),
        ("IK_GEN_SAMPLE_D", vec![k::SAMPLE_D.to_vec()]),
        ("IK_GEN_VANDER", rows(&k::VANDER)),
        ("IK_GEN_HALF_INV", rows(&k::HALF_INV)),
    ];
    (scalars, tables)
}

/// The core's constants in `lang` (C, Python or JavaScript): C as `#define` and `static
/// const double` tables, Python and JavaScript as names bound to numbers and lists; a table of
/// several rows nested by rows.
fn core_constant_code(lang: Port) -> String {
    let (scalars, tables) = core_constants();
    let c = lang == Port::C;
    let mut s = String::new();
    for (name, v) in scalars {
        s.push_str(&match lang {
            Port::C => format!("#define {name} {v}\n"),
            Port::Python => format!("{name} = {v}\n"),
            Port::JavaScript => format!("const {name} = {v};\n"),
        });
    }
    let (open, close) = if c { ("{", "}") } else { ("[", "]") };
    for (name, rows) in tables {
        let text: Vec<String> = rows
            .iter()
            .map(|r| {
                r.iter()
                    .map(|x| float_literal(*x))
                    .collect::<Vec<_>>()
                    .join(", ")
            })
            .collect();
        let (dims, body) = if let [row] = &text[..] {
            (format!("[{}]", rows[0].len()), row.clone())
        } else {
            let nested: Vec<String> = text.iter().map(|r| format!("{open}{r}{close}")).collect();
            (
                format!("[{}][{}]", rows.len(), rows[0].len()),
                nested.join(", "),
            )
        };
        s.push_str(&match lang {
            Port::C => format!("static const double {name}{dims} = {{{body}}};\n"),
            Port::Python => format!("{name} = [{body}]\n"),
            Port::JavaScript => format!("const {name} = [{body}];\n"),
        });
    }
    s
}

/// The axes `[kind, w, p]` and the home pose's top rows as statements at the top of the
/// solver (locals `ik_ax`, `ik_home`), in the parameters `args`.
fn chain_code(sol: &IkSolution, lang: Lang) -> Result<String, ScalarError> {
    let py = lang == Lang::Python;
    let lit = |v: f64| {
        if lang == Lang::Rust {
            lit(v)
        } else {
            float_literal(v)
        }
    };
    let (letk, end) = match lang {
        Lang::Python => ("", ""),
        Lang::Rust => ("let ", ";"),
        Lang::C => ("const double ", ";"),
    };
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
    let prog = lower(&outputs, &sol.params, &CodegenOptions::default())
        .map_err(|e| ScalarError::Unbound(e.to_string()))?;
    let mut s = String::new();
    for (k, atom) in prog.atoms.iter().enumerate() {
        let angle = prog.angle_code(k, &lit);
        let call = |f: &str| match lang {
            Lang::Python => format!("math.{f}({angle})"),
            Lang::Rust => format!("({angle}).{f}()"),
            Lang::C => format!("{f}({angle})"),
        };
        if prog.atom_used(k, Trig::Sin) {
            s.push_str(&format!(
                "    {letk}{} = {}{end}\n",
                atom.sin_name,
                call("sin")
            ));
        }
        if prog.atom_used(k, Trig::Cos) {
            s.push_str(&format!(
                "    {letk}{} = {}{end}\n",
                atom.cos_name,
                call("cos")
            ));
        }
    }
    for (id, name) in prog.temps() {
        s.push_str(&format!(
            "    {letk}{name} = {}{end}\n",
            prog.definition(id, &lit)
        ));
    }
    let ids: Vec<_> = prog
        .outputs
        .iter()
        .flat_map(|(_, ids)| ids.clone())
        .collect();
    let code = |i: usize| prog.code(ids[i], &lit);
    let (open, close) = if lang == Lang::C {
        ("{", "}")
    } else {
        ("[", "]")
    };
    let ax: Vec<String> = (0..6)
        .map(|i| {
            let v: Vec<String> = (0..6).map(|k| code(6 * i + k)).collect();
            // The kind: 1 for a joint that slides (the core's `GenAxis`).
            let kind = u8::from(sol.axes[i].kind == crate::kin::JointKind::Prismatic);
            format!("{open}{kind}.0, {}{close}", v.join(", "))
        })
        .collect();
    let hm: Vec<String> = (0..3)
        .map(|r| {
            let v: Vec<String> = (0..4).map(|c| code(36 + 4 * r + c)).collect();
            format!("{open}{}{close}", v.join(", "))
        })
        .collect();
    if lang == Lang::C {
        s.push_str(&format!(
            "    const double ik_ax[6][7] = {{{}}};\n    const double ik_home[3][4] = {{{}}};\n",
            ax.join(", "),
            hm.join(", ")
        ));
    } else if py {
        s.push_str(&format!(
            "    ik_ax = [{}]\n    ik_home = [{}]\n",
            ax.join(", "),
            hm.join(", ")
        ));
    } else {
        s.push_str(&format!(
            "    let ik_ax: [[f64; 7]; 6] = [{}];\n    let ik_home: [[f64; 4]; 3] = [{}];\n",
            ax.join(", "),
            hm.join(", ")
        ));
    }
    Ok(s)
}

/// The solver as Rust, with the interface of the family solvers: `ik_into`, `ik`, `ik_dq`
/// and `IkSolutions` (at most 16 solutions; `singular` is never set by this method).
///
/// # Errors
/// An axis entry that fails (term limit, work budget).
pub fn ik_rust(sol: &IkSolution) -> Result<String, ScalarError> {
    let sol = &*super::super::safe::solution(sol, names::Lang::Rust);
    let params: String = sol.params.iter().map(|p| format!(", {p}: f64")).collect();
    let pnames: String = sol.params.iter().map(|p| format!(", {p}")).collect();
    let degree = sol.general.as_ref().map_or(0, |g| g.degree);
    let mut s = String::new();
    let doc = [
        format!(
            "Inverse kinematics of {}: every solution, by the general 6R elimination.",
            sol.robot
        ),
        format!(
            "Raghavan-Roth / Manocha-Canny: a 12 x 12 quadratic matrix polynomial, degree {degree} reached at a generic target;"
        ),
        "roots by the eigenvalues of its 24 x 24 companion matrix, back-substitution, Gauss-Newton polish,".into(),
        "each solution checked by forward kinematics (approximate: residual above IK_POSE_TOL).".into(),
        format!("Joint vector order: {}; at most 16 solutions.", sol.variables.join(", ")),
        "Generated by dqsym ik.".into(),
    ];
    for l in doc.iter().flat_map(|l| comment_lines(Comment::Slashes, l)) {
        s.push_str(&format!("// {l}\n"));
    }
    s.push_str(&format!(
        "\n/// The most solutions the solver returns.\npub const IK_MAX: usize = 16;\n\
/// The residual above which a solution is flagged approximate.\npub const IK_POSE_TOL: f64 = {};\n\
/// The residual above which a root of the elimination is dropped (no solution).\npub const IK_KEEP_TOL: f64 = {};\n\
/// The arrangement of the loop tried first (the one that served at the derivation).\nconst IK_FIRST_ARRANGEMENT: usize = {};\n\n\
/// The solutions: `q` in joint order, with their flags.\n\
#[derive(Clone, Copy, Debug, PartialEq)]\npub struct IkSolutions {{\n    /// Joint vectors.\n    pub q: [[f64; 6]; IK_MAX],\n    \
/// Never set by the general method.\n    pub singular: [bool; IK_MAX],\n    /// The pose misses the target by more than IK_POSE_TOL.\n    pub approximate: [bool; IK_MAX],\n    \
/// The residual of each solution.\n    pub residual: [f64; IK_MAX],\n    /// How many are valid.\n    pub n: usize,\n}}\n\n\
impl Default for IkSolutions {{\n    fn default() -> Self {{\n        IkSolutions {{ q: [[0.0; 6]; IK_MAX], singular: [false; IK_MAX], approximate: [false; IK_MAX], residual: [0.0; IK_MAX], n: 0 }}\n    }}\n}}\n\n",
        float_literal(check::POSE_TOL),
        float_literal(super::KEEP_TOL),
        sol.general.as_ref().map_or(0, super::GeneralInfo::index),
    ));
    s.push_str("/// The numeric core of the general 6R solver.\n#[allow(dead_code, clippy::all)]\nmod ik_general {\n");
    s.push_str(CORE);
    s.push_str("}\n\n");
    s.push_str(&format!(
        "/// Every solution for the target pose `t` (row-major homogeneous matrix), written to\n\
/// `ik_out` (`ik_out.n` of them).\n\
#[allow(non_snake_case, unused_variables, clippy::too_many_arguments, clippy::excessive_precision, clippy::neg_multiply, clippy::double_parens, unused_parens)]\n\
pub fn ik_into(ik_out: &mut IkSolutions, ik_target: &[[f64; 4]; 4]{params}) {{\n"
    ));
    s.push_str(&chain_code(sol, Lang::Rust)?);
    s.push_str(
        "    // The robot's scale: the largest sum of absolute coordinates of an axis point, the\n\
    // home position or the target position (as ik::check::scale).\n\
    let mut ik_len: f64 = 0.0;\n\
    for a in &ik_ax {\n        ik_len = ik_len.max(a[4].abs() + a[5].abs() + a[6].abs());\n    }\n\
    ik_len = ik_len.max(ik_home[0][3].abs() + ik_home[1][3].abs() + ik_home[2][3].abs());\n\
    ik_len = ik_len.max(ik_target[0][3].abs() + ik_target[1][3].abs() + ik_target[2][3].abs());\n\
    if !(ik_len > 0.0 && ik_len.is_finite()) {\n        ik_len = 1.0;\n    }\n\
    let ik_tol = ik_general::GenTol { pose: IK_POSE_TOL, keep: IK_KEEP_TOL };\n\
    let ik_o = ik_general::gen_solve(&ik_ax, &ik_home, ik_target, ik_len, ik_tol, IK_FIRST_ARRANGEMENT);\n\
    ik_out.n = ik_o.n;\n\
    for i in 0..ik_o.n {\n        ik_out.q[i] = ik_o.q[i];\n        ik_out.singular[i] = false;\n        \
ik_out.residual[i] = ik_o.residual[i];\n        ik_out.approximate[i] = ik_o.residual[i] > IK_POSE_TOL || ik_o.residual[i].is_nan();\n    }\n}\n\n",
    );
    s.push_str(&format!(
        "/// Every solution for the target pose `t` (row-major homogeneous matrix).\n\
#[allow(non_snake_case, clippy::too_many_arguments)]\n\
pub fn ik(ik_target: &[[f64; 4]; 4]{params}) -> IkSolutions {{\n    let mut ik_out = IkSolutions::default();\n    \
ik_into(&mut ik_out, ik_target{pnames});\n    ik_out\n}}\n\n\
/// Every solution for the target given as a unit dual quaternion `(w, x, y, z)` +\n\
/// eps `(w, x, y, z)`.\n#[allow(non_snake_case, clippy::too_many_arguments)]\n\
pub fn ik_dq(ik_q: &[f64; 8]{params}) -> IkSolutions {{\n    ik(&ik_dq_matrix(ik_q){pnames})\n}}\n\n{DQ_MATRIX}"
    ));
    Ok(s)
}

const DQ_MATRIX: &str = r#"/// The homogeneous matrix of a unit dual quaternion (Appendix I).
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

/// The solver as C99, with the interface of the family solvers: `ik_solutions`, `void
/// ik(const double T[4][4], params..., ik_solutions *out)` and `ik_dq`; the numeric core
/// (`core.c`, a port of `core.rs`) with its constants written from `core.rs`. No allocation.
///
/// # Errors
/// An axis entry that fails (term limit, work budget).
pub fn ik_c(sol: &IkSolution) -> Result<String, ScalarError> {
    let sol = &*super::super::safe::solution(sol, names::Lang::C);
    let params: String = sol.params.iter().map(|p| format!(", double {p}")).collect();
    let pnames: String = sol.params.iter().map(|p| format!(", {p}")).collect();
    let degree = sol.general.as_ref().map_or(0, |g| g.degree);
    let first = sol.general.as_ref().map_or(0, super::GeneralInfo::index);
    let mut s = String::new();
    let doc = [
        format!(
            "Inverse kinematics of {}: every solution, by the general 6R elimination.",
            sol.robot
        ),
        format!(
            "Raghavan-Roth / Manocha-Canny: a 12 x 12 quadratic matrix polynomial, degree {degree} reached at a generic target;"
        ),
        "roots by the eigenvalues of its 24 x 24 companion matrix, back-substitution, Gauss-Newton polish,".into(),
        "each solution checked by forward kinematics (approximate: residual above IK_POSE_TOL).".into(),
        format!("Joint vector order: {}; at most 16 solutions; singular is never set.", sol.variables.join(", ")),
        "Generated by dqsym ik.".into(),
    ];
    for l in doc.iter().flat_map(|l| comment_lines(Comment::Block, l)) {
        s.push_str(&format!("/* {l} */\n"));
    }
    s.push_str(
        "#include <math.h>\n#include <string.h>\n\n#define IK_MAX 16\n#define IK_DOF 6\n\n\
typedef struct {\n    double q[IK_MAX][IK_DOF];\n    int singular[IK_MAX];\n    int approximate[IK_MAX];\n    double residual[IK_MAX];\n    int n;\n} ik_solutions;\n\n",
    );
    s.push_str(&super::super::emit::c_tolerances(sol));
    s.push_str(&format!(
        "/* The residual above which a root of the elimination is dropped (no solution), and the\n   arrangement of the loop tried first (the one that served at the derivation). */\n\
#define IK_KEEP_TOL {}\n#define IK_FIRST_ARRANGEMENT {first}\n\n/* The constants of the numeric core (from core.rs). */\n{}\n",
        float_literal(super::KEEP_TOL),
        core_constant_code(Port::C)
    ));
    s.push_str(C_CORE);
    s.push_str(&format!("\n{C_DQ_MATRIX}\n"));
    s.push_str(&format!(
        "/* Every solution for the target pose ik_target (row-major homogeneous matrix), written to\n   ik_out (ik_out->n of them). */\n\
void ik(const double ik_target[4][4]{params}, ik_solutions *ik_out) {{\n"
    ));
    for p in &sol.params {
        s.push_str(&format!("    (void){p};\n"));
    }
    s.push_str(&chain_code(sol, Lang::C)?);
    s.push_str(C_TAIL);
    s.push_str(&format!(
        "void ik_dq(const double ik_q[8]{params}, ik_solutions *ik_out) {{\n    double ik_target[4][4];\n    ik_dq_matrix(ik_q, ik_target);\n    ik((const double (*)[4])ik_target{pnames}, ik_out);\n}}\n"
    ));
    Ok(s)
}

const C_TAIL: &str = r#"    /* The robot's scale (as ik::check::scale). */
    double ik_len = 0.0;
    ik_gen_tol ik_tol;
    ik_gen_out ik_o;
    int ik_i, ik_k;
    for (ik_i = 0; ik_i < 6; ik_i++)
        ik_len = fmax(ik_len, fabs(ik_ax[ik_i][4]) + fabs(ik_ax[ik_i][5]) + fabs(ik_ax[ik_i][6]));
    ik_len = fmax(ik_len, fabs(ik_home[0][3]) + fabs(ik_home[1][3]) + fabs(ik_home[2][3]));
    ik_len = fmax(ik_len, fabs(ik_target[0][3]) + fabs(ik_target[1][3]) + fabs(ik_target[2][3]));
    if (!(ik_len > 0.0 && isfinite(ik_len))) ik_len = 1.0;
    ik_tol.pose = IK_POSE_TOL;
    ik_tol.keep = IK_KEEP_TOL;
    ik_gen_solve(ik_ax, ik_home, ik_target, ik_len, ik_tol, IK_FIRST_ARRANGEMENT, &ik_o);
    ik_out->n = ik_o.n;
    for (ik_i = 0; ik_i < ik_o.n; ik_i++) {
        for (ik_k = 0; ik_k < 6; ik_k++) ik_out->q[ik_i][ik_k] = ik_o.q[ik_i][ik_k];
        ik_out->singular[ik_i] = 0;
        ik_out->residual[ik_i] = ik_o.residual[ik_i];
        ik_out->approximate[ik_i] = ik_o.residual[ik_i] > IK_POSE_TOL || isnan(ik_o.residual[ik_i]);
    }
}

"#;

const C_DQ_MATRIX: &str = r#"/* The homogeneous matrix of a unit dual quaternion (w, x, y, z) + eps (w, x, y, z). */
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

/// The general method's JavaScript for the IK page (after [`crate::ik::ik_javascript_helpers`],
/// whose tolerances and `ik_scale` it reads): the numeric core (`core.js`, a port of
/// `core.rs`) with its constants written from `core.rs`, and `ik_general(ax, home, T)`, every
/// solution as `[q, singular, approximate, residual]` as the generated solvers return them.
pub fn ik_javascript_general(sol: &IkSolution) -> String {
    let first = sol.general.as_ref().map_or(0, super::GeneralInfo::index);
    format!(
        "// The general 6R method: the residual above which a root of the elimination is dropped,\n\
// the arrangement of the loop tried first, the numeric core's constants (from core.rs).\n\
const IK_KEEP_TOL = {};\nconst IK_FIRST_ARRANGEMENT = {first};\n{}\n{JS_CORE}\n{JS_DRIVER}",
        float_literal(super::KEEP_TOL),
        core_constant_code(Port::JavaScript)
    )
}

const JS_DRIVER: &str = r#"// Every solution by the general method for the axes [kind, w, p], the home pose and the target
// (lengths in the robot's): [q, singular (never), approximate, residual] each.
function ik_general(ax, home, T) {
    const len = ik_scale(ax, home, T);
    const tol = { pose: IK_POSE_TOL, keep: IK_KEEP_TOL };
    const o = ik_gen_solve(ax, home, T, len, tol, IK_FIRST_ARRANGEMENT);
    return o.q.map((q, i) => [q, false, !(o.residual[i] <= IK_POSE_TOL), o.residual[i]]);
}
"#;

/// The solver as Python (NumPy): `ik_full(T, *, params)` with every solution as `(q,
/// singular, approximate, residual)`, `ik(T, ...)` and `ik_dq(q, ...)`, the interface of the
/// family solvers.
///
/// # Errors
/// An axis entry that fails (term limit, work budget).
pub fn ik_python(sol: &IkSolution) -> Result<String, ScalarError> {
    let sol = &*super::super::safe::solution(sol, names::Lang::Python);
    let kw = if sol.params.is_empty() {
        String::new()
    } else {
        format!(", *, {}", sol.params.join(", "))
    };
    let pass: String = sol.params.iter().map(|p| format!(", {p}={p}")).collect();
    let degree = sol.general.as_ref().map_or(0, |g| g.degree);
    let first = sol.general.as_ref().map_or(0, super::GeneralInfo::index);
    let mut s = String::new();
    let doc = [
        format!(
            "Inverse kinematics of {}: every solution, by the general 6R elimination",
            sol.robot
        ),
        format!("(Raghavan-Roth / Manocha-Canny, degree {degree} reached at a generic target)."),
        format!(
            "Joint vector order: {}; at most 16 solutions.",
            sol.variables.join(", ")
        ),
        "Generated by dqsym ik.".into(),
    ];
    for l in doc.iter().flat_map(|l| comment_lines(Comment::Python, l)) {
        s.push_str(&format!("# {l}\n"));
    }
    s.push_str("import math\n\nimport numpy as np\n\n");
    s.push_str(&format!(
        "IK_POSE_TOL = {}\nIK_KEEP_TOL = {}\nIK_FIRST_ARRANGEMENT = {first}\n\n",
        float_literal(check::POSE_TOL),
        float_literal(super::KEEP_TOL)
    ));
    s.push_str(&core_constant_code(Port::Python));
    s.push('\n');
    s.push_str(PY_CORE);
    s.push_str(&format!(
        "\n\ndef ik_full(T{kw}):\n    \"\"\"Every solution as (q, singular, approximate, residual).\"\"\"\n    T = np.asarray(T, dtype=float)\n"
    ));
    s.push_str(&chain_code(sol, Lang::Python)?);
    s.push_str(PY_TAIL);
    s.push_str(&format!(
        "def ik(T{kw}):\n    \"\"\"Every solution: joint vectors in joint order ({}).\"\"\"\n    return [q for q, _, _, _ in ik_full(T{pass})]\n\n\n",
        sol.variables.join(", ")
    ));
    s.push_str(&format!(
        "def ik_dq(q{kw}):\n    \"\"\"ik for a unit dual quaternion (w, x, y, z) + eps (w, x, y, z).\"\"\"\n    return ik(_ik_dq_matrix(q){pass})\n\n\n{PY_DQ}"
    ));
    Ok(s)
}

const PY_DQ: &str = r#"def _ik_dq_matrix(q):
    w, x, y, z, a, b, c, d = (float(v) for v in q)
    return np.array([
        [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
         2 * (-a * x + b * w - c * z + d * y)],
        [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
         2 * (-a * y + b * z + c * w - d * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z,
         2 * (-a * z - b * y + c * x + d * w)],
        [0.0, 0.0, 0.0, 1.0],
    ])
"#;

const PY_TAIL: &str = r#"    # The robot's scale (as ik::check::scale).
    ik_len = max([abs(a[4]) + abs(a[5]) + abs(a[6]) for a in ik_ax]
                 + [abs(ik_home[0][3]) + abs(ik_home[1][3]) + abs(ik_home[2][3]),
                    abs(T[0, 3]) + abs(T[1, 3]) + abs(T[2, 3])])
    if not (ik_len > 0 and math.isfinite(ik_len)):
        ik_len = 1.0
    return _gen_solve(ik_ax, ik_home, T, ik_len, IK_POSE_TOL, IK_KEEP_TOL, IK_FIRST_ARRANGEMENT)


"#;
