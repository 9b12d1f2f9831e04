//! The interactive session: rustyline for editing, history and completion; evaluation on a
//! worker thread so that Ctrl-C can abandon a long computation while the bindings stay.
//!
//! Each statement runs in its own thread, the session moved there and back; what the
//! statement binds is undone unless it succeeds, uninterrupted (`Session::checkpoint`). Ctrl-C sets the cancel flag of the statement's
//! execution context, which every scalar operation, closed form and worker thread checks where
//! it charges work: the worker ends within milliseconds, is joined, and its memory is returned
//! before the prompt comes back.

use crate::Limits;
use dqsym::{
    lang::{parse_with, BindingKind, EvalErrorKind, BUILTINS, CONSTANTS},
    show, Session, ShowOptions,
};
use rustyline::completion::{Completer, Pair};
use rustyline::error::ReadlineError;
use rustyline::highlight::Highlighter;
use rustyline::hint::Hinter;
use rustyline::history::DefaultHistory;
use rustyline::validate::Validator;
use rustyline::{Context, Editor, Helper};
use std::collections::BTreeSet;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex};

const PROMPT: &str = "dq> ";
const MORE: &str = "..> ";
const COMMANDS: [&str; 6] = [":help", ":quit", ":vars", ":q", ":steps", ":ik"];

/// Completes commands, built-ins, constants and the names bound so far.
struct DqHelper {
    names: Arc<Mutex<BTreeSet<String>>>,
}

impl Completer for DqHelper {
    type Candidate = Pair;

    fn complete(
        &self,
        line: &str,
        pos: usize,
        _ctx: &Context<'_>,
    ) -> rustyline::Result<(usize, Vec<Pair>)> {
        let head = &line[..pos];
        let start = head
            .rfind(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
            .map_or(0, |i| {
                i + head[i..].chars().next().map_or(1, char::len_utf8)
            });
        let word = &head[start..];
        if word.is_empty() {
            return Ok((pos, Vec::new()));
        }
        let mut out: Vec<Pair> = Vec::new();
        let mut push = |name: &str, call: bool| {
            if name.starts_with(word) {
                let replacement = if call {
                    format!("{name}(")
                } else {
                    name.to_owned()
                };
                out.push(Pair {
                    display: name.to_owned(),
                    replacement,
                });
            }
        };
        COMMANDS.iter().for_each(|c| push(c, false));
        BUILTINS.iter().for_each(|b| push(b.name, true));
        CONSTANTS.iter().for_each(|(c, _)| push(c, false));
        push("syms", false);
        push("halfangle", false);
        if let Ok(names) = self.names.lock() {
            names.iter().for_each(|n| push(n, false));
        }
        out.sort_by(|a, b| a.display.cmp(&b.display));
        out.dedup_by(|a, b| a.display == b.display);
        Ok((start, out))
    }
}

impl Hinter for DqHelper {
    type Hint = String;
}
impl Highlighter for DqHelper {}
impl Validator for DqHelper {}
impl Helper for DqHelper {}

/// Where history is kept: `$XDG_STATE_HOME/dqsym_history`, else `~/.dqsym_history`.
fn history_path() -> Option<std::path::PathBuf> {
    if let Some(dir) = std::env::var_os("XDG_STATE_HOME").filter(|d| !d.is_empty()) {
        return Some(std::path::PathBuf::from(dir).join("dqsym_history"));
    }
    std::env::var_os("HOME").map(|h| std::path::PathBuf::from(h).join(".dqsym_history"))
}

/// The `:help` text: the language in brief, every built-in with an example, the commands.
pub(crate) fn help() -> String {
    let mut s = String::from(
        "dqsym: exact dual quaternions. Statements end at a line break or `;` (`;` also \
         hides the result).\n\
         \n\
         Values and rules\n\
         \x20 (w, x, y, z)      a quaternion;  (x, y, z) a vector;  [a, b; c, d] a matrix\n\
         \x20 I, eps           the dual unit: q + I*q_e is a dual quaternion; I*(x, y, z) = eps (0; x, y, z)\n\
         \x20 pi               the number pi\n\
         \x20 a*b              products keep their order (quaternions do not commute)\n\
         \x20 q'               quaternion conjugate, the same as conj(q)\n\
         \x20 + and -          a scalar may be added to a dual quaternion (points: 1 + I*(0, l, 0)),\n\
         \x20                  not to a quaternion or vector: (c, s, 0, 0) + l1 is an error; write\n\
         \x20                  (c + l1, s, 0, 0), l1*(1, 0, 0, 0), or a dual part I*(...)\n\
         \x20 /                only by nonzero numbers; use inverse(q) for quaternions\n",
    );
    s += &format!(
        "  ^                integer exponents up to {}; negative ones invert\n\
         \n\
         Declarations\n\
         \x20 syms l1 l2 t     declare symbols; names must be declared or assigned before use\n\
         \x20 halfangle c3, s3 = theta3\n\
         \x20                  c3 = cos(theta3/2), s3 = sin(theta3/2); results print in full angles,\n\
         \x20                  c3 = cos(theta3), c12 = cos(theta1 + theta2)\n\
         \x20 x = expr         assign; shown unless the statement ends with `;`\n\
         \x20 expr             shown as `expr = value` and stored in `ans`\n\
         \n\
         Built-ins\n",
        dqsym::Context::entered().max_exponent()
    );
    for b in BUILTINS {
        s += &format!(
            "  {:<44} {}\n  {:<44} e.g. {}\n",
            b.usage, b.doc, "", b.example
        );
    }
    s += "\nCommands\n  :help  this text    :vars  the bindings    :quit  leave (also Ctrl-D)\n  \
           :steps the walkthrough of every statement entered so far that succeeded: factors in \
           words,\n         products, identities applied, closed form, check against 4x4 matrices\n  \
           :ik NAME q1 q2 ... [--free qk]  closed-form inverse kinematics of the chain bound to \
           NAME\n         (a product of joint motions in the variables q1 q2 ...)\n  \
          Ctrl-C abandons the line being typed or the computation running; bindings stay.\n";
    s
}

/// Why `:ik` gave no report (printed after `error: `).
#[derive(Debug, thiserror::Error)]
enum IkCommandError {
    /// The command's words do not read.
    #[error("{0}")]
    Usage(&'static str),
    /// The chain named is bound to another kind of value.
    #[error("`{name}` is {what}, not a dual quaternion")]
    NotDualQuat { name: String, what: String },
    /// The chain named is not bound.
    #[error("`{0}` is not bound")]
    Unbound(String),
    /// The derivation failed.
    #[error(transparent)]
    Ik(#[from] dqsym::ik::IkError),
    /// The report failed (a limit).
    #[error(transparent)]
    Report(#[from] dqsym::ScalarError),
}

/// `:ik NAME q1 q2 ... [--free qk]`: the inverse kinematics of a bound chain DQ.
fn ik_command(session: &Session, cmd: &str, opts: &ShowOptions) -> Result<String, IkCommandError> {
    const USAGE: &str = "usage: :ik NAME q1 q2 ... [--free qk]";
    let mut words: Vec<&str> = cmd.split_whitespace().skip(1).collect();
    let mut free = None;
    if let Some(i) = words.iter().position(|w| *w == "--free") {
        free = Some(
            words
                .get(i + 1)
                .ok_or(IkCommandError::Usage("--free needs a joint variable"))?
                .to_string(),
        );
        words.drain(i..i + 2);
    }
    let (name, vars) = words.split_first().ok_or(IkCommandError::Usage(USAGE))?;
    if vars.is_empty() {
        return Err(IkCommandError::Usage(
            "usage: :ik NAME q1 q2 ... [--free qk] (name the joint variables)",
        ));
    }
    let q = match session.get(name) {
        Some(dqsym::Value::DualQuat(q)) => q.clone(),
        Some(v) => {
            return Err(IkCommandError::NotDualQuat {
                name: name.to_string(),
                what: v.describe(),
            })
        }
        None => return Err(IkCommandError::Unbound(name.to_string())),
    };
    let vars: Vec<String> = vars.iter().map(|v| v.to_string()).collect();
    let _derivation = dqsym::Context::entered().enter();
    let sol = dqsym::ik::solve_dq(
        name,
        &q,
        &vars,
        &dqsym::ik::IkOptions {
            free,
            ..Default::default()
        },
    )?;
    // The report, in LaTeX or SymPy when those are the session's format, else in plain text.
    let format = match opts.format {
        f @ (dqsym::Format::Latex | dqsym::Format::Sympy) => f,
        _ => dqsym::Format::Plain,
    };
    Ok(dqsym::ik::ik_report(&sol, format, !opts.explicit)?)
}

/// The `:vars` listing.
fn vars(session: &Session) -> String {
    let mut s = String::new();
    for (name, b) in session.bindings() {
        let what = match &b.kind {
            BindingKind::Symbol => "symbol".to_owned(),
            BindingKind::HalfAngle { .. } => b.kind.half_angle_meaning().unwrap_or_default(),
            _ => b.value.describe(),
        };
        s += &format!("  {name}: {what}\n");
    }
    if s.is_empty() {
        s = "  (no bindings)\n".to_owned();
    }
    s
}

/// Why a statement failed: Ctrl-C stopped it, or an error to print.
enum Failure {
    Interrupted,
    Error(String),
}

/// What a worker sends back for one statement: the session, the names it newly bound, and
/// the result.
type Outcome = (Session, Vec<String>, Result<Option<String>, Failure>);

/// The state of one interactive session.
struct Repl<'a> {
    session: Session,
    /// The lines of a statement still open (a bracket, a trailing `...`).
    buffer: String,
    /// The inputs that ran without error, replayed by `:steps`.
    entered: String,
    opts: &'a ShowOptions,
    limits: &'a Limits,
    /// The context statements run in: the command line's limits and the Ctrl-C flag.
    ctx: dqsym::Context,
    interrupt: Arc<AtomicBool>,
    /// The bound names, for completion: grown by each statement's new names (never a copy
    /// of every name per statement).
    names: Arc<Mutex<BTreeSet<String>>>,
}

/// What to do after one line.
enum Next {
    Continue,
    Quit,
}

/// Runs the REPL until `:quit` or end of input.
pub(crate) fn run(opts: &ShowOptions, limits: &Limits) -> ExitCode {
    let interrupt = Arc::new(AtomicBool::new(false));
    {
        let flag = interrupt.clone();
        // Without a handler Ctrl-C during a computation would end the process; if one cannot
        // be installed the REPL still works, only without that.
        let _ = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst));
    }
    let names = Arc::new(Mutex::new(BTreeSet::new()));
    let mut editor: Editor<DqHelper, DefaultHistory> = match Editor::new() {
        Ok(e) => e,
        Err(e) => {
            eprintln!("error: cannot start the line editor: {e}");
            return ExitCode::FAILURE;
        }
    };
    editor.set_helper(Some(DqHelper {
        names: names.clone(),
    }));
    let history = history_path();
    if let Some(h) = &history {
        let _ = editor.load_history(h);
    }
    let mut repl = Repl {
        session: Session::new(),
        buffer: String::new(),
        entered: String::new(),
        opts,
        limits,
        ctx: limits.context().clone().with_cancel_flag(interrupt.clone()),
        interrupt,
        names,
    };
    let mut status = ExitCode::SUCCESS;
    'read: loop {
        let prompt = if repl.buffer.is_empty() { PROMPT } else { MORE };
        let input = match editor.readline(prompt) {
            Ok(l) => l,
            Err(ReadlineError::Interrupted) => {
                repl.buffer.clear();
                continue;
            }
            Err(ReadlineError::Eof) => break,
            Err(e) => {
                // The terminal cannot be read or written (the prompt goes to stdout).
                eprintln!("error: {e}");
                status = ExitCode::FAILURE;
                break;
            }
        };
        // Pasted text (bracketed paste) arrives as one input with line breaks: it is taken
        // line by line, as if typed.
        for line in input.split('\n') {
            let line = line.strip_suffix('\r').unwrap_or(line);
            if let Next::Quit = repl.line(line, &mut editor) {
                break 'read;
            }
        }
    }
    // Input that ended inside a statement (an open bracket) gets its message, not silence.
    if !repl.buffer.is_empty() {
        let src = std::mem::take(&mut repl.buffer);
        repl.evaluate(&src);
    }
    if let Some(h) = &history {
        let _ = editor.save_history(h);
    }
    status
}

impl Repl<'_> {
    /// Takes one line: a command, or a line of a statement (run once complete).
    fn line(&mut self, line: &str, editor: &mut Editor<DqHelper, DefaultHistory>) -> Next {
        if self.buffer.is_empty() {
            match line.trim() {
                "" => return Next::Continue,
                ":quit" | ":q" | ":exit" => {
                    let _ = editor.add_history_entry(line);
                    return Next::Quit;
                }
                ":help" | ":h" => {
                    let _ = editor.add_history_entry(line);
                    print!("{}", help());
                    return Next::Continue;
                }
                ":vars" => {
                    let _ = editor.add_history_entry(line);
                    print!("{}", vars(&self.session));
                    return Next::Continue;
                }
                ":steps" => {
                    let _ = editor.add_history_entry(line);
                    match dqsym::walk_script(&self.entered, "the statements entered so far")
                        .and_then(|w| dqsym::walk_text(&w))
                    {
                        Ok(t) => print!("{t}"),
                        Err(e) => eprintln!("error: {e}"),
                    }
                    return Next::Continue;
                }
                cmd if cmd.starts_with(":ik ") || cmd == ":ik" => {
                    let _ = editor.add_history_entry(line);
                    let _in = self.ctx.enter();
                    match ik_command(&self.session, cmd, self.opts) {
                        Ok(t) => print!("{t}"),
                        Err(e) => eprintln!("error: {e}"),
                    }
                    return Next::Continue;
                }
                cmd if cmd.starts_with(':') => {
                    eprintln!("error: unknown command `{cmd}`; try :help");
                    return Next::Continue;
                }
                _ => {}
            }
        }
        self.buffer.push_str(line);
        self.buffer.push('\n');
        if dqsym::lang::continues(&self.buffer) {
            return Next::Continue;
        }
        let src = std::mem::take(&mut self.buffer);
        let _ = editor.add_history_entry(src.trim_end());
        if self.evaluate(&src) {
            self.entered.push_str(&src);
        }
        Next::Continue
    }

    /// Parses and runs one input, statement by statement, each on a worker thread; true when
    /// every statement succeeded.
    fn evaluate(&mut self, src: &str) -> bool {
        let program = match parse_with(src, &self.limits.parse_options()) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("{e}");
                return false;
            }
        };
        self.interrupt.store(false, Ordering::SeqCst);
        for stmt in program.statements {
            let (tx, rx) = mpsc::channel::<Outcome>();
            // The session moves to the worker and back (a copy per statement would cost time
            // in proportion to every binding's size); what the statement binds is recorded and
            // undone unless it succeeds, uninterrupted.
            let mut work = std::mem::take(&mut self.session);
            let opts = *self.opts;
            let ctx = self.ctx.clone();
            let source = src.to_owned();
            let spawned = std::thread::Builder::new()
                .stack_size(crate::STACK)
                .spawn(move || {
                    let _watch = crate::watch_stack();
                    let _entered = ctx.enter();
                    work.checkpoint();
                    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        statement(&mut work, &stmt, &opts, &source)
                    }))
                    .unwrap_or_else(|_| {
                        Err(Failure::Error(
                            "error: internal failure in the evaluation".to_owned(),
                        ))
                    });
                    // A computation that finished although Ctrl-C came (a step that does not
                    // look at the flag) still counts as interrupted: it binds nothing.
                    let result = match result {
                        Ok(_) if ctx.is_cancelled() => Err(Failure::Interrupted),
                        r => r,
                    };
                    let added = match result {
                        Ok(_) => work.commit(),
                        Err(_) => {
                            work.rollback();
                            Vec::new()
                        }
                    };
                    let _ = tx.send((work, added, result));
                });
            let worker = match spawned {
                Ok(w) => w,
                Err(e) => {
                    eprintln!("error: cannot start the evaluation: {e}");
                    return false;
                }
            };
            // Ctrl-C reaches the worker through the context: every scalar operation, closed
            // form and worker thread of it stops at its next charge of work, so the worker
            // always answers soon; it is joined so that its memory is gone before the prompt.
            let outcome = rx.recv().ok();
            let _ = worker.join();
            let Some((next, added, result)) = outcome else {
                eprintln!("error: internal failure in the evaluation; the bindings are lost");
                return false;
            };
            self.session = next;
            if let Ok(mut names) = self.names.lock() {
                names.extend(added);
            }
            match result {
                Ok(shown) => {
                    if let Some(text) = shown {
                        print!("{text}");
                    }
                }
                Err(Failure::Interrupted) => {
                    release_freed_memory();
                    eprintln!("{INTERRUPTED}");
                    return false;
                }
                Err(Failure::Error(message)) => {
                    eprintln!("{message}");
                    return false;
                }
            }
        }
        true
    }
}

/// Runs one statement and shows its result.
fn statement(
    work: &mut Session,
    stmt: &dqsym::lang::Stmt,
    opts: &ShowOptions,
    source: &str,
) -> Result<Option<String>, Failure> {
    match work.exec(stmt) {
        Ok(Some(d)) => show(&d, opts).map(Some).map_err(|e| match e {
            dqsym::lang::ShowError::Scalar(dqsym::ScalarError::Cancelled) => Failure::Interrupted,
            e => Failure::Error(e.at(stmt.span).render(source)),
        }),
        Ok(None) => Ok(None),
        Err(e) if matches!(e.kind(), EvalErrorKind::Interrupted) => Err(Failure::Interrupted),
        Err(e) => Err(Failure::Error(e.render(source))),
    }
}

/// The message after Ctrl-C stopped a computation.
const INTERRUPTED: &str = "interrupted; the bindings are unchanged";

/// Hands the memory an abandoned computation freed back to the system at once: mimalloc
/// (the binary's allocator, `main.rs`) otherwise keeps an exited worker's pages, and purges
/// free pages only after a delay.
fn release_freed_memory() {
    extern "C" {
        fn mi_collect(force: bool);
    }
    // SAFETY: mi_collect only frees and purges memory the allocator holds unused (and
    // reclaims the pages of exited threads); every thread may call it at any time.
    unsafe {
        mi_collect(true);
    }
}
