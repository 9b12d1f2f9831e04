//! What is wrong with one field of a robot file: the typed reasons behind the message that
//! [`super::RobotError`] prefixes with the file, joint and field.

use crate::ScalarError;
use thiserror::Error;

/// Why a field's expression has no exact value: the error type of a
/// [`FieldEval`](super::FieldEval) (the language's `eval_scalar_text` returns it).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ExprError {
    /// The text does not parse, or its evaluation fails; `message` is the evaluator's.
    #[error("`{text}`: {message}")]
    Invalid {
        /// The field's text.
        text: String,
        /// What the parser or evaluator said.
        message: String,
    },
    /// The text is a value of another kind (a quaternion, a matrix).
    #[error("`{text}` is {kind}, not a number or symbolic expression")]
    NotScalar {
        /// The field's text.
        text: String,
        /// The kind of value it is (`a quaternion`).
        kind: String,
    },
    /// A point written as text `"x, y"` does not have three coordinates.
    #[error("a point needs 3 coordinates separated by commas, found {found}")]
    PointArity {
        /// How many coordinates it has.
        found: usize,
    },
}

/// Why a field of a robot file is wrong (the message after `joint 2, field `axis`:`).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum FieldError {
    /// The field is absent.
    #[error("missing")]
    Missing,
    /// The expression has no exact value.
    #[error(transparent)]
    Expr(#[from] ExprError),
    /// An exact operation on the value failed (an angle without exact cosine, a limit).
    #[error(transparent)]
    Scalar(#[from] ScalarError),
    /// A number literal is infinite or NaN.
    #[error("field `{path}`: `{raw}` is not a finite number")]
    NotFinite {
        /// The dotted path of the field (`joint[2].d`).
        path: String,
        /// The literal as written.
        raw: String,
    },
    /// A bare angle past 2 pi: degrees, most likely.
    #[error(
        "{number} is past 2*pi as an angle in radians: for degrees write \"{number}deg\" \
         (or keep it in radians with --exact-angles)"
    )]
    PastTwoPi {
        /// The angle as a number text.
        number: String,
    },
    /// The field is neither a point nor a frame table.
    #[error("expected a point [\"x\", \"y\", \"z\"] or a table with `xyz` and `rpy`")]
    NotPoint,
    /// An array entry is not a number or an expression text.
    #[error("expected a number or an expression in quotes, found a {found}")]
    NotText {
        /// The TOML type found.
        found: &'static str,
    },
    /// The field is not an array.
    #[error("expected an array, found a {found}")]
    NotArray {
        /// The TOML type found.
        found: &'static str,
    },
    /// A vector field has another number of entries than 3.
    #[error("{name} needs 3 entries, found {found}")]
    Entries {
        /// What the vector is (`axis`, `a point`).
        name: String,
        /// How many entries it has.
        found: usize,
    },
    /// An array of frames holds something else than a table.
    #[error("expected a table")]
    NotTable,
    /// A `base` or `tool` value is not a frame table.
    #[error("expected a table with `xyz` and `rpy`")]
    NotFrames,
    /// A frame table has a key other than `xyz` and `rpy`.
    #[error("unknown key (a frame has `xyz` and `rpy`)")]
    UnknownFrameKey,
    /// An earlier joint has the same variable.
    #[error(
        "`{variable}` is already the variable of joint {joint}; every joint needs a variable of its own"
    )]
    SharedVariable {
        /// The variable.
        variable: String,
        /// The earlier joint, counted from 1.
        joint: usize,
    },
    /// The variable is a constant or a built-in name of the language.
    #[error("`{0}` is a constant or a built-in name of the language, not a joint variable")]
    BuiltinName(String),
    /// A screw joint's `variable` is a plain word that is not a symbol name (`2q`).
    #[error("`{0}` is not a symbol name")]
    NotSymbolName(String),
    /// The field has no symbol to be the joint variable.
    #[error("names no joint variable (it must contain exactly one symbol)")]
    NoVariable,
    /// The field has several symbols that could be the joint variable.
    #[error("names several symbols ({0}); exactly one must be the joint variable")]
    SeveralSymbols(String),
    /// A DH `theta` or `alpha` is not an angle.
    #[error(
        "`{0}` is not an angle (a rational combination of symbols plus a rational multiple of pi)"
    )]
    NotAngle(String),
    /// A symbolic axis whose length is not exactly 1.
    #[error("a symbolic axis must have unit length (x^2 + y^2 + z^2 = 1 exactly)")]
    AxisNotUnit,
    /// A limit was reached while checking a symbolic axis's length.
    #[error("a size limit was reached while checking that the axis has unit length: {0}")]
    AxisLimit(ScalarError),
    /// The axis is the zero vector.
    #[error("the axis is zero")]
    AxisZero,
    /// The joint `type` is not a known kind.
    #[error("unknown joint type `{0}` (expected \"revolute\" or \"prismatic\")")]
    UnknownJointType(String),
    /// A revolute screw joint without `point`.
    #[error("missing (a revolute joint needs a point of its axis)")]
    NoPoint,
    /// A prismatic screw joint with a `point`.
    #[error("a prismatic joint has no point")]
    PrismaticPoint,
}
