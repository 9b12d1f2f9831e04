//! A robot as a robot file (`dqsym convert robot.urdf --to toml`): classic DH when the joint
//! axes allow it, screw form otherwise (the file's first comment says why). Every value is
//! exact, written as a number or an expression the robot-file reader evaluates back to the
//! same scalar.
//!
//! DH form is built by the usual construction on the exact axes of the home pose: frame 0 has
//! its z axis on joint 1's axis (its rotation `[[base]] rpy = [0, polar, azimuth]`, its origin
//! the foot of the perpendicular from the base origin); frame i has its z axis on joint i+1's
//! axis and its x axis on the common normal of axes i and i+1 (for parallel axes the one
//! through frame i-1's origin, so `d = 0`; a prismatic joint's line, whose position is free,
//! is put on the next axis when parallel to it, else through the previous frame's origin); the last link is a pure rotation
//! (or slide) and the rest of the tip's home pose is the `[[tool]]` frame. Every angle
//! (`alpha`, the `theta` offsets, the frames' `rpy`) must be a multiple of pi/12 and every
//! length must come out without nested radicals; otherwise, or for a coupled (mimic) joint,
//! the file is in screw form. The DH file is checked before it is written: each joint's axis
//! in its home pose is exactly the screw axis and the tip's home pose is exactly the same, so
//! both forms give the same pose (product of exponentials).

use crate::algebra::cross;
use crate::{
    closed_form,
    emit::names::{line_comment, toml_string, Comment},
    emit::sympy::dqsym_text,
    kin::{Frame, JointGeometry},
    DualQuat, Joint, JointKind, Robot, Scalar, ScalarError,
};

type V = [Scalar; 3];

/// The robot file of `robot`: DH when its axes allow it, else screw form. Reading it back
/// gives the same pose.
///
/// # Errors
/// When a value has no closed form (a size limit).
pub fn robot_toml(robot: &Robot, source: &str) -> Result<String, ScalarError> {
    // A robot file has no local joints: their frames are carried to the base first.
    let robot = &robot.screw_form()?;
    let mut text = match dh_form(robot) {
        Ok(dh) => dh_toml(robot, &dh, source),
        Err(why) => screw_toml(robot, source, &why),
    }?;
    // The parameters' nominal values (a URDF angle kept as a name: its decimal).
    if !robot.values.is_empty() {
        text += "\n[values]\n";
        for (name, v) in &robot.values {
            text += &format!("{name} = {v:?}\n");
        }
    }
    Ok(text)
}

/// Why `robot` cannot be written in DH form (`None` when it can); the screw-form file says it.
pub fn dh_refusal(robot: &Robot) -> Option<DhRefusal> {
    match robot.screw_form() {
        Ok(r) => dh_form(&r).err(),
        Err(e) => Some(DhRefusal::Carry(e)),
    }
}

/// A value as text for a robot file: a TOML number when it is an integer or a terminating
/// decimal (read back from its text, exactly), else an expression in quotes.
fn value_text(x: &Scalar) -> Result<String, ScalarError> {
    if let Some(q) = x.as_rational() {
        if let Some(d) = decimal_text(&q) {
            return Ok(d);
        }
    }
    Ok(format!("\"{}\"", dqsym_text(&closed_form(x)?)))
}

/// The decimal text of a rational whose denominator has no prime factors but 2 and 5.
fn decimal_text(q: &num_rational::BigRational) -> Option<String> {
    use num_bigint::BigInt;
    use num_traits::{Signed, Zero};
    let (num, den) = (q.numer().clone(), q.denom().clone());
    let (two, five, ten) = (BigInt::from(2), BigInt::from(5), BigInt::from(10));
    let (mut d, mut digits) = (den.clone(), 0usize);
    let (mut twos, mut fives) = (0usize, 0usize);
    while (&d % &two).is_zero() {
        d /= &two;
        twos += 1;
    }
    while (&d % &five).is_zero() {
        d /= &five;
        fives += 1;
    }
    if d != BigInt::from(1) {
        return None;
    }
    digits = digits.max(twos).max(fives);
    if digits == 0 {
        return Some(num.to_string());
    }
    let scaled = &num * ten.pow(digits as u32) / &den;
    let neg = scaled.is_negative();
    let s = scaled.abs().to_string();
    let s = format!("{}{s}", "0".repeat((digits + 1).saturating_sub(s.len())));
    let (int, frac) = s.split_at(s.len() - digits);
    Some(format!("{}{int}.{frac}", if neg { "-" } else { "" }))
}

fn expr_text(x: &Scalar) -> Result<String, ScalarError> {
    Ok(dqsym_text(&closed_form(x)?))
}

fn v3_text(v: &V) -> Result<String, ScalarError> {
    Ok(format!(
        "[{}, {}, {}]",
        value_text(&v[0])?,
        value_text(&v[1])?,
        value_text(&v[2])?
    ))
}

fn frames_text(name: &str, frames: &[Frame]) -> Result<String, ScalarError> {
    let mut out = String::new();
    for f in frames {
        out += &format!(
            "\n[[{name}]]\nxyz = {}\nrpy = {}\n",
            v3_text(&f.xyz)?,
            v3_text(&f.rpy)?
        );
    }
    Ok(out)
}

/// The screw-form robot file, with `why` (the reason it is not DH) in its header.
fn screw_toml(robot: &Robot, source: &str, why: &DhRefusal) -> Result<String, ScalarError> {
    // The name and the file's path are text from outside: every line of them commented.
    let mut out = line_comment(
        Comment::Hash,
        "#",
        &format!(
            "{} in screw form, converted by dqsym from {source}: each joint turns about (or slides\n\
             along) its axis in the home pose, in base coordinates; the tool frames, in order,\n\
             give the last link's home pose.\nNot DH: {why}.",
            robot.name
        ),
    );
    out += &format!(
        "name = {}\nconvention = \"screw\"\n",
        toml_string(&robot.name)
    );
    out += &frames_text("base", &robot.base_frames)?;
    out += &frames_text("tool", &robot.tool_frames)?;
    for (i, (j, value)) in robot
        .chain
        .joints
        .iter()
        .zip(&robot.joint_values)
        .enumerate()
    {
        let JointGeometry::Screw { axis, point } = &j.geometry else {
            // Only URDF robots (screw form) are converted; other forms are robot files already.
            continue;
        };
        let kind = match j.kind {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
        };
        // A joint moving exactly with an earlier one (a mimic joint with multiplier 1 and no
        // offset) is written `1*q`: a plain name would declare a variable of its own.
        let mut var = expr_text(value)?;
        if robot.joint_values[..i].contains(value) {
            var = format!("1*{var}");
        }
        out += &format!(
            "\n[[joint]]\ntype = \"{kind}\"\nvariable = \"{var}\"\naxis = {}\n",
            v3_text(axis)?
        );
        if j.kind == JointKind::Revolute {
            out += &format!("point = {}\n", v3_text(point)?);
        }
    }
    Ok(out)
}

/// A robot in DH form: frames before the first joint, one row per joint, frames after.
struct Dh {
    base: Vec<Frame>,
    /// kind, value (the joint variable), theta offset, d offset, a, alpha.
    rows: Vec<(JointKind, Scalar, [Scalar; 4])>,
    tool: Vec<Frame>,
}

fn dh_toml(robot: &Robot, dh: &Dh, source: &str) -> Result<String, ScalarError> {
    let mut out = line_comment(
        Comment::Hash,
        "#",
        &format!(
            "{} in classic DH form (Rz(theta) Tz(d) Tx(a) Rx(alpha) per joint), converted by dqsym\n\
             from {source}; a base frame puts frame 0's z axis on joint 1's axis, the tool frame\n\
             is the tip in the last joint's frame.",
            robot.name
        ),
    );
    out += &format!("name = {}\nconvention = \"dh\"\n", toml_string(&robot.name));
    out += &frames_text("base", &dh.base)?;
    out += &frames_text("tool", &dh.tool)?;
    for (kind, value, [theta, d, a, alpha]) in &dh.rows {
        let (kind, theta, d) = match kind {
            JointKind::Revolute => (
                "revolute",
                format!("\"{}\"", expr_text(&(value + theta))?),
                value_text(d)?,
            ),
            JointKind::Prismatic => (
                "prismatic",
                value_text(theta)?,
                format!("\"{}\"", expr_text(&(value + d))?),
            ),
        };
        out += &format!(
            "\n[[joint]]\ntype = \"{kind}\"\ntheta = {theta}\nd = {d}\na = {}\nalpha = {}\n",
            value_text(a)?,
            value_text(alpha)?
        );
    }
    Ok(out)
}

fn sub(a: &V, b: &V) -> V {
    std::array::from_fn(|i| &a[i] - &b[i])
}

fn add(a: &V, b: &V) -> V {
    std::array::from_fn(|i| &a[i] + &b[i])
}

fn scale(k: &Scalar, v: &V) -> V {
    std::array::from_fn(|i| k * &v[i])
}

fn dot(a: &V, b: &V) -> Scalar {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

fn is_zero(v: &V) -> Result<bool, DhRefusal> {
    let mut all = true;
    for x in v {
        all &= vanishes(x)?;
    }
    Ok(all)
}

/// Whether `x` is zero; a limit reached by the arithmetic of the check is the refusal's
/// reason itself, never a "no" (it once read as "a mimic joint").
fn vanishes(x: &Scalar) -> Result<bool, DhRefusal> {
    x.try_is_zero().map_err(DhRefusal::Limit)
}

fn num(x: &Scalar) -> f64 {
    x.eval(&|_| None).unwrap_or(f64::NAN)
}

/// `x / y` for a nonzero constant `y`.
fn div(x: &Scalar, y: &Scalar) -> Result<Scalar, DhRefusal> {
    Ok(x.try_div(y)?)
}

/// The exact square root of `x`, which must be a rational (a nested radical has none here).
fn root(x: &Scalar, what: &str) -> Result<Scalar, DhRefusal> {
    x.sqrt()
        .check()
        .map_err(|_| DhRefusal::NotRationalRoot(what.to_string()))
}

/// The angle `k pi/12` whose cosine and sine are `c` and `s`.
fn angle_of(c: &Scalar, s: &Scalar, what: &str) -> Result<Scalar, DhRefusal> {
    let k = (num(s).atan2(num(c)) / (std::f64::consts::PI / 12.0)).round();
    let refuse = || DhRefusal::NotTwelfth(what.to_string());
    if !k.is_finite() {
        return Err(refuse());
    }
    let a = Scalar::pi() * <Scalar as crate::Ring>::from_ratio(k as i64, 12);
    let exact = |x: Scalar, y: &Scalar| vanishes(&(x - y)).map_err(|m| m.at(what));
    if exact(a.cos(), c)? && exact(a.sin(), s)? {
        Ok(a)
    } else {
        Err(refuse())
    }
}

/// The frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` equal to the unit DQ `f`, with angles
/// multiples of pi/12.
fn frame_of(f: &DualQuat<Scalar>, what: &str) -> Result<Frame, DhRefusal> {
    let m = f.to_matrix().rows;
    let r = |i: usize, j: usize| num(&m[i][j]);
    let (yaw, pitch, roll) = if r(0, 0).hypot(r(1, 0)) > 1e-9 {
        (
            r(1, 0).atan2(r(0, 0)),
            (-r(2, 0)).atan2(r(0, 0).hypot(r(1, 0))),
            r(2, 1).atan2(r(2, 2)),
        )
    } else {
        // Pitch +-pi/2: only yaw -+ roll is determined; roll = 0.
        ((-r(0, 1)).atan2(r(1, 1)), (-r(2, 0)).atan2(0.0), 0.0)
    };
    let snap = |x: f64| {
        let k = (x / (std::f64::consts::PI / 12.0)).round() as i64;
        Scalar::pi() * <Scalar as crate::Ring>::from_ratio(k, 12)
    };
    let frame = Frame {
        xyz: f.translation_part(),
        rpy: [snap(roll), snap(pitch), snap(yaw)],
    };
    let back = frame.dq()?.to_matrix().rows;
    let mut same = true;
    for (x, y) in back.iter().flatten().zip(m.iter().flatten()) {
        same &= vanishes(&(x - y)).map_err(|m| m.at(what))?;
    }
    if same {
        Ok(frame)
    } else {
        Err(DhRefusal::NoFrame(what.to_string()))
    }
}

/// A joint of the screw form: its kind, unit axis, a point of the axis and its value (its
/// own variable).
struct Line {
    kind: JointKind,
    axis: V,
    point: V,
    value: Scalar,
}

/// The DH form of a screw-form robot, or why there is none.
fn dh_form(robot: &Robot) -> Result<Dh, DhRefusal> {
    let lines = screw_lines(robot)?;
    let (base_frame, mut x, mut origin) = frame_zero(&lines[0])?;
    let zero = || Scalar::int(0);
    let mut rows = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(next) = lines.get(i + 1) else {
            rows.push((
                line.kind,
                line.value.clone(),
                [zero(), zero(), zero(), zero()],
            ));
            break;
        };
        let j = i + 1;
        let (d, a, xn) = common_normal(j, line, next, lines.get(i + 2), (&origin, &x))?;
        let (u, u2) = (&line.axis, &next.axis);
        let theta = angle_of(
            &dot(&x, &xn),
            &dot(&cross(&x, &xn), u),
            &format!("joint {j}'s angle from the previous common normal"),
        )?;
        let alpha = angle_of(
            &dot(u, u2),
            &dot(&cross(u, u2), &xn),
            &format!("the angle between axes {j} and {}", j + 1),
        )?;
        origin = add(&add(&origin, &scale(&d, u)), &scale(&a, &xn));
        x = xn;
        rows.push((line.kind, line.value.clone(), [theta, d, a, alpha]));
    }
    let home = home_checked(&base_frame, &rows, &lines)?;
    let tool = tool_frame(robot, home)?;
    let mut base = robot.base_frames.clone();
    let mut identity = true;
    for x in base_frame.xyz.iter().chain(&base_frame.rpy) {
        identity &= vanishes(x)?;
    }
    if !identity {
        base.push(base_frame);
    }
    Ok(Dh {
        base,
        rows,
        tool: vec![tool],
    })
}

/// The joints of a screw-form robot, each moved by its own variable (DH rows take one
/// variable each).
fn screw_lines(robot: &Robot) -> Result<Vec<Line>, DhRefusal> {
    if robot.chain.joints.is_empty() {
        return Err(DhRefusal::NoJoint);
    }
    let mut lines: Vec<Line> = Vec::new();
    for (i, (j, value)) in robot
        .chain
        .joints
        .iter()
        .zip(&robot.joint_values)
        .enumerate()
    {
        let mut plain = false;
        for v in &robot.variables {
            plain |= vanishes(&(value - &Scalar::sym(v)))
                .map_err(|m| m.at(&format!("joint {}", i + 1)))?;
        }
        let shared = lines.iter().any(|l| l.value == *value);
        if !plain || shared {
            return Err(DhRefusal::Mimic(i + 1));
        }
        let JointGeometry::Screw { axis, point } = &j.geometry else {
            return Err(DhRefusal::NotScrew);
        };
        lines.push(Line {
            kind: j.kind,
            axis: axis.clone(),
            point: point.clone(),
            value: value.clone(),
        });
    }
    Ok(lines)
}

/// Frame 0: z on joint 1's axis, `Rz(azimuth) Ry(polar)`, at the foot of the perpendicular
/// from the base origin; with its x axis and origin.
fn frame_zero(first: &Line) -> Result<(Frame, V, V), DhRefusal> {
    let zero = || Scalar::int(0);
    let one = Scalar::int(1);
    let u = &first.axis;
    let sin_polar = root(
        &(&one - &(&u[2] * &u[2])),
        "the sine of joint 1's polar angle",
    )?;
    let polar = angle_of(&u[2], &sin_polar, "joint 1's polar angle")?;
    let azimuth = if vanishes(&sin_polar)? {
        zero()
    } else {
        angle_of(
            &div(&u[0], &sin_polar)?,
            &div(&u[1], &sin_polar)?,
            "joint 1's azimuth",
        )?
    };
    let (cp, sp, ca, sa) = (polar.cos(), polar.sin(), azimuth.cos(), azimuth.sin());
    let x: V = [&ca * &cp, &sa * &cp, -sp.clone()];
    let origin: V = match first.kind {
        JointKind::Revolute => {
            let p = &first.point;
            sub(p, &scale(&dot(p, u), u))
        }
        JointKind::Prismatic => [zero(), zero(), zero()],
    };
    let frame = Frame {
        xyz: origin.clone(),
        rpy: [zero(), polar, azimuth],
    };
    Ok((frame, x, origin))
}

/// `d`, `a` and the new x axis of joint `j` (counted from 1) with axis `line`, the next
/// joint's `next` and the one after `after`: the common normal of the two axes from frame
/// `j - 1`'s `origin` and x axis `x`.
fn common_normal(
    j: usize,
    line: &Line,
    next: &Line,
    after: Option<&Line>,
    (origin, x): (&V, &V),
) -> Result<(Scalar, Scalar, V), DhRefusal> {
    let zero = || Scalar::int(0);
    let (u, u2) = (&line.axis, &next.axis);
    // A prismatic joint's line is free: on the axis after it when the two are parallel
    // (so that they coincide, a = 0), else through this frame's origin.
    let p2 = match (next.kind, after) {
        (JointKind::Revolute, _) => next.point.clone(),
        (JointKind::Prismatic, Some(l3))
            if l3.kind == JointKind::Revolute && is_zero(&cross(u2, &l3.axis))? =>
        {
            l3.point.clone()
        }
        (JointKind::Prismatic, _) => origin.clone(),
    };
    let w = sub(&p2, origin);
    let c = cross(u, u2);
    let at_joint = |m: DhRefusal| m.at(&format!("joint {j}"));
    if !is_zero(&c).map_err(at_joint)? {
        let s2 = dot(&c, &c);
        let s = root(
            &s2,
            &format!("the sine of the angle between axes {j} and {}", j + 1),
        )?;
        let mut xn: V = [div(&c[0], &s)?, div(&c[1], &s)?, div(&c[2], &s)?];
        let mut a = dot(&w, &xn);
        if num(&a) < 0.0 {
            xn = scale(&Scalar::int(-1), &xn);
            a = -a;
        }
        let d = div(&dot(&cross(&w, u2), &c), &s2)?;
        return Ok((d, a, xn));
    }
    let perp = sub(&w, &scale(&dot(&w, u), u));
    if is_zero(&perp).map_err(at_joint)? {
        // Parallel axes on one line: no offset; the x axis stays.
        return Ok((zero(), zero(), x.clone()));
    }
    let a = root(
        &dot(&perp, &perp),
        &format!("the distance between axes {j} and {}", j + 1),
    )?;
    let xn = [div(&perp[0], &a)?, div(&perp[1], &a)?, div(&perp[2], &a)?];
    Ok((zero(), a, xn))
}

/// The home pose of the DH chain, checked joint by joint against the screw axes.
fn home_checked(
    base_frame: &Frame,
    rows: &[(JointKind, Scalar, [Scalar; 4])],
    lines: &[Line],
) -> Result<DualQuat<Scalar>, DhRefusal> {
    let zero = || Scalar::int(0);
    let mut home = base_frame.dq()?;
    for (i, (kind, _, [theta, d, a, alpha])) in rows.iter().enumerate() {
        let Line {
            kind: k,
            axis: u,
            point: p,
            ..
        } = &lines[i];
        debug_assert_eq!(k, kind);
        let z = DualQuat::from_real(home.real.clone()).transform_point(&[
            zero(),
            zero(),
            Scalar::int(1),
        ]);
        let at = home.translation_part();
        let on_line = *kind == JointKind::Prismatic || is_zero(&cross(&sub(&at, p), u))?;
        if !is_zero(&sub(&z, u))? || !on_line {
            return Err(DhRefusal::MissesAxis(i + 1));
        }
        home = home
            * Joint::revolute_dh(theta.clone(), d.clone(), a.clone(), alpha.clone()).dq(&zero());
    }
    Ok(home)
}

/// The tip in the last joint's frame, checked to give the robot's own tip home pose.
fn tool_frame(robot: &Robot, home: DualQuat<Scalar>) -> Result<Frame, DhRefusal> {
    let tool = home.conjugate() * &robot.chain.tool;
    let tool = frame_of(&tool, "the tip in the last joint's frame")?;
    let tool_dq = tool.dq()?;
    let mut same = true;
    for (x, y) in (home * tool_dq)
        .to_matrix()
        .rows
        .iter()
        .flatten()
        .zip(robot.chain.tool.to_matrix().rows.iter().flatten())
    {
        same &= vanishes(&(x - y)).map_err(|m| m.at("the tip's home pose"))?;
    }
    if !same {
        return Err(DhRefusal::TipDiffers);
    }
    Ok(tool)
}

/// Why a robot has no DH form (the screw-form file's header says it).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DhRefusal {
    /// The chain has no joint.
    #[error("the chain has no moving joint")]
    NoJoint,
    /// A joint moves with another joint's variable (counted from 1).
    #[error("joint {0} moves with another joint's variable (a mimic joint)")]
    Mimic(usize),
    /// The joints are not screw motions.
    #[error("the robot is not in screw form")]
    NotScrew,
    /// A length or sine is a nested radical.
    #[error("{0} is not the square root of a rational")]
    NotRationalRoot(String),
    /// An angle is not a multiple of pi/12.
    #[error("{0} is not a multiple of pi/12")]
    NotTwelfth(String),
    /// A constant frame has no roll, pitch and yaw that are multiples of pi/12.
    #[error("{0} has no roll, pitch and yaw that are multiples of pi/12")]
    NoFrame(String),
    /// A limit was reached while checking whether a value is zero.
    #[error("a size limit was reached while checking it ({0})")]
    Limit(ScalarError),
    /// A limit was reached carrying a local-form robot's axes to the base.
    #[error("a size limit was reached carrying the axes to the base: {0}")]
    Carry(ScalarError),
    /// An exact operation failed.
    #[error(transparent)]
    Scalar(#[from] ScalarError),
    /// A reason, at the place named.
    #[error("{at}: {why}")]
    At {
        /// Where (`joint 2`, `the tip's home pose`).
        at: String,
        /// Why.
        why: Box<DhRefusal>,
    },
    /// The DH frame of a joint misses its axis (counted from 1): a bug.
    #[error("joint {0}'s DH frame misses its axis (a bug)")]
    MissesAxis(usize),
    /// The DH chain's tip differs from the robot's: a bug.
    #[error("the tip's home pose differs (a bug)")]
    TipDiffers,
}

impl DhRefusal {
    /// This reason at `at`.
    fn at(self, at: &str) -> DhRefusal {
        DhRefusal::At {
            at: at.to_string(),
            why: Box::new(self),
        }
    }
}
