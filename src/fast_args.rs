//! The common command lines read without clap: `-e EXPR`, `run FILE`, `paper`, `fk ROBOT`,
//! `ik ROBOT`, `ops [ROBOT]` and `convert ROBOT` with their options, and the global options
//! anywhere.
//!
//! Why: clap builds its whole command (every subcommand, argument and help text, the global
//! arguments copied into each subcommand) before it reads a single argument. That was a fifth
//! of the start-up of every run: `dqsym -e 1` 1.47 -> 1.30 ms of wall time at best and 284 -> 216
//! page faults without it (300 runs of each, alternating; a loaded machine).
//!
//! clap stays the one source of help, versions and errors: [`parse`] answers only for a
//! command line it reads completely and leaves every other to clap (`None`): help and version
//! flags, `help`, an unknown or repeated option, `--`, a value that is empty or starts with
//! `-`, a value attached in another way than `--name=value`, a number with anything but
//! digits, a missing or extra file, `walk`, the REPL (no command), text that is not UTF-8.
//! What it reads is what clap reads: the tests compare the two on the common forms and on
//! random command lines. Each `Cli` and `Command` below is written with all its fields, so a
//! new option does not compile until it is read here or left to clap.

use crate::{
    Cli, Command, ConvertTo, OutputFormat, RobotArgs, DEFAULT_MAX_DEPTH, DEFAULT_MAX_INPUT_SIZE,
    DEFAULT_WORK_BUDGET, MAX_MAX_DEPTH,
};
use std::ffi::OsString;
use std::path::PathBuf;

/// The command line `args` (without the program's name) as clap reads it, or `None` when it
/// is not one of the forms read here (clap reads it then; see the module's docs).
pub(crate) fn parse(args: &[OsString]) -> Option<Cli> {
    let args = args
        .iter()
        .map(|a| a.to_str())
        .collect::<Option<Vec<&str>>>()?;
    let mut read = Read::default();
    let mut i = 0;
    while i < args.len() {
        let arg = args[i];
        i += 1;
        if let Some(long) = arg.strip_prefix("--") {
            let (name, attached) = match long.split_once('=') {
                Some((name, value)) => (name, Some(value)),
                None => (long, None),
            };
            // A flag takes no value; an option takes the next argument unless one is attached.
            let mut value = || match attached {
                Some(v) => plain(v),
                None => {
                    let v = plain(args.get(i)?)?;
                    i += 1;
                    Some(v)
                }
            };
            read.option(name, attached, &mut value)?;
        } else if arg == "-e" && read.command.is_none() {
            let v = plain(args.get(i)?)?;
            i += 1;
            set(&mut read.expr, v.to_owned())?;
        } else if arg.is_empty() || arg.starts_with('-') {
            return None;
        } else if read.command.is_none() {
            read.command = Some(Name::of(arg)?);
        } else {
            set(&mut read.file, PathBuf::from(arg))?;
        }
    }
    read.finish()
}

/// A value clap reads the same way in every position: not empty, not starting with `-`.
fn plain(v: &str) -> Option<&str> {
    (!v.is_empty() && !v.starts_with('-')).then_some(v)
}

/// Fills an empty slot; a slot filled twice (an option given twice) is left to clap.
fn set<T>(slot: &mut Option<T>, value: T) -> Option<()> {
    match slot {
        Some(_) => None,
        None => {
            *slot = Some(value);
            Some(())
        }
    }
}

/// A number as clap's integer parsers read it, for the digits-only spellings.
fn number<T: std::str::FromStr>(v: &str) -> Option<T> {
    if v.bytes().all(|b| b.is_ascii_digit()) {
        v.parse().ok()
    } else {
        None
    }
}

/// The commands read here.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Name {
    Run,
    Paper,
    Fk,
    Ik,
    Ops,
    Convert,
}

impl Name {
    fn of(word: &str) -> Option<Name> {
        Some(match word {
            "run" => Name::Run,
            "paper" => Name::Paper,
            "fk" => Name::Fk,
            "ik" => Name::Ik,
            "ops" => Name::Ops,
            "convert" => Name::Convert,
            _ => return None,
        })
    }

    /// Whether the command reads a robot (the options of [`RobotArgs`]).
    fn reads_robot(self) -> bool {
        matches!(self, Name::Fk | Name::Ik | Name::Ops | Name::Convert)
    }
}

/// What was read so far: each slot once.
#[derive(Default)]
struct Read {
    command: Option<Name>,
    file: Option<PathBuf>,
    expr: Option<String>,
    format: Option<OutputFormat>,
    explicit: Option<()>,
    term_limit: Option<usize>,
    max_depth: Option<u16>,
    max_exponent: Option<u64>,
    max_cyclotomic_degree: Option<u64>,
    max_digits: Option<u64>,
    max_angle_symbols: Option<usize>,
    work_budget: Option<u64>,
    max_input_size: Option<u64>,
    point: Option<String>,
    jacobian: Option<String>,
    free: Option<String>,
    method: Option<String>,
    to: Option<ConvertTo>,
    tip: Option<String>,
    base: Option<String>,
    exact_angles: Option<()>,
}

impl Read {
    /// Reads the long option `--name` (`attached`: its `=value`, if any; `value`: its value).
    fn option<'a>(
        &mut self,
        name: &str,
        attached: Option<&str>,
        value: &mut dyn FnMut() -> Option<&'a str>,
    ) -> Option<()> {
        let command = self.command;
        let flag = |slot: &mut Option<()>| match attached {
            Some(_) => None,
            None => set(slot, ()),
        };
        match name {
            "format" => set(&mut self.format, named::<OutputFormat>(value()?)?),
            "explicit" => flag(&mut self.explicit),
            "term-limit" => set(&mut self.term_limit, number(value()?)?),
            "max-depth" => {
                let n: u16 = number(value()?)?;
                (1..=MAX_MAX_DEPTH).contains(&i64::from(n)).then_some(())?;
                set(&mut self.max_depth, n)
            }
            "max-exponent" => set(&mut self.max_exponent, number(value()?)?),
            "max-cyclotomic-degree" => set(&mut self.max_cyclotomic_degree, number(value()?)?),
            "max-digits" => set(&mut self.max_digits, number(value()?)?),
            "max-angle-symbols" => set(&mut self.max_angle_symbols, number(value()?)?),
            "work-budget" => set(&mut self.work_budget, number(value()?)?),
            "max-input-size" => set(&mut self.max_input_size, number(value()?)?),
            "point" if command == Some(Name::Fk) => set(&mut self.point, value()?.to_owned()),
            // fk's `--jacobian[=KIND]` takes its value only attached; ops' is a flag.
            "jacobian" if command == Some(Name::Fk) => {
                let kind = match attached {
                    Some(_) => value()?,
                    None => "",
                };
                set(&mut self.jacobian, kind.to_owned())
            }
            "jacobian" if command == Some(Name::Ops) => match attached {
                Some(_) => None,
                None => set(&mut self.jacobian, String::new()),
            },
            "free" if command == Some(Name::Ik) => set(&mut self.free, value()?.to_owned()),
            "method" if command == Some(Name::Ik) => {
                let m = value()?;
                dqsym::ik::IkMethod::parse(m)?;
                set(&mut self.method, m.to_owned())
            }
            "to" if command == Some(Name::Convert) => set(&mut self.to, named(value()?)?),
            "tip" if command.is_some_and(Name::reads_robot) => {
                set(&mut self.tip, value()?.to_owned())
            }
            "base" if command.is_some_and(Name::reads_robot) => {
                set(&mut self.base, value()?.to_owned())
            }
            "exact-angles" if command.is_some_and(Name::reads_robot) => {
                flag(&mut self.exact_angles)
            }
            _ => None,
        }
    }

    /// The `Cli` read, with clap's defaults for what was not given.
    fn finish(self) -> Option<Cli> {
        let robot_args = RobotArgs {
            tip: self.tip,
            base: self.base,
            exact_angles: self.exact_angles.is_some(),
        };
        let file = self.file;
        let command = match self.command {
            None => None,
            Some(Name::Run) => Some(Command::Run { file: file? }),
            Some(Name::Paper) => match file {
                Some(_) => return None,
                None => Some(Command::Paper),
            },
            Some(Name::Fk) => Some(Command::Fk {
                robot: file?,
                point: self.point,
                jacobian: self.jacobian,
                robot_args,
            }),
            Some(Name::Ik) => Some(Command::Ik {
                robot: file?,
                free: self.free,
                method: self.method.unwrap_or_else(|| "auto".to_owned()),
                robot_args,
            }),
            Some(Name::Ops) => Some(Command::Ops {
                robot: file,
                jacobian: self.jacobian.is_some(),
                robot_args,
            }),
            Some(Name::Convert) => Some(Command::Convert {
                robot: file?,
                to: self.to.unwrap_or(ConvertTo::Toml),
                robot_args,
            }),
        };
        // Exactly one of a command and `-e`: the REPL and their mixture are clap's.
        if command.is_some() == self.expr.is_some() {
            return None;
        }
        Some(Cli {
            expr: self.expr,
            format: self.format,
            explicit: self.explicit.is_some(),
            term_limit: self.term_limit,
            max_depth: self.max_depth.unwrap_or(DEFAULT_MAX_DEPTH),
            max_exponent: self
                .max_exponent
                .unwrap_or(dqsym::scalar::DEFAULT_MAX_EXPONENT),
            max_cyclotomic_degree: self
                .max_cyclotomic_degree
                .unwrap_or(dqsym::scalar::DEFAULT_MAX_CYCLOTOMIC_DEGREE),
            max_digits: self.max_digits.unwrap_or(dqsym::scalar::DEFAULT_MAX_DIGITS),
            max_angle_symbols: self
                .max_angle_symbols
                .unwrap_or(dqsym::scalar::DEFAULT_MAX_ANGLE_SYMBOLS),
            work_budget: self.work_budget.unwrap_or(DEFAULT_WORK_BUDGET),
            max_input_size: self.max_input_size.unwrap_or(DEFAULT_MAX_INPUT_SIZE),
            command,
        })
    }
}

/// A value of a `ValueEnum` option by its name, as clap matches it (case-sensitive, aliases
/// too), from the enum itself: no command is built.
fn named<T: clap::ValueEnum>(v: &str) -> Option<T> {
    T::from_str(v, false).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    fn os(args: &[&str]) -> Vec<OsString> {
        args.iter().map(OsString::from).collect()
    }

    /// clap's reading of `args`, `None` for its errors, help and version.
    fn clap(args: &[&str]) -> Option<Cli> {
        Cli::try_parse_from(std::iter::once("dqsym").chain(args.iter().copied())).ok()
    }

    #[test]
    fn the_common_forms_are_read_here_as_clap_reads_them() {
        let forms: &[&[&str]] = &[
            &["-e", "1"],
            &["-e", "sin(x)^2 + cos(x)^2"],
            &["--format", "latex", "-e", "x"],
            &["-e", "x", "--format=sympy", "--explicit"],
            &[
                "--term-limit",
                "1000000",
                "--work-budget",
                "1000000000",
                "-e",
                "(x+y+z)^30",
            ],
            &["--max-depth=4096", "--max-exponent", "7", "-e", "x"],
            &[
                "--max-cyclotomic-degree",
                "12",
                "--max-digits",
                "50",
                "-e",
                "x",
            ],
            &[
                "--max-angle-symbols",
                "3",
                "--max-input-size",
                "100",
                "-e",
                "x",
            ],
            &["run", "script.dq"],
            &["--format", "c", "run", "script.dq"],
            &["paper"],
            &["fk", "robot.toml"],
            &["fk", "--jacobian", "robot.toml"],
            &[
                "fk",
                "robot.toml",
                "--jacobian=geometric",
                "--format",
                "rust",
            ],
            &[
                "fk",
                "--point",
                "1, 2, 3",
                "robot.urdf",
                "--tip",
                "tool",
                "--base=b",
            ],
            &["fk", "--exact-angles", "robot.toml"],
            &["ik", "robot.toml"],
            &[
                "ik",
                "robot.toml",
                "--method",
                "general",
                "--free",
                "theta3",
            ],
            &["ik", "--format=python", "robot.toml"],
            &["ops"],
            &["ops", "robot.toml", "--jacobian"],
            &["convert", "robot.urdf", "--to", "toml", "--exact-angles"],
        ];
        for args in forms {
            let read = parse(&os(args));
            assert!(read.is_some(), "{args:?} is left to clap");
            assert_eq!(read, clap(args), "{args:?}");
        }
    }

    #[test]
    fn help_versions_errors_and_the_rest_are_left_to_clap() {
        let rest: &[&[&str]] = &[
            &[],
            &["--help"],
            &["-h"],
            &["-V"],
            &["--version"],
            &["help"],
            &["help", "fk"],
            &["fk", "--help"],
            &["-e"],
            &["-e", "1", "-e", "2"],
            &["-e", "-x"],
            &["-e", ""],
            &["-e1"],
            &["-e=1"],
            &["--format", "c"],
            &["--format", "LATEX", "-e", "x"],
            &["--explicit", "--explicit", "-e", "x"],
            &["--explicit=true", "-e", "x"],
            &["--max-depth", "0", "-e", "x"],
            &["--max-depth", "4097", "-e", "x"],
            &["--term-limit", "+5", "-e", "x"],
            &["--term-limit", "99999999999999999999999", "-e", "x"],
            &["fk"],
            &["fk", "a.toml", "b.toml"],
            &["fk", "--jacobian=", "a.toml"],
            &["fk", "--", "a.toml"],
            &["fk", "-e", "1", "a.toml"],
            &["-e", "1", "fk", "a.toml"],
            &["--jacobian", "fk", "a.toml"],
            &["ops", "--jacobian=pose"],
            &["ik", "a.toml", "--method", "other"],
            &["run", "--point", "1", "a.dq"],
            &["walk", "a.dq"],
            &["paper", "x"],
            &["bogus"],
        ];
        for args in rest {
            assert_eq!(parse(&os(args)), None, "{args:?}");
        }
    }

    /// Random command lines made of the pieces of every form above, good and bad, in any
    /// order: whenever one is read here, clap reads it the same. A seeded generator keeps
    /// failures reproducible.
    #[test]
    fn random_command_lines_are_read_as_clap_reads_them_or_left_to_it() {
        #[rustfmt::skip]
        const PIECES: &[&[&str]] = &[
            &["-e", "1"], &["-e", "x^2"], &["-e", "-x"], &["-e"], &["-e=1"], &["-ex"],
            &["-e", "fk"], &["run"], &["paper"], &["fk"], &["ik"], &["ops"], &["convert"],
            &["walk"], &["help"], &["a.toml"], &["b.urdf"], &["c.dq"], &["a.toml"], &["fk"],
            &["fk"], &["ik"], &["--format", "c"], &["--format=latex"], &["--format", "LATEX"],
            &["--format"], &["--explicit"], &["--explicit=no"], &["--term-limit", "5"],
            &["--term-limit", "+5"], &["--term-limit=007"], &["--max-depth", "0"],
            &["--max-depth", "4096"], &["--max-depth=4097"], &["--max-depth", "3"],
            &["--max-exponent", "99"], &["--max-exponent", "99999999999999999999999"],
            &["--max-cyclotomic-degree=12"], &["--max-digits", "40"],
            &["--max-angle-symbols", "2"], &["--work-budget=9"], &["--max-input-size", "1000"],
            &["--jacobian"], &["--jacobian=pose"], &["--jacobian="], &["--jacobian", "pose"],
            &["--point", "1,2,3"], &["--point=0,0,1"], &["--point", "-1,0,0"], &["--point", "ik"],
            &["--tip", "tool"], &["--base=link1"], &["--exact-angles"], &["--method", "auto"],
            &["--method=general"], &["--method", "x"], &["--free", "theta3"], &["--to", "toml"],
            &["--to=urdf"], &["--"], &["-h"], &["--help"], &["-V"], &["--bogus"], &["-"], &[""],
            &["x"],
        ];
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = |n: usize| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            usize::try_from(state >> 33).expect("31 bits") % n
        };
        let mut read_here = 0;
        for _ in 0..50_000 {
            let len = next(6);
            let args: Vec<&str> = (0..len)
                .flat_map(|_| PIECES[next(PIECES.len())].iter().copied())
                .collect();
            if let Some(read) = parse(&os(&args)) {
                read_here += 1;
                assert_eq!(Some(read), clap(&args), "{args:?}");
            }
        }
        // Enough of them are read here for the comparison to mean something.
        assert!(read_here > 1_000, "only {read_here} read here");
    }
}
