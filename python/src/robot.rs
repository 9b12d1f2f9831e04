//! `Robot`: a robot file (TOML: classic DH, modified DH or screw form), its forward kinematics,
//! Jacobian and point image as SymPy objects, the `dqsym fk` report in every format, and the
//! NumPy function the project's emitter generates.

use crate::convert::{FromPython, ToSympy};
use crate::errors;
use crate::walk::Walkthrough;
use crate::work::{self, Limits};
use dqsym::{
    app::{Family, FkEntries, Quantity},
    kin::Convention,
    FkOptions, Format, Scalar, Value,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyModule};
use std::ffi::CString;
use std::sync::{Arc, Mutex, PoisonError};

/// What a derivation was asked for: the Jacobian, and the point.
type CacheKey = (bool, Option<[Scalar; 3]>);

/// A robot read from a file: its joints with symbolic variables.
///
/// Safe to share between threads: the robot is immutable, and the one piece of state, the
/// last derivation, is behind a lock held only to read or replace it (two threads asking for
/// the same derivation at once may both compute it; neither waits for the other's).
#[pyclass(module = "dqsym", frozen)]
pub(crate) struct Robot {
    robot: Arc<dqsym::Robot>,
    /// The file's text and name, for walkthroughs.
    text: Arc<str>,
    file: String,
    limits: Limits,
    /// The last derivation, by (Jacobian, point): fk() and fk_matrix() share one.
    cache: Mutex<Option<(CacheKey, Arc<FkEntries>)>>,
    /// What reading a URDF file rounded.
    notes: Vec<String>,
}

fn read_robot(py: Python<'_>, text: &str, file: &str, limits: Limits) -> PyResult<dqsym::Robot> {
    let (t, f) = (text.to_owned(), file.to_owned());
    let (r, interrupted) = work::run(py, limits, None, move || {
        dqsym::parse_robot(&t, &f, &|field: &str| {
            // Each field is evaluated with a budget of its own, as on the command line.
            let _field = dqsym::Context::entered().enter();
            dqsym::eval_scalar_text(field)
        })
    })?;
    if let Some(e) = interrupted {
        return Err(e);
    }
    r.map_err(|e| errors::robot_error(py, &e))
}

/// A URDF file's chain, in screw form; the angles read as multiples of pi/12 are in `notes`.
fn read_urdf(
    py: Python<'_>,
    text: &str,
    file: &str,
    o: dqsym::kin::UrdfOptions,
    limits: Limits,
) -> PyResult<(dqsym::Robot, Vec<String>)> {
    let (t, f) = (text.to_owned(), file.to_owned());
    let (r, interrupted) = work::run(py, limits, None, move || dqsym::parse_urdf(&t, &f, &o))?;
    if let Some(e) = interrupted {
        return Err(e);
    }
    let r = r.map_err(|e| errors::other(py, e.to_string()))?;
    Ok((r.robot, r.notes))
}

impl Robot {
    fn new(py: Python<'_>, text: &str, file: &str, limits: Limits) -> PyResult<Robot> {
        let robot = read_robot(py, text, file, limits)?;
        Ok(Robot::of(robot, text, file, limits, Vec::new()))
    }

    fn of(
        robot: dqsym::Robot,
        text: &str,
        file: &str,
        limits: Limits,
        notes: Vec<String>,
    ) -> Robot {
        Robot {
            robot: Arc::new(robot),
            text: Arc::from(text),
            file: file.to_owned(),
            limits,
            cache: Mutex::new(None),
            notes,
        }
    }

    /// The inverse kinematics solution of the robot.
    fn ik_solution(
        &self,
        py: Python<'_>,
        free: Option<String>,
    ) -> PyResult<Arc<dqsym::ik::IkSolution>> {
        let robot = self.robot.clone();
        let (r, interrupted) = work::run(py, self.limits, None, move || {
            dqsym::ik::solve(
                &robot,
                &dqsym::ik::IkOptions {
                    free,
                    ..Default::default()
                },
            )
            .map(Arc::new)
        })?;
        if let Some(e) = interrupted {
            return Err(e);
        }
        r.map_err(|e| errors::other(py, e.to_string()))
    }

    /// The point argument: None (the file's tool), a "x, y, z" string, or three values.
    fn point_arg(
        &self,
        py: Python<'_>,
        p: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Option<[Scalar; 3]>> {
        let Some(p) = p else {
            return Ok(self.robot.tool.clone());
        };
        if p.is_none() {
            return Ok(self.robot.tool.clone());
        }
        if let Ok(s) = p.extract::<String>() {
            return dqsym::lang::eval_point_text(&s)
                .map(Some)
                .map_err(|m| PyValueError::new_err(format!("point: {m}")));
        }
        let _limits = self.limits.enter();
        match FromPython::new(py)?.value(p, "point")? {
            Value::Vector(v) => Ok(Some(v)),
            other => Err(PyValueError::new_err(format!(
                "point: expected 3 coordinates, found {}",
                other.describe()
            ))),
        }
    }

    /// The closed forms of the report with or without the Jacobian and a point.
    fn entries_of(
        &self,
        py: Python<'_>,
        jacobian: bool,
        point: Option<[Scalar; 3]>,
    ) -> PyResult<Arc<FkEntries>> {
        let key = (jacobian, point.clone());
        if let Some((k, e)) = &*self.cache.lock().unwrap_or_else(PoisonError::into_inner) {
            // A report with the Jacobian holds everything one without it does.
            if *k == key || (k.0 && !key.0 && k.1 == key.1) {
                return Ok(e.clone());
            }
        }
        let robot = self.robot.clone();
        let opts = FkOptions {
            format: Format::Sympy,
            shorthand: true,
            point: point.clone(),
            jacobian,
            max_terms: self.limits.term_limit,
        };
        let (r, interrupted) = work::run(py, self.limits, None, move || {
            dqsym::app::fk_entries(&robot, &opts)
        })?;
        if let Some(e) = interrupted {
            return Err(e);
        }
        let mut r = r.map_err(|e| errors::report_error(py, &e))?;
        // A robot whose file wrote decimals reads in decimals, as `dqsym fk` prints it (the
        // same exact values, the denominators pulled out of sums put back).
        dqsym::app::in_decimals(&self.robot, &mut r.sections);
        let e = Arc::new(r);
        *self.cache.lock().unwrap_or_else(PoisonError::into_inner) = Some((key, e.clone()));
        Ok(e)
    }

    fn expanded(
        &self,
        py: Python<'_>,
        jacobian: bool,
        point: Option<[Scalar; 3]>,
    ) -> PyResult<Arc<FkEntries>> {
        let e = self.entries_of(py, jacobian, point)?;
        if e.recurrence {
            return Err(errors::scalar_error(
                py,
                &dqsym::ScalarError::TooLarge {
                    // The expansion stopped past the limit; its exact size was not computed.
                    terms: self.limits.term_limit + 1,
                    limit: self.limits.term_limit,
                },
            ));
        }
        Ok(e)
    }

    /// The entries of one output (`Family::Dq`: `dq[0]` .. `dq[7]`), in order.
    fn rows(e: &FkEntries, family: Family) -> Vec<&(Quantity, dqsym::Expr)> {
        e.rows().filter(|(n, _)| n.family() == family).collect()
    }
}

#[pymethods]
impl Robot {
    /// Reads a robot file (TOML). Limits as `dqsym fk`'s options (term_limit 5,000: past it
    /// the pose is a recurrence, see `entries`).
    #[staticmethod]
    #[pyo3(signature = (path, term_limit=Limits::FK.term_limit, work_budget=Limits::FK.work_budget))]
    fn from_file(
        py: Python<'_>,
        path: std::path::PathBuf,
        term_limit: usize,
        work_budget: u64,
    ) -> PyResult<Robot> {
        let text = std::fs::read_to_string(&path)
            .map_err(|e| errors::other(py, format!("cannot read {}: {e}", path.display())))?;
        let limits = Limits {
            term_limit,
            work_budget,
            ..Limits::FK
        };
        let name = path.display().to_string();
        let urdf = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("urdf") || e.eq_ignore_ascii_case("xml"));
        if urdf {
            let (r, notes) =
                read_urdf(py, &text, &name, dqsym::kin::UrdfOptions::default(), limits)?;
            return Ok(Robot::of(r, &text, &name, limits, notes));
        }
        Robot::new(py, &text, &name, limits)
    }

    /// Reads the chain of a URDF file's text (screw form), from `base` (the root link) to
    /// `tip` (the only leaf); angles near a multiple of pi/12 are read as that multiple unless
    /// `exact_angles` (then refused), and listed in `notes`.
    #[staticmethod]
    #[pyo3(signature = (text, name="<string>", tip=None, base=None, exact_angles=false, term_limit=Limits::FK.term_limit, work_budget=Limits::FK.work_budget))]
    #[allow(clippy::too_many_arguments)]
    fn from_urdf(
        py: Python<'_>,
        text: &str,
        name: &str,
        tip: Option<String>,
        base: Option<String>,
        exact_angles: bool,
        term_limit: usize,
        work_budget: u64,
    ) -> PyResult<Robot> {
        let limits = Limits {
            term_limit,
            work_budget,
            ..Limits::FK
        };
        let o = dqsym::kin::UrdfOptions {
            tip,
            base,
            snap_angles: !exact_angles,
        };
        let (r, notes) = read_urdf(py, text, name, o, limits)?;
        Ok(Robot::of(r, text, name, limits, notes))
    }

    /// What reading a URDF file rounded (`joint elbow, origin rpy[0]: 1.5708 read as pi/2`).
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }

    /// The closed-form inverse kinematics (`dqsym ik --format sympy`) as a dict from each name
    /// to a SymPy expression: each joint's coefficients (`theta1_a`, ...) and the joint
    /// (`theta1 = atan2(...) + sign_theta1*atan2(...)`, `sign_q` choosing the branch), in the
    /// target `r11 ... r33, px, py, pz`, the parameters and the joints solved before. `free`
    /// names a joint given as a parameter (a 7-joint arm).
    #[pyo3(signature = (free=None))]
    fn ik<'py>(&self, py: Python<'py>, free: Option<String>) -> PyResult<Bound<'py, PyDict>> {
        let text = self.ik_report(py, "sympy", free, false)?;
        // The report's SymPy lines, read with every name bound to a plain Symbol.
        let sympy = py.import("sympy")?;
        let symbol = sympy.getattr("Symbol")?;
        let sympify = sympy.getattr("sympify")?;
        let locals = PyDict::new(py);
        for f in ["atan2", "sqrt", "cos", "sin", "pi"] {
            locals.set_item(f, sympy.getattr(f)?)?;
        }
        let out = PyDict::new(py);
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let Some((name, expr)) = line.split_once(" = ") else {
                continue;
            };
            for word in expr.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
                if word.starts_with(|c: char| c.is_ascii_alphabetic()) && !locals.contains(word)? {
                    locals.set_item(word, symbol.call1((word,))?)?;
                }
            }
            let kw = PyDict::new(py);
            kw.set_item("locals", &locals)?;
            out.set_item(name, sympify.call((expr,), Some(&kw))?)?;
        }
        Ok(out)
    }

    /// The inverse kinematics report (`dqsym ik`): format "plain", "latex", "sympy", "rust",
    /// "c" or "python".
    #[pyo3(signature = (format="plain", free=None, explicit=false))]
    fn ik_report(
        &self,
        py: Python<'_>,
        format: &str,
        free: Option<String>,
        explicit: bool,
    ) -> PyResult<String> {
        use dqsym::Format;
        let sol = self.ik_solution(py, free)?;
        let format = match format {
            "plain" => Format::Plain,
            "latex" => Format::Latex,
            "sympy" => Format::Sympy,
            "rust" => Format::Rust,
            "c" => Format::C,
            "python" | "numpy" => Format::Python,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown format `{other}` (plain, latex, sympy, rust, c, python)"
                )))
            }
        };
        dqsym::ik::ik_report(&sol, format, !explicit).map_err(|e| errors::scalar_error(py, &e))
    }

    /// The inverse kinematics solver the project's emitter generates (Python): `ik(T, **params)`
    /// returns every solution of a 4x4 target pose as joint vectors; `ik_full` and `ik_dq` are
    /// attributes of it, and `source` its text.
    #[pyo3(signature = (free=None))]
    fn ik_function(&self, py: Python<'_>, free: Option<String>) -> PyResult<PyObject> {
        let src = self.ik_report(py, "python", free, false)?;
        let code = CString::new(src.clone()).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let file = CString::new(format!("<dqsym ik {}>", self.robot.name)).unwrap_or_default();
        let module_name = CString::new("dqsym_generated_ik").unwrap_or_default();
        let m = PyModule::from_code(py, &code, &file, &module_name)?;
        let f = m.getattr("ik")?;
        f.setattr("ik_full", m.getattr("ik_full")?)?;
        f.setattr("ik_dq", m.getattr("ik_dq")?)?;
        f.setattr("source", src)?;
        Ok(f.unbind())
    }

    /// Reads a robot from the text of a TOML robot file; `name` stands for the file in messages.
    #[staticmethod]
    #[pyo3(signature = (text, name="<string>", term_limit=Limits::FK.term_limit, work_budget=Limits::FK.work_budget))]
    fn from_toml(
        py: Python<'_>,
        text: &str,
        name: &str,
        term_limit: usize,
        work_budget: u64,
    ) -> PyResult<Robot> {
        Robot::new(
            py,
            text,
            name,
            Limits {
                term_limit,
                work_budget,
                ..Limits::FK
            },
        )
    }

    /// The robot's name.
    #[getter]
    fn name(&self) -> String {
        self.robot.name.clone()
    }

    /// "dh", "mdh", "screw", or "local" (a URDF file whose origins hold angles kept as
    /// parameters: each joint in its own frame).
    #[getter]
    fn convention(&self) -> &'static str {
        match self.robot.convention {
            Convention::Dh => "dh",
            Convention::Mdh => "mdh",
            Convention::Screw => "screw",
            Convention::Local => "local",
        }
    }

    /// The joint variables in joint order.
    #[getter]
    fn variables(&self) -> Vec<String> {
        self.robot.variables.clone()
    }

    /// The other symbols (lengths, offsets), sorted.
    #[getter]
    fn parameters(&self) -> Vec<String> {
        self.robot.parameters()
    }

    /// The forward kinematics: the unit dual quaternion (a `dqsym.DQ`) in closed form.
    fn fk(&self, py: Python<'_>) -> PyResult<PyObject> {
        let e = self.expanded(py, false, None)?;
        let rows: Vec<dqsym::Expr> = Robot::rows(&e, Family::Dq)
            .into_iter()
            .map(|(_, x)| x.clone())
            .collect();
        Ok(ToSympy::new(py)?.dual_quat(&rows)?.unbind())
    }

    /// The forward kinematics as the 4x4 homogeneous matrix (a SymPy Matrix) in closed form:
    /// the product of the joint factors' matrices, as `dqsym fk` prints it.
    fn fk_matrix(&self, py: Python<'_>) -> PyResult<PyObject> {
        let e = self.expanded(py, false, None)?;
        let cells: Vec<dqsym::Expr> = Robot::rows(&e, Family::T)
            .into_iter()
            .map(|(_, x)| x.clone())
            .collect();
        let mut rows: Vec<Vec<dqsym::Expr>> =
            cells.chunks(4).map(<[dqsym::Expr]>::to_vec).collect();
        let num = |n: i64| dqsym::Expr::Num(num_rational::BigRational::from_integer(n.into()));
        rows.push(vec![num(0), num(0), num(0), num(1)]);
        Ok(ToSympy::new(py)?.matrix(&rows)?.unbind())
    }

    /// The 8 x n Jacobian of the DQ components with respect to the joint variables (a SymPy
    /// Matrix), as `dqsym fk --jacobian` prints it.
    fn jacobian(&self, py: Python<'_>) -> PyResult<PyObject> {
        let e = self.expanded(py, true, None)?;
        let n = self.robot.variables.len().max(1);
        let cells: Vec<dqsym::Expr> = Robot::rows(&e, Family::JACOBIAN)
            .into_iter()
            .map(|(_, x)| x.clone())
            .collect();
        let rows: Vec<Vec<dqsym::Expr>> = cells.chunks(n).map(<[dqsym::Expr]>::to_vec).collect();
        Ok(ToSympy::new(py)?.matrix(&rows)?.unbind())
    }

    /// The image of a point of the last link (a 3x1 Matrix): `p` as three values or the text
    /// "x, y, z"; by default the file's `tool`.
    #[pyo3(signature = (p=None))]
    fn point(&self, py: Python<'_>, p: Option<&Bound<'_, PyAny>>) -> PyResult<PyObject> {
        let p = self.point_arg(py, p)?;
        if p.is_none() {
            return Err(PyValueError::new_err(
                "point: the robot file has no `tool`; give the point",
            ));
        }
        let e = self.expanded(py, false, p)?;
        let cells: Vec<Vec<dqsym::Expr>> = Robot::rows(&e, Family::Point)
            .into_iter()
            .map(|(_, x)| vec![x.clone()])
            .collect();
        Ok(ToSympy::new(py)?.matrix(&cells)?.unbind())
    }

    /// Every entry of the `dqsym fk --format sympy` report as a dict from its name (`dq[0]`,
    /// `T[1][3]`, `p[2]`, `J[7][5]`; for a chain past the term limit, the recurrence's
    /// `L1[0]`, `Q2[3]`, ..., entry `X[k]` being the symbol `X_k` of later entries) to a SymPy
    /// expression.
    #[pyo3(signature = (jacobian=false, point=None))]
    fn entries<'py>(
        &self,
        py: Python<'py>,
        jacobian: bool,
        point: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let p = self.point_arg(py, point)?;
        let e = self.entries_of(py, jacobian, p)?;
        ToSympy::new(py)?.dict(&e.named_rows())
    }

    /// The `dqsym fk` report as text: format "plain", "latex", "sympy", "rust", "c", "python"
    /// (the NumPy function) or "ops".
    #[pyo3(signature = (format="plain", jacobian=false, point=None, explicit=false))]
    fn report(
        &self,
        py: Python<'_>,
        format: &str,
        jacobian: bool,
        point: Option<&Bound<'_, PyAny>>,
        explicit: bool,
    ) -> PyResult<String> {
        // None: the operation counts of the generated code.
        let format = match format {
            "plain" => Some(Format::Plain),
            "latex" => Some(Format::Latex),
            "sympy" => Some(Format::Sympy),
            "rust" => Some(Format::Rust),
            "c" => Some(Format::C),
            "python" | "numpy" => Some(Format::Python),
            "ops" => None,
            other => {
                return Err(PyValueError::new_err(format!(
                    "unknown format `{other}` (plain, latex, sympy, rust, c, python, ops)"
                )))
            }
        };
        let point = self.point_arg(py, point)?;
        let robot = self.robot.clone();
        let max_terms = self.limits.term_limit;
        let (r, interrupted) = work::run(py, self.limits, None, move || {
            let o = FkOptions {
                format: format.unwrap_or_default(),
                shorthand: !explicit,
                point,
                jacobian,
                max_terms,
            };
            match format {
                Some(_) => dqsym::fk_report(&robot, &o),
                None => dqsym::app::fk_ops(&robot, &o),
            }
        })?;
        if let Some(e) = interrupted {
            return Err(e);
        }
        r.map_err(|e| errors::report_error(py, &e))
    }

    /// A NumPy function generated by the project's emitter (`report(format="python")`),
    /// vectorized over arrays of configurations: arguments the joint variables in joint order,
    /// then the parameters alphabetically (`numpy_args`); it returns a dict of arrays, `dq`
    /// (S + (8,)), `t` (S + (3, 4), rows 0..2 of the matrix), `p` (S + (3,), with a point) and
    /// `j` (S + (8, n), with `jacobian=True`). Its source is the attribute `source`.
    #[pyo3(signature = (jacobian=false, point=None))]
    fn lambdify(
        &self,
        py: Python<'_>,
        jacobian: bool,
        point: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyObject> {
        let src = self.report(py, "python", jacobian, point, false)?;
        let name = src
            .lines()
            .find_map(|l| l.strip_prefix("def ")?.split('(').next())
            .ok_or_else(|| errors::other(py, "the generated code has no function".into()))?
            .to_owned();
        let code = CString::new(src.clone()).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let file = CString::new(format!("<dqsym {}>", self.robot.name)).unwrap_or_default();
        let module_name = CString::new("dqsym_generated").unwrap_or_default();
        let m = PyModule::from_code(py, &code, &file, &module_name)?;
        let mut f = m.getattr(name.as_str())?;
        // The parameters are the symbols, a name Python or the function reserves renamed
        // (`shape` -> `shape_`, `lambda` -> `lambda_`); the docstring lists each renamed one
        // as `shape_ (the symbol shape)`. The function returned takes the symbols' names.
        let listed = src
            .lines()
            .find_map(|l| l.trim().strip_prefix("Arguments (floats or arrays"))
            .and_then(|l| l.split_once(": "))
            .map(|(_, l)| l.trim_end_matches('.'))
            .unwrap_or_default();
        let mut args: Vec<String> = Vec::new();
        let renamed = PyDict::new(py);
        for item in listed.split(", ").filter(|s| !s.is_empty()) {
            match item.split_once(" (the symbol ") {
                Some((param, sym)) => {
                    let sym = sym.trim_end_matches(')');
                    renamed.set_item(sym, param)?;
                    args.push(sym.to_owned());
                }
                None => args.push(item.to_owned()),
            }
        }
        if !renamed.is_empty() {
            let wrap = PyModule::from_code(py, WRAP_KEYWORDS, c"<dqsym wrap>", c"dqsym_wrap")?;
            f = wrap.getattr("wrap")?.call1((f, renamed))?;
        }
        f.setattr("source", src)?;
        f.setattr("args", args)?;
        Ok(f.unbind())
    }

    /// `lambdify`, under the name NumPy users look for.
    #[pyo3(signature = (jacobian=false, point=None))]
    fn numpy_function(
        &self,
        py: Python<'_>,
        jacobian: bool,
        point: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyObject> {
        self.lambdify(py, jacobian, point)
    }

    /// The derivation step by step (`dqsym walk`): factors in words, products, the check
    /// against plain 4x4 matrices; in Jupyter the HTML page with the drawing.
    fn walk(&self, py: Python<'_>) -> PyResult<Walkthrough> {
        let (text, file) = (self.text.clone(), self.file.clone());
        let (r, interrupted) = work::run(py, self.limits, None, move || {
            dqsym::walk_robot(&text, &file, &|field: &str| {
                let _field = dqsym::Context::entered().enter();
                dqsym::eval_scalar_text(field)
            })
        })?;
        if let Some(e) = interrupted {
            return Err(e);
        }
        r.map(Walkthrough::new)
            .map_err(|e| errors::other(py, e.to_string()))
    }

    fn __repr__(&self) -> String {
        format!(
            "dqsym.Robot({:?}, {} joints: {})",
            self.robot.name,
            self.robot.variables.len(),
            self.robot.variables.join(", ")
        )
    }
}

/// A wrapper that passes keyword arguments named after the symbols to the generated
/// function's renamed parameters. Fixed text: no name from a robot is executed.
const WRAP_KEYWORDS: &std::ffi::CStr = c"import functools


def wrap(f, renamed):
    @functools.wraps(f)
    def call(*args, **kwargs):
        return f(*args, **{renamed.get(k, k): v for k, v in kwargs.items()})

    return call
";
