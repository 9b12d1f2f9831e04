//! A walkthrough of a robot file: one factor per joint, the running products, the image of
//! the tool point (or of the last frame's origin) with its identities, the pose, the check.

use super::check::{check, check_pose};
use super::motion::Motion;
use super::script::traces;
use super::{Mechanism, Step, WalkError, Walkthrough};
use crate::{parse_robot, DualQuat, FieldEval, JointGeometry, JointKind, Scalar, Value};

/// The walkthrough of the robot file `text`; `file` names it in messages, `eval` evaluates a
/// field (`eval_scalar_text`).
///
/// # Errors
/// When the file is invalid, or a value cannot be shown.
pub fn walk_robot(text: &str, file: &str, eval: FieldEval) -> Result<Walkthrough, WalkError> {
    let robot = parse_robot(text, file, eval)?;
    let mut steps = Vec::new();
    let mut motions = Vec::new();
    let mut acc: Option<DualQuat<Scalar>> = None;
    let mut names: Vec<String> = Vec::new();
    for (i, (joint, var)) in robot.chain.joints.iter().zip(&robot.variables).enumerate() {
        let v = Scalar::sym(var);
        let revolute = joint.kind == JointKind::Revolute;
        let add = |x: &Scalar, on: bool| if on { x + &v } else { x.clone() };
        let m = match &joint.geometry {
            JointGeometry::Screw { axis, point } => Motion::Screw {
                axis: axis.clone(),
                point: point.clone(),
                angle: if revolute { v.clone() } else { Scalar::int(0) },
                slide: if revolute { Scalar::int(0) } else { v.clone() },
            },
            JointGeometry::Dh { theta, d, a, alpha } => Motion::Dh {
                theta: add(theta, revolute),
                d: add(d, !revolute),
                a: a.clone(),
                alpha: alpha.clone(),
            },
            JointGeometry::Mdh { alpha, a, theta, d } => Motion::Mdh {
                alpha: alpha.clone(),
                a: a.clone(),
                theta: add(theta, revolute),
                d: add(d, !revolute),
            },
        };
        let q = joint.dq(&v);
        let name = format!("q{}", i + 1);
        steps.push(Step::Factor {
            name: name.clone(),
            value: Value::DualQuat(q.clone()),
            meaning: m.describe(),
        });
        motions.push(m);
        acc = Some(match acc {
            None => q,
            Some(p) => {
                let prod = &p * &q;
                steps.push(Step::Product {
                    left: names.join("*"),
                    right: name.clone(),
                    value: Value::DualQuat(prod.clone()),
                });
                prod
            }
        });
        names.push(name);
    }
    let pose = acc.unwrap_or_else(DualQuat::identity);
    let pose = &pose * &robot.chain.tool;
    let zero = || [Scalar::int(0), Scalar::int(0), Scalar::int(0)];
    let home = robot.tool.clone().unwrap_or_else(zero);
    let image = pose.transform_point(&home);
    let chain = names.join("*");
    steps.push(Step::Transform {
        label: "p".to_owned(),
        q: chain.clone(),
        v: tuple_text(&home)?,
        value: Value::Vector(image.clone()),
        half_angles: super::script::half_angle_symbols(&pose)
            .into_iter()
            .map(|symbol| super::HalfAngle {
                symbol,
                names: None,
            })
            .collect(),
        traces: traces("p", &image)?,
    });
    steps.push(Step::Result {
        label: "q".to_owned(),
        value: Value::DualQuat(pose.clone()),
    });
    steps.push(Step::Result {
        label: "T".to_owned(),
        value: Value::Matrix(pose.to_matrix().rows.iter().map(|r| r.to_vec()).collect()),
    });
    if let Some(s) = check(&motions, &home, &image, "p") {
        steps.push(s);
    }
    if let Some(s) = check_pose(&motions, &pose, "T") {
        steps.push(s);
    }
    Ok(Walkthrough {
        title: robot.name.clone(),
        steps,
        mechanism: Some(Mechanism {
            motions,
            tool: robot.tool.clone(),
            values: robot.values.clone(),
        }),
    })
}

fn tuple_text(v: &[Scalar; 3]) -> Result<String, WalkError> {
    let mut parts = Vec::new();
    for x in v {
        parts.push(crate::plain(
            &crate::closed_form(x)?,
            &crate::PlainOptions::default(),
        ));
    }
    Ok(format!("({})", parts.join(", ")))
}
