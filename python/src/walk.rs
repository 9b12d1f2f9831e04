//! `Walkthrough`: a derivation step by step (`dqsym walk`), as text, Markdown, or the
//! self-contained HTML page (KaTeX inlined, the mechanism drawn), which Jupyter shows inline.

use crate::errors;
use crate::work::{self, Limits};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// A walkthrough: `text`, `markdown`, `html()`; `_repr_html_` shows the page in Jupyter.
#[pyclass(module = "dqsym", frozen)]
pub(crate) struct Walkthrough {
    inner: dqsym::Walkthrough,
}

impl Walkthrough {
    pub(crate) fn new(inner: dqsym::Walkthrough) -> Walkthrough {
        Walkthrough { inner }
    }
}

/// Why the page's KaTeX could not be read (raised as `DqsymError` with this message).
#[derive(Debug)]
enum KatexError {
    /// No folder holds `katex.min.js`.
    NotInstalled,
    /// A file of the folder could not be read.
    Read {
        path: PathBuf,
        error: std::io::Error,
    },
    /// The assets do not form a page (the library's message).
    Assets(dqsym::walk::WalkError),
}

impl std::fmt::Display for KatexError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            KatexError::NotInstalled => f.write_str(
                "KaTeX is not installed (node_modules/katex/dist/katex.min.js): run `npm install \
                 katex` in the dqsym directory (or `bash scripts/test.sh`), or pass katex_dir",
            ),
            KatexError::Read { path, error } => {
                write!(f, "cannot read {}: {error}", path.display())
            }
            KatexError::Assets(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for KatexError {}

/// Where KaTeX's `dist` folder is: `katex_dir`, `$DQSYM_KATEX_DIR`, `node_modules/katex/dist`
/// in the current folder or a parent, or in the source tree the package was built from.
fn katex_dir(given: Option<PathBuf>) -> Result<PathBuf, KatexError> {
    let mut candidates: Vec<PathBuf> = Vec::new();
    candidates.extend(given);
    if let Some(d) = std::env::var_os("DQSYM_KATEX_DIR") {
        candidates.push(PathBuf::from(d));
    }
    if let Ok(cwd) = std::env::current_dir() {
        for dir in cwd.ancestors() {
            candidates.push(dir.join("node_modules/katex/dist"));
        }
    }
    candidates.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("../node_modules/katex/dist"));
    candidates
        .into_iter()
        .find(|d| d.join("katex.min.js").is_file())
        .ok_or(KatexError::NotInstalled)
}

fn katex_assets(given: Option<PathBuf>) -> Result<dqsym::walk::KatexAssets, KatexError> {
    let dir = katex_dir(given)?;
    let read = |name: &str| {
        let path = dir.join(name);
        std::fs::read_to_string(&path).map_err(|error| KatexError::Read { path, error })
    };
    let css = read("katex.min.css")?;
    let js = read("katex.min.js")?;
    let font = |name: &str| std::fs::read(dir.join("fonts").join(name)).ok();
    dqsym::walk::KatexAssets::new(&css, &js, &font).map_err(KatexError::Assets)
}

fn attr_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[pymethods]
impl Walkthrough {
    /// What is derived.
    #[getter]
    fn title(&self) -> String {
        self.inner.title.clone()
    }

    /// Terminal text, as `dqsym walk FILE` prints it.
    #[getter]
    fn text(&self, py: Python<'_>) -> PyResult<String> {
        dqsym::walk_text(&self.inner).map_err(|e| errors::other(py, e.to_string()))
    }

    /// Markdown with LaTeX (`dqsym walk --markdown`).
    #[getter]
    fn markdown(&self, py: Python<'_>) -> PyResult<String> {
        dqsym::walk_markdown(&self.inner).map_err(|e| errors::other(py, e.to_string()))
    }

    /// The self-contained page (`dqsym walk --html`), the mechanism drawn at `config`
    /// (`"theta2=-0.4,a2=0.43"`); KaTeX is read from `katex_dir` or found as `katex_dir` says.
    #[pyo3(signature = (config="", katex_dir=None))]
    fn html(&self, py: Python<'_>, config: &str, katex_dir: Option<PathBuf>) -> PyResult<String> {
        let cfg = dqsym::walk::Config::parse(config)
            .map_err(|e| errors::other(py, format!("config: {e}")))?;
        let assets = katex_assets(katex_dir).map_err(|e| errors::other(py, e.to_string()))?;
        dqsym::walk_html(&self.inner, &assets, &cfg).map_err(|e| errors::other(py, e.to_string()))
    }

    /// The page in an iframe, so that its styles stay apart from the notebook's. Without
    /// KaTeX, the text with a note saying how to get the page.
    fn _repr_html_(&self, py: Python<'_>) -> PyResult<String> {
        match self.html(py, "", None) {
            Ok(page) => Ok(format!(
                "<iframe srcdoc=\"{}\" style=\"width:100%;height:720px;border:1px solid #ddd\" \
                 title=\"{}\"></iframe>",
                attr_escape(&page),
                attr_escape(&self.inner.title)
            )),
            Err(_) => Ok(format!(
                "<p><em>The page needs KaTeX (npm install katex); the text:</em></p><pre>{}</pre>",
                attr_escape(&self.text(py)?)
            )),
        }
    }

    fn _repr_markdown_(&self, py: Python<'_>) -> PyResult<String> {
        self.markdown(py)
    }

    fn __str__(&self, py: Python<'_>) -> PyResult<String> {
        self.text(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "dqsym.Walkthrough({:?}, {} steps)",
            self.inner.title,
            self.inner.steps.len()
        )
    }
}

/// The walkthrough of a script (`src`, the text of a `.dq` script; `title` names it).
#[pyfunction]
#[pyo3(signature = (src, title="script"))]
pub(crate) fn walk(py: Python<'_>, src: &str, title: &str) -> PyResult<Walkthrough> {
    let (s, t) = (src.to_owned(), title.to_owned());
    let (r, interrupted) = work::run(py, Limits::SCRIPT, None, move || dqsym::walk_script(&s, &t))?;
    if let Some(e) = interrupted {
        return Err(e);
    }
    r.map(Walkthrough::new).map_err(|e| match e {
        // Already rendered with line, column and caret.
        dqsym::walk::WalkError::Script(m) => errors::rendered(py, m),
        other => errors::other(py, other.to_string()),
    })
}
