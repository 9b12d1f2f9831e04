//! The Python extension module `dqsym._dqsym`: a thin layer over the `dqsym` crate.
//!
//! Every computation is the library's; this crate only converts at the boundary (SymPy trees
//! to exact values and closed forms back to SymPy trees, in `convert`), maps errors to Python
//! exceptions (`errors`), and runs the work on a worker thread with the GIL released while the
//! calling thread watches for KeyboardInterrupt (`work`).
//!
//! - `session.rs`: `Session`, `evaluate`, `Output`, `latex`.
//! - `robot.rs`: `Robot` (fk, Jacobian, point, report, NumPy function).
//! - `walk.rs`: `Walkthrough` (text, Markdown, the HTML page for Jupyter).

mod convert;
mod errors;
mod robot;
mod session;
mod walk;
mod work;

use pyo3::prelude::*;

#[pymodule]
fn _dqsym(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("DqsymError", py.get_type::<errors::DqsymError>())?;
    m.add("ParseError", py.get_type::<errors::ParseError>())?;
    m.add("EvalError", py.get_type::<errors::EvalError>())?;
    m.add("LimitError", py.get_type::<errors::LimitError>())?;
    m.add("RobotError", py.get_type::<errors::RobotError>())?;
    m.add_class::<session::Session>()?;
    m.add_class::<session::Output>()?;
    m.add_class::<robot::Robot>()?;
    m.add_class::<walk::Walkthrough>()?;
    m.add_function(wrap_pyfunction!(session::evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(session::latex, m)?)?;
    m.add_function(wrap_pyfunction!(session::text, m)?)?;
    m.add_function(wrap_pyfunction!(walk::walk, m)?)?;
    Ok(())
}
