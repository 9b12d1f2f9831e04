//! `dqsym paper`: the paper's worked examples and the PUMA 560 pose, derived from the files of
//! `examples/` (compiled in): the planar RRR arm of sec 6.1 from Appendix III's listing, the
//! 6R robot of sec 6.3 from its script, and the PUMA 560 from its robot file. Each value is
//! shown as its closed form in plain text, with the shorthand legend.

use crate::{
    closed_form, eval_scalar_text, parse, parse_robot, plain, print::legend, DualQuat, Expr,
    PlainOptions, Scalar, Session, Value,
};

/// Appendix III: the planar RRR arm, one link at a time (sec 6.1).
const RRR: &str = include_str!("../examples/appendix3_rrr.dq");
/// Sec 6.3: the 6R robot's tool point carried back to the base frame.
const SIX_R: &str = include_str!("../examples/sec6_3_6r.dq");
/// The PUMA 560 in standard DH.
const PUMA_560: &str = include_str!("../examples/robots/puma560.toml");

/// Why an example compiled in could not be derived (a bug: neither happens with the files
/// compiled in).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PaperError {
    /// A script failed to parse or run, or did not bind the point.
    #[error("{file}: {message}")]
    Script {
        /// The example's file name.
        file: &'static str,
        /// What went wrong, rendered.
        message: String,
    },
    /// The robot file was refused.
    #[error(transparent)]
    Robot(#[from] crate::kin::RobotError),
    /// A closed form could not be found.
    #[error(transparent)]
    Closed(#[from] crate::ScalarError),
}

/// The paper's derivations as plain text (`o.shorthand`: `c12` for `cos(theta1 + theta2)`).
///
/// # Errors
///
/// [`PaperError`] when an example file fails to run or a closed form cannot be found (neither
/// happens with the files compiled in).
pub fn paper(o: &PlainOptions) -> Result<String, PaperError> {
    let mut out = String::new();
    out += &block(
        "sec 6.1, planar RRR arm: end effector v0",
        &named("v0.", &point(RRR, "appendix3_rrr.dq", "v0")?),
        o,
    )?;
    out += &block(
        "sec 6.3, 6R robot: tool point (0, l1 + l2 + l3 + l4, 0) in the base frame",
        &named("v0.", &point(SIX_R, "sec6_3_6r.dq", "v0")?),
        o,
    )?;
    let robot = parse_robot(PUMA_560, "puma560.toml", &eval_scalar_text)?;
    let q = robot.forward();
    let m = q.to_matrix();
    let mut entries = Vec::new();
    for (i, row) in m.rows[..3].iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            entries.push((format!("T[{i}][{j}]"), x.clone()));
        }
    }
    out += &block("PUMA 560 (standard DH): 4x4 pose", &entries, o)?;
    let comps: Vec<(String, Scalar)> = q
        .components()
        .iter()
        .enumerate()
        .map(|(k, c)| (format!("dq[{k}]"), c.clone()))
        .collect();
    out += &block(
        "PUMA 560: unit dual quaternion (w, x, y, z, w_e, x_e, y_e, z_e)",
        &comps,
        o,
    )?;
    Ok(out)
}

/// The point `1 + eps (x, y, z)` bound to `name` after running the script `src`.
fn point(src: &str, file: &'static str, name: &str) -> Result<[Scalar; 3], PaperError> {
    let script = |message: String| PaperError::Script { file, message };
    let program = parse(src).map_err(|e| script(e.rendered().to_owned()))?;
    let mut session = Session::new();
    session.run(&program).map_err(|e| script(e.render(src)))?;
    match session.get(name) {
        Some(Value::DualQuat(DualQuat { dual, .. })) => {
            Ok([dual.x.clone(), dual.y.clone(), dual.z.clone()])
        }
        _ => Err(script(format!("`{name}` is not a point 1 + eps v"))),
    }
}

/// `v` as the entries `{prefix}x`, `{prefix}y`, `{prefix}z`.
fn named(prefix: &str, v: &[Scalar; 3]) -> Vec<(String, Scalar)> {
    ["x", "y", "z"]
        .iter()
        .zip(v)
        .map(|(k, x)| (format!("{prefix}{k}"), x.clone()))
        .collect()
}

/// Closed forms of `values`, one line each, followed by the shorthand legend.
fn block(title: &str, values: &[(String, Scalar)], o: &PlainOptions) -> Result<String, PaperError> {
    let mut out = format!("{title}\n");
    let mut exprs: Vec<Expr> = Vec::new();
    for (name, v) in values {
        let e = closed_form(v)?;
        out.push_str(&format!("  {name} = {}\n", plain(&e, o)));
        exprs.push(e);
    }
    let refs: Vec<&Expr> = exprs.iter().collect();
    let leg = legend(&refs);
    if o.shorthand && !leg.is_empty() {
        out.push_str(&format!("  where {}\n", leg.join(", ")));
    }
    Ok(out + "\n")
}
