//! Teaching walkthroughs: a derivation as numbered steps, each factor with its meaning in
//! words, each product with its result, each trigonometric identity by name with the terms it
//! combined, the closed form, and a numeric check against plain 4x4 matrices.
//!
//! - `motion.rs`: [`Motion`], a rigid motion described by its geometry, in words and as an
//!   independent 4x4 matrix (the check's oracle); reading the motion of a unit DQ.
//! - `script.rs`: a [`Walkthrough`] from a `.dq` script, by listening to the evaluator.
//! - `robot.rs`: a [`Walkthrough`] from a robot file.
//! - `ik.rs`: [`walk_ik`], the [`Walkthrough`] of a derived inverse kinematics.
//! - `text.rs`: [`walk_text`] and [`walk_markdown`].
//! - `svg.rs`: [`mechanism_svg`], the drawing of the mechanism; `view.rs`: the view it is
//!   seen from (chosen so no link is foreshortened) and where its labels go.
//! - `html.rs`: [`walk_html`], a self-contained page (KaTeX inlined).
//! - `forms.rs`: [`Forms`], the closed form of every scalar shown, computed once by the
//!   builders ([`Walkthrough::prepare`]).
//!
//! Walkthroughs are data; renderers are pure functions of them and never simplify: they look
//! the closed forms up in [`Walkthrough::forms`].

mod check;
mod forms;
mod html;
mod ik;
mod motion;
mod notation;
mod robot;
mod script;
mod svg;
mod text;
mod view;

pub use forms::Forms;
pub use html::{ik_walk_html, is_walk_page, walk_html, KatexAssets, PAGE_MARKER};
pub use ik::walk_ik;
pub use motion::{Motion, Word, Words};
pub use robot::{robot_mechanism, walk_robot, walk_robot_chain, walk_robot_read};
pub use script::walk_script;
pub use svg::{mechanism_svg, Config, SvgOptions};
pub use text::{walk_markdown, walk_text};

use crate::{closed::TraceStep, Value};
use thiserror::Error;

/// A derivation as a list of typed steps.
#[derive(Clone, Debug)]
pub struct Walkthrough {
    /// What is derived: the script's file name or the robot's name.
    pub title: String,
    /// The steps in order; renderers number them from 1.
    pub steps: Vec<Step>,
    /// The chain of the final result, for the drawing (when its factors are known motions).
    pub mechanism: Option<Mechanism>,
    /// The closed forms of the scalars the steps show ([`Walkthrough::prepare`]).
    pub forms: Forms,
}

/// One step of a walkthrough.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum Step {
    /// A notation introduced by the script: `c3 = cos(theta3/2)`.
    Notation {
        /// The names.
        names: Vec<String>,
        /// What they stand for, plain text.
        meaning: String,
    },
    /// A motion (a dual quaternion factor) with its meaning in words.
    Factor {
        /// Its name, or the expression as written.
        name: String,
        /// The value.
        value: Value,
        /// What it does.
        meaning: Words,
    },
    /// A point `1 + eps (0, x, y, z)`, or another value defined along the way.
    Define {
        /// Its name.
        name: String,
        /// The value.
        value: Value,
        /// What it is.
        meaning: Words,
    },
    /// A product of two operands.
    Product {
        /// The left operand as written.
        left: String,
        /// The right operand as written.
        right: String,
        /// The product.
        value: Value,
    },
    /// A point carried by a motion: `q v q‾*` (eq 10) or `transform(q, v)`, with the
    /// trigonometric identities that bring each coordinate to its closed form.
    Transform {
        /// The name of the image (`v2`) or the expression.
        label: String,
        /// The motion as written.
        q: String,
        /// The point as written.
        v: String,
        /// The image point (a point DQ or a vector).
        value: Value,
        /// The half angles of the motion lifted to full angles in the product.
        half_angles: Vec<HalfAngle>,
        /// Each coordinate's trace, for the coordinates that needed identities.
        traces: Vec<ComponentTrace>,
    },
    /// The final closed form.
    Result {
        /// Its name.
        label: String,
        /// The value.
        value: Value,
    },
    /// A part of a derivation told in prose and formulas (the inverse kinematics walkthrough).
    Explain {
        /// Its heading.
        title: Prose,
        /// Prose, lists and formulas, in order.
        blocks: Vec<Block>,
    },
    /// Lines of the page's notation legend beside the shorthands it hands out (what the
    /// target's entries and the parameters are).
    Legend(Vec<Prose>),
    /// A solver run on one pose: every distinct solution with the deviation of its own pose
    /// from the target, computed with independent 4x4 matrices.
    Solutions {
        /// The pose and where its numbers come from.
        what: Prose,
        /// The joint variables, in joint order.
        variables: Vec<String>,
        /// The distinct solutions.
        rows: Vec<SolutionRow>,
    },
    /// The result evaluated at random configurations against plain 4x4 homogeneous matrices.
    Check {
        /// What was compared.
        what: String,
        /// The matrix product used as the oracle, in words.
        oracle: String,
        /// The configurations tried.
        samples: usize,
        /// The largest absolute difference of a coordinate.
        max_deviation: f64,
    },
}

/// Prose in two forms: LaTeX math in `$...$` for Markdown and pages, plain text for terminals.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Prose {
    /// With `$...$` math and `` `code` ``.
    pub tex: String,
    /// Plain text.
    pub plain: String,
}

impl Prose {
    /// Prose with no math: the same text in both forms.
    pub fn text(t: impl Into<String>) -> Prose {
        let t = t.into();
        Prose {
            tex: t.clone(),
            plain: t,
        }
    }
}

/// A piece of an [`Step::Explain`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum Block {
    /// A paragraph.
    Text(Prose),
    /// A bulleted list.
    List(Vec<Prose>),
    /// A display formula (LaTeX, and its plain twin).
    Display(Prose),
    /// Named values, one per row: `a = ...`, or a tuple `k1 = (0, 0, 1)`.
    Formulas(Vec<Shown>),
}

/// A named value of an [`Block::Formulas`]: one closed form or a tuple of them.
#[derive(Clone, Debug)]
pub struct Shown {
    /// A symbol-like name (`a`, `k1`, `beta`).
    pub label: String,
    /// One part, or the entries of a tuple.
    pub parts: Vec<crate::Expr>,
}

/// One distinct solution of a [`Step::Solutions`].
#[derive(Clone, Debug, PartialEq)]
pub struct SolutionRow {
    /// The joint values, in joint order.
    pub q: Vec<f64>,
    /// How many of the solver's branches gave it (more than 1 where branches merge, at a
    /// singularity).
    pub branches: usize,
    /// A singular set was met.
    pub singular: bool,
    /// The largest difference of an entry of its pose from the target's.
    pub deviation: f64,
}

/// A half angle of a motion, and the names the script gave its cosine and sine.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HalfAngle {
    /// The joint symbol, `theta3`.
    pub symbol: String,
    /// The script's names for cos and sin of the half angle (`c3`, `s3`), when it has them.
    pub names: Option<(String, String)>,
}

/// The trace of one coordinate's closed form.
#[derive(Clone, Debug)]
pub struct ComponentTrace {
    /// `v2.y`.
    pub label: String,
    /// The steps of [`closed_form_traced`](crate::closed::closed_form_traced).
    pub steps: Vec<TraceStep>,
}

/// The joints of a chain, for the drawing.
#[derive(Clone, Debug)]
pub struct Mechanism {
    /// The motions, base first.
    pub motions: Vec<Motion>,
    /// The point carried by the chain (the tool), in the home pose, if there is one.
    pub tool: Option<[crate::Scalar; 3]>,
    /// Nominal values of symbolic parameters for the drawing (a robot file's `[values]`).
    pub values: Vec<(String, f64)>,
}

/// Why a walkthrough could not be made.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum WalkError {
    /// The script does not parse or a statement fails; the message is rendered with a caret.
    #[error("{0}")]
    Script(String),
    /// The robot file is invalid.
    #[error(transparent)]
    Robot(#[from] crate::kin::RobotError),
    /// A value could not be shown.
    #[error(transparent)]
    Show(#[from] crate::lang::ShowError),
    /// An exact operation failed.
    #[error(transparent)]
    Scalar(#[from] crate::ScalarError),
    /// A `--config` entry is invalid.
    #[error("{0}")]
    Config(String),
    /// A value has no prepared closed form: the steps were edited after
    /// [`Walkthrough::prepare`].
    #[error("a value of the walkthrough has no closed form prepared (call Walkthrough::prepare)")]
    Unprepared,
    /// The robot's chain is too large to expand and show product by product.
    #[error(
        "{file}: the chain is too large for a walkthrough: its pose expands past {limit} terms \
         (or {budget} term operations); `dqsym fk {file}` derives it, as a recurrence over the \
         joint factors when it is this large"
    )]
    TooLarge {
        /// The robot file.
        file: String,
        /// The largest pose component a walkthrough expands, in terms.
        limit: usize,
        /// The work the size probe may do.
        budget: u64,
    },
}
