//! The generated solvers of a general-method solution: the robot's exact axes and home pose
//! as expressions in its parameters, and the numeric core: `core.rs` verbatim in Rust, so that
//! the generated solver and the reference solver are the same algorithm, and its ports
//! `core.py` (Python, NumPy), `core.c` (C99) and `core.js` (the IK page's JavaScript), each
//! followed by its port of `apart_solver.rs` (`apart.py`, `apart.c`, `apart.js`) for a 4R2P with
//! its slides three joints apart. The ports read the core's tolerances and tables as constants
//! written here from `core.rs` (`core_constants`), never as copies; the tests of
//! `tests/it/ik_general_ports.rs` and `tests/it/ik_4r2p_apart.rs` hold the C and JavaScript
//! ports to the reference solver's solution sets.
//!
//! What the solver computes is decided here, once; every statement and the file around it
//! are written by the language's [`SolverSyntax`] (`emit/{rust,c,python}.rs`), as for the
//! family solvers (`ik/emit.rs`).

use super::super::check;
use super::super::IkSolution;
use crate::emit::codegen::{lower, CodegenOptions};
use crate::emit::names::{comment_lines, Lang};
use crate::emit::syntax::{solver_syntax, syntax, GeneralFile, SolverSyntax, Syntax};
use crate::scalar::Trig;
use crate::ScalarError;

/// The numeric core, included in the generated solver.
const CORE: &str = include_str!("core.rs");

/// The numeric core of a 4R2P with its slides three joints apart (`apart_solver.rs`, which
/// `apart.rs` includes after its one import), after the core in the generated Rust solver.
const APART: &str = include_str!("apart_solver.rs");

/// The apart core in Python (a port of `apart.rs`, after `core.py`).
const PY_APART: &str = include_str!("apart.py");

/// The numeric core in Python (NumPy).
const PY_CORE: &str = include_str!("core.py");

/// The numeric core in C99 (a port of `core.rs`).
const C_CORE: &str = include_str!("core.c");

/// The numeric core in JavaScript (a port of `core.rs`, for the IK page).
const JS_CORE: &str = include_str!("core.js");

/// The apart core in C99 (a port of `apart_solver.rs`, after `core.c`).
const C_APART: &str = include_str!("apart.c");

/// The apart core in JavaScript (a port of `apart_solver.rs`, after `core.js`).
const JS_APART: &str = include_str!("apart.js");

/// A constant of the core by the name the ports read it by.
type Named<T> = (&'static str, T);

/// A table of the core by name: its rows (one for a vector).
type Table = Named<Vec<Vec<f64>>>;

/// The constants of `core.rs` the C, Python and JavaScript ports read, by name: the scalars as
/// literals of `w`, then the tables as rows (one row for a vector), from their one definition there.
fn core_constants(w: &dyn Syntax) -> (Vec<Named<String>>, Vec<Table>) {
    use super::core as k;
    let f = |v: f64| w.literal(v);
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
        ("IK_GEN_FOLD_REACH", f(k::FOLD_REACH)),
        ("IK_GEN_MIN_POSITIVE", f(f64::MIN_POSITIVE)),
        ("IK_GEN_PRISM_FAR", f(k::PRISM_FAR)),
        ("IK_GEN_DET_SAMPLES", k::DET_SAMPLES.to_string()),
        ("IK_GEN_DET_DEGREE", k::DET_DEGREE.to_string()),
        ("IK_GEN_TAYLOR", k::TAYLOR.to_string()),
        ("IK_GEN_ROOT_GRID", k::ROOT_GRID.to_string()),
        ("IK_GEN_ROOT_EVALS", k::ROOT_EVALS.to_string()),
        ("IK_GEN_DET_CHECK", f(k::DET_CHECK)),
        ("IK_GEN_DET_TRIM", f(k::DET_TRIM)),
        ("IK_GEN_ROOT_MARGIN", f(k::ROOT_MARGIN)),
        ("IK_GEN_ROOT_LEAF", f(k::ROOT_LEAF)),
        ("IK_GEN_BRACKET_TOL", f(k::BRACKET_TOL)),
        ("IK_GEN_BRACKET_WIDTH", f(k::BRACKET_WIDTH)),
        ("IK_GEN_NULL_RESIDUAL", f(k::NULL_RESIDUAL)),
        ("IK_GEN_GRID_STEP", f(k::GRID_STEP)),
        ("IK_GEN_GRID_STEP_HI", f(k::GRID_STEP_HI)),
        ("IK_GEN_GRID_STEP_LO", f(k::GRID_STEP_LO)),
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
        ("IK_GEN_GRID_SIN", vec![k::GRID_SIN.to_vec()]),
        ("IK_GEN_DET_SIN", vec![k::DET_SIN.to_vec()]),
        ("IK_GEN_DET_COS", vec![k::DET_COS.to_vec()]),
        (
            "IK_GEN_DET_COLS",
            vec![k::DET_COLS.iter().map(|&j| j as f64).collect()],
        ),
    ];
    (scalars, tables)
}

/// The core's constants in the language of `w` (C, Python or JavaScript): C as `#define` and
/// `static const double` tables, Python and JavaScript as names bound to numbers and lists; a
/// table of several rows nested by rows.
fn core_constant_code(w: &dyn Syntax) -> String {
    let (scalars, tables) = core_constants(w);
    let mut s = String::new();
    for (name, v) in scalars {
        s.push_str(&w.constant(name, &v, "f64"));
    }
    for (name, rows) in tables {
        let text: Vec<String> = rows
            .iter()
            .map(|r| {
                let v: Vec<String> = r.iter().map(|x| w.literal(*x)).collect();
                v.join(", ")
            })
            .collect();
        let (dims, value) = if let [row] = &text[..] {
            (vec![rows[0].len()], w.list(row))
        } else {
            let nested: Vec<String> = text.iter().map(|r| w.list(r)).collect();
            (vec![rows.len(), rows[0].len()], w.list(&nested.join(", ")))
        };
        s.push_str(&w.table(name, &dims, &value));
    }
    s
}

/// The axes `[kind, w, p]` and the home pose's top rows as statements at the top of the
/// solver (locals `ik_ax`, `ik_home`), in the parameters.
fn chain_code(sol: &IkSolution, w: &dyn Syntax) -> Result<String, ScalarError> {
    let lit = |v: f64| w.literal(v);
    let outputs = super::super::emit::chain_outputs(sol)?;
    let prog = lower(&outputs, &sol.params, &CodegenOptions::default())
        .map_err(|e| ScalarError::Unbound(e.to_string()))?;
    let mut s = String::new();
    for (k, atom) in prog.atoms.iter().enumerate() {
        let angle = prog.angle_code(k, &lit);
        for (t, name, f) in [
            (Trig::Sin, &atom.sin_name, "sin"),
            (Trig::Cos, &atom.cos_name, "cos"),
        ] {
            if prog.atom_used(k, t) {
                s.push_str(&format!("    {}\n", w.local(name, &w.call(f, &angle))));
            }
        }
    }
    for (id, name) in prog.temps() {
        s.push_str(&format!(
            "    {}\n",
            w.local(name, &prog.definition(id, &lit))
        ));
    }
    let ids: Vec<_> = prog
        .outputs
        .iter()
        .flat_map(|(_, ids)| ids.clone())
        .collect();
    let code = |i: usize| prog.code(ids[i], &lit);
    let ax: Vec<String> = (0..6)
        .map(|i| {
            let v: Vec<String> = (0..6).map(|k| code(6 * i + k)).collect();
            // The kind: 1 for a joint that slides (the core's `GenAxis`).
            let kind = u8::from(sol.axes[i].kind == crate::kin::JointKind::Prismatic);
            w.list(&format!("{kind}.0, {}", v.join(", ")))
        })
        .collect();
    let hm: Vec<String> = (0..3)
        .map(|r| {
            let v: Vec<String> = (0..4).map(|c| code(36 + 4 * r + c)).collect();
            w.list(&v.join(", "))
        })
        .collect();
    for (name, dims, rows) in [("ik_ax", [6, 7], ax), ("ik_home", [3, 4], hm)] {
        let value = w.list(&rows.join(", "));
        s.push_str(&format!("    {}\n", w.array_local(name, &dims, &value)));
    }
    Ok(s)
}

/// The solver's documentation, one comment line each (the robot's name is text from
/// outside: every line of it commented): `long` adds the method's steps (Rust, C), `singular`
/// says that the flag is never set (C).
fn doc(sol: &IkSolution, w: &dyn SolverSyntax, long: bool, singular: bool) -> String {
    let degree = sol.general.as_ref().map_or(0, |g| g.degree);
    let robot = &sol.robot;
    let order = format!(
        "Joint vector order: {}; at most 16 solutions{}.",
        sol.variables.join(", "),
        if singular {
            "; singular is never set"
        } else {
            ""
        }
    );
    let apart = super::apart_chain(&sol.axes);
    let lines: Vec<String> = if apart && long {
        vec![
            format!("Inverse kinematics of {robot}: every solution, by the general method for a 4R2P with its slides three joints apart."),
            "The four turns fix the orientation (F), the slides' plane the position (P); their resultant in".into(),
            format!("tan(theta5/2) is a trigonometric polynomial D(theta4), degree {degree} reached at a generic target;"),
            "real roots of D (17 samples, certified interval search; the eigenvalues of its companion matrix where that search".into(),
            "gives up in both readings of the loop), back-substitution, Gauss-Newton polish,".into(),
            "each solution checked by forward kinematics (approximate: residual above IK_POSE_TOL).".into(),
            order,
            "Generated by dqsym ik.".into(),
        ]
    } else if apart {
        vec![
            format!("Inverse kinematics of {robot}: every solution, by the general method for a 4R2P with its slides"),
            format!("three joints apart (one resultant in tan(theta/2), degree {degree} reached at a generic target)."),
            order,
            "Generated by dqsym ik.".into(),
        ]
    } else if long {
        vec![
            format!("Inverse kinematics of {robot}: every solution, by the general 6R elimination."),
            format!("Raghavan-Roth / Manocha-Canny: a 12 x 12 quadratic matrix polynomial, degree {degree} reached at a generic target;"),
            "real roots of det M / (1 + x^2)^12 (17 samples, certified interval search; the eigenvalues of".into(),
            "the 24 x 24 companion matrix where that search gives up), back-substitution, Gauss-Newton polish,".into(),
            "each solution checked by forward kinematics (approximate: residual above IK_POSE_TOL).".into(),
            order,
            "Generated by dqsym ik.".into(),
        ]
    } else {
        vec![
            format!("Inverse kinematics of {robot}: every solution, by the general 6R elimination"),
            format!(
                "(Raghavan-Roth / Manocha-Canny, degree {degree} reached at a generic target)."
            ),
            order,
            "Generated by dqsym ik.".into(),
        ]
    };
    lines
        .iter()
        .flat_map(|l| comment_lines(w.doc_syntax(), l))
        .map(|l| w.comment_line(&l))
        .collect()
}

/// The general solver of `sol` in `lang`: what it computes here, its file through the
/// language's [`SolverSyntax::general_file`].
fn solver(sol: &IkSolution, lang: Lang) -> Result<String, ScalarError> {
    let w = solver_syntax(lang).expect("a language IK solvers are written in");
    let sol = &*super::super::safe::solution(sol, lang);
    let apart = super::apart_chain(&sol.axes);
    let rust_core = if apart {
        format!("{CORE}\n{APART}")
    } else {
        CORE.to_string()
    };
    let py_core = if apart {
        format!("{PY_CORE}\n\n{PY_APART}")
    } else {
        PY_CORE.to_string()
    };
    let c_core = if apart {
        format!("{C_CORE}\n{C_APART}")
    } else {
        C_CORE.to_string()
    };
    let (long, core, mut constants) = match lang {
        Lang::Rust => (true, rust_core.as_str(), String::new()),
        Lang::C => (true, c_core.as_str(), core_constant_code(w)),
        _ => (false, py_core.as_str(), core_constant_code(w)),
    };
    if apart && lang != Lang::Rust {
        constants.push_str(&apart_constant_code(w));
    }
    let dq_matrix = crate::emit::helpers::helper(lang, w.helper("ik_dq_matrix").as_str())
        .map_or("", |h| h.text);
    let file = w.general_file(&GeneralFile {
        doc: doc(sol, w, long, lang == Lang::C),
        params: &sol.params,
        variables: &sol.variables,
        pose_tol: w.literal(check::POSE_TOL),
        keep_tol: w.literal(super::KEEP_TOL),
        first: sol.general.as_ref().map_or(0, |g| g.first),
        tolerances: super::super::emit::tolerances_of(sol, lang),
        constants,
        core,
        chain: chain_code(sol, w)?,
        dq_matrix,
        apart,
    });
    Ok(file)
}

/// The apart core's constants (`apart.rs`) in the language of `w`, for its ports.
fn apart_constant_code(w: &dyn Syntax) -> String {
    use super::apart as a;
    let mut s = String::new();
    for (name, v) in [
        ("IK_GEN_APART_PARALLEL", a::APART_PARALLEL),
        ("IK_GEN_APART_P_TOL", a::APART_P_TOL),
    ] {
        s.push_str(&w.constant(name, &w.literal(v), "f64"));
    }
    s
}

/// The solver as Rust, with the interface of the family solvers: `ik_into`, `ik`, `ik_dq`
/// and `IkSolutions` (at most 16 solutions; `singular` is never set by this method).
///
/// # Errors
/// An axis entry that fails (term limit, work budget).
pub fn ik_rust(sol: &IkSolution) -> Result<String, ScalarError> {
    solver(sol, Lang::Rust)
}

/// The solver as C99, with the interface of the family solvers: `ik_solutions`, `void
/// ik(const double T[4][4], params..., ik_solutions *out)` and `ik_dq`; the numeric core
/// (`core.c`, a port of `core.rs`) with its constants written from `core.rs`. No allocation.
///
/// # Errors
/// An axis entry that fails (term limit, work budget).
pub fn ik_c(sol: &IkSolution) -> Result<String, ScalarError> {
    solver(sol, Lang::C)
}

/// The solver as Python (NumPy): `ik_full(T, *, params)` with every solution as `(q,
/// singular, approximate, residual)`, `ik(T, ...)` and `ik_dq(q, ...)`, the interface of the
/// family solvers.
///
/// # Errors
/// An axis entry that fails (term limit, work budget).
pub fn ik_python(sol: &IkSolution) -> Result<String, ScalarError> {
    solver(sol, Lang::Python)
}

/// The general method's JavaScript for the IK page (after [`crate::ik::ik_javascript_helpers`],
/// whose tolerances and `ik_scale` it reads): the numeric core (`core.js`, a port of
/// `core.rs`) with its constants written from `core.rs`, and `ik_general(ax, home, T)`, every
/// solution as `[q, singular, approximate, residual]` as the generated solvers return them.
pub fn ik_javascript_general(sol: &IkSolution) -> String {
    let js = syntax(Lang::JavaScript);
    let first = sol.general.as_ref().map_or(0, |g| g.first);
    // A 4R2P with its slides three joints apart: the apart core after the core, its entry
    // called by the driver.
    let (apart, constants, solve) = if super::apart_chain(&sol.axes) {
        (
            format!("\n{JS_APART}"),
            apart_constant_code(js),
            "ik_gen_apart_solve",
        )
    } else {
        (String::new(), String::new(), "ik_gen_solve")
    };
    format!(
        "// The general 6R method: the residual above which a root of the elimination is dropped,\n\
// the arrangement of the loop tried first, the numeric core's constants (from core.rs).\n\
{}{}{}{constants}\n{JS_CORE}{apart}\n{JS_DRIVER}    const o = {solve}(ax, home, T, len, tol, IK_FIRST_ARRANGEMENT);\n{JS_DRIVER_TAIL}",
        js.constant("IK_KEEP_TOL", &js.literal(super::KEEP_TOL), "f64"),
        js.constant("IK_FIRST_ARRANGEMENT", &first.to_string(), "usize"),
        core_constant_code(js)
    )
}

/// The page's driver of the general method, before the core's call.
const JS_DRIVER: &str = r#"// Every solution by the general method for the axes [kind, w, p], the home pose and the target
// (lengths in the robot's): [q, singular (never), approximate, residual] each.
function ik_general(ax, home, T) {
    const len = ik_scale(ax, home, T);
    const tol = { pose: IK_POSE_TOL, keep: IK_KEEP_TOL };
"#;

/// The page's driver after the core's call.
const JS_DRIVER_TAIL: &str = r#"    return o.q.map((q, i) => [q, false, !(o.residual[i] <= IK_POSE_TOL), o.residual[i]]);
}
"#;
