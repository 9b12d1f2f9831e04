//! `dqsym walk ROBOT --ik`: the derivation step by step (the axes as Plücker lines, the
//! decisions, the wrist centre or carried point, each subproblem with its identity and its
//! branches), then a numeric check at one configuration.

use super::{home_axes, Formula, IkSolution};
use crate::emit::{latex, latex_symbol, LatexOptions};
use crate::kin::{Chain, Joint, JointGeometry, Robot};
use crate::print::{plain, PlainOptions};
use crate::{closed_form, Scalar, ScalarError};

fn num(x: &Scalar, env: &[(String, f64)]) -> Result<f64, ScalarError> {
    x.eval(&|n| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
}

/// The robot's chain with every parameter bound (f64), built from its joint fields.
fn numeric_chain(robot: &Robot, env: &[(String, f64)]) -> Result<Chain<f64>, ScalarError> {
    let mut joints = Vec::new();
    for j in &robot.chain.joints {
        let f = |x: &Scalar| num(x, env);
        let g = match &j.geometry {
            JointGeometry::Dh { theta, d, a, alpha } => JointGeometry::Dh {
                theta: f(theta)?,
                d: f(d)?,
                a: f(a)?,
                alpha: f(alpha)?,
            },
            JointGeometry::Mdh { alpha, a, theta, d } => JointGeometry::Mdh {
                alpha: f(alpha)?,
                a: f(a)?,
                theta: f(theta)?,
                d: f(d)?,
            },
            JointGeometry::Screw { axis, point } => JointGeometry::Screw {
                axis: [f(&axis[0])?, f(&axis[1])?, f(&axis[2])?],
                point: [f(&point[0])?, f(&point[1])?, f(&point[2])?],
            },
        };
        joints.push(Joint::new(j.kind, g));
    }
    let dq = |q: &crate::DualQuat<Scalar>| -> Result<crate::DualQuat<f64>, ScalarError> {
        let c = q.components();
        let mut t = [0.0; 8];
        for (o, c) in t.iter_mut().zip(&c) {
            *o = num(c, env)?;
        }
        Ok(crate::DualQuat::from_components(t))
    };
    Ok(Chain::new(joints)
        .with_base(dq(&robot.chain.base)?)
        .with_tool(dq(&robot.chain.tool)?))
}

/// The walkthrough of a derived inverse kinematics; `markdown` writes LaTeX in `$...$`.
///
/// # Errors
/// A closed form that fails.
pub fn ik_walk(robot: &Robot, sol: &IkSolution, markdown: bool) -> Result<String, ScalarError> {
    let po = PlainOptions::default();
    let lo = LatexOptions::default();
    let show = |e: &crate::Expr| -> String {
        if markdown {
            format!("${}$", latex(e, &lo))
        } else {
            plain(e, &po)
        }
    };
    let h = |level: usize, t: &str| -> String {
        if markdown {
            format!("{} {t}\n\n", "#".repeat(level))
        } else {
            format!(
                "{t}\n{}\n\n",
                if level == 1 { "=" } else { "-" }.repeat(t.chars().count())
            )
        }
    };
    let mut out = String::new();
    out.push_str(&h(
        1,
        &format!(
            "Inverse kinematics of {}, step by step",
            if markdown {
                crate::emit::names::html_text(&sol.robot)
            } else {
                crate::emit::names::printable(&sol.robot)
            }
        ),
    ));
    out.push_str(&h(2, "1. The joint axes as Plücker lines (home pose)"));
    out.push_str(
        "Every joint, whatever its convention, turns about (or slides along) a line of the home \
         pose: FK(q) = E1(q1) ... En(qn) M. Each line is (direction k, moment m = p x k), \
         computed exactly from the chain's home-pose prefix products.\n\n",
    );
    let (axes, _) = home_axes(robot);
    for a in &axes {
        let f = |v: &[Scalar; 3]| -> Result<String, ScalarError> {
            let e: Vec<String> = v
                .iter()
                .map(|x| closed_form(x).map(|e| show(&e)))
                .collect::<Result<_, _>>()?;
            Ok(format!("({})", e.join(", ")))
        };
        out.push_str(&format!(
            "- {}: k = {}, m = {}\n",
            if markdown {
                format!("${}$", latex_symbol(&a.variable))
            } else {
                a.variable.clone()
            },
            f(&a.dir)?,
            f(&a.moment)?
        ));
    }
    out.push('\n');
    out.push_str(&h(2, "2. The geometry, decided exactly"));
    out.push_str(
        "Two axes are parallel when k1 x k2 = 0, and intersect when they are not parallel and \
         the reciprocal product k1·m2 + k2·m1 = 0. A symbolic product is a condition.\n\n",
    );
    for g in &sol.geometry {
        out.push_str(&format!("- {g}\n"));
    }
    out.push_str(&format!("\nFamily: {}.\n\n", sol.family));
    out.push_str(&h(2, "3. The subproblems"));
    out.push_str(
        "The target pose T gives G = T M^-1 = E1 ... En. Each joint below is one Paden-Kahan \
         subproblem on the exact axis data, written as one of two identities:\n\n\
         - a cos q + b sin q = c  has  q = atan2(b, a) ± atan2(sqrt(a² + b² − c²), c) \
         (two branches; none when the radicand is negative: out of reach);\n\
         - Rot(k, q) u = v  has  q = atan2(k·(u x v), u·v − (k·u)(k·v)).\n\n",
    );
    let forms = sol.forms()?;
    for (i, step) in sol.steps.iter().enumerate() {
        out.push_str(&h(3, &format!("Step {}: {}", i + 1, step.variable)));
        out.push_str(&format!("{}.\n\n", step.method));
        for (n, e) in &forms[i] {
            out.push_str(&format!("- {n} = {}\n", show(e)));
        }
        out.push('\n');
        let q = &step.variable;
        out.push_str(&match &step.formula {
            Formula::Atan2 { .. } => format!("{q} = atan2(y, x).\n"),
            Formula::Trig { .. } => format!(
                "{q} = atan2(b, a) ± atan2(sqrt(a² + b² − c²), c); exists where a² + b² − c² ≥ 0.\n"
            ),
            Formula::Value { .. } => format!("{q} = v.\n"),
            Formula::Quadratic { .. } => format!(
                "{q}² + 2 beta {q} + gamma = 0: {q} = −beta ± sqrt(beta² − gamma); exists where beta² ≥ gamma.\n"
            ),
        });
        if let Some((n, p, m)) = step.branch.as_ref().map(super::Branch::words) {
            out.push_str(&format!("Branch {n}: + is {p}, − is {m}.\n"));
        }
        out.push_str(&format!("Singular: {}.\n\n", step.singular));
    }
    out.push_str(&h(2, "4. Check at one configuration"));
    let mut env: Vec<(String, f64)> = sol
        .params
        .iter()
        .enumerate()
        .map(|(i, p)| (p.clone(), 0.3 + 0.1 * i as f64))
        .collect();
    let q0: Vec<f64> = robot
        .variables
        .iter()
        .enumerate()
        .map(|(i, _)| [0.4, -0.7, 0.9, 0.5, -0.6, 0.8, 0.3][i % 7])
        .collect();
    for (v, x) in robot.variables.iter().zip(&q0) {
        if sol.free.as_deref() == Some(v.as_str()) {
            env.retain(|(k, _)| k != v);
            env.push((v.clone(), *x));
        }
    }
    // The end ik solves for: the tool point folded into the tool motion.
    let chain = numeric_chain(&super::with_tool_point(robot), &env)?;
    let t = chain
        .forward_matrix(&q0)
        .map_err(|e| ScalarError::Unbound(e.to_string()))?
        .rows;
    let p: Vec<(&str, f64)> = env.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    let sols = sol.solve_numeric(&t, &p).map_err(ScalarError::Unbound)?;
    out.push_str(&format!(
        "Parameters {}; configuration {} = ({}); the solver returns {} solutions:\n\n",
        env.iter()
            .map(|(k, v)| format!("{k} = {v:.1}"))
            .collect::<Vec<_>>()
            .join(", "),
        robot.variables.join(", "),
        q0.iter()
            .map(|x| format!("{x:.1}"))
            .collect::<Vec<_>>()
            .join(", "),
        sols.len()
    ));
    let free_k = sol
        .free
        .as_ref()
        .and_then(|f| robot.variables.iter().position(|v| v == f));
    for s in &sols {
        let mut q = s.q.clone();
        if let Some(k) = free_k {
            q.insert(k, q0[k]);
        }
        let back = chain
            .forward_matrix(&q)
            .map_err(|e| ScalarError::Unbound(e.to_string()))?
            .rows;
        let dev = sol.deviation(&t, &back);
        let dev = if dev < 1e-12 {
            "below 1e-12".to_string()
        } else {
            format!("{dev:.1e}")
        };
        out.push_str(&format!(
            "- ({}): pose deviation {dev}{}\n",
            s.q.iter()
                .map(|x| format!("{x:.4}"))
                .collect::<Vec<_>>()
                .join(", "),
            if s.singular { " (singular)" } else { "" }
        ));
    }
    Ok(out)
}
