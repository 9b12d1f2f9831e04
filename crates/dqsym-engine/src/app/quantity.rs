//! The entries and sections of an fk report as data: every entry is a [`Quantity`] (`dq[3]` is
//! `Quantity::Dq(3)`, `T[1][2]` is `Quantity::T(1, 2)`), every section a [`SectionKind`].
//!
//! This module is the one place where they become text: the entry's name in plain text and
//! SymPy ([`Quantity::name`]), the symbol later entries of a recurrence read it by
//! ([`Quantity::symbol`]), its LaTeX ([`Quantity::latex`]), the generated output it belongs to
//! ([`Family::output`]) and the section's title ([`SectionKind::title`]). No reader recognises
//! an entry or a section by its text: they match on these types.

use super::task::TaskJacobian;
use crate::emit::{latex_symbol, Output};
use crate::Expr;

/// The task Jacobian an entry belongs to, by its letters (`J`, `Jr`, `Jt`, ...).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum TaskBase {
    /// `J`: d dq / d q (8 x n).
    Pose,
    /// `Jr`: d r / d q (4 x n).
    Rotation,
    /// `Jt`: d t / d q (4 x n).
    Translation,
    /// `Jg`: the geometric Jacobian in the base frame (6 x n).
    Geometric,
    /// `Jb`: the geometric Jacobian in the end-effector frame (6 x n).
    GeometricBody,
    /// `Jl`: the line Jacobian (8 x n).
    Line,
    /// `Jpi`: the plane Jacobian (8 x n).
    Plane,
    /// `Jd`: a distance Jacobian (1 x n).
    Distance,
}

impl TaskBase {
    /// The letters of its entries: `J` then the superscript (`TaskBase::superscript`).
    pub fn letters(self) -> &'static str {
        match self {
            TaskBase::Pose => "J",
            TaskBase::Rotation => "Jr",
            TaskBase::Translation => "Jt",
            TaskBase::Geometric => "Jg",
            TaskBase::GeometricBody => "Jb",
            TaskBase::Line => "Jl",
            TaskBase::Plane => "Jpi",
            TaskBase::Distance => "Jd",
        }
    }

    /// The superscript of its LaTeX letter (`r` of `J^{r}`), none for the pose Jacobian.
    fn superscript(self) -> Option<&'static str> {
        match self {
            TaskBase::Pose => None,
            b => Some(&b.letters()[1..]),
        }
    }

    /// The one-line documentation of its generated output.
    fn doc(self) -> &'static str {
        match self {
            TaskBase::Pose => "Jacobian d dq[i] / d q[j] (8 x n).",
            TaskBase::Rotation => "Rotation Jacobian d r[i] / d q[j] (4 x n).",
            TaskBase::Translation => {
                "Translation Jacobian d t[i] / d q[j], t = (0, x, y, z) (4 x n)."
            }
            TaskBase::Geometric => "Geometric Jacobian (v; omega), base frame (6 x n).",
            TaskBase::GeometricBody => {
                "Body geometric Jacobian (R^T v; R^T omega), end-effector frame (6 x n)."
            }
            TaskBase::Line => "Line Jacobian d vec8(l + eps t x l)[i] / d q[j] (8 x n).",
            TaskBase::Plane => "Plane Jacobian d vec8(n + eps t . n)[i] / d q[j] (8 x n).",
            TaskBase::Distance => "Distance Jacobian d (squared) distance / d q[j] (1 x n).",
        }
    }
}

/// A task Jacobian's name: its kind and whether it is the time derivative (`Jrdot`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TaskName {
    /// The Jacobian.
    pub base: TaskBase,
    /// Its time derivative `sum_k dJ/dq_k qdot_k`.
    pub derivative: bool,
}

impl TaskName {
    /// `Jr`, `Jrdot`, ...
    pub fn letters(self) -> String {
        let dot = if self.derivative { "dot" } else { "" };
        format!("{}{dot}", self.base.letters())
    }

    /// The one-line documentation of its generated output.
    fn doc(self) -> String {
        let d = self.base.doc();
        if self.derivative {
            format!(
                "Time derivative sum_k d/d q[k] q_dot[k] of the {}",
                lower(d)
            )
        } else {
            d.to_owned()
        }
    }
}

/// A step of the recurrence over the joint factors (`app/recurrence.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Step {
    /// `L{i}`: the joint factor.
    Factor,
    /// `dL{i}`: its derivative by its joint variable.
    FactorDerivative,
    /// `Q{i} = Q{i-1} L{i}`: a prefix product.
    Prefix,
    /// `P{i} = L{i} P{i+1}`: a suffix product.
    Suffix,
}

impl Step {
    fn letters(self) -> &'static str {
        match self {
            Step::Factor => "L",
            Step::FactorDerivative => "dL",
            Step::Prefix => "Q",
            Step::Suffix => "P",
        }
    }
}

/// One entry of an fk report. Indices count from 0 but joints (`joint`) from 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Quantity {
    /// `dq[k]`: component k of the unit DQ (w, x, y, z, w_e, x_e, y_e, z_e).
    Dq(usize),
    /// `T[i][j]`: the homogeneous matrix, rows 0..2.
    T(usize, usize),
    /// `p[k]`: the image of the point.
    Point(usize),
    /// `J[row][col]`: the 8 x n Jacobian of the DQ components.
    J {
        /// The DQ component.
        row: usize,
        /// The joint variable.
        col: usize,
    },
    /// `Jr[row][col]`, `Jdot[row][col]`, `Jd_num[row][col]`: an entry of a task Jacobian (the
    /// pose Jacobian itself is [`Quantity::J`]), or of its numerators over
    /// [`Quantity::TaskDenominator`].
    Task {
        /// The Jacobian.
        name: TaskName,
        /// A numerator over the common denominator.
        numerator: bool,
        /// The task coordinate.
        row: usize,
        /// The joint variable.
        col: usize,
    },
    /// `Jd_den`: the common denominator of a task Jacobian's numerators.
    TaskDenominator(TaskName),
    /// `Jd_b[k]`: `b = D(l . lz)` (k = 0) and d b / d q[k-1] of the line-to-line distance.
    DistanceB(usize),
    /// `Jd_a[k]`: `a = |P(l x lz)|^2` (k = 0) and d a / d q[k-1] of the line-to-line distance.
    DistanceA(usize),
    /// `L{joint}[k]`, `dL{joint}[k]`, `Q{joint}[k]`, `P{joint}[k]`: component k of a step of
    /// the recurrence.
    Step {
        /// Which product.
        step: Step,
        /// The joint, from 1.
        joint: usize,
        /// The DQ component.
        k: usize,
    },
}

/// What [`Quantity::family`] groups: the entries of one generated output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Family {
    /// `dq`.
    Dq,
    /// `T`.
    T,
    /// `p`.
    Point,
    /// A Jacobian (`J`, `Jr`, `Jdot`, ...) or its numerators (`Jd_num`).
    Jacobian {
        /// The Jacobian.
        name: TaskName,
        /// Numerators over a common denominator.
        numerator: bool,
    },
    /// A task Jacobian's common denominator.
    Denominator(TaskName),
    /// `Jd_b`.
    DistanceB,
    /// `Jd_a`.
    DistanceA,
    /// A step of the recurrence for one joint (`Q2`).
    Step(Step, usize),
}

impl Quantity {
    /// An entry of a task Jacobian: [`Quantity::J`] for the pose Jacobian, so that one entry
    /// has one value of this type.
    pub fn task(name: TaskName, numerator: bool, row: usize, col: usize) -> Quantity {
        if name.base == TaskBase::Pose && !name.derivative && !numerator {
            Quantity::J { row, col }
        } else {
            Quantity::Task {
                name,
                numerator,
                row,
                col,
            }
        }
    }

    /// The generated output this entry is part of.
    pub fn family(&self) -> Family {
        match *self {
            Quantity::Dq(_) => Family::Dq,
            Quantity::T(..) => Family::T,
            Quantity::Point(_) => Family::Point,
            Quantity::J { .. } => Family::JACOBIAN,
            Quantity::Task {
                name, numerator, ..
            } => Family::Jacobian { name, numerator },
            Quantity::TaskDenominator(name) => Family::Denominator(name),
            Quantity::DistanceB(_) => Family::DistanceB,
            Quantity::DistanceA(_) => Family::DistanceA,
            Quantity::Step { step, joint, .. } => Family::Step(step, joint),
        }
    }

    /// Its indices, in the order they are written.
    pub fn indices(&self) -> Vec<usize> {
        match *self {
            Quantity::Dq(k) | Quantity::Point(k) | Quantity::DistanceB(k) => vec![k],
            Quantity::DistanceA(k) | Quantity::Step { k, .. } => vec![k],
            Quantity::T(i, j) | Quantity::J { row: i, col: j } => vec![i, j],
            Quantity::Task { row, col, .. } => vec![row, col],
            Quantity::TaskDenominator(_) => Vec::new(),
        }
    }

    /// Its name in plain text, SymPy and Python's `entries`: `dq[3]`, `T[1][2]`, `Q2[3]`,
    /// `Jd_den`.
    pub fn name(&self) -> String {
        let mut s = self.family().base();
        for i in self.indices() {
            s.push_str(&format!("[{i}]"));
        }
        s
    }

    /// The symbol later entries of a recurrence read it by: `Q2[3]` is `Q2_3`.
    pub fn symbol(&self) -> String {
        let mut s = self.family().base();
        for i in self.indices() {
            s.push_str(&format!("_{i}"));
        }
        s
    }

    /// Its LaTeX: `q_{3}`, `T_{1,2}`, `J^{r}_{0,1}`, `\dot{J}_{0,1}` (the letters of `l`); a
    /// step of a recurrence (`Q2[3]`) like its symbol `Q2_3`.
    pub fn latex(&self, l: &Letters) -> String {
        let idx = || {
            self.indices()
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
        };
        let sub = |letter: &str| format!("{letter}_{{{}}}", idx().join(","));
        match *self {
            Quantity::Dq(_) => sub(l.dq),
            Quantity::T(..) => sub(l.t),
            Quantity::Point(_) => sub(l.p),
            Quantity::J { .. } => sub(l.j),
            Quantity::Task {
                name,
                numerator: false,
                ..
            } => match (name.base.superscript(), name.derivative) {
                (Some(s), false) => {
                    format!("{}^{{{}}}_{{{}}}", l.j, latex_symbol(s), idx().join(","))
                }
                (None, true) => format!("\\dot{{{}}}_{{{}}}", l.j, idx().join(",")),
                _ => self.latex_as_symbol(),
            },
            _ => self.latex_as_symbol(),
        }
    }

    /// `X_{i}_{j}` written as the symbol `X_i_j` is (a trailing `_` when there is no index).
    fn latex_as_symbol(&self) -> String {
        let idx: Vec<String> = self.indices().iter().map(usize::to_string).collect();
        latex_symbol(&format!("{}_{}", self.family().base(), idx.join("_")))
    }
}

impl Family {
    /// The 8 x n Jacobian of the DQ components (`J`).
    pub const JACOBIAN: Family = Family::Jacobian {
        name: TaskName {
            base: TaskBase::Pose,
            derivative: false,
        },
        numerator: false,
    };

    /// The name of its entries without their indices: `dq`, `T`, `Jrdot`, `Jd_num`, `Q2`.
    pub fn base(&self) -> String {
        match *self {
            Family::Dq => "dq".to_owned(),
            Family::T => "T".to_owned(),
            Family::Point => "p".to_owned(),
            Family::Jacobian {
                name,
                numerator: false,
            } => name.letters(),
            Family::Jacobian {
                name,
                numerator: true,
            } => format!("{}_num", name.letters()),
            Family::Denominator(name) => format!("{}_den", name.letters()),
            Family::DistanceB => "Jd_b".to_owned(),
            Family::DistanceA => "Jd_a".to_owned(),
            Family::Step(step, joint) => format!("{}{joint}", step.letters()),
        }
    }

    /// The generated output of its entries `v` (in order), for a robot of `n` joint variables.
    pub fn output(&self, v: Vec<Expr>, n: usize) -> Output {
        let step = "A step of the recurrence.";
        match *self {
            Family::Dq => Output::vector(
                "dq",
                "Unit dual quaternion (w, x, y, z, w_e, x_e, y_e, z_e), q = r + eps t r / 2.",
                v,
            ),
            Family::T => Output::matrix(
                "t",
                "Homogeneous matrix, rows 0..2 (the last row is 0 0 0 1).",
                v.chunks(4).map(<[Expr]>::to_vec).collect(),
            ),
            Family::Point => Output::vector("p", "Image of the point.", v),
            Family::Jacobian { name, numerator } => {
                let d = name.doc();
                let doc = if numerator {
                    format!(
                        "Numerators (over `{}_den`) of the {}",
                        name.letters().to_lowercase(),
                        lower(&d)
                    )
                } else {
                    d
                };
                Output::matrix(
                    &self.base().to_lowercase(),
                    &doc,
                    v.chunks(n.max(1)).map(<[Expr]>::to_vec).collect(),
                )
            }
            Family::Denominator(name) => {
                let doc = format!("Common denominator of the {}", lower(&name.doc()));
                match v.first() {
                    Some(e) => Output::scalar(&self.base().to_lowercase(), &doc, e.clone()),
                    None => Output::intermediate(&self.base(), step, v),
                }
            }
            Family::DistanceB | Family::DistanceA | Family::Step(..) => {
                Output::intermediate(&self.base(), step, v)
            }
        }
    }
}

/// Where the matrix of a report comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatrixFrom {
    /// The expanded product of the joint factors' matrices.
    Expanded,
    /// The polynomial in the cosines and sines of the joint matrices (a recurrence).
    CosSin,
    /// The last prefix product of a recurrence.
    LastQ,
}

/// What a section of an fk report holds; its title is [`SectionKind::title`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SectionKind {
    /// The unit DQ; `last_q` in a recurrence.
    Pose {
        /// Read from the last prefix product of a recurrence.
        last_q: bool,
    },
    /// The homogeneous matrix.
    Matrix(MatrixFrom),
    /// The image of the point.
    Point,
    /// The 8 x n Jacobian; `recurrence` from the factors' derivatives.
    Jacobian {
        /// Built from the products of a recurrence.
        recurrence: bool,
    },
    /// The joint factors of a recurrence, the first after the base frame, the last times
    /// the tool frame.
    Factors {
        /// The first factor includes the base frame.
        base: bool,
        /// The last factor includes the tool frame.
        tool: bool,
    },
    /// Their derivatives.
    FactorDerivatives,
    /// The prefix products.
    PrefixProducts,
    /// The suffix products.
    SuffixProducts,
    /// A task Jacobian; `quotient` when its entries are numerators over a denominator.
    Task {
        /// The Jacobian.
        task: Box<TaskJacobian>,
        /// Numerators over a common denominator.
        quotient: bool,
    },
    /// A task Jacobian's common denominator.
    TaskDenominator(TaskName),
    /// `b` of the line-to-line distance and its derivatives.
    DistanceB,
    /// `a` of the line-to-line distance and its derivatives.
    DistanceA,
    /// The line-to-line distance Jacobian as numerators over `Jd_den`.
    DistanceQuotient,
    /// Its denominator.
    DistanceDenominator,
}

impl SectionKind {
    /// The title, the comment line before the section in plain text and LaTeX.
    pub fn title(&self) -> String {
        let dq = "unit dual quaternion (w, x, y, z, w_e, x_e, y_e, z_e)";
        let factors = "joint factors L{i} (unit DQs";
        let s = match self {
            SectionKind::Pose { last_q: false } => dq,
            SectionKind::Pose { last_q: true } => return format!("{dq}: the last Q"),
            SectionKind::Matrix(MatrixFrom::Expanded) => "homogeneous matrix (rows 0..2)",
            SectionKind::Matrix(MatrixFrom::CosSin) => {
                "homogeneous matrix (rows 0..2), from the cos/sin polynomial of the joint matrices"
            }
            SectionKind::Matrix(MatrixFrom::LastQ) => "homogeneous matrix (rows 0..2) of the last Q",
            SectionKind::Point => "image of the point",
            SectionKind::Jacobian { recurrence: false } => "Jacobian d dq[i] / d q[j]",
            SectionKind::Jacobian { recurrence: true } => {
                "Jacobian d dq[k] / d q[i-1]: component k of Q{i-1} dL{i} P{i+1}, Q{0} = P{n+1} = 1"
            }
            SectionKind::Factors { base, tool } => {
                let how = match (base, tool) {
                    (false, false) => "",
                    (false, true) => "; the last one times the tool",
                    (true, false) => "; the first one after the base",
                    (true, true) => "; the first one after the base, the last one times the tool",
                };
                return format!("{factors}{how})");
            }
            SectionKind::FactorDerivatives => {
                "derivatives dL{i} = d L{i} / d q_i of the joint factors"
            }
            SectionKind::PrefixProducts => "prefix products Q{i} = Q{i-1} L{i}, Q{1} = L{1}",
            SectionKind::SuffixProducts => "suffix products P{i} = L{i} P{i+1}, P{n} = L{n}",
            SectionKind::Task {
                task,
                quotient: false,
            } => return task.title(),
            SectionKind::Task {
                task,
                quotient: true,
            } => {
                let name = task.name();
                let num = Family::Jacobian {
                    name,
                    numerator: true,
                };
                return format!(
                    "{}, = {}[i][j] / {}",
                    task.title(),
                    num.base(),
                    Family::Denominator(name).base()
                );
            }
            SectionKind::TaskDenominator(name) => {
                return format!(
                    "the common denominator {}",
                    Family::Denominator(*name).base()
                )
            }
            SectionKind::DistanceB => "b = D(l . lz) and its derivatives d b / d q[j] (entry X[k] is the symbol X_k of later entries)",
            SectionKind::DistanceA => "a = |P(l x lz)|^2 and its derivatives d a / d q[j]; the squared distance is b^2 / a",
            SectionKind::DistanceQuotient => {
                let zero = || [0, 0, 0].map(crate::Scalar::int);
                let t = TaskJacobian::LineToLine(zero(), zero(), zero());
                return format!("{} = Jd_num[0][j] / Jd_den, Jd_num[0][j] = 2 b (d b / d q[j]) a - b^2 (d a / d q[j])", t.title());
            }
            SectionKind::DistanceDenominator => "the common denominator Jd_den = a^2",
        };
        s.to_owned()
    }
}

/// One section of an fk report: what it holds and its entries in order.
#[derive(Clone, Debug)]
pub struct Section {
    /// What the section holds.
    pub kind: SectionKind,
    /// Its entries.
    pub rows: Vec<(Quantity, Expr)>,
}

/// The LaTeX letters of a report's entries (the DQ components, the matrix, the point, the
/// Jacobians), each the first of its candidates that no symbol of the robot is written with:
/// `q_{k}` for the DQ, but `x_{k}` for a robot whose joints are `q1 ... q7`, so no entry is
/// defined in terms of a symbol that looks like itself.
pub struct Letters {
    dq: &'static str,
    t: &'static str,
    p: &'static str,
    j: &'static str,
}

impl Letters {
    /// The letters for a robot whose symbols are `symbols`.
    pub fn avoiding(symbols: impl Iterator<Item = String>) -> Letters {
        // The LaTeX base of every symbol: `q` of `q_{1}`, `\theta` of `\theta_{1}`.
        let taken: std::collections::BTreeSet<String> = symbols
            .map(|n| {
                let t = latex_symbol(&n);
                t.split("_{").next().unwrap_or_default().to_owned()
            })
            .collect();
        let pick = |c: &[&'static str]| {
            c.iter()
                .copied()
                .find(|l| !taken.contains(*l))
                .unwrap_or(c[c.len() - 1])
        };
        Letters {
            dq: pick(&["q", "x", "\\xi", "\\eta", "\\mathsf{q}"]),
            t: pick(&["T", "A", "M", "\\mathsf{T}"]),
            p: pick(&["p", "y", "\\rho", "\\mathsf{p}"]),
            j: pick(&["J", "G", "\\mathcal{J}", "\\mathsf{J}"]),
        }
    }
}

/// `s` with its first letter in lower case.
fn lower(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map_or(String::new(), |f| f.to_lowercase().chain(c).collect())
}
