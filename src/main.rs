//! The `dqsym` command line. Only this file does I/O.

// GNU/Linux: the process starts at this file's C `main`, not through the Rust runtime's
// start-up (see `c_main`).
#![cfg_attr(all(target_os = "linux", target_env = "gnu", not(test)), no_main)]

use clap::{Parser, Subcommand, ValueEnum};
use dqsym::{
    lang::{parse_with, show_value, ParseOptions, StmtKind},
    show, Context, Format, PlainOptions, Preset, Session, ShowOptions,
};
use std::io::Write;
use std::process::ExitCode;

/// Every write of the binary to stdout goes through [`write_out`], so these shadow the standard
/// macros in this crate (`repl.rs` included: it is declared below them): a write error (a full
/// disk, an I/O error) ends the process with `error: cannot write output: ...` and status 1,
/// never a panic. A closed pipe ends it quietly before that (see [`quiet_on_closed_pipe`]).
macro_rules! print {
    ($($arg:tt)*) => { $crate::write_out(format_args!($($arg)*)) };
}

/// [`print!`] with a line break (none is written today; the shadow keeps any new one safe).
#[allow(unused_macros)]
macro_rules! println {
    () => { $crate::write_out(format_args!("\n")) };
    ($($arg:tt)*) => { $crate::write_out(format_args!("{}\n", format_args!($($arg)*))) };
}

/// Messages to stderr: a stderr that cannot be written to loses them, but the status the
/// command chose stays (an error's 1), never a panic's 101.
macro_rules! eprintln {
    ($($arg:tt)*) => { $crate::write_err(format_args!("{}\n", format_args!($($arg)*))) };
}

mod allocator;
mod fast_args;
mod repl;
#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod start;

/// Writes to stdout; a failed write ends the process (see [`print!`]).
pub(crate) fn write_out(args: std::fmt::Arguments<'_>) {
    if let Err(e) = std::io::stdout().lock().write_fmt(args) {
        output_failed(&e);
    }
}

/// Writes to stderr, ignoring a failure: there is nowhere left to report it.
pub(crate) fn write_err(args: std::fmt::Arguments<'_>) {
    let _ = std::io::stderr().lock().write_fmt(args);
}

/// Flushes stdout (what is left after the last line break): a failure is the same error as
/// a failed write.
pub(crate) fn flush_out() {
    if let Err(e) = std::io::stdout().lock().flush() {
        output_failed(&e);
    }
}

/// Ends the process after stdout failed: the message on stderr (if it can still be written),
/// status 1. Called from the worker thread too; nothing else is pending then, since every
/// command writes its output last.
pub(crate) fn output_failed(e: &std::io::Error) -> ! {
    if e.kind() != std::io::ErrorKind::BrokenPipe {
        write_err(format_args!(
            "error: cannot write output: {}\n",
            os_message(e)
        ));
    }
    std::process::exit(1)
}

/// An I/O error's message without the ` (os error N)` suffix the standard library adds.
fn os_message(e: &std::io::Error) -> String {
    let m = e.to_string();
    match m.rfind(" (os error ") {
        Some(i) if m.ends_with(')') => m[..i].to_owned(),
        _ => m,
    }
}

#[derive(Parser, Debug, PartialEq)]
#[command(
    name = "dqsym",
    version,
    about = "Exact symbolic dual quaternions for robot kinematics",
    after_help = "Without a command or -e, dqsym starts an interactive session (type :help)."
)]
struct Cli {
    /// Evaluate one expression (or `;`-separated statements) and print its closed form. Free
    /// names are symbols here.
    #[arg(short = 'e', value_name = "EXPR", allow_hyphen_values = true)]
    expr: Option<String>,
    /// Output format of -e, run, fk and the REPL [default: plain].
    #[arg(long, value_enum, global = true)]
    format: Option<OutputFormat>,
    /// Print cos(theta1 + theta2) instead of the shorthand c12.
    #[arg(long, global = true)]
    explicit: bool,
    /// The most terms an expanded scalar may have; larger results are errors, not hangs
    /// [default: 20000, and 5000 for fk].
    #[arg(long, value_name = "N", global = true)]
    term_limit: Option<usize>,
    /// The deepest nesting of brackets and operators a script may have.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_DEPTH, global = true,
          value_parser = clap::value_parser!(u16).range(1..=MAX_MAX_DEPTH))]
    max_depth: u16,
    /// The largest exponent `^` accepts, in absolute value.
    #[arg(long, value_name = "N", default_value_t = dqsym::scalar::DEFAULT_MAX_EXPONENT, global = true)]
    max_exponent: u64,
    /// The largest degree of the cyclotomic field in which constants at rational multiples
    /// of pi (cos(pi/7), x + 3 pi/29) are computed exactly; a larger one is an error.
    #[arg(long, value_name = "N", default_value_t = dqsym::scalar::DEFAULT_MAX_CYCLOTOMIC_DEGREE, global = true)]
    max_cyclotomic_degree: u64,
    /// The most decimal digits a computed number (a numerator or denominator) may have; a
    /// larger one is an error, not a computation that eats memory.
    #[arg(long, value_name = "N", default_value_t = dqsym::scalar::DEFAULT_MAX_DIGITS, global = true)]
    max_digits: u64,
    /// The most symbols one angle may hold (`cos(q1 + ... + qn)` of a chain of collinear
    /// joints); more is an error (fk then prints a recurrence).
    #[arg(long, value_name = "N", default_value_t = dqsym::scalar::DEFAULT_MAX_ANGLE_SYMBOLS, global = true)]
    max_angle_symbols: usize,
    /// The most term operations (terms of sums, term pairs of products) one statement, one
    /// robot file field or the whole fk derivation may do; more is an error, not a hang.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_WORK_BUDGET, global = true)]
    work_budget: u64,
    /// The largest input file (script, robot file, URDF) read, in bytes; a larger one is an
    /// error before it is read whole.
    #[arg(long, value_name = "BYTES", default_value_t = DEFAULT_MAX_INPUT_SIZE, global = true)]
    max_input_size: u64,
    #[command(subcommand)]
    command: Option<Command>,
}

/// The default `--max-input-size`: 16 MB, ten times a URDF of 10,000 joints (1.5 MB), which is
/// already past what the derivation takes at the default limits.
const DEFAULT_MAX_INPUT_SIZE: u64 = 16 << 20;

/// `--max-input-size`, set once by [`dispatch`] before any file is read (a setting of this
/// binary's one run, so that every reader sees it without threading it through each command).
static MAX_INPUT_SIZE: std::sync::OnceLock<u64> = std::sync::OnceLock::new();

/// Reads an input file as text, at most `--max-input-size` bytes: a device (`/dev/zero`) or a
/// huge file is an error after that many bytes, not a read until memory runs out.
fn read_input(path: &std::path::Path) -> Result<String, String> {
    use std::io::Read;
    let limit = *MAX_INPUT_SIZE.get_or_init(|| DEFAULT_MAX_INPUT_SIZE);
    let cannot = |e: std::io::Error| format!("cannot read {}: {}", path.display(), os_message(&e));
    let file = std::fs::File::open(path).map_err(cannot)?;
    let too_large = || {
        format!(
            "{}: larger than the input size limit of {limit} bytes (--max-input-size)",
            path.display()
        )
    };
    // A regular file's length sizes the buffer: read in one call, not in reads of 32, 64,
    // 128, ... bytes (seven for the PUMA 560's robot file).
    let size = file
        .metadata()
        .ok()
        .filter(std::fs::Metadata::is_file)
        .map(|m| m.len());
    if size.is_some_and(|n| n > limit) {
        return Err(too_large());
    }
    let mut bytes =
        Vec::with_capacity(size.map_or(0, |n| usize::try_from(n).unwrap_or(0).saturating_add(1)));
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "cannot read {}: not UTF-8 text (byte {})",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })
}

#[derive(Subcommand, Debug, PartialEq)]
enum Command {
    /// Run a .dq script and print each displayed result.
    Run {
        /// The script.
        file: std::path::PathBuf,
    },
    /// Derive and print the paper's worked examples (sec 6) and the PUMA 560 pose.
    Paper,
    /// A derivation step by step: each factor with its meaning, each product, each identity
    /// applied, the closed form, and the check against 4x4 matrices. FILE is a .dq script or
    /// a robot .toml file.
    Walk {
        /// The script or robot file.
        file: std::path::PathBuf,
        /// Markdown with LaTeX instead of terminal text.
        #[arg(long, conflicts_with = "html")]
        markdown: bool,
        /// Write a self-contained web page (KaTeX inlined from node_modules/katex, and a
        /// drawing of the mechanism) to OUT.html.
        #[arg(long, value_name = "OUT.html")]
        html: Option<std::path::PathBuf>,
        /// With --html: write over an existing OUT.html that is not a page dqsym wrote (or is a
        /// symbolic link). The input file is never written over.
        #[arg(long, requires = "html")]
        force: bool,
        /// The configuration drawn on the page: `theta1=0.3,theta2=-0.5,l1=2`; joints not
        /// given take a fixed default, lengths 1.
        #[arg(long, value_name = "NAME=VALUE,...")]
        config: Option<String>,
        /// The inverse kinematics of a robot file instead: the axes, the decisions, each
        /// subproblem and branch, a numeric check (text or --markdown).
        #[arg(long)]
        ik: bool,
        /// With --ik: a joint variable given as a parameter.
        #[arg(long, value_name = "VARIABLE", requires = "ik")]
        free: Option<String>,
        #[command(flatten)]
        robot_args: RobotArgs,
    },
    /// Forward kinematics of a robot file (TOML: dh, mdh or screw convention; or URDF) in closed form:
    /// the unit DQ and the 4x4 matrix; with --point the image of a point, with --jacobian the
    /// 8 x n Jacobian of the DQ components.
    Fk {
        /// The robot description file.
        robot: std::path::PathBuf,
        /// A point of the last link, "x, y, z" (default: the file's tool point, if any).
        #[arg(long, value_name = "X, Y, Z")]
        point: Option<String>,
        /// Add the 8 x n Jacobian d dq[i] / d q[j]; `--jacobian=KIND` gives instead a task
        /// Jacobian: geometric (6 x n: the end-effector origin's velocity over the angular
        /// velocity, base frame), geometric_body (the same in the end-effector frame), or one
        /// of DQ Robotics: pose (the same 8 x n), rotation, translation,
        /// line[:X,Y,Z], plane[:X,Y,Z] (end-effector direction, default z), distance,
        /// point_to_point:X,Y,Z, point_to_line:DX,DY,DZ,PX,PY,PZ, point_to_plane:NX,NY,NZ,PX,PY,PZ
        /// (workspace point, line, plane), or pose_derivative (a function of q and the rates
        /// <q>_dot).
        #[arg(long, value_name = "KIND", num_args = 0..=1, require_equals = true, default_missing_value = "")]
        jacobian: Option<String>,
        #[command(flatten)]
        robot_args: RobotArgs,
    },
    /// Convert a URDF file to a robot file (screw form) that fk reads to the same pose.
    Convert {
        /// The URDF file.
        robot: std::path::PathBuf,
        /// The output format.
        #[arg(long, value_enum, default_value_t = ConvertTo::Toml)]
        to: ConvertTo,
        #[command(flatten)]
        robot_args: RobotArgs,
    },
    /// Inverse kinematics of a robot file in closed form: the family decided exactly from the
    /// axes, every joint as atan2 of closed forms, every branch; --format rust, c or python
    /// emit a solver returning every solution for a target pose.
    Ik {
        /// The robot description file.
        robot: std::path::PathBuf,
        /// A joint variable given as a parameter (7-joint arms): `--free theta3`.
        #[arg(long, value_name = "VARIABLE")]
        free: Option<String>,
        /// The method: auto (a special family when one applies, else the general 6R
        /// elimination), family (the special families only), general (the elimination).
        #[arg(long, value_name = "METHOD", default_value = "auto", value_parser = ["auto", "family", "general"])]
        method: String,
        #[command(flatten)]
        robot_args: RobotArgs,
    },
    /// Operation counts: the paper's Tables 1 and 2, counted by running the products (with the
    /// corrections of ERRATA 10 and 11); with a robot file, also its generated forward kinematics.
    Ops {
        /// A robot description file.
        robot: Option<std::path::PathBuf>,
        /// Count the Jacobian too.
        #[arg(long)]
        jacobian: bool,
        #[command(flatten)]
        robot_args: RobotArgs,
    },
}

/// How a robot is read: the one argument group of every command that reads a robot (`fk`,
/// `ik`, `walk` with or without `--ik`, `ops`, `convert`), passed whole to [`load_robot`] so
/// that each option means the same everywhere (the URDF options are errors on a TOML file).
#[derive(clap::Args, Clone, Debug, Default, PartialEq)]
struct RobotArgs {
    /// URDF: the last link of the chain (default: the only leaf link).
    #[arg(long, value_name = "LINK")]
    tip: Option<String>,
    /// URDF: the first link of the chain (default: the root link).
    #[arg(long, value_name = "LINK")]
    base: Option<String>,
    /// Take angles as written, in radians: a robot file's decimals and URDF angles are not
    /// read as multiples of pi/12 (1.5708 as pi/2, within the tolerance of their decimals),
    /// a robot file's bare angle past 2 pi is not refused (URDF: every nonzero angle becomes
    /// a named parameter, its decimal the nominal value).
    #[arg(long)]
    exact_angles: bool,
}

/// The output formats of `convert`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ConvertTo {
    /// A robot file (TOML, screw form).
    Toml,
}

/// Whether `path` names a URDF file (by its extension).
fn is_urdf(path: &std::path::Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("urdf") || e.eq_ignore_ascii_case("xml"))
}

/// Reads a robot file or a URDF file; the angles a URDF file rounds are reported on stderr.
fn load_robot(path: &std::path::Path, args: &RobotArgs) -> Result<dqsym::Robot, String> {
    let text = read_input(path)?;
    let name = path.display().to_string();
    if is_urdf(path) {
        let o = dqsym::kin::UrdfOptions {
            tip: args.tip.clone(),
            base: args.base.clone(),
            snap_angles: !args.exact_angles,
        };
        let r = dqsym::parse_urdf(&text, &name, &o).map_err(|e| e.to_string())?;
        for n in &r.notes {
            eprintln!("note: {n}");
        }
        Ok(r.robot)
    } else {
        urdf_only(args)?;
        let o = dqsym::kin::RobotOptions {
            exact_angles: args.exact_angles,
        };
        let r = dqsym::kin::parse_robot_with(&text, &name, &dqsym::eval_scalar_text, &o)
            .map_err(|e| e.to_string())?;
        for n in &r.notes {
            eprintln!("note: {n}");
        }
        Ok(r)
    }
}

/// The URDF options are errors on any other file (never silently dropped).
fn urdf_only(args: &RobotArgs) -> Result<(), String> {
    if args.tip.is_some() || args.base.is_some() {
        return Err("--tip and --base apply to URDF files only".into());
    }
    Ok(())
}

/// The output formats of `--format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum OutputFormat {
    /// Plain text in robotics notation (c12 = cos(theta1 + theta2)).
    Plain,
    /// LaTeX.
    Latex,
    /// Rust source.
    Rust,
    /// Text that SymPy's sympify parses.
    Sympy,
    /// C99 source.
    C,
    /// Python source (NumPy, vectorized).
    Python,
}

/// The command line's names for the library's one output format.
impl From<OutputFormat> for Format {
    fn from(f: OutputFormat) -> Format {
        match f {
            OutputFormat::Plain => Format::Plain,
            OutputFormat::Latex => Format::Latex,
            OutputFormat::Rust => Format::Rust,
            OutputFormat::Sympy => Format::Sympy,
            OutputFormat::C => Format::C,
            OutputFormat::Python => Format::Python,
        }
    }
}

/// The options for the library's printers.
fn show_options(format: OutputFormat, explicit: bool) -> Result<ShowOptions, String> {
    Ok(ShowOptions {
        format: format.into(),
        explicit,
    })
}

/// Deep but legal inputs recurse up to the parser's depth limit in the evaluator and the
/// printers; a large stack makes that safe in debug builds too.
pub(crate) const STACK: usize = 256 << 20;

/// The default `--max-depth`, the parser's own default (256 fits in a `u16`).
const DEFAULT_MAX_DEPTH: u16 = dqsym::lang::DEFAULT_MAX_DEPTH as u16;

/// The largest `--max-depth`: the evaluator and printers recurse once per level, and this many
/// levels fit in [`STACK`] with room to spare even in debug builds.
const MAX_MAX_DEPTH: i64 = 4096;

/// The default `--work-budget`, that of every [`Preset`] (its docs say why).
const DEFAULT_WORK_BUDGET: u64 = Preset::Script.work_budget();

/// The limits of the command line: the parser's depth and the execution context every
/// evaluation runs in.
#[derive(Clone, Debug)]
pub(crate) struct Limits {
    max_depth: usize,
    ctx: Context,
}

impl Limits {
    /// The parser's options.
    pub(crate) fn parse_options(&self) -> ParseOptions {
        ParseOptions {
            max_depth: self.max_depth,
            ..ParseOptions::default()
        }
    }

    /// The execution context of every evaluation.
    pub(crate) fn context(&self) -> &Context {
        &self.ctx
    }
}

/// The library's default context with the threads of [`threads_from_env`]: what every
/// command's limits are set on, and what the helper threads are started under.
fn base_context() -> Context {
    let base = Context::new();
    match threads_from_env() {
        Some(n) => base.with_threads(n),
        None => base,
    }
}

/// The threads of parallel maps: `DQSYM_THREADS` if set (at least 1), else the library's
/// default (the available cores, at most 8).
fn threads_from_env() -> Option<usize> {
    std::env::var("DQSYM_THREADS")
        .ok()
        .and_then(|s| s.trim().parse::<usize>().ok())
        .map(|n| n.max(1))
}

// The unwinder (panics, backtraces) linked in from libgcc's static `libgcc_eh.a` where the C
// compiler has it (`build.rs`), not loaded from `libgcc_s.so.1`: one shared library fewer to
// find, map and relocate at every start, and its constructor, which probes the processor with
// `cpuid` (costly in a virtual machine), never runs: ~0.1 ms of a run. The same libgcc code,
// as in `-static-libgcc` builds. With LLD, Rust's linker here, the archive's members answer
// the standard library's references although it comes first on the command line, and
// `libgcc_s.so.1`, no longer needed, is dropped (`--as-needed`); another linker takes them
// from `libgcc_s.so.1` as before.
#[cfg(static_unwinder)]
#[link(name = "gcc_eh", kind = "static", modifiers = "-bundle")]
extern "C" {}

/// The allocator of the command line (`allocator.rs` says why).
#[global_allocator]
static ALLOCATOR: allocator::MiMalloc = allocator::MiMalloc;

/// Writing to a closed pipe (`dqsym fk robot.toml | head -1`) ends the process quietly, as it
/// ends `cat`: the default action of SIGPIPE, which the Rust runtime sets to "ignore" (every
/// `print!` would then panic on the broken pipe).
#[cfg(unix)]
fn quiet_on_closed_pipe() {
    extern "C" {
        fn signal(signum: std::ffi::c_int, handler: usize) -> usize;
    }
    const SIGPIPE: std::ffi::c_int = 13;
    const SIG_DFL: usize = 0;
    // SAFETY: restores the default disposition of one signal before any thread exists.
    unsafe {
        signal(SIGPIPE, SIG_DFL);
    }
}

#[cfg(not(unix))]
fn quiet_on_closed_pipe() {}

/// The process's entry on GNU/Linux: C's `main`, called by glibc, instead of the Rust
/// runtime's start-up and `fn main`. That start-up found the main thread's stack for its
/// stack-overflow report by reading `/proc/self/maps`, ~0.1 ms of every run (`start.rs`);
/// the main thread here only starts the worker and waits. What the binary needs of the
/// start-up is done here and on the worker ([`watch_stack`]); the arguments reach
/// `std::env::args_os` as before (glibc hands them to the standard library before `main`).
#[cfg(all(target_os = "linux", target_env = "gnu", not(test)))]
#[export_name = "main"]
extern "C" fn c_main(
    _argc: std::ffi::c_int,
    _argv: *const *const std::ffi::c_char,
) -> std::ffi::c_int {
    start::open_standard_descriptors();
    start::one_malloc_arena();
    // The engine's helper threads report a stack overflow as the evaluating threads do.
    dqsym::scalar::on_helper_start(|| Box::new(start::watch_stack()));
    let code = run();
    // What is left in stdout when the worker did not end the process (it failed): the
    // runtime flushed it at exit.
    let _ = std::io::stdout().flush();
    status(code)
}

#[cfg(any(not(all(target_os = "linux", target_env = "gnu")), test))]
fn main() -> ExitCode {
    run()
}

/// While the value lives, a stack overflow of this thread is reported (`start.rs`).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
pub(crate) fn watch_stack() -> Option<start::Watch> {
    start::watch_stack()
}

/// Elsewhere than on GNU/Linux, the Rust runtime reports every thread's stack overflow.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub(crate) fn watch_stack() {}

/// Runs the command line: on a worker thread with a [`STACK`] stack.
fn run() -> ExitCode {
    quiet_on_closed_pipe();
    // The command line is parsed on the worker too: every allocation of a run is then of one
    // thread's heap, and the pages of the allocator's size classes are touched once, not once
    // per thread (`dqsym -e 1`: 261 page faults instead of 278). The common forms are read
    // without building clap's command (`fast_args.rs` says why); clap reads the others and
    // writes every help, version and error.
    // fk's closed forms are found in parallel once its robot is read and its matrices
    // multiplied: the worker asks this thread, which only waits, to start the engine's helper
    // threads as soon as it has read an `fk` command, and they start meanwhile, on another
    // core (reading the cgroup files for the number of cores, mapping each helper's stack,
    // the helper's own start-up), instead of on the worker when its first parallel stage
    // needs them (PUMA 560 `fk --jacobian`: ~0.15 ms less wall time).
    let (helpers_wanted, helpers_asked) = std::sync::mpsc::channel::<()>();
    let worker = std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(move || {
            let _watch = watch_stack();
            let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
            let read = match args.split_first() {
                Some((_, rest)) => fast_args::parse(rest),
                None => None,
            };
            let cli = match read.map_or_else(|| Cli::try_parse_from(&args), Ok) {
                Ok(cli) => cli,
                Err(e) => return clap_exit(&e),
            };
            if matches!(cli.command, Some(Command::Fk { .. })) {
                // This thread goes on whether or not the other one is still there to hear it.
                let _ = helpers_wanted.send(());
            }
            drop(helpers_wanted);
            let code = dispatch(cli);
            flush_out();
            exit_now(code)
        });
    let worker = match worker {
        Ok(w) => w,
        Err(e) => {
            eprintln!(
                "error: cannot start the evaluation thread with its {} MB stack: {} (the \
                 address-space limit, `ulimit -v`, must leave room for it)",
                STACK >> 20,
                os_message(&e)
            );
            return ExitCode::FAILURE;
        }
    };
    // Told once, or never (the sender is dropped): then only the worker's end is waited for.
    if helpers_asked.recv().is_ok() {
        let _threads = base_context().enter();
        dqsym::scalar::start_helpers();
    }
    match worker.join() {
        Ok(code) => code,
        Err(_) => {
            eprintln!("error: internal failure");
            ExitCode::FAILURE
        }
    }
}

/// Ends the process with `code` from the worker, once its output is flushed and every value
/// of the run dropped: `_exit`, not `exit` or a return to `main`. What those run next is
/// teardown the kernel does anyway at exit: the worker's exit (mimalloc collecting its heap,
/// glibc releasing the 256 MB stack with `madvise` and `munmap`, waking `main`), then the
/// process's exit handlers (mimalloc collecting and purging its arena again with five
/// `madvise` calls). `dqsym -e 1`: 1.02 M instructions and 118 system calls before, 0.97 M
/// and 104 after (callgrind, `strace -f -c`), 286 page faults before, 275 after. Nothing of the binary's is pending by then: stdout is
/// flushed (a failure there already ended the process), stderr is unbuffered, files are
/// closed when their owners drop inside `dispatch`, and nothing registers an exit handler.
#[cfg(unix)]
fn exit_now(code: ExitCode) -> ! {
    extern "C" {
        fn _exit(status: std::ffi::c_int) -> !;
    }
    // SAFETY: `_exit` ends the process without running anything of this one; the other thread,
    // `main`, only waits for this one.
    unsafe { _exit(status(code)) }
}

/// The process status of `code`. `ExitCode` has no stable conversion to a status; every
/// status this binary returns is an `ExitCode::from(u8)` (`SUCCESS` and `FAILURE` are 0 and 1
/// on unix), so it is one of these.
#[cfg(unix)]
fn status(code: ExitCode) -> std::ffi::c_int {
    (0..=u8::MAX)
        .find(|&n| ExitCode::from(n) == code)
        .map_or(1, std::ffi::c_int::from)
}

#[cfg(not(unix))]
fn exit_now(code: ExitCode) -> ExitCode {
    code
}

/// Prints clap's help, version or usage error and returns its status: a help or version
/// text that cannot be written to stdout (a full disk) is an output error like any other,
/// not a success (`Cli::parse` ignores the write's failure and exits 0).
fn clap_exit(e: &clap::Error) -> ExitCode {
    let printed = e.print().and_then(|()| std::io::stdout().flush());
    match printed {
        Err(w) if !e.use_stderr() => output_failed(&w),
        _ => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2)),
    }
}

/// An option given to a command it does not apply to: every option applies or is an error
/// (walk, ops and paper have no output formats; `-e` is a command of its own).
fn inapplicable_option(cli: &Cli) -> Option<String> {
    let formatless = match &cli.command {
        Some(Command::Walk { .. }) => Some("walk (it has --markdown and --html)"),
        Some(Command::Ops { .. }) => Some("ops (it prints operation counts)"),
        Some(Command::Paper) => Some("paper (it prints plain text)"),
        _ => None,
    };
    if let (Some(what), Some(_)) = (formatless, cli.format) {
        return Some(format!("--format does not apply to {what}"));
    }
    (cli.command.is_some() && cli.expr.is_some())
        .then(|| "-e cannot be combined with a command".to_owned())
}

fn dispatch(cli: Cli) -> ExitCode {
    let _ = MAX_INPUT_SIZE.set(cli.max_input_size);
    // The default `--term-limit` is the command's preset's.
    let preset = match cli.command {
        Some(Command::Fk { .. } | Command::Ops { .. }) => Preset::Fk,
        _ => Preset::Script,
    };
    let base = base_context();
    let limits = Limits {
        max_depth: usize::from(cli.max_depth),
        ctx: base
            .clone()
            .with_term_limit(cli.term_limit.unwrap_or(preset.term_limit()))
            .with_max_exponent(cli.max_exponent)
            .with_max_cyclotomic_degree(cli.max_cyclotomic_degree)
            .with_max_digits(cli.max_digits)
            .with_max_angle_symbols(cli.max_angle_symbols)
            .with_work_budget(cli.work_budget),
    };
    // The limits guard scripts, one-liners and robot files; paper keeps the library defaults.
    let _entered = if matches!(cli.command, Some(Command::Paper)) {
        base.enter()
    } else {
        limits.context().enter()
    };
    if let Some(message) = inapplicable_option(&cli) {
        eprintln!("error: {message}");
        return ExitCode::from(2);
    }
    let format = cli.format.unwrap_or(OutputFormat::Plain);
    // fk has its own formats (a report per entry); the other commands share show options.
    let opts = match &cli.command {
        Some(Command::Fk { .. } | Command::Ops { .. } | Command::Ik { .. }) => None,
        _ => match show_options(format, cli.explicit) {
            Ok(o) => Some(o),
            Err(message) => {
                eprintln!("{message}");
                return ExitCode::FAILURE;
            }
        },
    };
    let opts = opts.unwrap_or(ShowOptions {
        format: Format::Plain,
        explicit: cli.explicit,
    });
    // convert reads its file back with the term limit fk will read it with.
    let fk_terms = cli.term_limit.unwrap_or(Preset::Fk.term_limit());
    match (cli.command, cli.expr) {
        (
            Some(Command::Ops {
                robot,
                jacobian,
                robot_args,
            }),
            _,
        ) => ops(robot.as_deref(), jacobian, &robot_args),
        (
            Some(Command::Fk {
                robot,
                point,
                jacobian,
                robot_args,
            }),
            _,
        ) => fk(
            &robot,
            point.as_deref(),
            jacobian.as_deref(),
            format,
            cli.explicit,
            &robot_args,
        ),
        (
            Some(Command::Convert {
                robot,
                to,
                robot_args,
            }),
            _,
        ) => convert(&robot, to, &robot_args, fk_terms),
        (
            Some(Command::Ik {
                robot,
                free,
                method,
                robot_args,
            }),
            _,
        ) => ik(&robot, free, &method, &robot_args, format, cli.explicit),
        (Some(Command::Paper), _) => match dqsym::paper(&PlainOptions {
            shorthand: !cli.explicit,
            decimals: false,
        }) {
            Ok(text) => {
                print!("{text}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            }
        },
        (Some(Command::Run { file }), _) => run_file(&file, &opts, &limits),
        (
            Some(Command::Walk {
                file,
                markdown,
                html,
                config,
                ik: true,
                free,
                robot_args,
                force,
            }),
            _,
        ) => walk_ik(
            &file,
            markdown,
            html.as_deref().map(|h| (h, force)),
            config.as_deref(),
            free,
            &robot_args,
        ),
        (
            Some(Command::Walk {
                file,
                markdown,
                html,
                config,
                robot_args,
                force,
                ..
            }),
            _,
        ) => walk(
            &file,
            markdown,
            html.as_deref().map(|h| (h, force)),
            config.as_deref(),
            &robot_args,
        ),
        (None, Some(expr)) => one_liner(&expr, &opts, &limits),
        (None, None) => repl::run(&opts, &limits),
    }
}

/// `dqsym ik ROBOT`: reads the file, derives the closed-form inverse kinematics, prints the
/// derivation or the solver code; every failure is a message and status 1.
fn ik(
    path: &std::path::Path,
    free: Option<String>,
    method: &str,
    robot_args: &RobotArgs,
    format: OutputFormat,
    explicit: bool,
) -> ExitCode {
    let fail = |m: String| {
        eprintln!("error: {m}");
        ExitCode::FAILURE
    };
    let robot = match load_robot(path, robot_args) {
        Ok(r) => r,
        Err(m) => return fail(m),
    };
    let Some(method) = dqsym::ik::IkMethod::parse(method) else {
        return fail(format!(
            "--method {method}: expected auto, family or general"
        ));
    };
    let _derivation = dqsym::Context::entered().enter();
    let sol = match dqsym::ik::solve(&robot, &dqsym::ik::IkOptions { free, method }) {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    let out = dqsym::ik::ik_report(&sol, format.into(), !explicit);
    match out {
        Ok(t) => {
            print!("{t}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(e.to_string()),
    }
}

/// `dqsym walk ROBOT --ik`: the inverse kinematics derivation step by step.
fn walk_ik(
    path: &std::path::Path,
    markdown: bool,
    html: Option<(&std::path::Path, bool)>,
    config: Option<&str>,
    free: Option<String>,
    robot_args: &RobotArgs,
) -> ExitCode {
    let fail = |m: String| {
        eprintln!("error: {m}");
        ExitCode::FAILURE
    };
    if config.is_some() && html.is_none() {
        return fail("--config only applies to the --html page".to_owned());
    }
    let robot = match load_robot(path, robot_args) {
        Ok(r) => r,
        Err(m) => return fail(m),
    };
    let _derivation = dqsym::Context::entered().enter();
    let sol = match dqsym::ik::solve(
        &robot,
        &dqsym::ik::IkOptions {
            free,
            ..Default::default()
        },
    ) {
        Ok(s) => s,
        Err(e) => return fail(e.to_string()),
    };
    let w = match dqsym::walk::walk_ik(&robot, &sol) {
        Ok(w) => w,
        Err(e) => return fail(e.to_string()),
    };
    if let Some((out, force)) = html {
        let page = (|| -> Result<String, String> {
            let cfg = dqsym::walk::Config::parse(config.unwrap_or(""))
                .map_err(|e| format!("--config: {e}"))?;
            let assets = katex_assets()?;
            dqsym::walk::ik_walk_html(&w, &sol, &assets, &cfg).map_err(|e| e.to_string())
        })();
        return match page.and_then(|p| write_page(out, path, &p, force)) {
            Ok(()) => {
                eprintln!("wrote {}", out.display());
                ExitCode::SUCCESS
            }
            Err(m) => fail(m),
        };
    }
    let text = if markdown {
        dqsym::walk_markdown(&w)
    } else {
        dqsym::walk_text(&w)
    };
    match text {
        Ok(t) => {
            print!("{t}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(e.to_string()),
    }
}

/// `dqsym fk ROBOT`: reads the file, derives, prints; every failure is a message and status 1.
fn fk(
    path: &std::path::Path,
    point: Option<&str>,
    jacobian: Option<&str>,
    format: OutputFormat,
    explicit: bool,
    robot_args: &RobotArgs,
) -> ExitCode {
    let fail = |m: String| {
        eprintln!("error: {m}");
        ExitCode::FAILURE
    };
    // `--jacobian` alone (and `--jacobian=pose`) is the 8 x n Jacobian of the report; any
    // other kind is a task Jacobian with the pose.
    let task = match jacobian {
        None | Some("") => None,
        Some(k) => match dqsym::app::TaskJacobian::parse(k, &|v| dqsym::lang::eval_point_text(v)) {
            Ok(dqsym::app::TaskJacobian::Pose) => None,
            Ok(t) => Some(t),
            Err(m) => return fail(format!("--jacobian: {m}")),
        },
    };
    let jacobian = jacobian.is_some();
    let robot = match load_robot(path, robot_args) {
        Ok(r) => r,
        Err(m) => return fail(m),
    };
    let point = match point.map(dqsym::lang::eval_point_text) {
        Some(Err(m)) => return fail(format!("--point: {m}")),
        Some(Ok(p)) => Some(p),
        None => robot.tool.clone(),
    };
    // The fields were evaluated each with its own budget; the derivation gets a whole one.
    let derivation = Context::entered();
    let _derivation = derivation.enter();
    let options = dqsym::FkOptions {
        format: format.into(),
        shorthand: !explicit,
        point,
        jacobian,
        // Past the evaluation's term limit, the pose is printed as a recurrence.
        max_terms: derivation.term_limit(),
    };
    let report = match &task {
        Some(t) => dqsym::app::task_report(&robot, &options, t),
        // The entries are not dropped: the process ends once the report is printed
        // (`exit_now`), and dropping them took ~0.1 ms of the PUMA 560's `fk --jacobian`
        // (SCHED_FIFO runs: wall minimum 4.28 -> 4.19 ms, median 4.59 -> 4.47 ms).
        None => dqsym::app::fk_report_and_entries(&robot, &options).map(|(text, entries)| {
            std::mem::forget(entries);
            text
        }),
    };
    match report {
        Ok(t) => {
            print!("{t}");
            ExitCode::SUCCESS
        }
        // A limit reached in the derivation names the file, as a limit in a field does.
        Err(e) => fail(format!("{}: {e}", path.display())),
    }
}

/// `dqsym ops [ROBOT]`: the paper's tables, then the robot's generated code.
fn ops(path: Option<&std::path::Path>, jacobian: bool, robot_args: &RobotArgs) -> ExitCode {
    let Some(path) = path else {
        if let Err(m) = urdf_only(robot_args) {
            eprintln!("error: {m}");
            return ExitCode::FAILURE;
        }
        print!("{}", dqsym::app::ops_tables());
        return ExitCode::SUCCESS;
    };
    print!("{}", dqsym::app::ops_tables());
    let robot = match load_robot(path, robot_args) {
        Ok(r) => r,
        Err(m) => {
            eprintln!("error: {m}");
            return ExitCode::FAILURE;
        }
    };
    // The fields were evaluated each with its own budget; the derivation gets a whole one,
    // and, as fk, prints a recurrence past the term limit.
    let derivation = Context::entered();
    let _derivation = derivation.enter();
    let o = dqsym::FkOptions {
        jacobian,
        point: robot.tool.clone(),
        max_terms: derivation.term_limit(),
        ..dqsym::FkOptions::default()
    };
    match dqsym::app::fk_ops(&robot, &o) {
        Ok(t) => {
            print!("{t}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {}: {e}", path.display());
            ExitCode::FAILURE
        }
    }
}

/// `dqsym convert ROBOT.urdf --to toml`: the robot file on stdout.
/// The file is read back as `fk` reads it, at `fk_terms`, fk's term limit (convert's own
/// default is higher).
fn convert(
    path: &std::path::Path,
    to: ConvertTo,
    robot_args: &RobotArgs,
    fk_terms: usize,
) -> ExitCode {
    let ConvertTo::Toml = to;
    if !is_urdf(path) {
        eprintln!(
            "error: {}: convert reads URDF files (.urdf)",
            path.display()
        );
        return ExitCode::FAILURE;
    }
    let r = load_robot(path, robot_args).and_then(|robot| {
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        if let Some(why) = dqsym::app::dh_refusal(&robot) {
            eprintln!("note: written in screw form, not DH: {why}");
        }
        let text = dqsym::app::robot_toml(&robot, &name).map_err(|e| e.to_string())?;
        // Nothing is written that `fk` would refuse (a chain without a moving joint, a
        // symbolic axis whose unit length the reader cannot confirm within the limits): the
        // file is read back as `fk` reads it first, with fk's limits.
        let fk_limits = Context::entered().with_term_limit(fk_terms);
        let _fk = fk_limits.enter();
        dqsym::parse_robot(&text, &name, &dqsym::eval_scalar_text)
            .map_err(|e| format!("no robot file written: fk would not read it back: {e}"))?;
        Ok(text)
    });
    match r {
        Ok(t) => {
            print!("{t}");
            ExitCode::SUCCESS
        }
        Err(m) => {
            eprintln!("error: {m}");
            ExitCode::FAILURE
        }
    }
}

/// `dqsym walk FILE`: the walkthrough as text, Markdown or a web page.
fn walk(
    path: &std::path::Path,
    markdown: bool,
    html: Option<(&std::path::Path, bool)>,
    config: Option<&str>,
    robot_args: &RobotArgs,
) -> ExitCode {
    let fail = |m: String| {
        eprintln!("error: {m}");
        ExitCode::FAILURE
    };
    let text = match read_input(path) {
        Ok(t) => t,
        Err(m) => return fail(m),
    };
    let name = path.display().to_string();
    let robot_file = is_urdf(path) || path.extension().is_some_and(|e| e == "toml");
    let w = if is_urdf(path) {
        match load_robot(path, robot_args) {
            Ok(r) => dqsym::walk::walk_robot_chain(&r),
            Err(m) => return fail(m),
        }
    } else if let Err(m) = urdf_only(robot_args) {
        return fail(m);
    } else if path.extension().is_some_and(|e| e == "toml") {
        // Read here, so that its notes are printed and --exact-angles is honoured.
        match load_robot(path, robot_args) {
            Ok(r) => dqsym::walk::walk_robot_read(&r, &name),
            Err(m) => return fail(m),
        }
    } else {
        dqsym::walk_script(&text, &name)
    };
    let w = match w {
        Ok(w) => w,
        Err(e @ dqsym::walk::WalkError::TooLarge { .. }) => return fail(e.to_string()),
        // A robot's walkthrough that fails past the probe (a limit in a product or a closed
        // form) names its file as every other robot-file error does.
        Err(e) if robot_file => return fail(format!("{name}: {e}")),
        Err(dqsym::walk::WalkError::Script(m)) => {
            eprintln!("{}", with_origin(&m, &name));
            return ExitCode::FAILURE;
        }
        Err(e) => return fail(e.to_string()),
    };
    if let Some((out, force)) = html {
        let cfg = match dqsym::walk::Config::parse(config.unwrap_or("")) {
            Ok(c) => c,
            Err(e) => return fail(format!("--config: {e}")),
        };
        let assets = match katex_assets() {
            Ok(a) => a,
            Err(m) => return fail(m),
        };
        return match dqsym::walk_html(&w, &assets, &cfg) {
            Ok(page) => match write_page(out, path, &page, force) {
                Ok(()) => {
                    eprintln!("wrote {}", out.display());
                    ExitCode::SUCCESS
                }
                Err(m) => fail(m),
            },
            Err(e) => fail(e.to_string()),
        };
    }
    if config.is_some() {
        return fail("--config only applies to the --html page".to_owned());
    }
    let r = if markdown {
        dqsym::walk_markdown(&w)
    } else {
        dqsym::walk_text(&w)
    };
    match r {
        Ok(t) => {
            print!("{t}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(e.to_string()),
    }
}

/// Writes the page of `walk --html` to `out`. The rule: never over the input file (whatever
/// the path says: the same file through another name or a link counts); over an existing
/// regular file only when it is a page dqsym wrote ([`dqsym::walk::is_walk_page`]) or with
/// `--force` (a link is judged by the file it points to, and stays a link); a device or pipe
/// (`/dev/stdout`) is written to as it is. A regular file is written to a temporary file
/// beside it first and renamed over it, so a failed write (a full disk) leaves it as it was.
fn write_page(
    out: &std::path::Path,
    input: &std::path::Path,
    page: &str,
    force: bool,
) -> Result<(), String> {
    use std::io::Read;
    let shown = out.display();
    let cannot = |e: std::io::Error| format!("cannot write {shown}: {}", os_message(&e));
    if same_file(out, input) {
        return Err(format!(
            "{shown} is the input file; give the page another name"
        ));
    }
    let target = match std::fs::metadata(out) {
        Ok(m) if m.is_dir() => return Err(format!("{shown} is a directory")),
        Ok(m) if !m.is_file() => return std::fs::write(out, page).map_err(cannot),
        Ok(_) => {
            let mut head = String::new();
            let readable = std::fs::File::open(out)
                .and_then(|f| f.take(4096).read_to_string(&mut head))
                .is_ok();
            let ours = readable && dqsym::walk::is_walk_page(&head);
            if !(force || ours) {
                return Err(format!(
                    "{shown} exists and is not a page dqsym wrote; pass --force to write over it"
                ));
            }
            std::fs::canonicalize(out).map_err(cannot)?
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            if std::fs::symlink_metadata(out).is_ok() && !force {
                return Err(format!(
                    "{shown} is a link to a file that does not exist; pass --force to replace it"
                ));
            }
            out.to_path_buf()
        }
        Err(e) => return Err(cannot(e)),
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let file_name = target
        .file_name()
        .map_or_else(|| "page".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{file_name}.{}.tmp", std::process::id()));
    let written = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .and_then(|mut f| {
            f.write_all(page.as_bytes())?;
            f.sync_all()
        })
        .and_then(|()| std::fs::rename(&tmp, &target));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(cannot(e));
    }
    Ok(())
}

/// Whether two paths name one existing file (device and inode on Unix; the canonical paths
/// elsewhere).
fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (std::fs::metadata(a), std::fs::metadata(b)) {
            (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

/// KaTeX's stylesheet, script and fonts from `node_modules/katex/dist`, looked for in the
/// current directory and then in the source tree this binary was built from.
fn katex_assets() -> Result<dqsym::walk::KatexAssets, String> {
    let candidates = [
        std::path::PathBuf::from("node_modules/katex/dist"),
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("node_modules/katex/dist"),
    ];
    let Some(dir) = candidates.iter().find(|d| d.join("katex.min.js").is_file()) else {
        return Err(
            "KaTeX is not installed (node_modules/katex/dist/katex.min.js): run \
                    `npm install katex` in the dqsym directory, or `bash scripts/test.sh`, \
                    which installs it"
                .to_owned(),
        );
    };
    let read = |name: &str| {
        std::fs::read_to_string(dir.join(name))
            .map_err(|e| format!("cannot read {}: {e}", dir.join(name).display()))
    };
    let css = read("katex.min.css")?;
    let js = read("katex.min.js")?;
    let font = |name: &str| std::fs::read(dir.join("fonts").join(name)).ok();
    dqsym::walk::KatexAssets::new(&css, &js, &font).map_err(|e| e.to_string())
}

/// `dqsym run FILE`: prints results as statements complete; stops at the first error.
fn run_file(path: &std::path::Path, opts: &ShowOptions, limits: &Limits) -> ExitCode {
    let src = match read_input(path) {
        Ok(s) => s,
        Err(m) => {
            eprintln!("error: {m}");
            return ExitCode::FAILURE;
        }
    };
    let mut session = Session::new();
    if run_source(
        &mut session,
        &src,
        opts,
        limits,
        &path.display().to_string(),
    ) {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// Parses and runs `src`, printing each result to stdout and any error to stderr, with `origin`
/// naming the text. Returns whether everything succeeded.
pub(crate) fn run_source(
    session: &mut Session,
    src: &str,
    opts: &ShowOptions,
    limits: &Limits,
    origin: &str,
) -> bool {
    let program = match parse_with(src, &limits.parse_options()) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("{}", with_origin(&e.to_string(), origin));
            return false;
        }
    };
    for stmt in &program.statements {
        match session.exec(stmt) {
            Ok(Some(d)) => match show(&d, opts) {
                Ok(text) => print!("{text}"),
                Err(e) => {
                    eprintln!("{}", with_origin(&e.at(stmt.span).render(src), origin));
                    return false;
                }
            },
            Ok(None) => {}
            Err(e) => {
                eprintln!("{}", with_origin(&e.render(src), origin));
                return false;
            }
        }
    }
    true
}

/// Puts the file name into the ` --> line:col` line of a rendered error.
fn with_origin(rendered: &str, origin: &str) -> String {
    if origin.is_empty() {
        return rendered.to_owned();
    }
    match rendered.find("--> ") {
        Some(i) => format!("{}--> {origin}:{}", &rendered[..i], &rendered[i + 4..]),
        None => rendered.to_owned(),
    }
}

/// `dqsym -e EXPR`: free names are symbols; a lone expression prints without a label.
fn one_liner(src: &str, opts: &ShowOptions, limits: &Limits) -> ExitCode {
    let mut session = Session::with_implicit_symbols();
    let program = match parse_with(src, &limits.parse_options()) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    if let [stmt] = program.statements.as_slice() {
        if let StmtKind::Expr(e) = &stmt.kind {
            return match session.eval(e) {
                Ok(v) => match show_value(&v, opts) {
                    Ok(text) => {
                        print!("{text}");
                        ExitCode::SUCCESS
                    }
                    Err(err) => {
                        eprintln!("{}", err.at(e.span).render(src));
                        ExitCode::FAILURE
                    }
                },
                Err(e) => {
                    eprintln!("{}", e.render(src));
                    ExitCode::FAILURE
                }
            };
        }
    }
    if run_source(&mut session, src, opts, limits, "") {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
