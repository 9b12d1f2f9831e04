//! A robot as a robot file (`dqsym convert robot.urdf --to toml`): screw form, each joint's
//! axis and point in the home pose, its variable (an expression in one symbol for a coupled
//! joint), and the constant frames as `[[base]]` and `[[tool]]` tables. Every value is exact,
//! written as an expression the robot-file reader evaluates back to the same scalar.

use crate::{closed_form, sympy, JointGeometry, JointKind, Robot, Scalar, ScalarError};

/// The robot file of `robot`, screw form. Reading it back gives the same pose.
///
/// # Errors
/// When a value has no closed form (a size limit).
pub fn robot_toml(robot: &Robot, source: &str) -> Result<String, ScalarError> {
    let t = |x: &Scalar| -> Result<String, ScalarError> { Ok(sympy(&closed_form(x)?)) };
    let quoted = |x: &Scalar| -> Result<String, ScalarError> {
        let s = t(x)?;
        // Numbers stay TOML numbers; everything else is an expression in quotes.
        Ok(if s.parse::<i64>().is_ok() {
            s
        } else {
            format!("\"{s}\"")
        })
    };
    let v3 = |v: &[Scalar; 3]| -> Result<String, ScalarError> {
        Ok(format!(
            "[{}, {}, {}]",
            quoted(&v[0])?,
            quoted(&v[1])?,
            quoted(&v[2])?
        ))
    };
    let mut out = format!(
        "# {} in screw form, converted by dqsym from {source}: each joint turns about (or slides\n\
         # along) its axis in the home pose, in base coordinates; the tool frames, in order,\n\
         # give the last link's home pose.\n",
        robot.name
    );
    out += &format!("name = {:?}\nconvention = \"screw\"\n", robot.name);
    for (name, frames) in [("base", &robot.base_frames), ("tool", &robot.tool_frames)] {
        for f in frames.iter() {
            out += &format!(
                "\n[[{name}]]\nxyz = {}\nrpy = {}\n",
                v3(&f.xyz)?,
                v3(&f.rpy)?
            );
        }
    }
    for (j, value) in robot.chain.joints.iter().zip(&robot.joint_values) {
        let JointGeometry::Screw { axis, point } = &j.geometry else {
            // Only URDF robots (screw form) are converted; other forms are robot files already.
            continue;
        };
        let kind = match j.kind {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
        };
        out += &format!(
            "\n[[joint]]\ntype = \"{kind}\"\nvariable = \"{}\"\naxis = {}\n",
            t(value)?,
            v3(axis)?
        );
        if j.kind == JointKind::Revolute {
            out += &format!("point = {}\n", v3(point)?);
        }
    }
    Ok(out)
}
