//! Robot description files (TOML) in three conventions: classic DH, modified DH (Craig) and the
//! paper's screw form (sec 6), where each joint turns about or slides along an axis given in the
//! home pose.
//!
//! Every field is an expression of the dqsym language. This module does not evaluate them
//! itself: the caller passes the evaluator, so the kinematics layer stays free of the language.

use super::{Chain, Joint, JointGeometry, JointKind};
use crate::{DualQuat, Matrix4, Scalar};
use serde::Deserialize;
use thiserror::Error;

/// The joint convention of a robot file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// `Rz(theta) Tz(d) Tx(a) Rx(alpha)`.
    Dh,
    /// `Rx(alpha) Tx(a) Rz(theta) Tz(d)` (Craig).
    Mdh,
    /// A motion about (or along) a home-pose axis in base coordinates.
    Screw,
}

/// A robot read from a file: its chain with symbolic joint variables.
#[derive(Clone, Debug)]
pub struct Robot {
    /// The `name` field, or the file name.
    pub name: String,
    /// The convention the joints were given in.
    pub convention: Convention,
    /// The joint variables in joint order.
    pub variables: Vec<String>,
    /// The chain; its joint values are the variables.
    pub chain: Chain<Scalar>,
    /// The `tool` point of a screw-form file, in the home pose.
    pub tool: Option<[Scalar; 3]>,
    /// The `[values]` table: nominal numbers for symbolic parameters (`a2 = 0.4318`), used
    /// where a number is needed (the walkthrough's drawing); results stay symbolic.
    pub values: Vec<(String, f64)>,
}

/// What is wrong with a robot file; every message names the file, and the joint and field
/// where there is one.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum RobotError {
    /// The file is not valid TOML or misses a top-level field.
    #[error("{file}: {message}")]
    File { file: String, message: String },
    /// A joint field is missing or wrong.
    #[error("{file}: joint {joint}, field `{field}`: {message}")]
    Field {
        file: String,
        joint: usize,
        field: String,
        message: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotFile {
    name: Option<String>,
    convention: String,
    tool: Option<Vec<String>>,
    #[serde(default)]
    values: std::collections::BTreeMap<String, toml::Value>,
    #[serde(default)]
    joint: Vec<JointFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JointFile {
    #[serde(rename = "type")]
    kind: String,
    theta: Option<String>,
    d: Option<String>,
    a: Option<String>,
    alpha: Option<String>,
    variable: Option<String>,
    axis: Option<Vec<String>>,
    point: Option<Vec<String>>,
}

/// Evaluates a field's text to an exact scalar, or says why it cannot.
pub type FieldEval<'a> = &'a dyn Fn(&str) -> Result<Scalar, String>;

/// Reads a robot file. `file` names it in messages; `eval` evaluates one field expression.
pub fn parse_robot(text: &str, file: &str, eval: FieldEval) -> Result<Robot, RobotError> {
    let f: RobotFile = toml::from_str(text).map_err(|e| {
        let at = e.span().map(|s| {
            let before = &text[..s.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let col = before.chars().rev().take_while(|&c| c != '\n').count() + 1;
            format!("line {line}, column {col}: ")
        });
        RobotError::File {
            file: file.to_string(),
            message: format!("{}{}", at.unwrap_or_default(), e.message()),
        }
    })?;
    let convention = match f.convention.as_str() {
        "dh" => Convention::Dh,
        "mdh" => Convention::Mdh,
        "screw" => Convention::Screw,
        other => {
            return Err(RobotError::File {
                file: file.into(),
                message: format!(
                    "unknown convention `{other}` (expected \"dh\", \"mdh\" or \"screw\")"
                ),
            })
        }
    };
    if f.joint.is_empty() {
        return Err(RobotError::File {
            file: file.into(),
            message: "no [[joint]] tables".into(),
        });
    }
    let mut joints = Vec::new();
    let mut variables = Vec::new();
    for (i, j) in f.joint.iter().enumerate() {
        let n = i + 1;
        let err = |field: &str, message: String| RobotError::Field {
            file: file.into(),
            joint: n,
            field: field.into(),
            message,
        };
        let kind = match j.kind.as_str() {
            "revolute" => JointKind::Revolute,
            "prismatic" => JointKind::Prismatic,
            other => {
                return Err(err(
                    "type",
                    format!(
                        "unknown joint type `{other}` (expected \"revolute\" or \"prismatic\")"
                    ),
                ))
            }
        };
        let field = |name: &str, v: &Option<String>| -> Result<Scalar, RobotError> {
            let text = v.as_ref().ok_or_else(|| err(name, "missing".into()))?;
            eval(text).map_err(|m| err(name, m))
        };
        match convention {
            Convention::Dh | Convention::Mdh => {
                let (theta, d, a, alpha) = (
                    field("theta", &j.theta)?,
                    field("d", &j.d)?,
                    field("a", &j.a)?,
                    field("alpha", &j.alpha)?,
                );
                // The variable is the one symbol of theta (revolute) or d (prismatic); the rest
                // of that field is a constant offset.
                let (vname, vfield) = match kind {
                    JointKind::Revolute => ("theta", &theta),
                    JointKind::Prismatic => ("d", &d),
                };
                let var = joint_variable(vfield).map_err(|m| err(vname, m))?;
                let off = |x: &Scalar, is_var: bool| {
                    if is_var {
                        x - &Scalar::sym(&var)
                    } else {
                        x.clone()
                    }
                };
                let theta = off(&theta, kind == JointKind::Revolute);
                let d = off(&d, kind == JointKind::Prismatic);
                let geometry = if convention == Convention::Dh {
                    JointGeometry::Dh { theta, d, a, alpha }
                } else {
                    JointGeometry::Mdh { alpha, a, theta, d }
                };
                variables.push(var);
                joints.push(Joint::new(kind, geometry));
            }
            Convention::Screw => {
                let var = j
                    .variable
                    .clone()
                    .ok_or_else(|| err("variable", "missing".into()))?;
                if var.is_empty() || !var.chars().all(|c| c.is_alphanumeric() || c == '_') {
                    return Err(err("variable", format!("`{var}` is not a symbol name")));
                }
                let axis = vec3(j.axis.as_ref(), "axis", eval).map_err(|m| err("axis", m))?;
                let axis = unit_numeric(&axis).map_err(|m| err("axis", m))?;
                let point = match (kind, j.point.as_ref()) {
                    (JointKind::Revolute, None) => {
                        return Err(err(
                            "point",
                            "missing (a revolute joint needs a point of its axis)".into(),
                        ))
                    }
                    (JointKind::Prismatic, Some(_)) => {
                        return Err(err("point", "a prismatic joint has no point".into()))
                    }
                    (_, p) => match p {
                        Some(_) => vec3(p, "point", eval).map_err(|m| err("point", m))?,
                        None => [Scalar::int(0), Scalar::int(0), Scalar::int(0)],
                    },
                };
                variables.push(var);
                joints.push(Joint::new(kind, JointGeometry::Screw { axis, point }));
            }
        }
    }
    let tool = match &f.tool {
        None => None,
        Some(t) => Some(vec3(Some(t), "tool", eval).map_err(|m| RobotError::File {
            file: file.into(),
            message: format!("field `tool`: {m}"),
        })?),
    };
    let mut values = Vec::new();
    for (name, v) in &f.values {
        let bad = |m: &str| RobotError::File {
            file: file.into(),
            message: format!("[values], `{name}`: {m}"),
        };
        if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
            return Err(bad("not a symbol name"));
        }
        if variables.contains(name) {
            return Err(bad("a joint variable has no nominal value"));
        }
        let x = match v {
            toml::Value::Integer(i) => *i as f64,
            toml::Value::Float(x) if x.is_finite() => *x,
            _ => return Err(bad("not a finite number")),
        };
        values.push((name.clone(), x));
    }
    Ok(Robot {
        name: f.name.unwrap_or_else(|| file.to_string()),
        convention,
        variables,
        chain: Chain::new(joints),
        tool,
        values,
    })
}

impl Robot {
    /// The forward kinematics at the symbolic joint variables.
    pub fn forward(&self) -> DualQuat<Scalar> {
        let q: Vec<Scalar> = self.variables.iter().map(|v| Scalar::sym(v)).collect();
        self.chain
            .forward(&q)
            .unwrap_or_else(|_| DualQuat::identity())
    }

    /// Each joint's factor at its symbolic variable, base first.
    pub fn joint_dqs(&self) -> Vec<DualQuat<Scalar>> {
        self.chain
            .joints
            .iter()
            .zip(&self.variables)
            .map(|(j, v)| j.dq(&Scalar::sym(v)))
            .collect()
    }

    /// The homogeneous matrix of the forward kinematics: the product of the joint factors'
    /// matrices (and the tool's). Equal to `self.forward().to_matrix()` (a test checks it on
    /// every example robot), and much cheaper: the factors' matrices are in full angles, while
    /// converting the product DQ multiplies long half-angle sums.
    pub fn forward_matrix(&self) -> Matrix4<Scalar> {
        self.matrix_product(None, |x| Some(x.clone()))
            .unwrap_or_else(Matrix4::identity)
    }

    /// [`Robot::forward_matrix`], or `None` as soon as an entry of a partial product has more
    /// than `max_terms` terms (or is an error value).
    pub fn forward_matrix_within(&self, max_terms: usize) -> Option<Matrix4<Scalar>> {
        self.matrix_product(Some(max_terms), |x| Some(x.clone()))
    }

    /// The product of the joint factors' matrices (and the tool's), each entry first passed
    /// through `entry` (`None` there gives `None`); `None` as soon as an entry of a partial
    /// product has more than `max_terms` terms or is an error value.
    fn matrix_product(
        &self,
        max_terms: Option<usize>,
        entry: impl Fn(&Scalar) -> Option<Scalar>,
    ) -> Option<Matrix4<Scalar>> {
        let mut acc: Option<Matrix4<Scalar>> = None;
        for f in self
            .joint_dqs()
            .iter()
            .chain(std::iter::once(&self.chain.tool))
        {
            let mut rows = f.to_matrix().rows;
            for x in rows.iter_mut().flatten() {
                *x = entry(x)?;
            }
            let m = Matrix4::from_rows(rows);
            let next = match acc {
                None => m,
                Some(a) => a.mul_ref(&m),
            };
            if let Some(limit) = max_terms {
                if next
                    .rows
                    .iter()
                    .flatten()
                    .any(|x| x.len() > limit || x.as_error().is_some())
                {
                    return None;
                }
            }
            acc = Some(next);
        }
        Some(acc.unwrap_or_else(Matrix4::identity))
    }

    /// The homogeneous matrix as polynomials in the cosines and sines of the joint variables
    /// and angle parameters (see [`Scalar::to_cos_sin_polynomial`]), or `None` when a joint
    /// factor's matrix holds a half or multiple angle, or an entry exceeds `max_terms`.
    /// For chains whose Fourier form explodes (a 6R with every DH parameter symbolic: 1,595
    /// monomials against about 300,000 Fourier terms); put it in closed form with
    /// [`crate::closed_form_cos_sin`].
    pub fn forward_matrix_cos_sin(&self, max_terms: usize) -> Option<Matrix4<Scalar>> {
        self.matrix_product(Some(max_terms), Scalar::to_cos_sin_polynomial)
    }

    /// The forward kinematics, or `None` as soon as a component of a partial product has more
    /// than `max_terms` terms: a chain whose expansion grows exponentially (every DH parameter
    /// symbolic, many joints) is detected after a few products instead of exhausting memory.
    pub fn forward_within(&self, max_terms: usize) -> Option<DualQuat<Scalar>> {
        let factors = self.joint_dqs();
        let product = |fs: &[DualQuat<Scalar>]| -> Option<DualQuat<Scalar>> {
            let mut acc = DualQuat::identity();
            for f in fs {
                acc = acc * f.clone();
                if acc
                    .components()
                    .iter()
                    .any(|c| c.len() > max_terms || c.as_error().is_some())
                {
                    return None;
                }
            }
            Some(acc)
        };
        // The two halves of a long chain on two threads, then their product (exact, so the
        // same value as the product from the left).
        let acc = if factors.len() >= 4 && crate::scalar::worker_threads() > 1 {
            let (a, b) = factors.split_at(factors.len() / 2);
            let (pa, pb) = crate::scalar::join(|| product(a), || product(b));
            product(&[pa?, pb?])?
        } else {
            product(&factors)?
        };
        Some(acc * self.chain.tool.clone())
    }

    /// The symbols other than the joint variables (and pi), sorted by name: those of the joint
    /// factors and the tool, so nothing is expanded to find them.
    pub fn parameters(&self) -> Vec<String> {
        let mut names: Vec<String> = Vec::new();
        for f in self
            .joint_dqs()
            .iter()
            .chain(std::iter::once(&self.chain.tool))
        {
            names.extend(
                f.components()
                    .iter()
                    .flat_map(|c| c.symbols())
                    .map(|s| s.name().to_string()),
            );
        }
        if let Some(t) = &self.tool {
            names.extend(
                t.iter()
                    .flat_map(|c| c.symbols())
                    .map(|s| s.name().to_string()),
            );
        }
        names.sort();
        names.dedup();
        names.retain(|n| n != "pi" && !self.variables.contains(n));
        names
    }
}

fn joint_variable(x: &Scalar) -> Result<String, String> {
    let syms: Vec<String> = x
        .symbols()
        .into_iter()
        .map(|s| s.name().to_string())
        .filter(|n| n != "pi")
        .collect();
    match syms.as_slice() {
        [one] => Ok(one.clone()),
        [] => Err("names no joint variable (it must contain exactly one symbol)".into()),
        _ => Err(format!(
            "names several symbols ({}); exactly one must be the joint variable",
            syms.join(", ")
        )),
    }
}

fn vec3(v: Option<&Vec<String>>, name: &str, eval: FieldEval) -> Result<[Scalar; 3], String> {
    let v = v.ok_or_else(|| "missing".to_string())?;
    if v.len() != 3 {
        return Err(format!("{name} needs 3 entries, found {}", v.len()));
    }
    Ok([eval(&v[0])?, eval(&v[1])?, eval(&v[2])?])
}

/// The axis scaled to unit length, exactly; the axis must be numeric and nonzero.
fn unit_numeric(a: &[Scalar; 3]) -> Result<[Scalar; 3], String> {
    if !a.iter().all(Scalar::is_constant) {
        return Err("the axis must be numeric".into());
    }
    let n2 = &a[0] * &a[0] + &a[1] * &a[1] + &a[2] * &a[2];
    if n2.is_zero_value() {
        return Err("the axis is zero".into());
    }
    let n = n2.sqrt().check().map_err(|e| e.to_string())?;
    let div = |x: &Scalar| x.try_div(&n).map_err(|e| e.to_string());
    Ok([div(&a[0])?, div(&a[1])?, div(&a[2])?])
}
