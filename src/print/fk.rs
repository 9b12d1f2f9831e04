//! The forward-kinematics report of a robot (`dqsym fk`): the unit DQ, the 4x4 matrix, the image
//! of a point and the 8 x n Jacobian, each entry in closed form, in one of three text formats.
//!
//! Entry names are the same in every format: `dq[k]` (k = 0..7, the components
//! (w, x, y, z, w_e, x_e, y_e, z_e) of q = r + eps q_e with q_e = t r / 2), `T[i][j]`
//! (i = 0..2, j = 0..3), `p[i]` and `J[i][j]` (i = 0..7, j = 0..n-1).

use crate::emit::{latex_aligned, latex_symbol, sympy, LatexOptions};
use crate::kin::{dq_jacobian, Robot};
use crate::print::{legend, plain, PlainOptions};
use crate::{closed_form, Expr, Scalar, ScalarError};

/// The text format of a report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReportFormat {
    /// Plain text; `shorthand` selects `c12` over `cos(theta1 + theta2)`.
    Plain { shorthand: bool },
    /// LaTeX (an `aligned` block per section).
    Latex { shorthand: bool },
    /// Exactly one line per entry, `NAME = EXPR`, EXPR parsable by SymPy's sympify.
    Sympy,
}

/// What the report contains.
#[derive(Clone, Debug)]
pub struct FkOptions {
    /// The text format.
    pub format: ReportFormat,
    /// A point of the last link (home pose for screw robots, last frame for DH) to transform.
    pub point: Option<[Scalar; 3]>,
    /// Add the 8 x n Jacobian of the DQ components.
    pub jacobian: bool,
}

/// The report, or the error of an exact operation.
pub fn fk_report(robot: &Robot, o: &FkOptions) -> Result<String, ScalarError> {
    let q = robot.forward();
    let mut sections: Vec<(&str, Vec<(String, Expr)>)> = Vec::new();
    let named =
        |prefix: &str, xs: &[(String, &Scalar)]| -> Result<Vec<(String, Expr)>, ScalarError> {
            xs.iter()
                .map(|(n, x)| Ok((format!("{prefix}{n}"), closed_form(x)?)))
                .collect()
        };
    let comps = q.components();
    let dq: Vec<(String, &Scalar)> = comps
        .iter()
        .enumerate()
        .map(|(k, c)| (format!("[{k}]"), c))
        .collect();
    sections.push((
        "unit dual quaternion (w, x, y, z, w_e, x_e, y_e, z_e)",
        named("dq", &dq)?,
    ));
    let m = q.to_matrix();
    let t: Vec<(String, &Scalar)> = (0..3)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| (format!("[{i}][{j}]"), &m.rows[i][j]))
        .collect();
    sections.push(("homogeneous matrix (rows 0..2)", named("T", &t)?));
    if let Some(p) = &o.point {
        let img = q.transform_point(p);
        let ps: Vec<(String, &Scalar)> = img
            .iter()
            .enumerate()
            .map(|(k, c)| (format!("[{k}]"), c))
            .collect();
        sections.push(("image of the point", named("p", &ps)?));
    }
    if o.jacobian {
        let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
        let j = dq_jacobian(&q, &vars);
        let js: Vec<(String, &Scalar)> = j
            .iter()
            .enumerate()
            .flat_map(|(i, row)| {
                row.iter()
                    .enumerate()
                    .map(move |(k, x)| (format!("[{i}][{k}]"), x))
            })
            .collect();
        sections.push(("Jacobian d dq[i] / d q[j]", named("J", &js)?));
    }
    Ok(match o.format {
        ReportFormat::Sympy => sections
            .iter()
            .flat_map(|(_, rows)| rows.iter().map(|(n, e)| format!("{n} = {}\n", sympy(e))))
            .collect(),
        ReportFormat::Plain { shorthand } => {
            let po = PlainOptions { shorthand };
            let mut out = header(robot);
            for (title, rows) in &sections {
                out.push_str(&format!("# {title}\n"));
                for (n, e) in rows {
                    out.push_str(&format!("{n} = {}\n", plain(e, &po)));
                }
            }
            let all: Vec<&Expr> = sections
                .iter()
                .flat_map(|(_, r)| r.iter().map(|(_, e)| e))
                .collect();
            let leg = legend(&all);
            if shorthand && !leg.is_empty() {
                out.push_str(&format!("# where {}\n", leg.join(", ")));
            }
            out
        }
        ReportFormat::Latex { shorthand } => {
            let lo = LatexOptions {
                shorthand,
                ..LatexOptions::default()
            };
            let mut out = format!("% {}", header(robot));
            for (title, rows) in &sections {
                out.push_str(&format!("% {title}\n"));
                let rows: Vec<(String, Expr)> = rows
                    .iter()
                    .map(|(n, e)| (latex_name(n), e.clone()))
                    .collect();
                out.push_str(&latex_aligned(&rows, &lo));
                out.push('\n');
            }
            out
        }
    })
}

fn header(robot: &Robot) -> String {
    let params = robot.parameters();
    format!(
        "# {} ({} joints: {}; parameters: {})\n",
        robot.name,
        robot.variables.len(),
        robot.variables.join(", "),
        if params.is_empty() {
            "none".to_string()
        } else {
            params.join(", ")
        }
    )
}

/// `T[1][2]` -> `T_{1,2}`, `dq[3]` -> `q_{3}` style subscripts.
fn latex_name(n: &str) -> String {
    let (base, rest) = n.split_once('[').unwrap_or((n, ""));
    let idx: Vec<&str> = rest.split(['[', ']']).filter(|s| !s.is_empty()).collect();
    let base = match base {
        "dq" => "q".to_string(),
        b => latex_symbol(b),
    };
    format!("{base}_{{{}}}", idx.join(","))
}
