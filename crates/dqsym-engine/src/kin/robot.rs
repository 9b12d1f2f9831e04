//! Robot description files (TOML) in three conventions: classic DH, modified DH (Craig) and the
//! paper's screw form (sec 6), where each joint turns about or slides along an axis given in the
//! home pose.
//!
//! Every field is an expression of the dqsym language, or a TOML number (read from its decimal
//! text, never through binary floating point: `0.4318` is 2159/5000). This module does not
//! evaluate them itself: the caller passes the evaluator, so the kinematics layer stays free
//! of the language.
//!
//! Optional `[base]` and `[tool]` tables give constant frames before the first joint and after
//! the last, URDF style: `xyz = [x, y, z]` and `rpy = [roll, pitch, yaw]` (fixed axes: roll
//! about x, then pitch about y, then yaw about z, so `R = Rz(yaw) Ry(pitch) Rx(roll)`), the
//! frame being `Trans(xyz) R`. `tool = ["x", "y", "z"]` (or `"x, y, z"`) is a point instead.

pub use super::field_error::{ExprError, FieldError};
use super::{Chain, Joint, JointGeometry, JointKind};
use crate::emit::names::terminal_text;
use crate::scalar::Small;
use crate::{DualQuat, Matrix4, Quat, Scalar, ScalarError, Sym};
use num_traits::CheckedMul;
use serde::Deserialize;
use std::sync::atomic::{AtomicBool, Ordering as AtomicOrdering};
use std::sync::{Arc, OnceLock};
use thiserror::Error;

/// The joint convention of a robot file: its `convention` field, `"dh"`, `"mdh"` or `"screw"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Convention {
    /// `Rz(theta) Tz(d) Tx(a) Rx(alpha)`.
    Dh,
    /// `Rx(alpha) Tx(a) Rz(theta) Tz(d)` (Craig).
    Mdh,
    /// A motion about (or along) a home-pose axis in base coordinates.
    Screw,
    /// A URDF joint as written ([`super::JointGeometry::Local`]): its origin frames, then a
    /// motion about (or along) its axis in its own frame. Only the URDF reader makes it (a
    /// file whose origins hold angles kept as parameters); robot files cannot say it.
    #[serde(skip_deserializing)]
    Local,
}

/// A robot read from a file: its chain with symbolic joint variables.
///
/// The pose is `chain.forward(&joint_values)`: `base · J₁(v₁) … Jₙ(vₙ) · tool`. Usually joint
/// i's value `vᵢ` is the symbol of `variables[i]`; a URDF `mimic` joint's value is instead
/// `multiplier · v + offset` for the variable `v` of the joint it follows, so `variables` (the
/// independent variables, one Jacobian column each, in order of first use) can be shorter than
/// the chain.
#[derive(Clone, Debug)]
pub struct Robot {
    /// The `name` field, or the file name.
    pub name: String,
    /// The convention the joints were given in (URDF files become screw or local form).
    pub convention: Convention,
    /// The independent joint variables, in joint order.
    pub variables: Vec<String>,
    /// Each joint's value in the variables, one per joint of `chain`.
    pub joint_values: Vec<Scalar>,
    /// The chain; its base and tool motions are the products of `base_frames` and
    /// `tool_frames`.
    pub chain: Chain<Scalar>,
    /// The constant frames before the first joint, in order (`[base]`).
    pub base_frames: Vec<Frame>,
    /// The constant frames after the last joint, in order (`[tool]`; for a URDF file in screw
    /// form, the joints' origins, whose product is the tip's home pose; in local form, the
    /// origins after the last moving joint).
    pub tool_frames: Vec<Frame>,
    /// The `tool` point, if the file gives one (in the home pose for screw robots, in the last
    /// frame for DH).
    pub tool: Option<[Scalar; 3]>,
    /// The `[values]` table: nominal numbers for symbolic parameters (`a2 = 0.4318`), used
    /// where a number is needed (the walkthrough's drawing); results stay symbolic.
    pub values: Vec<(String, f64)>,
    /// What the reader read other than as written, one line each (`joint 1, field `alpha`:
    /// 1.5708 read as pi/2`), for the caller to show.
    pub notes: Vec<String>,
    /// The decimals the file wrote (`0.425`; their magnitudes, sorted), none when it wrote
    /// none: reports then print exact decimals as decimals (`0.425 c2`, not `1/10000 (4250 c2
    /// ...)`), showing these as typed where they can.
    pub decimals: Vec<num_rational::BigRational>,
}

/// How a robot file is read.
#[derive(Clone, Debug, Default)]
pub struct RobotOptions {
    /// Take every angle as written (in radians): no decimal read as a multiple of pi/12 and
    /// no refusal of a bare angle past 2 pi (see [`super::angles`]).
    pub exact_angles: bool,
}

/// A constant frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)`, with `rpy = [roll, pitch, yaw]`
/// (the URDF `origin`: fixed axes, roll about x first).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// The translation.
    pub xyz: [Scalar; 3],
    /// Roll, pitch and yaw, angles (symbols or rational multiples of pi).
    pub rpy: [Scalar; 3],
}

impl Frame {
    /// The frame as a unit DQ, or why an angle has no exact cosine.
    pub fn dq(&self) -> Result<DualQuat<Scalar>, ScalarError> {
        frame_dq(&self.xyz, &self.rpy)
    }

    /// The product of `frames` in order (the identity for none).
    pub fn product(frames: &[Frame]) -> Result<DualQuat<Scalar>, ScalarError> {
        let mut acc = DualQuat::identity();
        for f in frames {
            acc = acc * f.dq()?;
        }
        Ok(acc)
    }
}

/// What is wrong with a robot file; every message names the file, and the joint and field
/// where there is one.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum RobotError {
    /// The file is not valid TOML or misses a top-level field.
    #[error("{}: {}", terminal_text(file), terminal_text(message))]
    File {
        /// The file's name.
        file: String,
        /// What is wrong.
        message: String,
    },
    /// A joint field is missing or wrong.
    #[error(
        "{}: joint {joint}, field `{field}`: {}",
        terminal_text(file),
        terminal_text(message)
    )]
    Field {
        /// The file's name.
        file: String,
        /// The joint, counted from 1.
        joint: usize,
        /// The field's name.
        field: String,
        /// What is wrong.
        message: String,
    },
}

/// A keyword field of a robot file: the variant of `T` it names, or the text when it names
/// none (reported with the file, joint and field, the expected names listed).
enum Keyword<T> {
    Known(T),
    Unknown(String),
}

impl<'de, T: serde::de::DeserializeOwned> Deserialize<'de> for Keyword<T> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::IntoDeserializer;
        let text = String::deserialize(d)?;
        let known: Result<T, serde::de::value::Error> =
            T::deserialize(text.as_str().into_deserializer());
        Ok(match known {
            Ok(t) => Keyword::Known(t),
            Err(_) => Keyword::Unknown(text),
        })
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotFile {
    name: Option<String>,
    convention: Keyword<Convention>,
    base: Option<toml::Value>,
    tool: Option<toml::Value>,
    #[serde(default)]
    values: std::collections::BTreeMap<String, toml::Value>,
    #[serde(default)]
    joint: Vec<JointFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JointFile {
    #[serde(rename = "type")]
    kind: Keyword<JointKind>,
    theta: Option<String>,
    d: Option<String>,
    a: Option<String>,
    alpha: Option<String>,
    variable: Option<String>,
    axis: Option<Vec<String>>,
    point: Option<Vec<String>>,
}

/// Evaluates a field's text to an exact scalar, or says why it cannot.
pub type FieldEval<'a> = &'a dyn Fn(&str) -> Result<Scalar, ExprError>;

/// The values of the field texts evaluated so far: a table's equal texts (the zeros and
/// right angles of a DH table) are evaluated once, each evaluation being a parse of its own
/// (the PUMA 560: 28 fields, 14 distinct texts, ~20,000 instructions a parse, all before
/// the product begins). A text whose evaluation fails is evaluated again, for its message.
#[derive(Default)]
struct Memo(std::cell::RefCell<Vec<(String, Scalar)>>);

impl Memo {
    /// `eval(text)`, or the value it gave before.
    fn eval(&self, text: &str, eval: FieldEval) -> Result<Scalar, ExprError> {
        if let Some((_, x)) = self.0.borrow().iter().find(|(t, _)| t == text) {
            return Ok(x.clone());
        }
        let x = eval(text)?;
        self.0.borrow_mut().push((text.to_owned(), x.clone()));
        Ok(x)
    }
}

/// Reads a robot file. `file` names it in messages; `eval` evaluates one field expression.
/// Angles are read by the rule of [`super::angles`] (notes in [`Robot::notes`]).
pub fn parse_robot(text: &str, file: &str, eval: FieldEval) -> Result<Robot, RobotError> {
    parse_robot_with(text, file, eval, &RobotOptions::default())
}

/// [`parse_robot`] with options.
pub fn parse_robot_with(
    text: &str,
    file: &str,
    eval: FieldEval,
    opts: &RobotOptions,
) -> Result<Robot, RobotError> {
    let file_err = |message: String| RobotError::File {
        file: file.to_string(),
        message,
    };
    let (text, decimals) = numbers_as_text(text).map_err(|e| file_err(e.to_string()))?;
    let f = toml_file(&text, file)?;
    let convention = match &f.convention {
        Keyword::Known(c) => *c,
        Keyword::Unknown(other) => {
            return Err(file_err(format!(
                "unknown convention `{other}` (expected \"dh\", \"mdh\" or \"screw\")"
            )))
        }
    };
    if f.joint.is_empty() {
        return Err(file_err("no [[joint]] tables".into()));
    }
    let memo = Memo::default();
    let remembered = |text: &str| memo.eval(text, eval);
    let eval: FieldEval = &remembered;
    let mut reader = Reader {
        file,
        eval,
        opts,
        params: &f.values,
        notes: Vec::new(),
        joints: Vec::new(),
        variables: Vec::new(),
        values: Vec::new(),
    };
    for (i, j) in f.joint.iter().enumerate() {
        reader.joint(i + 1, j, convention)?;
    }
    let nominal = nominal_values(&f.values, &reader.variables, file, eval)?;
    let ends = reader.end_frames(&f)?;
    let product = |fs: &[Frame], name: &str| {
        Frame::product(fs).map_err(|e| file_err(format!("field `{name}.rpy`: {e}")))
    };
    let chain = Chain::new(reader.joints)
        .with_base(product(&ends.base_frames, "base")?)
        .with_tool(product(&ends.tool_frames, "tool")?);
    Ok(Robot {
        name: f.name.unwrap_or_else(|| file.to_string()),
        convention,
        joint_values: reader.values,
        variables: reader.variables,
        chain,
        base_frames: ends.base_frames,
        tool_frames: ends.tool_frames,
        tool: ends.tool,
        values: nominal,
        notes: reader.notes,
        decimals,
    })
}

/// The TOML text read into a [`RobotFile`]; a syntax error names its line and column.
fn toml_file(text: &str, file: &str) -> Result<RobotFile, RobotError> {
    toml::from_str(text).map_err(|e| {
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
    })
}

/// The nominal numbers of the `[values]` table; each name must be a symbol that is not a
/// joint variable.
fn nominal_values(
    params: &std::collections::BTreeMap<String, toml::Value>,
    variables: &[String],
    file: &str,
    eval: FieldEval,
) -> Result<Vec<(String, f64)>, RobotError> {
    let mut nominal = Vec::new();
    for (name, v) in params {
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
            // A TOML number may arrive as its decimal text (read exactly elsewhere).
            toml::Value::String(t) => match eval(t).ok().and_then(|x| x.eval(&|_| None).ok()) {
                Some(x) if x.is_finite() => x,
                _ => return Err(bad("not a finite number")),
            },
            _ => return Err(bad("not a finite number")),
        };
        nominal.push((name.clone(), x));
    }
    Ok(nominal)
}

/// The constant frames and the tool point of a robot file.
struct EndFrames {
    tool: Option<[Scalar; 3]>,
    base_frames: Vec<Frame>,
    tool_frames: Vec<Frame>,
}

/// The state of reading a robot file's joints: what it reads with, and what it has read.
struct Reader<'a> {
    file: &'a str,
    eval: FieldEval<'a>,
    opts: &'a RobotOptions,
    /// The `[values]` table: its names are parameters, never joint variables.
    params: &'a std::collections::BTreeMap<String, toml::Value>,
    notes: Vec<String>,
    joints: Vec<Joint<Scalar>>,
    variables: Vec<String>,
    values: Vec<Scalar>,
}

impl Reader<'_> {
    /// The error of joint `n`'s `field`.
    fn err(&self, n: usize, field: &str, e: impl Into<FieldError>) -> RobotError {
        RobotError::Field {
            file: self.file.into(),
            joint: n,
            field: field.into(),
            message: e.into().to_string(),
        }
    }

    /// A required field's value.
    fn field(&self, n: usize, name: &str, v: &Option<String>) -> Result<Scalar, RobotError> {
        let text = v
            .as_ref()
            .ok_or_else(|| self.err(n, name, FieldError::Missing))?;
        (self.eval)(text).map_err(|e| self.err(n, name, e))
    }

    /// An angle by [`angle_field`], its note (if any) recorded under `at`.
    fn angle(&mut self, x: Scalar, at: &str) -> Result<Scalar, FieldError> {
        let (x, note) = angle_field(x, self.opts)?;
        if let Some(note) = note {
            self.notes.push(format!("{at}: {note}"));
        }
        Ok(x)
    }

    /// Reads joint `n` and adds it to the chain.
    fn joint(&mut self, n: usize, j: &JointFile, convention: Convention) -> Result<(), RobotError> {
        let kind = match &j.kind {
            Keyword::Known(k) => *k,
            Keyword::Unknown(other) => {
                return Err(self.err(n, "type", FieldError::UnknownJointType(other.clone())))
            }
        };
        match convention {
            Convention::Dh | Convention::Mdh => self.dh_joint(n, j, kind, convention),
            // `Local` is never deserialized (only the URDF reader makes it).
            Convention::Screw | Convention::Local => self.screw_joint(n, j, kind),
        }
    }

    /// A DH or modified DH joint: four fields, the variable the one symbol of `theta`
    /// (revolute) or `d` (prismatic).
    fn dh_joint(
        &mut self,
        n: usize,
        j: &JointFile,
        kind: JointKind,
        convention: Convention,
    ) -> Result<(), RobotError> {
        let (theta, d, a, alpha) = (
            self.field(n, "theta", &j.theta)?,
            self.field(n, "d", &j.d)?,
            self.field(n, "a", &j.a)?,
            self.field(n, "alpha", &j.alpha)?,
        );
        let theta = self
            .angle(theta, &format!("joint {n}, field `theta`"))
            .map_err(|e| self.err(n, "theta", e))?;
        let alpha = self
            .angle(alpha, &format!("joint {n}, field `alpha`"))
            .map_err(|e| self.err(n, "alpha", e))?;
        // The variable is the one symbol of theta (revolute) or d (prismatic); the rest
        // of that field is a constant offset.
        let (vname, vfield) = match kind {
            JointKind::Revolute => ("theta", &theta),
            JointKind::Prismatic => ("d", &d),
        };
        // theta and alpha are angles (halved in the joint's DQ): say so here, naming
        // the field as written, rather than deep in the derivation.
        for (name, value, text) in [("theta", &theta, &j.theta), ("alpha", &alpha, &j.alpha)] {
            if value.cos().check().is_err() {
                let text = text.as_deref().unwrap_or_default().to_string();
                return Err(self.err(n, name, FieldError::NotAngle(text)));
            }
        }
        let var = joint_variable(vfield, self.params).map_err(|e| self.err(n, vname, e))?;
        check_distinct(&self.variables, &var).map_err(|e| self.err(n, vname, e))?;
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
        self.values.push(Scalar::sym(&var));
        self.variables.push(var);
        self.joints.push(Joint::new(kind, geometry));
        Ok(())
    }

    /// A screw joint: its variable, and its axis and point in the home pose.
    fn screw_joint(&mut self, n: usize, j: &JointFile, kind: JointKind) -> Result<(), RobotError> {
        let text = j
            .variable
            .clone()
            .ok_or_else(|| self.err(n, "variable", FieldError::Missing))?;
        let (var, value) = self
            .screw_variable(n, &text, kind)
            .map_err(|e| self.err(n, "variable", e))?;
        let eval = self.eval;
        let axis = vec3(j.axis.as_ref(), "axis", eval)
            .and_then(|a| unit_numeric(&a))
            .map_err(|e| self.err(n, "axis", e))?;
        let point = match (kind, j.point.as_ref()) {
            (JointKind::Revolute, None) => return Err(self.err(n, "point", FieldError::NoPoint)),
            (JointKind::Prismatic, Some(_)) => {
                return Err(self.err(n, "point", FieldError::PrismaticPoint))
            }
            (_, p) => match p {
                Some(_) => vec3(p, "point", eval).map_err(|e| self.err(n, "point", e))?,
                None => [Scalar::int(0), Scalar::int(0), Scalar::int(0)],
            },
        };
        self.values.push(value);
        if !self.variables.contains(&var) {
            self.variables.push(var);
        }
        self.joints
            .push(Joint::new(kind, JointGeometry::Screw { axis, point }));
        Ok(())
    }

    /// A screw joint's variable and value: a symbol, or an expression in one symbol for a
    /// coupled joint (`2*q1 + pi/4`, as a converted URDF mimic joint reads).
    fn screw_variable(
        &mut self,
        n: usize,
        text: &str,
        kind: JointKind,
    ) -> Result<(String, Scalar), FieldError> {
        let plain_name = !text.is_empty() && text.chars().all(|c| c.is_alphanumeric() || c == '_');
        if plain_name {
            if !text.starts_with(char::is_alphabetic) {
                return Err(FieldError::NotSymbolName(text.to_string()));
            }
            // The same name twice is a mistake; a coupling is written as an
            // expression in the other joint's variable.
            check_distinct(&self.variables, text)?;
            builtin_name(text, self.eval)?;
            return Ok((text.to_string(), Scalar::sym(text)));
        }
        let value = (self.eval)(text)?;
        let value = if kind == JointKind::Revolute {
            self.angle(value, &format!("joint {n}, field `variable`"))?
        } else {
            value
        };
        let var = joint_variable(&value, self.params)?;
        Ok((var, value))
    }

    /// The `[base]` and `[tool]` frames (their angles read by [`angle_field`]) and the
    /// `tool` point.
    fn end_frames(&mut self, f: &RobotFile) -> Result<EndFrames, RobotError> {
        let file_err = |field: &str, e: FieldError| RobotError::File {
            file: self.file.into(),
            message: format!("field `{field}`: {e}"),
        };
        let eval = self.eval;
        let (tool, tool_frames) = match &f.tool {
            None => (None, Vec::new()),
            Some(v @ (toml::Value::Table(_) | toml::Value::Array(_))) if is_frames(v) => (
                None,
                frames(v, eval).map_err(|(k, e)| file_err(&format!("tool{k}"), e))?,
            ),
            Some(v) => (
                Some(point(v, eval).map_err(|e| file_err("tool", e))?),
                Vec::new(),
            ),
        };
        let base_frames = match &f.base {
            None => Vec::new(),
            Some(v) if is_frames(v) => {
                frames(v, eval).map_err(|(k, e)| file_err(&format!("base{k}"), e))?
            }
            Some(_) => {
                return Err(RobotError::File {
                    file: self.file.into(),
                    message: "field `base`: expected a table `[base]` with `xyz` and `rpy`".into(),
                })
            }
        };
        let mut ends = EndFrames {
            tool,
            base_frames,
            tool_frames,
        };
        for (name, v) in [("base", &f.base), ("tool", &f.tool)] {
            let single = matches!(v, Some(toml::Value::Table(_)));
            let fs = if name == "base" {
                &mut ends.base_frames
            } else {
                &mut ends.tool_frames
            };
            for (k, fr) in fs.iter_mut().enumerate() {
                for (i, x) in fr.rpy.iter_mut().enumerate() {
                    let at = if single {
                        format!("{name}.rpy[{i}]")
                    } else {
                        format!("{name}[{}].rpy[{i}]", k + 1)
                    };
                    let (y, note) =
                        angle_field(x.clone(), self.opts).map_err(|e| file_err(&at, e))?;
                    if let Some(note) = note {
                        self.notes.push(format!("field `{at}`: {note}"));
                    }
                    *x = y;
                }
            }
        }
        Ok(ends)
    }
}

/// An angle field by the rule of [`super::angles`]: its rational term (`1.5708` of `q2 +
/// 1.5708`) read as a multiple of pi/12 when within the tolerance of its decimals, refused
/// when past 2 pi (degrees, most likely), else kept; with a note when it is not read as
/// written or may not mean what it says. `opts.exact_angles` keeps every angle as written.
fn angle_field(x: Scalar, opts: &RobotOptions) -> Result<(Scalar, Option<String>), FieldError> {
    use super::angles::{self, AngleReading};
    if opts.exact_angles {
        return Ok((x, None));
    }
    let c = x.rational_term();
    match angles::read_angle(&c) {
        AngleReading::Zero => Ok((x, None)),
        AngleReading::Multiple { twelfths } => Ok((
            x - Scalar::rational(c.clone()) + angles::pi_twelfths(twelfths),
            Some(angles::snapped_note(&c, twelfths)),
        )),
        AngleReading::Literal { near } => {
            let t = angles::number_text(&c);
            let past = num_traits::ToPrimitive::to_f64(&c)
                .is_none_or(|v| v.abs() > 2.0 * std::f64::consts::PI);
            if past {
                return Err(FieldError::PastTwoPi { number: t });
            }
            let why = match near {
                Some(k) => angles::near_note(&c, k),
                None if c.is_integer() => {
                    format!("not near a multiple of pi/12 (for degrees write \"{t}deg\")")
                }
                None => "not near a multiple of pi/12".to_owned(),
            };
            Ok((x, Some(format!("{t} read as {t} rad: {why}"))))
        }
    }
}

/// Whether a `base` or `tool` value is a frame table `[tool]` or an array of them `[[tool]]`.
fn is_frames(v: &toml::Value) -> bool {
    match v {
        toml::Value::Table(_) => true,
        toml::Value::Array(a) => !a.is_empty() && a.iter().all(toml::Value::is_table),
        _ => false,
    }
}

/// One frame table, or an array of frame tables applied in order; errors name the key
/// (`.rpy`, `[2].xyz`).
fn frames(v: &toml::Value, eval: FieldEval) -> Result<Vec<Frame>, (String, FieldError)> {
    match v {
        toml::Value::Table(t) => Ok(vec![frame(t, eval).map_err(|(k, m)| (format!(".{k}"), m))?]),
        toml::Value::Array(a) => a
            .iter()
            .enumerate()
            .map(|(i, t)| match t {
                toml::Value::Table(t) => {
                    frame(t, eval).map_err(|(k, m)| (format!("[{}].{k}", i + 1), m))
                }
                _ => Err((format!("[{}]", i + 1), FieldError::NotTable)),
            })
            .collect(),
        _ => Err((String::new(), FieldError::NotFrames)),
    }
}

/// The text with every TOML number turned into a string of its decimal text (`0.4318` into
/// `"0.4318"`, `0x10` into `"16"`), so that every field reads as an expression and no value
/// passes through binary floating point. Text that is not valid TOML is returned unchanged,
/// for the TOML reader to report.
/// Also says whether a field (other than `name` and `[values]`) holds a decimal (`0.425`,
/// `"q1 + 0.5"`).
fn numbers_as_text(text: &str) -> Result<(String, Vec<num_rational::BigRational>), FieldError> {
    let Ok(mut doc) = text.parse::<toml_edit::DocumentMut>() else {
        return Ok((text.to_string(), Vec::new()));
    };
    let mut changed = Visit::default();
    visit_table(doc.as_table_mut(), "", &mut changed)?;
    let mut decimals = changed.decimals;
    decimals.sort();
    Ok(if changed.changed {
        (doc.to_string(), decimals)
    } else {
        (text.to_string(), decimals)
    })
}

/// What [`numbers_as_text`] saw.
#[derive(Default)]
struct Visit {
    /// A number was turned into text.
    changed: bool,
    /// The decimals of the fields (magnitudes).
    decimals: Vec<num_rational::BigRational>,
}

impl Visit {
    /// Records the decimal literals of a field's text (`0.425`, `q1 + 0.5`).
    fn note_decimals(&mut self, text: &str) {
        if !has_decimal(text) {
            return;
        }
        let b = text.as_bytes();
        let mut i = 0;
        while i < b.len() {
            let starts = (b[i].is_ascii_digit() || b[i] == b'.')
                && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'));
            if !starts {
                i += 1;
                continue;
            }
            let mut j = i;
            while j < b.len() && (b[j].is_ascii_digit() || b[j] == b'.') {
                j += 1;
            }
            if let Some(x) = crate::scalar::parse_decimal(&text[i..j], 1_000) {
                if text[i..j].contains('.') {
                    let x = num_traits::Signed::abs(&x);
                    if !self.decimals.contains(&x) {
                        self.decimals.push(x);
                    }
                }
            }
            i = j;
        }
    }
}

/// Whether `text` holds a decimal literal: a point followed by a digit, not inside a name.
fn has_decimal(text: &str) -> bool {
    let b = text.as_bytes();
    (0..b.len()).any(|i| {
        b[i] == b'.'
            && b.get(i + 1).is_some_and(u8::is_ascii_digit)
            && (i == 0 || !(b[i - 1].is_ascii_alphabetic() || b[i - 1] == b'_'))
    })
}

fn visit_table(
    t: &mut dyn toml_edit::TableLike,
    path: &str,
    ch: &mut Visit,
) -> Result<(), FieldError> {
    for (k, item) in t.iter_mut() {
        let path = if path.is_empty() {
            k.get().to_string()
        } else {
            format!("{path}.{}", k.get())
        };
        visit_item(item, &path, ch)?;
    }
    Ok(())
}

fn visit_item(item: &mut toml_edit::Item, path: &str, ch: &mut Visit) -> Result<(), FieldError> {
    match item {
        toml_edit::Item::Value(v) => visit_value(v, path, ch),
        toml_edit::Item::Table(t) => visit_table(t, path, ch),
        toml_edit::Item::ArrayOfTables(a) => {
            for (i, t) in a.iter_mut().enumerate() {
                visit_table(t, &format!("{path}[{}]", i + 1), ch)?;
            }
            Ok(())
        }
        toml_edit::Item::None => Ok(()),
    }
}

fn visit_value(v: &mut toml_edit::Value, path: &str, ch: &mut Visit) -> Result<(), FieldError> {
    let text = match v {
        toml_edit::Value::Integer(i) => i.value().to_string(),
        toml_edit::Value::Float(f) => {
            let raw = f
                .as_repr()
                .and_then(|r| r.as_raw().as_str())
                .map(|r| r.replace('_', ""))
                .unwrap_or_else(|| f.value().to_string());
            if !f.value().is_finite() {
                return Err(FieldError::NotFinite {
                    path: path.to_string(),
                    raw,
                });
            }
            raw
        }
        toml_edit::Value::Array(a) => {
            for (i, x) in a.iter_mut().enumerate() {
                visit_value(x, &format!("{path}[{i}]"), ch)?;
            }
            return Ok(());
        }
        toml_edit::Value::InlineTable(t) => return visit_table(t, path, ch),
        toml_edit::Value::String(t) => {
            if is_field(path) {
                ch.note_decimals(t.value());
            }
            return Ok(());
        }
        _ => return Ok(()),
    };
    if is_field(path) {
        ch.note_decimals(&text);
    }
    let decor = v.decor().clone();
    *v = toml_edit::Value::from(text);
    *v.decor_mut() = decor;
    ch.changed = true;
    Ok(())
}

/// Whether the value at `path` is a field of the kinematics (not the name, nor a nominal
/// value of `[values]`, which only the drawing reads).
fn is_field(path: &str) -> bool {
    path != "name" && !path.starts_with("values.")
}

/// A point: an array of three fields, or one text `"x, y, z"`.
fn point(v: &toml::Value, eval: FieldEval) -> Result<[Scalar; 3], FieldError> {
    match v {
        toml::Value::String(s) => {
            let parts = split_top_level(s);
            if parts.len() != 3 {
                return Err(ExprError::PointArity { found: parts.len() }.into());
            }
            Ok([eval(parts[0])?, eval(parts[1])?, eval(parts[2])?])
        }
        toml::Value::Array(_) => vec3(Some(&strings(v)?), "a point", eval),
        _ => Err(FieldError::NotPoint),
    }
}

/// The entries of an array as field texts (numbers were already turned into text).
fn strings(v: &toml::Value) -> Result<Vec<String>, FieldError> {
    match v {
        toml::Value::Array(a) => a
            .iter()
            .map(|x| match x {
                toml::Value::String(s) => Ok(s.clone()),
                other => Err(FieldError::NotText {
                    found: other.type_str(),
                }),
            })
            .collect(),
        other => Err(FieldError::NotArray {
            found: other.type_str(),
        }),
    }
}

/// A constant frame from a table with `xyz` and `rpy` (each optional, zero by default); errors
/// name the key.
fn frame(
    t: &toml::map::Map<String, toml::Value>,
    eval: FieldEval,
) -> Result<Frame, (String, FieldError)> {
    if let Some(k) = t.keys().find(|k| *k != "xyz" && *k != "rpy") {
        return Err((k.clone(), FieldError::UnknownFrameKey));
    }
    let get = |k: &str| -> Result<[Scalar; 3], (String, FieldError)> {
        match t.get(k) {
            None => Ok([Scalar::int(0), Scalar::int(0), Scalar::int(0)]),
            Some(v) => strings(v)
                .and_then(|s| vec3(Some(&s), k, eval))
                .map_err(|m| (k.to_string(), m)),
        }
    };
    let f = Frame {
        xyz: get("xyz")?,
        rpy: get("rpy")?,
    };
    f.dq().map_err(|e| ("rpy".to_string(), e.into()))?;
    Ok(f)
}

/// `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` as a unit DQ (the URDF `origin` convention), or why
/// an angle has no exact cosine (`rpy` entries must be angles: symbols, multiples of pi).
pub(crate) fn frame_dq(
    xyz: &[Scalar; 3],
    rpy: &[Scalar; 3],
) -> Result<DualQuat<Scalar>, ScalarError> {
    let (o, l) = (Scalar::int(0), Scalar::int(1));
    let rx = Quat::rotation(&[l.clone(), o.clone(), o.clone()], &rpy[0]);
    let ry = Quat::rotation(&[o.clone(), l.clone(), o.clone()], &rpy[1]);
    let rz = Quat::rotation(&[o.clone(), o.clone(), l], &rpy[2]);
    let q = DualQuat::from_rotation_and_translation(rz * ry * rx, xyz);
    for c in q.components() {
        c.check()?;
    }
    Ok(q)
}

/// Splits at commas outside parentheses and brackets (a robot file's and the language's
/// comma-separated fields).
pub fn split_top_level(text: &str) -> Vec<&str> {
    let mut depth = 0i32;
    let mut start = 0;
    let mut out = Vec::new();
    for (i, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' if depth == 0 => {
                out.push(text[start..i].trim());
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(text[start..].trim());
    out
}

impl Robot {
    /// The same robot in screw form, as a [`Convention::Local`] robot is not: each joint's
    /// axis carried to the base by the frames before it (the home pose), every origin frame a
    /// tool frame, their product the tool motion. Other robots are returned as they are.
    ///
    /// # Errors
    /// A size limit reached by the product of the frames (frames at symbolic angles multiply
    /// the terms of every later axis).
    pub fn screw_form(&self) -> Result<Robot, ScalarError> {
        if self.convention != Convention::Local {
            return Ok(self.clone());
        }
        let checked = |q: &DualQuat<Scalar>| -> Result<(), ScalarError> {
            for c in q.components() {
                c.check()?;
            }
            Ok(())
        };
        let mut home = DualQuat::identity();
        let (mut joints, mut frames) = (Vec::new(), Vec::new());
        for j in &self.chain.joints {
            let JointGeometry::Local { frames: fs, axis } = &j.geometry else {
                return Ok(self.clone());
            };
            for f in fs {
                home = home * super::local_frame_dq(f);
                checked(&home)?;
                frames.push(Frame {
                    xyz: f.0.clone(),
                    rpy: f.1.clone(),
                });
            }
            let dir = DualQuat::from_real(home.real.clone()).transform_point(axis);
            for c in &dir {
                c.clone().check()?;
            }
            joints.push(match j.kind {
                JointKind::Revolute => Joint::revolute_screw(dir, home.translation_part()),
                JointKind::Prismatic => Joint::prismatic_screw(dir),
            });
        }
        let tool = home * &self.chain.tool;
        checked(&tool)?;
        frames.extend(self.tool_frames.iter().cloned());
        Ok(Robot {
            convention: Convention::Screw,
            chain: Chain::new(joints)
                .with_base(self.chain.base.clone())
                .with_tool(tool),
            tool_frames: frames,
            ..self.clone()
        })
    }

    /// The forward kinematics at the symbolic joint variables (base and tool frames included).
    pub fn forward(&self) -> DualQuat<Scalar> {
        self.chain
            .forward(&self.joint_values)
            .unwrap_or_else(|_| DualQuat::identity())
    }

    /// Each joint's factor at its symbolic value, first joint first (without the base and
    /// tool frames).
    pub fn joint_dqs(&self) -> Vec<DualQuat<Scalar>> {
        self.chain
            .joints
            .iter()
            .zip(&self.joint_values)
            .map(|(j, v)| j.dq(v))
            .collect()
    }

    /// [`Robot::joint_dqs`], kept with the work they were charged (see [`MadeJoints`]).
    pub(crate) fn made_joints(&self) -> MadeJoints {
        let before = crate::scalar::work_used();
        let dqs = self.joint_dqs();
        MadeJoints {
            units: crate::scalar::work_used().saturating_sub(before),
            matrices: sound(&dqs).then(|| JointMatrices::new(dqs.len())),
            dqs: Some(dqs),
        }
    }

    /// The factors of the pose, in order: the joint factors, the first one after the base
    /// frame and the last one before the tool frame (`base J₁`, `J₂`, ..., `Jₙ tool`), so
    /// that their product is the pose and each joint's variables sit in its own factor. A
    /// chain without joints gives the single factor `base tool`.
    pub fn pose_factors(&self) -> Vec<DualQuat<Scalar>> {
        self.pose_factors_of(self.joint_dqs())
    }

    /// [`Robot::pose_factors`] from the joint factors `joints` ([`Robot::joint_dqs`], made
    /// once by a caller that needs them more than once).
    pub(crate) fn pose_factors_of(&self, joints: Vec<DualQuat<Scalar>>) -> Vec<DualQuat<Scalar>> {
        let mut f = joints;
        let (base, tool) = (&self.chain.base, &self.chain.tool);
        let id = DualQuat::identity();
        if f.is_empty() {
            return vec![base * tool];
        }
        if *base != id {
            f[0] = base * &f[0];
        }
        if *tool != id {
            let last = f.len() - 1;
            f[last] = &f[last] * tool;
        }
        f
    }

    /// The variables joint `i`'s value depends on (its own, or the followed joint's).
    pub fn joint_variables(&self, i: usize) -> Vec<String> {
        let mut v: Vec<String> = self.joint_values[i]
            .symbols()
            .into_iter()
            .map(|s| s.name().to_string())
            .filter(|n| self.variables.contains(n))
            .collect();
        v.dedup();
        v
    }

    /// The homogeneous matrix of the forward kinematics: the product of the joint factors'
    /// matrices (and the tool's). Equal to `self.forward().to_matrix()` (a test checks it on
    /// every example robot), and much cheaper: the factors' matrices are in full angles, while
    /// converting the product DQ multiplies long half-angle sums.
    pub fn forward_matrix(&self) -> Matrix4<Scalar> {
        self.matrix_product(None, Some)
            .unwrap_or_else(Matrix4::identity)
    }

    /// [`Robot::forward_matrix`], or `None` as soon as an entry of a partial product has more
    /// than `max_terms` terms (or is an error value).
    pub fn forward_matrix_within(&self, max_terms: usize) -> Option<Matrix4<Scalar>> {
        self.matrix_product(Some(max_terms), Some)
    }

    /// [`Robot::forward_matrix_within`] that gives up (`None`) once `stop` is set, and sets
    /// it when it gives up; it also gives up early when the growth of the partial products
    /// says the last one will exceed the limit (see [`Growth`]). For running it next to
    /// [`Robot::forward_within_until`]: whichever expansion is abandoned first stops the other.
    /// `factors` are [`Robot::factor_matrices`] of the joint factors.
    /// `seen` is told of each entry of the last product as it is made (row, column, entry),
    /// largest first, and abandons the expansion by answering `false`: a caller that would
    /// throw the matrix away for what its first entries show (`fk`: text past its limit)
    /// never makes the others.
    pub(crate) fn forward_matrix_until(
        &self,
        factors: FactorMatrices,
        max_terms: usize,
        stop: &AtomicBool,
        seen: EntrySeen,
    ) -> Option<Matrix4<Scalar>> {
        let r = matrix_product_until(factors, Some(max_terms), Some, Some(stop), Some(seen), None);
        if r.is_none() {
            stop.store(true, AtomicOrdering::Relaxed);
        }
        r
    }

    /// The product of the joint factors' matrices (and the tool's), each entry first passed
    /// through `entry` (`None` there gives `None`); `None` as soon as an entry of a partial
    /// product has more than `max_terms` terms or is an error value.
    fn matrix_product(
        &self,
        max_terms: Option<usize>,
        entry: impl Fn(Scalar) -> Option<Scalar>,
    ) -> Option<Matrix4<Scalar>> {
        self.matrix_product_of(&self.joint_dqs(), None, max_terms, entry)
    }

    /// [`Robot::matrix_product`] of the joint factors `joints` ([`Robot::joint_dqs`]), their
    /// matrices those `kept` where it has them ([`JointMatrices`]).
    fn matrix_product_of(
        &self,
        joints: &[DualQuat<Scalar>],
        kept: Option<&JointMatrices>,
        max_terms: Option<usize>,
        entry: impl Fn(Scalar) -> Option<Scalar>,
    ) -> Option<Matrix4<Scalar>> {
        let factors = self.factor_matrices(joints, 0, kept);
        matrix_product_until(factors, max_terms, entry, None, None, None)
    }

    /// The factors the matrix product multiplies: the base (unless it is the identity), the
    /// joint factors `joints` ([`Robot::joint_dqs`]) and the tool, up to the last that is not
    /// the identity (the tool of most chains leaves the product as it is, exactly). Their
    /// matrices are made while [`FactorMatrices::small`]'s estimate of the partial products
    /// stays below `terms`, the others' as the product reaches them (a product given up for
    /// its size never converts the factors after it). The joint factors' matrices are taken
    /// from `kept` (the matrices of these `joints`, [`MadeJoints::matrices`]) where it has
    /// them, and left there when it has not.
    pub(crate) fn factor_matrices(
        &self,
        joints: &[DualQuat<Scalar>],
        terms: usize,
        kept: Option<&JointMatrices>,
    ) -> FactorMatrices {
        let id = DualQuat::identity();
        let base = (self.chain.base != id).then_some(&self.chain.base);
        let factors: Vec<&DualQuat<Scalar>> = base
            .into_iter()
            .chain(joints)
            .chain(std::iter::once(&self.chain.tool))
            .collect();
        let last = factors.iter().rposition(|f| **f != id).unwrap_or(0);
        let kept = kept
            .filter(|k| k.0.len() == joints.len())
            .map(|k| (k.clone(), usize::from(base.is_some())));
        FactorMatrices::new(&factors[..=last], factors.len(), terms, kept)
    }

    /// The homogeneous matrix as polynomials in the cosines and sines of the joint variables
    /// and angle parameters (see [`Scalar::to_cos_sin_polynomial`]), or `None` when a joint
    /// factor's matrix holds a half or multiple angle, or an entry exceeds `max_terms`.
    /// For chains whose Fourier form explodes (a 6R with every DH parameter symbolic: 1,595
    /// monomials against about 300,000 Fourier terms); put it in closed form with
    /// [`crate::closed::closed_form_cos_sin`].
    pub fn forward_matrix_cos_sin(&self, max_terms: usize) -> Option<Matrix4<Scalar>> {
        self.matrix_product(Some(max_terms), |x| x.to_cos_sin_polynomial())
    }

    /// [`Robot::forward_matrix_cos_sin`] of the joint factors `joints` ([`Robot::joint_dqs`]),
    /// their matrices those `kept` where it has them (see [`Robot::factor_matrices`]).
    pub(crate) fn forward_matrix_cos_sin_of(
        &self,
        joints: &[DualQuat<Scalar>],
        kept: Option<&JointMatrices>,
        max_terms: usize,
    ) -> Option<Matrix4<Scalar>> {
        self.matrix_product_of(joints, kept, Some(max_terms), |x| x.to_cos_sin_polynomial())
    }

    /// The forward kinematics, or `None` as soon as a component of a partial product has more
    /// than `max_terms` terms: a chain whose expansion grows exponentially (every DH parameter
    /// symbolic, many joints) is detected after a few products instead of exhausting memory.
    pub fn forward_within(&self, max_terms: usize) -> Option<DualQuat<Scalar>> {
        self.forward_within_until(self.joint_dqs(), max_terms, &AtomicBool::new(false))
    }

    /// [`Robot::forward_within`] of the joint factors `joints` ([`Robot::joint_dqs`]) that
    /// gives up (`None`) once `stop` is set, and sets it when it gives up (see
    /// [`Robot::forward_matrix_until`]).
    pub(crate) fn forward_within_until(
        &self,
        joints: Vec<DualQuat<Scalar>>,
        max_terms: usize,
        stop: &AtomicBool,
    ) -> Option<DualQuat<Scalar>> {
        let r = self.forward_product(joints, max_terms, stop, None);
        if r.is_none() {
            stop.store(true, AtomicOrdering::Relaxed);
        }
        r
    }

    /// The pose's factors multiplied out in two halves (on two threads when there are two),
    /// then the product of the halves: exact, so the same value as the product from the
    /// left, and cheaper, also on one thread (the PUMA 560: 2.3 M instructions against
    /// 4.0 M; before, one thread multiplied from the left).
    /// With `fits`, also `None` once a component of a partial product does not fit.
    fn forward_product(
        &self,
        joints: Vec<DualQuat<Scalar>>,
        max_terms: usize,
        stop: &AtomicBool,
        fits: Option<&Fits<'_>>,
    ) -> Option<DualQuat<Scalar>> {
        let factors = self.pose_factors_of(joints);
        if factors.len() < 4 {
            return product_until(&factors, max_terms, stop, fits);
        }
        let (a, b) = factors.split_at(factors.len() / 2);
        let (pa, pb) = crate::scalar::join(
            || product_until(a, max_terms, stop, fits),
            || product_until(b, max_terms, stop, fits),
        );
        product_until(&[pa?, pb?], max_terms, stop, fits)
    }

    /// The symbols other than the joint variables (and pi), sorted by name: those of the joint
    /// factors and the tool, so nothing is expanded to find them.
    pub fn parameters(&self) -> Vec<String> {
        self.parameters_of(&self.joint_dqs())
    }

    /// [`Robot::parameters`] from the joint factors `joints` ([`Robot::joint_dqs`], made once
    /// by a caller that needs them more than once).
    pub(crate) fn parameters_of(&self, joints: &[DualQuat<Scalar>]) -> Vec<String> {
        let mut names: Vec<String> = Vec::new();
        for f in joints.iter().chain([&self.chain.base, &self.chain.tool]) {
            names.extend(
                f.components()
                    .iter()
                    .flat_map(|c| c.symbols())
                    .filter(|s| !s.is_pi())
                    .map(|s| s.name().to_string()),
            );
        }
        if let Some(t) = &self.tool {
            names.extend(
                t.iter()
                    .flat_map(|c| c.symbols())
                    .filter(|s| !s.is_pi())
                    .map(|s| s.name().to_string()),
            );
        }
        names.sort();
        names.dedup();
        names.retain(|n| !self.variables.contains(n));
        names
    }
}

/// A chain's joint factors with the constant angle offsets of some revolute joints left out
/// (`theta = q2 + 5 pi/9` multiplied as `theta = q2`), and those offsets, put back into each
/// entry of a product once ([`Scalar::shift_angles`]): the same canonical entries, while the
/// partial products never carry the offsets' cyclotomic phases (the Jaco-style arm's matrix
/// and DQ products: 10.6 M and 7.1 M instructions with its elbow offset, 2.7 M and 2.9 M
/// without).
///
/// A joint is shifted when its angle is its variable `q`, a plain symbol, plus `c pi`, `c`
/// not a multiple of 1/12 (those offsets are expanded exactly, without a cyclotomic basis),
/// and `q` is in no other factor (other joints, base, tool) and in none of the joint's other
/// parameters: then `q` occurs only inside angles, and substituting `q -> q + c pi` in the
/// offset-free factors gives the factors, so in their products the products (a
/// substitution is a ring homomorphism, and equal values have one canonical form).
///
/// What the products decide on their entries' sizes (the term limit, the growth's early
/// stop) is decided as the products with the offsets decide it: the offset-free products
/// are kept only when every entry of every partial product, shifted back, has fewer than a
/// sixteenth of the smaller of the term limits by [`Scalar::shifted_size_bound`]; then none
/// of those checks stops the products with the offsets ([`Growth::predicts`] needs a
/// sixteenth of the limit), and otherwise the caller multiplies the factors with their
/// offsets, as before. Degree errors: the route is taken only when every group the factors
/// with their offsets can make is within the degree limit (`levels_hold`), so neither
/// product meets one; an entry shifted back that is an error value or past `max_terms`
/// also sends the caller to the products with the offsets. The attempt runs on a work
/// budget of its own and is charged only when kept, so a product given up for the route
/// with the offsets leaves that route the budget it had. Not bounded so: the values inside
/// one entry's product with the offsets (its term products and partial sums, each held to
/// the context's term limit as it is made, and their digits) and the work the products
/// charge, which is less offset-free (Jaco-style arm: 146.7 M -> 139.8 M instructions), and
/// less again since the shift back writes each moved term in its canonical form and merges
/// them ([`Scalar::shift_angles`]) where it rewrote every moved group from scratch. A
/// chain given up only for those (an intermediate past a limit while every entry stays
/// below a sixteenth of the term limit, or the budget's very edge) may now be expanded;
/// every chain expanded before gives the same entries (outputs unchanged on the example
/// robots and random chains with offsets). The closed forms searched after the products
/// share that budget and find more of it left: where a nested search of their optional
/// candidates (`trigfac::nested_closed_form`, a share of the budget left) ran out before, it
/// may now end and be taken, a different form of the same value at that edge only (as with
/// every earlier cut in the work charged).
pub(crate) struct OffsetFree {
    /// The joint factors, the shifted joints' at offset 0.
    joints: Vec<DualQuat<Scalar>>,
    /// Each shifted joint's variable and its offset, a multiple of pi.
    shifts: Vec<(Sym, Small)>,
}

impl OffsetFree {
    /// Whether the entry `x` of an offset-free partial product fits (see [`OffsetFree`]).
    fn fits(&self, x: &Scalar, below: usize) -> bool {
        x.shifted_size_bound(&self.shifts)
            .is_some_and(|n| n < below)
    }

    /// A sixteenth of the smaller of `max_terms` and the context's term limit.
    fn below(max_terms: usize) -> usize {
        max_terms.min(crate::scalar::term_limit()) / 16
    }

    /// What the closed form of an entry `x` shifted back from the offset-free entry `y` is
    /// told of it (`closed::report_form_prepared`).
    pub(crate) fn hint<'a>(&'a self, y: &'a Scalar) -> crate::closed::Hint<'a> {
        crate::closed::Hint {
            shifts: &self.shifts,
            y,
        }
    }
}

impl Robot {
    /// The joint factors `joints` ([`Robot::joint_dqs`]) with the offsets of the joints that
    /// [`OffsetFree`] shifts left out; `None` when no joint is shifted.
    pub(crate) fn offset_free(&self, joints: &[DualQuat<Scalar>]) -> Option<OffsetFree> {
        let has =
            |f: &DualQuat<Scalar>, q: &Sym| f.components().iter().any(|c| c.symbols().contains(q));
        let mut shifted = Vec::new();
        for (i, (j, v)) in self.chain.joints.iter().zip(&self.joint_values).enumerate() {
            let Some((c, zero)) = offset_of(j) else {
                continue;
            };
            let Some(q) = v.as_plain_symbol() else {
                continue;
            };
            let elsewhere = joints.iter().enumerate().any(|(k, f)| k != i && has(f, &q))
                || has(&self.chain.base, &q)
                || has(&self.chain.tool, &q)
                || has(&zero.dq(&Scalar::int(0)), &q);
            if !elsewhere {
                shifted.push((i, zero.dq(v), (q, c)));
            }
        }
        if shifted.is_empty() || !levels_hold(joints, [&self.chain.base, &self.chain.tool]) {
            return None;
        }
        let mut free = joints.to_vec();
        let mut shifts = Vec::with_capacity(shifted.len());
        for (i, factor, shift) in shifted {
            free[i] = factor;
            shifts.push(shift);
        }
        Some(OffsetFree {
            joints: free,
            shifts,
        })
    }

    /// [`Robot::forward_matrix_until`] multiplied offset-free (see [`OffsetFree`]): `None`
    /// when the offset-free product is not kept (the caller multiplies the factors with their
    /// offsets), else what that gives, with the offset-free product beside it (each entry
    /// shifted back is the matrix's: [`OffsetFree::hint`]). `seen` is told of the last
    /// product's entries with their offsets, once all are made, largest first.
    pub(crate) fn forward_matrix_offset_free(
        &self,
        free: &OffsetFree,
        max_terms: usize,
        stop: &AtomicBool,
        seen: EntrySeen,
    ) -> Option<Option<(Matrix4<Scalar>, Matrix4<Scalar>)>> {
        let below = OffsetFree::below(max_terms);
        let fits = |x: &Scalar| free.fits(x, below);
        let factors = self.factor_matrices(&free.joints, 0, None);
        let rows = charged_if_kept(|| {
            let made = matrix_product_until(
                factors,
                Some(max_terms),
                Some,
                Some(stop),
                None,
                Some(&fits),
            );
            let Some(m) = made else {
                return stop.load(AtomicOrdering::Relaxed).then_some(None);
            };
            let mut rows: [[Scalar; 4]; 4] = Default::default();
            for (row, from) in rows.iter_mut().zip(&m.rows) {
                for (x, y) in row.iter_mut().zip(from) {
                    *x = shifted_back(y, free, max_terms)?;
                }
            }
            Some(Some((rows, m)))
        })?;
        let Some((rows, made)) = rows else {
            return Some(None);
        };
        let mut order: Vec<(usize, usize)> =
            (0..4).flat_map(|i| (0..4).map(move |j| (i, j))).collect();
        order.sort_by_key(|&(i, j)| std::cmp::Reverse(rows[i][j].len()));
        for (i, j) in order {
            if !seen(i, j, &rows[i][j]) {
                stop.store(true, AtomicOrdering::Relaxed);
                return Some(None);
            }
        }
        Some(Some((Matrix4::from_rows(rows), made)))
    }

    /// [`Robot::forward_within_until`] multiplied offset-free (see [`OffsetFree`]): `None`
    /// when the offset-free product is not kept (the caller multiplies the factors with their
    /// offsets), else what that gives, with the offset-free product's components beside it
    /// (each shifted back is the product's: [`OffsetFree::hint`]).
    pub(crate) fn forward_within_offset_free(
        &self,
        free: &OffsetFree,
        max_terms: usize,
        stop: &AtomicBool,
    ) -> Option<Option<(DualQuat<Scalar>, [Scalar; 8])>> {
        let below = OffsetFree::below(max_terms);
        let fits = |x: &Scalar| free.fits(x, below);
        charged_if_kept(|| {
            let made = self.forward_product(free.joints.clone(), max_terms, stop, Some(&fits));
            let Some(q) = made else {
                return stop.load(AtomicOrdering::Relaxed).then_some(None);
            };
            let made = q.components();
            let mut comps: [Scalar; 8] = Default::default();
            for (c, y) in comps.iter_mut().zip(&made) {
                *c = shifted_back(y, free, max_terms)?;
            }
            Some(Some((DualQuat::from_components(comps), made)))
        })
    }
}

/// Whether every group of the products of `joints` (the factors with their offsets), `base`
/// and `tool`, and so of the offset-free products, is within the degree limit whatever its
/// offsets ([`crate::scalar::levels_within_limit`] of the lcm of their terms' pi
/// denominators): then neither product meets a degree error, in any partial product, and
/// the route with the offsets does not stop on one where the offset-free one goes on.
fn levels_hold<'a>(joints: &'a [DualQuat<Scalar>], frames: [&'a DualQuat<Scalar>; 2]) -> bool {
    let mut den: u64 = 1;
    for f in joints.iter().chain(frames) {
        for c in f.components() {
            let Ok(terms) = c.terms() else {
                return false;
            };
            for t in terms {
                let d = t.mode.pi.denom().unsigned_abs();
                let Some(l) = (den / num_integer::gcd(den, d)).checked_mul(d) else {
                    return false;
                };
                den = l;
            }
        }
    }
    crate::scalar::levels_within_limit(den)
}

/// `y` of an offset-free product with the offsets put back, or `None` (the caller then
/// multiplies the factors with their offsets) when that is an error value or has more than
/// `max_terms` terms: the products with the offsets would have stopped there.
fn shifted_back(y: &Scalar, free: &OffsetFree, max_terms: usize) -> Option<Scalar> {
    let x = y.shift_angles(&free.shifts)?;
    (x.as_error().is_none() && x.len() <= max_terms).then_some(x)
}

/// `attempt` under a work budget of its own, what is left of this thread's, its work charged
/// to this thread only when it is kept (`Some`): an offset-free product given up for the
/// products with the offsets spends nothing, so those run on the budget they had before.
fn charged_if_kept<R>(attempt: impl FnOnce() -> Option<R>) -> Option<R> {
    let own = crate::Context::current()
        .with_work_budget(crate::scalar::work_left())
        .enter();
    let r = attempt();
    let used = own.work_used();
    drop(own);
    if r.is_some() {
        // An overrun shows in the next operation here, as it would have in the products.
        let _: Result<(), ScalarError> = crate::scalar::charge(used);
    }
    r
}

/// The joint factors ([`Robot::joint_dqs`]) made once, with the work they were charged, for
/// the callers that would make them again: `fk` makes them for the expansion and the
/// header, and the recurrence that follows an expansion given up made them three times more
/// (its factors, its parameters' names, its matrix in cosines and sines: 1.15 M of a fully
/// symbolic 6R's 94.6 M instructions). Their matrices too, as they are made
/// ([`JointMatrices`]).
pub(crate) struct MadeJoints {
    /// The factors; `None` once [`MadeJoints::take`] moved them out.
    dqs: Option<Vec<DualQuat<Scalar>>>,
    /// The work units making them charged the context they were made in.
    units: u64,
    /// Their matrices as the matrix products make them; `None` when a factor is an error
    /// value (see [`MadeJoints::again`]).
    matrices: Option<JointMatrices>,
}

/// Whether no component of the factors `dqs` is an error value.
fn sound(dqs: &[DualQuat<Scalar>]) -> bool {
    dqs.iter().all(|q| {
        [&q.real, &q.dual].iter().all(|p| {
            [&p.w, &p.x, &p.y, &p.z]
                .iter()
                .all(|c| c.as_error().is_none())
        })
    })
}

/// Whether the entered context takes the whole charge `units` in one step (`charge` checks the
/// cancel flag before it adds anything): the rule by which a factor or matrix kept is given
/// in place of its making again ([`MadeJoints::again`], [`JointMatrices`]).
fn charged_whole(units: u64) -> bool {
    units <= crate::scalar::work_left() && crate::scalar::charge(units).is_ok()
}

impl MadeJoints {
    /// The factors (empty once taken).
    pub(crate) fn dqs(&self) -> &[DualQuat<Scalar>] {
        self.dqs.as_deref().unwrap_or(&[])
    }

    /// The factors' matrices made so far, kept for the next product that needs them
    /// ([`Robot::factor_matrices`]); they stay when the factors are taken.
    pub(crate) fn matrices(&self) -> Option<&JointMatrices> {
        self.matrices.as_ref()
    }

    /// The work making them charged (tests).
    #[cfg(test)]
    pub(crate) fn units_for_tests(&self) -> u64 {
        self.units
    }

    /// The factors moved out: [`MadeJoints::again`] makes them anew after this.
    pub(crate) fn take(&mut self) -> Vec<DualQuat<Scalar>> {
        self.dqs.take().unwrap_or_default()
    }

    /// `robot.joint_dqs()` (of the robot they were made of), charged the work their making
    /// was: the factors kept when the entered context can take that whole charge (`charge`
    /// checks the cancel flag before it adds anything), else made again.
    ///
    /// What the budget sees. Making the factors is a pure function of the robot, and so is
    /// its charge (counts of term operations), but for the caches charged on a miss only
    /// (`cyclo`'s term templates and fields): made again on caches their first making
    /// filled, the factors may charge those misses less (16 of 568 units on a random chain
    /// with angles off the pi/12 grid).
    /// So the recurrence is charged, at each of the three places it made them, the same work
    /// or up to those few units more, in one step where no operation in between could see
    /// it: an input whose recurrence ends within those units of the work budget may now
    /// stop at the budget. A budget too small for the whole charge, a cancelled context, or
    /// factors that held an error value are where making them again can end otherwise (an
    /// error value, at some operation): there they are made again, as before.
    pub(crate) fn again(&self, robot: &Robot) -> std::borrow::Cow<'_, [DualQuat<Scalar>]> {
        // Factors with an error value are made again: there, it may be another, or none.
        let units = self.units;
        match &self.dqs {
            Some(dqs) if sound(dqs) && charged_whole(units) => std::borrow::Cow::Borrowed(dqs),
            _ => std::borrow::Cow::Owned(robot.joint_dqs()),
        }
    }
}

/// The matrices ([`DualQuat::to_matrix`]) of the joint factors of a [`MadeJoints`], each kept
/// with the work its making charged once a matrix product made it: `fk`'s expansion of a
/// fully symbolic 6R converts five of its six joint factors before it gives the pose up, and
/// the recurrence's matrix in cosines and sines converted the same five again (0.4 M
/// instructions each). Shared (an `Arc`) by the products that read them, on any thread.
///
/// The charging rule is [`MadeJoints::again`]'s: a matrix kept is given only when the entered
/// context can take the whole charge its making was (`charge` checks the cancel flag before
/// it adds anything), else it is made again, as before; the conversion is a pure function
/// of the factor, so the matrix is the same, and so is its charge, but for the caches charged
/// on a miss (`cyclo`'s templates and fields, for angles off the pi/12 grid): made on caches
/// its first making filled, a matrix may charge those misses less. So the product that takes
/// it is charged, where it made it, the same work or a few units more, in one step where no
/// operation in between could see it: an input whose recurrence ends within those units of
/// the work budget may now stop at the budget. A matrix with an error value (a budget or a
/// limit met while it was made) is not kept.
#[derive(Clone)]
pub(crate) struct JointMatrices(Arc<[OnceLock<KeptMatrix>]>);

/// A joint factor's matrix and the work units its making charged.
type KeptMatrix = (Matrix4<Scalar>, u64);

impl JointMatrices {
    /// Room for the matrices of `n` joint factors, none made.
    fn new(n: usize) -> JointMatrices {
        JointMatrices((0..n).map(|_| OnceLock::new()).collect())
    }

    /// The matrix of joint factor `i`, `dq`: the one kept, charged as its making was, or
    /// made now (and kept when it is not an error value and none is).
    fn matrix(&self, i: usize, dq: &DualQuat<Scalar>) -> Matrix4<Scalar> {
        let slot = &self.0[i];
        if let Some((m, units)) = slot.get() {
            if charged_whole(*units) {
                return m.clone();
            }
            return dq.to_matrix();
        }
        let before = crate::scalar::work_used();
        let m = dq.to_matrix();
        let units = crate::scalar::work_used().saturating_sub(before);
        if m.rows.iter().flatten().all(|x| x.as_error().is_none()) {
            let _ = slot.set((m.clone(), units));
        }
        m
    }
}

/// A revolute DH or MDH joint's constant angle offset `c` (its angle is `q + c pi`) when `c`
/// is not a multiple of 1/12, and the joint with the offset 0.
fn offset_of(j: &Joint<Scalar>) -> Option<(Small, Joint<Scalar>)> {
    if j.kind != JointKind::Revolute {
        return None;
    }
    let c = match &j.geometry {
        JointGeometry::Dh { theta, .. } | JointGeometry::Mdh { theta, .. } => {
            theta.as_pi_multiple()?
        }
        _ => return None,
    };
    let twelfths = c.checked_mul(&Small::from_integer(12))?;
    if twelfths.is_integer() {
        return None;
    }
    let zero = Scalar::int(0);
    let geometry = match &j.geometry {
        JointGeometry::Dh { d, a, alpha, .. } => JointGeometry::Dh {
            theta: zero,
            d: d.clone(),
            a: a.clone(),
            alpha: alpha.clone(),
        },
        JointGeometry::Mdh { alpha, a, d, .. } => JointGeometry::Mdh {
            alpha: alpha.clone(),
            a: a.clone(),
            theta: zero,
            d: d.clone(),
        },
        _ => return None,
    };
    Some((c, Joint::new(JointKind::Revolute, geometry)))
}

/// The product of `fs` from the left, or `None` once a component of a partial product has
/// more than `max_terms` terms or is an error value, or `stop` is set (checked before each
/// factor), or (with `fits`) a component does not fit.
fn product_until(
    fs: &[DualQuat<Scalar>],
    max_terms: usize,
    stop: &AtomicBool,
    fits: Option<&Fits<'_>>,
) -> Option<DualQuat<Scalar>> {
    let mut acc: Option<DualQuat<Scalar>> = None;
    for f in fs {
        if stop.load(AtomicOrdering::Relaxed) {
            return None;
        }
        let next = match acc {
            Some(a) => a * f.clone(),
            None => f.clone(),
        };
        if next
            .components()
            .iter()
            .any(|c| c.len() > max_terms || c.as_error().is_some() || fits.is_some_and(|f| !f(c)))
        {
            return None;
        }
        acc = Some(next);
    }
    Some(acc.unwrap_or_else(DualQuat::identity))
}

/// `a b`, or `None` as soon as an entry has more than `limit` terms (or is an error value).
/// The entries are computed largest first by the count of their term pairs, so that a product
/// past the limit (the last factor of a long numeric chain, whose entries reach tens of
/// thousands of terms) usually stops after its first entry instead of computing all sixteen.
/// Each entry is shown to `seen` as it is made; `false` there gives `None`, and so does
/// `early` of the largest entry made so far.
///
/// Without `seen`, whether the product is `None` does not depend on the order its entries
/// are made in, so an entry likely to stop it early is made first (see [`early_first`]).
/// `pairs_before` holds the term pairs of the entries of the product before (`a`), for
/// that estimate, and is left holding this product's.
fn product_within(
    a: &Matrix4<Scalar>,
    b: &Matrix4<Scalar>,
    limit: usize,
    stop: Option<&AtomicBool>,
    mut seen: Option<EntrySeen>,
    early: Option<&dyn Fn(usize) -> bool>,
    pairs_before: &mut Option<EntryPairs>,
) -> Option<Matrix4<Scalar>> {
    let pairs: EntryPairs = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..4)
                .map(|k| a.rows[i][k].len() * b.rows[k][j].len())
                .sum()
        })
    });
    let mut order: Vec<(usize, usize)> = (0..4).flat_map(|i| (0..4).map(move |j| (i, j))).collect();
    order.sort_by_key(|&(i, j)| std::cmp::Reverse(pairs[i][j]));
    if let (None, Some(early)) = (&seen, early) {
        if !largest_first_in_tests() {
            // Each entry's size estimated from its pairs at the terms per pair of the same
            // entry of `a` (the product before: the translations of a DH chain merge to
            // about 1.47 terms a pair, its rotations make exactly two), else two a pair.
            let before = pairs_before.as_ref();
            let estimate = |(i, j): (usize, usize)| match before {
                Some(p) if p[i][j] > 0 => pairs[i][j].saturating_mul(a.rows[i][j].len()) / p[i][j],
                _ => pairs[i][j].saturating_mul(2),
            };
            early_first(&mut order, |(i, j)| pairs[i][j], estimate, early);
        }
    }
    *pairs_before = Some(pairs);
    let mut rows: [[Scalar; 4]; 4] = Default::default();
    let mut largest = 0;
    for (i, j) in order {
        if stop.is_some_and(|s| s.load(AtomicOrdering::Relaxed)) {
            return None;
        }
        let x = (0..4).fold(Scalar::int(0), |acc, k| acc + &a.rows[i][k] * &b.rows[k][j]);
        if x.len() > limit || x.as_error().is_some() {
            return None;
        }
        largest = largest.max(x.len());
        if early.is_some_and(|f| f(largest)) {
            return None;
        }
        if let Some(seen) = seen.as_mut() {
            if !seen(i, j, &x) {
                return None;
            }
        }
        rows[i][j] = x;
    }
    Some(Matrix4::from_rows(rows))
}

/// The term pairs of each entry of a matrix product (row, column).
type EntryPairs = [[usize; 4]; 4];

/// Moves to the front of `order` (the entries of a product, largest first by their term
/// pairs) the entry with the fewest term pairs among those whose `estimate`d size `early`
/// says stops the product (the first of them on a tie); the others keep their order.
/// Nothing moves when no estimate stops it.
///
/// Why the order cannot change what [`product_within`] without `seen` gives: it is `None`
/// exactly when some entry has more than `limit` terms, is an error value, or when `early`
/// holds of the largest entry made so far, or `stop` is set. Each entry is a pure function
/// of `a` and `b`, so every order makes the same entries. `early` is monotone in the size
/// (`Growth::predicts`), so it holds of the largest entry made so far at some point exactly
/// when it holds of the largest entry of the product, whichever order they come in; `stop`
/// is set by another thread at a time of its own, in any order. The work budget: a product
/// made to the end makes the same entries and is charged the same work in every order (the
/// caches charged on a miss, `cyclo`'s templates and fields, miss on the same keys), so a
/// budget that runs out in one order runs out in every order (its error value gives
/// `None`); a product given up is `None` whatever it was charged. `fk` runs these products
/// on a budget of its own, not charged to the caller when given up: what changes is only
/// which entries a given-up product made, so which cache entries the work after it (the
/// recurrence) finds already made. That can change its charge by the few units of a cache
/// miss (a template or a field, made for angles off the pi/12 grid), at the budget's very
/// edge.
///
/// Only the work done before a product is given up changes: on a fully symbolic 6R, whose
/// fourth product is given up for its growth (its largest entry past 363 terms), the first
/// entry made is one of 353 term pairs (517 terms, estimated 518) instead of one of 448
/// (896 terms). When the estimate is wrong, one entry more is made before the others, and
/// nothing when the product is made to the end. (Two terms a pair for every entry would
/// estimate that entry at 706 terms, which on a fully symbolic 5R, one link fewer left,
/// stops the product where its 517 do not: the 5R made it first for nothing, 1.5% more.)
fn early_first(
    order: &mut [(usize, usize)],
    pairs: impl Fn((usize, usize)) -> usize,
    estimate: impl Fn((usize, usize)) -> usize,
    early: &dyn Fn(usize) -> bool,
) {
    let mut first: Option<(usize, usize)> = None;
    for (k, &e) in order.iter().enumerate() {
        let fewer = first.is_none_or(|(_, n)| pairs(e) < n);
        if fewer && early(estimate(e)) {
            first = Some((k, pairs(e)));
        }
    }
    if let Some((k, _)) = first {
        order[..=k].rotate_right(1);
    }
}

#[cfg(test)]
thread_local! {
    /// Tests: [`product_within`] on this thread makes its entries largest first, as it did
    /// before [`early_first`]: the reference the new order is compared with.
    pub(crate) static LARGEST_FIRST: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Whether a test asked for the order before [`early_first`] ([`LARGEST_FIRST`]).
fn largest_first_in_tests() -> bool {
    #[cfg(test)]
    return LARGEST_FIRST.with(std::cell::Cell::get);
    #[cfg(not(test))]
    false
}

/// A fully symbolic revolute chain of `n` joints for tests: joint `i` has the variable
/// `{var}{i}` and the parameters `d{i}`, `a{i}`, `alpha{i}`, DH or modified DH (`mdh`), no
/// offsets; the rest (name, frames) is a [`random_test_chain`]'s, drawn from `next`.
#[cfg(test)]
pub(crate) fn symbolic_test_chain(
    next: &mut impl FnMut(u64) -> u64,
    n: usize,
    mdh: bool,
    var: &str,
) -> Robot {
    let mut r = random_test_chain(next, n);
    let s = |name: &str, i: usize| Scalar::sym(&format!("{name}{i}"));
    r.chain = Chain::new(
        (1..=n)
            .map(|i| {
                let (z, d, a, al) = (Scalar::int(0), s("d", i), s("a", i), s("alpha", i));
                if mdh {
                    Joint::revolute_mdh(al, a, z, d)
                } else {
                    Joint::revolute_dh(z, d, a, al)
                }
            })
            .collect(),
    );
    r.variables = (1..=n).map(|i| format!("{var}{i}")).collect();
    r.joint_values = (1..=n).map(|i| s(var, i)).collect();
    r.convention = if mdh { Convention::Mdh } else { Convention::Dh };
    r
}

/// A random chain for tests of `fk`'s decisions: 3 to 8 joints, DH or MDH, revolute or (one
/// in five) prismatic, each DH parameter a symbol of its own, a number, zero, or a number
/// plus a symbol; twists of right angles, thirds, quarters and fifths of pi or a symbol;
/// revolute joints with angle offsets on and off the pi/12 grid or symbolic. `max_joints`
/// caps the joints (at least 3).
#[cfg(test)]
pub(crate) fn random_test_chain(next: &mut impl FnMut(u64) -> u64, max_joints: usize) -> Robot {
    use crate::Ring;
    let count = 3 + next(max_joints.max(3) as u64 - 2) as usize;
    let mdh = next(2) == 0;
    let pi = |n: i64, d: i64| Scalar::pi() * Scalar::from_ratio(n, d);
    let mut joints = Vec::new();
    let mut variables = Vec::new();
    let mut values = Vec::new();
    for i in 1..=count {
        let sym = |name: &str| Scalar::sym(&format!("{name}{i}"));
        let mut length = |name: &str| match next(4) {
            0 => sym(name),
            1 => Scalar::from_ratio(next(9) as i64 + 1, 4),
            2 => Scalar::from_ratio(next(5) as i64 + 1, 2) + sym(name),
            _ => Scalar::int(0),
        };
        let (d, a) = (length("d"), length("a"));
        let alpha = match next(8) {
            0 => pi(1, 2),
            1 => pi(-1, 2),
            2 => pi(1, 3),
            3 => pi(1, 4),
            4 => pi(2, 5),
            5 => Scalar::int(0),
            _ => sym("alpha"),
        };
        let theta = match next(6) {
            0 => pi(next(23) as i64 + 1, 12),
            1 => pi(next(9) as i64 + 1, 5),
            2 => sym("theta"),
            _ => Scalar::int(0),
        };
        let q = format!("q{i}");
        values.push(Scalar::sym(&q));
        variables.push(q);
        let prismatic = next(5) == 0;
        joints.push(match (mdh, prismatic) {
            (false, false) => Joint::revolute_dh(theta, d, a, alpha),
            (false, true) => Joint::prismatic_dh(theta, d, a, alpha),
            (true, false) => Joint::revolute_mdh(alpha, a, theta, d),
            (true, true) => Joint::prismatic_mdh(alpha, a, theta, d),
        });
    }
    Robot {
        name: "test".into(),
        convention: if mdh { Convention::Mdh } else { Convention::Dh },
        variables,
        joint_values: values,
        chain: Chain::new(joints),
        base_frames: Vec::new(),
        tool_frames: Vec::new(),
        tool: None,
        values: Vec::new(),
        notes: Vec::new(),
        decimals: Vec::new(),
    }
}

/// The factors a matrix product multiplies ([`Robot::factor_matrices`]), the first ones
/// already as matrices.
pub(crate) struct FactorMatrices {
    /// The first factors' matrices.
    mats: Vec<Matrix4<Scalar>>,
    /// The factors after them, converted as the product reaches them.
    rest: Vec<DualQuat<Scalar>>,
    /// The number of factors, the identities after the last other one included: the growth
    /// of the partial products is measured against the links left (see [`Growth`]).
    count: usize,
    /// Whether every factor is converted and the estimate stayed below the threshold.
    small: bool,
    /// The joint factors' matrices kept ([`Robot::factor_matrices`]), and the index of the
    /// first joint factor among the factors (1 after a base frame).
    kept: Option<(JointMatrices, usize)>,
}

impl FactorMatrices {
    /// `factors` (`count` in all, identities after them included), converted while every
    /// entry of every partial product has fewer than `terms` terms by an estimate from the
    /// matrices' term counts alone: an entry of a product has at most two terms per term
    /// pair (a product of two Fourier terms is at most two).
    fn new(
        factors: &[&DualQuat<Scalar>],
        count: usize,
        terms: usize,
        kept: Option<(JointMatrices, usize)>,
    ) -> FactorMatrices {
        let mut mats = Vec::with_capacity(factors.len());
        let mut estimate: Option<[[usize; 4]; 4]> = None;
        let mut small = true;
        while small && mats.len() < factors.len() {
            let m = converted(&kept, mats.len(), factors[mats.len()]);
            let counts = m.rows.each_ref().map(|r| r.each_ref().map(Scalar::len));
            let e = estimate.map_or(counts, |a| {
                std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        (0..4)
                            .map(|k| a[i][k].saturating_mul(counts[k][j]).saturating_mul(2))
                            .fold(0, usize::saturating_add)
                    })
                })
            });
            small = e.iter().flatten().all(|&n| n < terms);
            estimate = Some(e);
            mats.push(m);
        }
        FactorMatrices {
            rest: factors[mats.len()..].iter().map(|f| (*f).clone()).collect(),
            mats,
            count,
            small,
            kept,
        }
    }

    /// Whether every entry of every partial product has fewer terms than the threshold
    /// [`Robot::factor_matrices`] was given, by its estimate. An estimate, not a bound (a
    /// cyclotomic rewriting may add terms), for scheduling only: `fk` begins the DQ product
    /// beside a matrix product that stays small, which its size never abandons (the PUMA
    /// 560; a chain with twists other than multiples of a right angle, or symbolic ones,
    /// fills its factors' matrices and passes 512 within a few links).
    pub(crate) fn small(&self) -> bool {
        self.small
    }
}

/// The matrix of factor `k`, `f`, of a [`FactorMatrices`]: a joint factor's from `kept`
/// ([`JointMatrices::matrix`]), another's made.
fn converted(
    kept: &Option<(JointMatrices, usize)>,
    k: usize,
    f: &DualQuat<Scalar>,
) -> Matrix4<Scalar> {
    match kept {
        Some((m, first)) if k >= *first && k - first < m.0.len() => m.matrix(k - first, f),
        _ => f.to_matrix(),
    }
}

/// The product of `factors` ([`Robot::factor_matrices`]), each entry of each factor's matrix
/// first passed through `entry` (`None` there gives `None`); `None` as soon as an entry of a
/// partial product has more than `max_terms` terms or is an error value; with `stop`, also
/// `None` once `stop` is set or when the growth of the partial products predicts that the
/// last one exceeds `max_terms`; with `seen` (and `max_terms`), also `None` when it refuses an
/// entry of the last product (see [`Robot::forward_matrix_until`]); with `fits` (and
/// `max_terms`), also `None` once an entry of a partial product does not fit.
fn matrix_product_until(
    factors: FactorMatrices,
    max_terms: Option<usize>,
    entry: impl Fn(Scalar) -> Option<Scalar>,
    stop: Option<&AtomicBool>,
    mut seen: Option<EntrySeen>,
    fits: Option<&Fits<'_>>,
) -> Option<Matrix4<Scalar>> {
    let FactorMatrices {
        mats,
        rest,
        count,
        kept,
        ..
    } = factors;
    let made = mats.len();
    let last = made + rest.len() - 1;
    let (mut mats, mut rest) = (mats.into_iter(), rest.iter().enumerate());
    let stopped = || stop.is_some_and(|s| s.load(AtomicOrdering::Relaxed));
    let mut growth = Growth::default();
    let mut pairs_before: Option<EntryPairs> = None;
    let mut acc: Option<Matrix4<Scalar>> = None;
    for k in 0..count {
        if stopped() {
            return None;
        }
        // The identity factors after the last other one leave the product as it is.
        let Some(mut m) = mats
            .next()
            .or_else(|| rest.next().map(|(r, f)| converted(&kept, made + r, f)))
        else {
            continue;
        };
        for x in m.rows.iter_mut().flatten() {
            *x = entry(std::mem::take(x))?;
        }
        let seen = if k == last { seen.take() } else { None };
        // The growth's prediction (below) made on the entries as they come: it only grows
        // with the largest entry, so once it says the limit will be passed, it says so of the
        // whole product (a fully symbolic 6R gives up after one entry of its fourth product,
        // not twelve).
        let left = count - 1 - k;
        let predicts =
            |size: usize| max_terms.is_some_and(|limit| growth.predicts(size, left, limit));
        let early: Option<&dyn Fn(usize) -> bool> = stop.is_some().then_some(&predicts);
        let next = match (acc, max_terms) {
            (None, _) => m,
            (Some(a), None) => a.mul_ref(&m),
            (Some(a), Some(limit)) => {
                product_within(&a, &m, limit, stop, seen, early, &mut pairs_before)?
            }
        };
        if let Some(limit) = max_terms {
            if next
                .rows
                .iter()
                .flatten()
                .any(|x| x.len() > limit || x.as_error().is_some() || fits.is_some_and(|f| !f(x)))
            {
                return None;
            }
            let largest = next.rows.iter().flatten().map(Scalar::len).max();
            if stop.is_some() && growth.exceeds(largest.unwrap_or(0), left, limit) {
                return None;
            }
        }
        acc = Some(next);
    }
    Some(acc.unwrap_or_else(Matrix4::identity))
}

/// Whether an entry of a partial product may be kept (see [`OffsetFree`]).
type Fits<'a> = dyn Fn(&Scalar) -> bool + Sync + 'a;

/// Told of each entry of a matrix product as it is made (row, column, entry); `false`
/// abandons the product (see [`Robot::forward_matrix_until`]).
pub(crate) type EntrySeen<'a> = &'a mut dyn FnMut(usize, usize, &Scalar) -> bool;

/// The sizes of the partial products of a chain, to predict the last one's.
///
/// The largest entry of a partial product grows by a steady factor per link on a chain of
/// numeric links in general position (2.73 for the matrices of RTB's Ball and of 9 links
/// a = d = 1, alpha = pi/2; the Fourier modes of k revolute joints number up to 3^k / 2), so
/// once a partial product is large enough for its growth to be measured, the smaller of the
/// last two growth factors raised to the number of links left predicts the last size; past
/// twice the limit the expansion is abandoned before its most expensive products.
#[derive(Default)]
struct Growth {
    /// The largest entry of the last two partial products.
    last: [usize; 2],
}

impl Growth {
    /// Records the largest entry `size` of the next partial product; whether `left` more
    /// links at the present growth take it past twice `limit`.
    fn exceeds(&mut self, size: usize, left: usize, limit: usize) -> bool {
        let r = self.predicts(size, left, limit);
        self.last = [self.last[1], size];
        r
    }

    /// [`Growth::exceeds`] without recording `size`: true of a size, it is true of every
    /// larger one (the growth factor only grows with it).
    fn predicts(&self, size: usize, left: usize, limit: usize) -> bool {
        let [a, b] = self.last;
        if a == 0 || b == 0 || size < limit / 16 || left == 0 {
            return false;
        }
        let rate = (b as f64 / a as f64).min(size as f64 / b as f64);
        rate > 1.0 && size as f64 * rate.powi(left.min(64) as i32) > 2.0 * limit as f64
    }
}

/// Refuses a joint variable an earlier joint already has: each Jacobian column is the
/// derivative by one joint's variable, so a shared one would make both columns the total
/// derivative.
fn check_distinct(earlier: &[String], var: &str) -> Result<(), FieldError> {
    match earlier.iter().position(|v| v == var) {
        Some(k) => Err(FieldError::SharedVariable {
            variable: var.to_string(),
            joint: k + 1,
        }),
        None => Ok(()),
    }
}

/// Refuses a joint variable that the language reads as something else than that symbol: the
/// constant `pi` (a joint `pi` would be a fixed half turn with a zero Jacobian column), the
/// dual unit `eps`, the quaternion units, any built-in name.
fn builtin_name(name: &str, eval: FieldEval) -> Result<(), FieldError> {
    let sym = Scalar::sym(name);
    let own = !crate::scalar::Sym::new(name).is_pi() && eval(name).is_ok_and(|v| v == sym);
    if own {
        Ok(())
    } else {
        Err(FieldError::BuiltinName(name.to_string()))
    }
}

/// The joint variable of a field: its one symbol that is not `pi` nor a parameter with a
/// nominal value in `[values]` (a constant angle kept as a name, as in `q1 + offset`).
fn joint_variable(
    x: &Scalar,
    params: &std::collections::BTreeMap<String, toml::Value>,
) -> Result<String, FieldError> {
    let syms: Vec<String> = x
        .symbols()
        .into_iter()
        .filter(|s| !s.is_pi())
        .map(|s| s.name().to_string())
        .filter(|n| !params.contains_key(n))
        .collect();
    match syms.as_slice() {
        [one] => Ok(one.clone()),
        [] => Err(FieldError::NoVariable),
        _ => Err(FieldError::SeveralSymbols(syms.join(", "))),
    }
}

fn vec3(v: Option<&Vec<String>>, name: &str, eval: FieldEval) -> Result<[Scalar; 3], FieldError> {
    let v = v.ok_or(FieldError::Missing)?;
    if v.len() != 3 {
        return Err(FieldError::Entries {
            name: name.to_string(),
            found: v.len(),
        });
    }
    Ok([eval(&v[0])?, eval(&v[1])?, eval(&v[2])?])
}

/// The axis scaled to unit length, exactly; the axis must be numeric and nonzero, or
/// symbolic (in constant angles such as a URDF angle kept as a parameter) of unit length.
pub(crate) fn unit_numeric(a: &[Scalar; 3]) -> Result<[Scalar; 3], FieldError> {
    let n2 = &a[0] * &a[0] + &a[1] * &a[1] + &a[2] * &a[2];
    if !a.iter().all(Scalar::is_constant) {
        // A limit reached by the check is that limit, not a "no".
        return match (&n2 - &Scalar::int(1)).try_is_zero() {
            Ok(true) => Ok(a.clone()),
            Ok(false) => Err(FieldError::AxisNotUnit),
            Err(e) => Err(FieldError::AxisLimit(e)),
        };
    }
    if n2.is_zero_value() {
        return Err(FieldError::AxisZero);
    }
    let n = n2.sqrt().check()?;
    let div = |x: &Scalar| x.try_div(&n);
    Ok([div(&a[0])?, div(&a[1])?, div(&a[2])?])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kin::dh::dh_link;
    use crate::Ring;

    /// The factors of classic DH links at the joint variables `q1..qn`, with twists
    /// `twists` and the lengths `a_i` and offsets `d_i` symbols where `lengths` says so, as
    /// `fk` converts them (threshold 512, its `EARLY_FORM_TERMS`).
    fn dh_factors(twists: &[Scalar], lengths: &[(bool, bool)]) -> FactorMatrices {
        let links: Vec<DualQuat<Scalar>> = twists
            .iter()
            .zip(lengths)
            .enumerate()
            .map(|(i, (alpha, &(a, d)))| {
                let sym = |name: &str, on: bool| {
                    if on {
                        Scalar::sym(&format!("{name}{}", i + 1))
                    } else {
                        Scalar::int(0)
                    }
                };
                let theta = Scalar::sym(&format!("q{}", i + 1));
                dh_link(&theta, &sym("d", d), &sym("a", a), alpha)
            })
            .collect();
        let refs: Vec<&DualQuat<Scalar>> = links.iter().collect();
        FactorMatrices::new(&refs, refs.len(), EARLY, None)
    }

    /// The largest entry of the product of `f`, multiplied out.
    fn largest_entry(f: FactorMatrices) -> usize {
        matrix_product_until(f, None, Some, None, None, None).map_or(0, |m| {
            m.rows.iter().flatten().map(Scalar::len).max().unwrap_or(0)
        })
    }

    #[test]
    fn a_right_angled_arm_is_estimated_small_and_a_dense_one_is_not() {
        let angle = |k: i64| Scalar::pi() * Scalar::from_ratio(k, 2);
        // The PUMA 560's twists, lengths a2, a3 and offsets d3, d4.
        let puma = dh_factors(
            &[angle(1), angle(0), angle(-1), angle(1), angle(-1), angle(0)],
            &[
                (false, false),
                (true, false),
                (true, true),
                (false, true),
                (false, false),
                (false, false),
            ],
        );
        assert!(puma.small());
        assert!(puma.rest.is_empty());
        assert!(largest_entry(puma) < EARLY);
        // Twists of 60 degrees (a Jaco-style arm) and symbolic ones fill the factors'
        // matrices: both estimates pass the threshold, and the symbolic product's entries do.
        let third = Scalar::pi() * Scalar::from_ratio(1, 3);
        let jaco = dh_factors(&vec![third; 6], &[(true, true); 6]);
        assert!(!jaco.small());
        let twists: Vec<Scalar> = (1..=6).map(|i| Scalar::sym(&format!("t{i}"))).collect();
        let symbolic = dh_factors(&twists[..4], &[(true, true); 4]);
        assert!(!symbolic.small());
        // A longer one is converted only until the estimate passes the threshold.
        let longer = dh_factors(&twists, &[(true, true); 6]);
        assert!(!longer.small());
        assert!(!longer.rest.is_empty());
        assert!(largest_entry(symbolic) >= EARLY);
    }

    /// `fk`'s threshold (its `EARLY_FORM_TERMS`).
    const EARLY: usize = 512;

    /// A random DH or MDH chain of 3 to 5 revolute joints: twists from right angles, thirds
    /// and quarters of pi and a symbol, lengths symbolic, numeric or zero, and on one or two
    /// joints an angle offset `k pi / n` (`n` in 5, 7, 9, 10, 18), some a multiple of pi/12.
    fn random_chain(next: &mut impl FnMut(u64) -> u64) -> Robot {
        random_chain_of(next, 7)
    }

    /// [`random_chain`] with its twists drawn from the first `kinds` of the list: 10 adds
    /// fifths, sevenths and ninths of pi.
    fn random_chain_of(next: &mut impl FnMut(u64) -> u64, kinds: usize) -> Robot {
        let joints_count = 3 + next(3) as usize;
        let mdh = next(2) == 0;
        let twists = [
            Scalar::pi() * Scalar::from_ratio(1, 2),
            Scalar::pi() * Scalar::from_ratio(-1, 2),
            Scalar::pi() * Scalar::from_ratio(1, 3),
            Scalar::pi() * Scalar::from_ratio(1, 4),
            Scalar::pi(),
            Scalar::int(0),
            Scalar::sym("t"),
            Scalar::pi() * Scalar::from_ratio(1, 5),
            Scalar::pi() * Scalar::from_ratio(2, 7),
            Scalar::pi() * Scalar::from_ratio(1, 9),
        ];
        let mut joints = Vec::new();
        let mut variables = Vec::new();
        for i in 1..=joints_count {
            let mut length = |name: &str| match next(3) {
                0 => Scalar::sym(&format!("{name}{i}")),
                1 => Scalar::from_ratio(next(9) as i64 + 1, 4),
                _ => Scalar::int(0),
            };
            let (d, a) = (length("d"), length("a"));
            let alpha = twists[next(kinds as u64) as usize].clone();
            let n = [5, 7, 9, 10, 18][next(5) as usize];
            let theta = if next(2) == 0 {
                Scalar::pi() * Scalar::from_ratio(next(2 * n as u64 - 1) as i64 + 1, n)
            } else {
                Scalar::int(0)
            };
            joints.push(if mdh {
                Joint::revolute_mdh(alpha, a, theta, d)
            } else {
                Joint::revolute_dh(theta, d, a, alpha)
            });
            variables.push(format!("q{i}"));
        }
        let values = variables.iter().map(|v| Scalar::sym(v)).collect();
        let convention = if mdh { Convention::Mdh } else { Convention::Dh };
        bare_robot(convention, variables, values, Chain::new(joints))
    }

    /// A robot of `chain` with its variables and joint values, and no frames, tool point,
    /// values, notes or decimals.
    fn bare_robot(
        convention: Convention,
        variables: Vec<String>,
        joint_values: Vec<Scalar>,
        chain: Chain<Scalar>,
    ) -> Robot {
        Robot {
            name: "test".into(),
            convention,
            variables,
            joint_values,
            chain,
            base_frames: Vec::new(),
            tool_frames: Vec::new(),
            tool: None,
            values: Vec::new(),
            notes: Vec::new(),
            decimals: Vec::new(),
        }
    }

    #[test]
    fn products_without_the_offsets_shifted_back_are_the_products_with_them() {
        let mut next = crate::testing::xorshift_below(17);
        let (mut compared, mut kept) = (0, 0);
        for _ in 0..60 {
            let robot = random_chain(&mut next);
            let joints = robot.joint_dqs();
            let Some(free) = robot.offset_free(&joints) else {
                continue;
            };
            // Every shifted joint's offset is off the pi/12 grid, and its variable shifted.
            assert!(free.shifts.iter().all(|(q, c)| {
                !(*c * Small::from_integer(12)).is_integer()
                    && robot.variables.contains(&q.name().to_string())
            }));
            // A flag each: a product given up sets its own.
            let flag = || AtomicBool::new(false);
            let mut all = |_: usize, _: usize, _: &Scalar| true;
            let factors = robot.factor_matrices(&joints, EARLY, None);
            let matrix = robot.forward_matrix_until(factors, 20_000, &flag(), &mut all);
            let dq = robot.forward_within_until(joints.clone(), 20_000, &flag());
            let mut seen = Vec::new();
            let mut record = |i: usize, j: usize, x: &Scalar| {
                seen.push((i, j, x.clone()));
                true
            };
            let free_matrix = robot.forward_matrix_offset_free(&free, 20_000, &flag(), &mut record);
            let free_dq = robot.forward_within_offset_free(&free, 20_000, &flag());
            // Beside each product, the offset-free one whose entries shifted back are its.
            let back = |y: &Scalar| y.shift_angles(&free.shifts);
            if let Some(Some((m, made))) = &free_matrix {
                for (row, from) in m.rows.iter().zip(&made.rows) {
                    assert!(row
                        .iter()
                        .zip(from)
                        .all(|(x, y)| back(y).as_ref() == Some(x)));
                }
            }
            if let Some(Some((q, made))) = &free_dq {
                let comps = q.components();
                assert!(comps
                    .iter()
                    .zip(made)
                    .all(|(x, y)| back(y).as_ref() == Some(x)));
            }
            let free_matrix = free_matrix.map(|m| m.map(|(m, _)| m));
            let free_dq = free_dq.map(|q| q.map(|(q, _)| q));
            compared += 1;
            if let (Some(m), Some(q)) = (free_matrix, free_dq) {
                kept += 1;
                assert!(m == matrix, "the matrix of {:?}", robot.chain);
                assert!(q == dq, "the DQ of {:?}", robot.chain);
                // `seen` was shown every entry of the product, with its offsets.
                let m = m.expect("a product within the limits");
                assert_eq!(seen.len(), 16);
                assert!(seen.iter().all(|(i, j, x)| m.rows[*i][*j] == *x));
            }
        }
        assert!(compared >= 30, "{compared} chains with offsets");
        assert!(
            kept * 10 >= compared * 8,
            "{kept} of {compared} kept offset-free"
        );
    }

    /// The products as `fk` makes them (offset-free where kept, else with the offsets) and
    /// with the offsets, under small term limits, low degree limits (twists and offsets of
    /// fifths, sevenths and ninths of pi mix levels once shifted back) and small work
    /// budgets: where the products with the offsets are made, the route makes the same (a
    /// product given up on it leaves the products with the offsets their whole budget); under
    /// no budget they decide alike (both made or both given up).
    #[test]
    fn the_route_decides_as_the_products_with_the_offsets() {
        let mut next = crate::testing::xorshift_below(71);
        let (mut compared, mut given_up, mut fell_back) = (0, 0, 0);
        for _ in 0..40 {
            let robot = random_chain_of(&mut next, 10);
            for (terms, degree, budget) in [
                (64, 768, None),
                (256, 24, None),
                (20_000, 48, None),
                (20_000, 768, Some(20_000)),
                (20_000, 768, Some(200_000)),
            ] {
                let mut ctx = crate::Context::new().with_max_cyclotomic_degree(degree);
                if let Some(b) = budget {
                    ctx = ctx.with_work_budget(b);
                }
                let run = |offset_free: bool| {
                    let _in = ctx.clone().enter();
                    let joints = robot.joint_dqs();
                    let flag = || AtomicBool::new(false);
                    let mut all = |_: usize, _: usize, _: &Scalar| true;
                    let free = offset_free.then(|| robot.offset_free(&joints)).flatten();
                    // Each product falls back on its own, as in `fk`.
                    let tried = free.as_ref().and_then(|f| {
                        robot
                            .forward_matrix_offset_free(f, terms, &flag(), &mut all)
                            .map(|m| m.map(|(m, _)| m))
                    });
                    let m = tried.clone().unwrap_or_else(|| {
                        let factors = robot.factor_matrices(&joints, EARLY, None);
                        robot.forward_matrix_until(factors, terms, &flag(), &mut all)
                    });
                    let tried_q = free.as_ref().and_then(|f| {
                        robot
                            .forward_within_offset_free(f, terms, &flag())
                            .map(|q| q.map(|(q, _)| q))
                    });
                    let fell = free.is_some() && (tried.is_none() || tried_q.is_none());
                    let q = tried_q.unwrap_or_else(|| {
                        robot.forward_within_until(joints.clone(), terms, &flag())
                    });
                    (m, q, fell)
                };
                let (m0, q0, _) = run(false);
                let (m1, q1, fell) = run(true);
                compared += 1;
                fell_back += usize::from(fell);
                given_up += usize::from(m0.is_none() || q0.is_none());
                if budget.is_none() || m0.is_some() {
                    assert!(
                        m0 == m1,
                        "the matrix of {:?} at {terms}, {degree}",
                        robot.chain
                    );
                }
                if budget.is_none() || q0.is_some() {
                    assert!(q0 == q1, "the DQ of {:?} at {terms}, {degree}", robot.chain);
                }
            }
        }
        assert_eq!(compared, 200);
        assert!(given_up >= 100, "{given_up} given up");
        assert!(fell_back >= 40, "{fell_back} fell back");
    }

    /// The fully symbolic 6R (`tests/data/generic_6r.toml`).
    fn generic_6r() -> Robot {
        let s = |name: &str, i: usize| Scalar::sym(&format!("{name}{i}"));
        let joints = (1..=6)
            .map(|i| Joint::revolute_dh(s("theta", i), s("d", i), s("a", i), s("alpha", i)))
            .collect();
        let variables: Vec<String> = (1..=6).map(|i| format!("q{i}")).collect();
        let values = variables.iter().map(|v| Scalar::sym(v)).collect();
        bare_robot(Convention::Dh, variables, values, Chain::new(joints))
    }

    /// The matrix product as `fk` runs it (with its growth's prediction), its result and the
    /// work it charged, with the entries of each product made in the order of
    /// [`early_first`], or largest first (`largest_first`, the order before it). On a thread
    /// of its own: the per-thread caches (cyclotomic templates, mode products), whose misses
    /// are charged, start empty, so two orders are charged alike for the same entries.
    fn product_in_order(
        robot: &Robot,
        limit: usize,
        largest_first: bool,
    ) -> (Option<Matrix4<Scalar>>, u64) {
        std::thread::scope(|s| {
            s.spawn(|| {
                LARGEST_FIRST.with(|f| f.set(largest_first));
                let _in = crate::Context::new().with_threads(1).enter();
                let joints = robot.joint_dqs();
                let before = crate::scalar::work_used();
                let mut all = |_: usize, _: usize, _: &Scalar| true;
                let factors = robot.factor_matrices(&joints, EARLY, None);
                let stop = AtomicBool::new(false);
                let m = robot.forward_matrix_until(factors, limit, &stop, &mut all);
                (m, crate::scalar::work_used() - before)
            })
            .join()
            .expect("the product")
        })
    }

    /// The product decides as it did when its entries were made largest first, on random
    /// chains (symbolic, numeric and mixed parameters, offsets, prismatic joints) at term
    /// limits below and above `fk`'s: the same matrix, or `None` for both. Made to the end,
    /// it charges the same work whatever the order (the same entries, on fresh per-thread
    /// caches, the process-wide ones filled by a first run); given up, the work differs, and
    /// on the fully symbolic 6R it is less.
    #[test]
    fn making_an_entry_likely_to_stop_the_product_first_decides_the_same() {
        let mut next = crate::testing::xorshift_below(29);
        let (mut made, mut given_up, mut moved) = (0, 0, 0);
        for _ in 0..60 {
            let robot = random_test_chain(&mut next, 8);
            for limit in [100, 1_000, 5_000] {
                let _ = product_in_order(&robot, limit, true);
                let (new, new_work) = product_in_order(&robot, limit, false);
                let (old, old_work) = product_in_order(&robot, limit, true);
                assert!(new == old, "the matrix of {:?} at {limit}", robot.chain);
                if new.is_some() {
                    made += 1;
                    assert_eq!(new_work, old_work, "{:?} at {limit}", robot.chain);
                } else {
                    given_up += 1;
                    moved += usize::from(new_work != old_work);
                }
            }
        }
        assert!(
            made >= 40 && given_up >= 40,
            "{made} made, {given_up} given up"
        );
        assert!(moved >= 5, "{moved} given up after other entries");
        let r6 = generic_6r();
        let (new, new_work) = product_in_order(&r6, 5_000, false);
        let (old, old_work) = product_in_order(&r6, 5_000, true);
        assert!(new.is_none() && old.is_none());
        assert!(new_work < old_work, "{new_work} against {old_work}");
    }

    /// [`early_first`] moves the fewest pairs among the entries whose estimate stops the
    /// product to the front, the first of them on a tie, and leaves the others in order.
    #[test]
    fn early_first_moves_the_cheapest_entry_that_would_stop() {
        let pairs = [9, 7, 5, 5, 2];
        let twice = |(k, _): (usize, usize)| 2 * pairs[k];
        let mut order: Vec<(usize, usize)> = (0..5).map(|k| (k, 0)).collect();
        early_first(&mut order, |(k, _)| pairs[k], twice, &|size| size >= 10);
        assert_eq!(order, [(2, 0), (0, 0), (1, 0), (3, 0), (4, 0)]);
        let mut all = order.clone();
        early_first(&mut all, |(k, _)| pairs[k], twice, &|size| size >= 1);
        assert_eq!(all, [(4, 0), (2, 0), (0, 0), (1, 0), (3, 0)]);
        let mut none: Vec<(usize, usize)> = (0..5).map(|k| (k, 0)).collect();
        early_first(&mut none, |(k, _)| pairs[k], twice, &|size| size >= 100);
        assert_eq!(none, [(0, 0), (1, 0), (2, 0), (3, 0), (4, 0)]);
        // Estimates of their own: the entry of 5 pairs estimated at 4 terms stays.
        let merged = [18, 14, 4, 10, 4];
        let mut some: Vec<(usize, usize)> = (0..5).map(|k| (k, 0)).collect();
        early_first(&mut some, |(k, _)| pairs[k], |(k, _)| merged[k], &|size| {
            size >= 10
        });
        assert_eq!(some, [(3, 0), (0, 0), (1, 0), (2, 0), (4, 0)]);
    }

    /// `MadeJoints::again` gives the factors `joint_dqs` makes, charged the work their
    /// making was; made again on warm caches the factors charge that too (on cold ones, the
    /// first making, at most the cache misses more: see `MadeJoints::again`); under a budget
    /// short of it by one unit they are made anew, with the error values that gives.
    #[test]
    fn joint_factors_kept_are_charged_as_made() {
        let mut next = crate::testing::xorshift_below(33);
        for _ in 0..40 {
            let robot = random_test_chain(&mut next, 8);
            let _in = crate::Context::new().with_threads(1).enter();
            let _ = robot.joint_dqs();
            let made = robot.made_joints();
            let units = made.units_for_tests();
            let before = crate::scalar::work_used();
            let again = robot.joint_dqs();
            assert_eq!(crate::scalar::work_used() - before, units);
            assert!(made.dqs() == again.as_slice());
            let before = crate::scalar::work_used();
            assert!(*made.again(&robot) == *again.as_slice());
            assert_eq!(crate::scalar::work_used() - before, units);
            let tight = || {
                crate::Context::new()
                    .with_threads(1)
                    .with_work_budget(units - 1)
                    .enter()
            };
            let kept = {
                let _t = tight();
                made.again(&robot).into_owned()
            };
            let _t = tight();
            let anew = robot.joint_dqs();
            assert!(kept == anew);
            assert!(anew
                .iter()
                .any(|q| q.components().iter().any(|c| c.as_error().is_some())));
        }
    }

    /// `JointMatrices::matrix` gives the matrix `to_matrix` makes, kept or not; kept, it is
    /// charged the work its making was (made on warm caches, as in
    /// `joint_factors_kept_are_charged_as_made`); under a budget short of that by one unit it
    /// is made anew, with the error values that gives, and a matrix with an error value is
    /// not kept. The products `fk` makes from kept matrices are those made without.
    #[test]
    fn joint_matrices_kept_are_charged_as_made() {
        let mut next = crate::testing::xorshift_below(3131);
        let mut tight_errors = 0;
        for _ in 0..30 {
            let robot = random_test_chain(&mut next, 8);
            let _in = crate::Context::new().with_threads(1).enter();
            let made = robot.made_joints();
            let kept = made.matrices().expect("sound factors").clone();
            for (i, q) in made.dqs().iter().enumerate() {
                let _ = q.to_matrix();
                let before = crate::scalar::work_used();
                let m = q.to_matrix();
                let units = crate::scalar::work_used() - before;
                // Not kept yet: made (and kept), charged as `to_matrix` is.
                let before = crate::scalar::work_used();
                assert!(kept.matrix(i, q) == m);
                assert_eq!(crate::scalar::work_used() - before, units);
                // Kept: the same matrix, the same charge.
                let before = crate::scalar::work_used();
                assert!(kept.matrix(i, q) == m);
                assert_eq!(crate::scalar::work_used() - before, units);
                if units == 0 {
                    continue;
                }
                let tight = || {
                    crate::Context::new()
                        .with_threads(1)
                        .with_work_budget(units - 1)
                        .enter()
                };
                let from_kept = {
                    let _t = tight();
                    kept.matrix(i, q)
                };
                let _t = tight();
                let anew = q.to_matrix();
                assert!(from_kept == anew);
                if anew.rows.iter().flatten().any(|x| x.as_error().is_some()) {
                    tight_errors += 1;
                    // Not kept: a fresh slot stays empty.
                    let fresh = JointMatrices::new(made.dqs().len());
                    let _ = fresh.matrix(i, q);
                    assert!(fresh.0[i].get().is_none());
                }
            }
            // The matrix products of `fk`'s expansion and of the recurrence, from the matrices
            // kept and without.
            let (with, without) = (
                robot.forward_matrix_cos_sin_of(made.dqs(), Some(&kept), 1_000),
                robot.forward_matrix_cos_sin_of(made.dqs(), None, 1_000),
            );
            assert!(with == without);
            let flag = || AtomicBool::new(false);
            let mut all = |_: usize, _: usize, _: &Scalar| true;
            let factors = robot.factor_matrices(made.dqs(), EARLY, Some(&kept));
            let with = robot.forward_matrix_until(factors, 5_000, &flag(), &mut all);
            let factors = robot.factor_matrices(made.dqs(), EARLY, None);
            let without = robot.forward_matrix_until(factors, 5_000, &flag(), &mut all);
            assert!(with == without);
        }
        assert!(tight_errors > 20, "{tight_errors}");
    }

    #[test]
    fn a_joint_whose_variable_is_elsewhere_is_not_shifted() {
        let offset = Scalar::pi() * Scalar::from_ratio(5, 9);
        let right = Scalar::pi() * Scalar::from_ratio(1, 2);
        let (q1, q2) = (Scalar::sym("q1"), Scalar::sym("q2"));
        let chain = |d2: Scalar| {
            Chain::new(vec![
                Joint::revolute_dh(
                    offset.clone(),
                    Scalar::int(1),
                    Scalar::int(0),
                    right.clone(),
                ),
                Joint::revolute_dh(Scalar::int(0), d2, Scalar::sym("a2"), right.clone()),
            ])
        };
        let robot = |d2: Scalar, values: Vec<Scalar>| {
            let variables = vec!["q1".into(), "q2".into()];
            bare_robot(Convention::Dh, variables, values, chain(d2))
        };
        let shifted = |r: &Robot| r.offset_free(&r.joint_dqs()).map(|f| f.shifts.len());
        assert_eq!(
            shifted(&robot(Scalar::int(0), vec![q1.clone(), q2.clone()])),
            Some(1)
        );
        // q1 also the second joint's length, or its value (coupled): no shift.
        assert_eq!(
            shifted(&robot(q1.clone(), vec![q1.clone(), q2.clone()])),
            None
        );
        assert_eq!(
            shifted(&robot(
                Scalar::int(0),
                vec![q1.clone(), q1.clone() * Scalar::int(2)]
            )),
            None
        );
        // A value other than a plain symbol is not shifted.
        assert_eq!(
            shifted(&robot(Scalar::int(0), vec![q1 * Scalar::int(2), q2])),
            None
        );
    }
}
