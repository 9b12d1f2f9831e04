//! A walkthrough of a robot file: one factor per joint, the running products, the image of
//! the tool point (or of the last frame's origin) with its identities, the pose, the check.

use super::check::{check, check_pose};
use super::motion::Motion;
use super::motion::{Word, Words};
use super::script::traces;
use super::{Mechanism, Step, WalkError, Walkthrough};
use crate::{
    kin::{FieldEval, Frame, JointGeometry},
    parse_robot, DualQuat, JointKind, Robot, Scalar, Value,
};

/// The largest pose component, in terms, a robot walkthrough expands.
const WALK_MAX_TERMS: usize = 2_000;

/// The work the size probe of a robot walkthrough may do.
const WALK_PROBE_BUDGET: u64 = 2_000_000;

/// The walkthrough of the robot file `text`; `file` names it in messages, `eval` evaluates a
/// field (`eval_scalar_text`).
///
/// # Errors
/// When the file is invalid, the chain is too large to expand ([`WalkError::TooLarge`]), or a
/// value cannot be shown.
pub fn walk_robot(text: &str, file: &str, eval: FieldEval) -> Result<Walkthrough, WalkError> {
    let robot = parse_robot(text, file, eval)?;
    walk_robot_read(&robot, file)
}

/// The walkthrough of a robot file already read (with its options: `--exact-angles`); `file`
/// names it in messages.
///
/// # Errors
/// As [`walk_robot`], but for reading the file.
pub fn walk_robot_read(robot: &Robot, file: &str) -> Result<Walkthrough, WalkError> {
    // Decide at once whether the chain can be shown expanded: the pose under a small term
    // limit and work budget (a fully symbolic chain grows exponentially and is noticed after a
    // few products), instead of failing after seconds of closed forms.
    let fits = {
        let _probe = crate::Context::entered()
            .with_work_budget(WALK_PROBE_BUDGET)
            .enter();
        robot.forward_within(WALK_MAX_TERMS).is_some()
    };
    if !fits {
        return Err(WalkError::TooLarge {
            file: file.to_owned(),
            limit: WALK_MAX_TERMS,
            budget: WALK_PROBE_BUDGET,
        });
    }
    walk_robot_chain(robot)
}

/// The motions of a constant frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`, zero parts left out.
fn frame_motions(f: &Frame) -> Vec<Motion> {
    let (o, l) = (Scalar::int(0), Scalar::int(1));
    let mut out = Vec::new();
    if f.xyz.iter().any(|x| !x.is_zero_value()) {
        out.push(Motion::Translation { t: f.xyz.clone() });
    }
    let axes = [
        [o.clone(), o.clone(), l.clone()],
        [o.clone(), l.clone(), o.clone()],
        [l, o.clone(), o.clone()],
    ];
    for (axis, angle) in axes.into_iter().zip(f.rpy.iter().rev()) {
        if !angle.is_zero_value() {
            out.push(Motion::Screw {
                axis,
                point: [o.clone(), o.clone(), o.clone()],
                angle: angle.clone(),
                slide: o.clone(),
            });
        }
    }
    out
}

/// The motions of a joint at the value `v` of its variable: the joint's own motion last,
/// after the constant frames a [`JointGeometry::Local`] joint holds.
fn joint_motions(joint: &crate::kin::Joint<Scalar>, v: &Scalar) -> Vec<Motion> {
    let mut out = Vec::new();
    if let JointGeometry::Local { frames, .. } = &joint.geometry {
        out = frames
            .iter()
            .flat_map(|(xyz, rpy)| {
                frame_motions(&Frame {
                    xyz: xyz.clone(),
                    rpy: rpy.clone(),
                })
            })
            .collect();
    }
    out.push(joint_motion(joint, v));
    out
}

/// The motion of a joint at the value `v` of its variable (a local joint's about its axis in
/// its own frame, without its frames).
fn joint_motion(joint: &crate::kin::Joint<Scalar>, v: &Scalar) -> Motion {
    let revolute = joint.kind == JointKind::Revolute;
    let add = |x: &Scalar, on: bool| if on { x + v } else { x.clone() };
    match &joint.geometry {
        JointGeometry::Screw { axis, point } => Motion::Screw {
            axis: axis.clone(),
            point: point.clone(),
            angle: if revolute { v.clone() } else { Scalar::int(0) },
            slide: if revolute { Scalar::int(0) } else { v.clone() },
        },
        JointGeometry::Local { axis, .. } => Motion::Screw {
            axis: axis.clone(),
            point: [Scalar::int(0), Scalar::int(0), Scalar::int(0)],
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
    }
}

/// The mechanism of a robot for the drawing: its base frames, joints and tool frames as
/// motions, without the walkthrough's products.
pub fn robot_mechanism(robot: &Robot) -> Mechanism {
    let mut motions: Vec<Motion> = robot.base_frames.iter().flat_map(frame_motions).collect();
    for (joint, v) in robot.chain.joints.iter().zip(&robot.joint_values) {
        motions.extend(joint_motions(joint, v));
    }
    motions.extend(robot.tool_frames.iter().flat_map(frame_motions));
    Mechanism {
        motions,
        tool: robot.tool.clone(),
        values: robot.values.clone(),
    }
}

/// The walkthrough of a robot already read (from a robot file or a URDF file).
///
/// # Errors
/// When a value cannot be shown.
pub fn walk_robot_chain(robot: &Robot) -> Result<Walkthrough, WalkError> {
    let mut steps = Vec::new();
    let mut motions = Vec::new();
    let mut acc: Option<DualQuat<Scalar>> = None;
    let mut names: Vec<String> = Vec::new();
    let push = |name: String,
                q: DualQuat<Scalar>,
                meaning: Words,
                steps: &mut Vec<Step>,
                acc: &mut Option<DualQuat<Scalar>>,
                names: &mut Vec<String>| {
        steps.push(Step::Factor {
            name: name.clone(),
            value: Value::DualQuat(q.clone()),
            meaning,
        });
        *acc = Some(match acc.take() {
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
    };
    for (i, f) in robot.base_frames.iter().enumerate() {
        let ms = frame_motions(f);
        let q = f.dq().map_err(|e| WalkError::Script(e.to_string()))?;
        push(
            format!("b{}", i + 1),
            q,
            frame_words("base frame", f),
            &mut steps,
            &mut acc,
            &mut names,
        );
        motions.extend(ms);
    }
    for (i, (joint, v)) in robot
        .chain
        .joints
        .iter()
        .zip(&robot.joint_values)
        .enumerate()
    {
        let ms = joint_motions(joint, v);
        let q = joint.dq(v);
        let meaning = ms.last().expect("a joint's own motion").describe();
        motions.extend(ms);
        push(
            format!("q{}", i + 1),
            q,
            meaning,
            &mut steps,
            &mut acc,
            &mut names,
        );
    }
    for (i, f) in robot.tool_frames.iter().enumerate() {
        let ms = frame_motions(f);
        let q = f.dq().map_err(|e| WalkError::Script(e.to_string()))?;
        push(
            format!("t{}", i + 1),
            q,
            frame_words("tool frame", f),
            &mut steps,
            &mut acc,
            &mut names,
        );
        motions.extend(ms);
    }
    let pose = acc.unwrap_or_else(DualQuat::identity);
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
    let mut w = Walkthrough {
        title: robot.name.clone(),
        steps,
        mechanism: Some(Mechanism {
            motions,
            tool: robot.tool.clone(),
            values: robot.values.clone(),
        }),
        forms: super::Forms::default(),
    };
    w.prepare();
    Ok(w)
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

/// "base frame: translation by (x, y, z), then roll r, pitch p, yaw y (R = Rz Ry Rx)".
fn frame_words(what: &str, f: &Frame) -> Words {
    Words(vec![
        Word::Text(format!("{what}: translation by ")),
        Word::Tuple(f.xyz.to_vec()),
        Word::Text(", rotation Rz(yaw) Ry(pitch) Rx(roll) with (roll, pitch, yaw) = ".into()),
        Word::Tuple(f.rpy.to_vec()),
    ])
}
