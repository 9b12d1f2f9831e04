//! The execution context: the limits of a computation and its cancel flag, as one value.
//!
//! A [`Context`] says how large a scalar may grow (`term_limit`), the largest exponent `^`
//! accepts (`max_exponent`), the most decimal digits a computed number may have
//! (`max_digits`), the most symbols inside one angle (`max_angle_symbols`), how much work one unit of evaluation may do (`work_budget`, in
//! term operations), how many threads parallel maps use (`threads`), and carries a cancel flag
//! shared with whoever may want to stop the computation (a Ctrl-C handler).
//!
//! Scalar arithmetic goes through `std::ops`, so the context is not an argument of `+` and
//! `*`: it is *entered* on a thread ([`Context::enter`]), which installs it until the returned
//! guard is dropped, and restores what was there before. Worker threads of
//! [`par_map`](super::par_map) and [`join`](super::join) enter the caller's context (with what
//! is left of its budget) and charge their work back to it. Every scalar sum and product, and
//! every step of a closed-form search, charges its work to the entered context; that is where
//! the budget is checked and where cancellation is noticed, so a cancelled computation ends at
//! its next charge with [`ScalarError::Cancelled`], on every thread it runs on.
//!
//! On a thread that never entered a context the default one applies: 200,000 terms, exponents
//! up to [`DEFAULT_MAX_EXPONENT`], no work budget, the available cores (at most 8), and no way
//! to cancel.
//!
//! ```
//! use dqsym_engine::{Context, Scalar, ScalarError};
//! let ctx = Context::new().with_term_limit(10);
//! let _in = ctx.enter();
//! let x = Scalar::sym("x") + Scalar::sym("y") + Scalar::sym("z");
//! assert!(matches!(x.pow(5).check(), Err(ScalarError::TooManyPairs { .. })));
//! ```

use super::ScalarError;
use std::cell::{Cell, RefCell};
use std::marker::PhantomData;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// The default largest exponent of `^`, in absolute value.
pub const DEFAULT_MAX_EXPONENT: u64 = 10_000;

/// The default term limit.
const DEFAULT_TERM_LIMIT: usize = 200_000;

/// The default largest number of decimal digits of a computed rational's numerator or
/// denominator: the language's limit for an integer literal. A product of two such numbers
/// takes microseconds, a term limit's worth of them tens of megabytes.
pub const DEFAULT_MAX_DIGITS: u64 = 10_000;

/// The default largest number of symbols inside one angle: a chain of that many joints with
/// collinear axes adds every joint variable into one `cos(q1 + ... + qn)`, and each partial
/// product holds its own prefix of the sum (memory quadratic in the joints: 1,000 of them
/// about 200 MB, 10,000 past any machine).
pub const DEFAULT_MAX_ANGLE_SYMBOLS: usize = 1_000;

/// The default largest degree `phi(W)` of the cyclotomic field `Q(zeta_W)` in which the
/// constants at rational multiples of pi of one group of terms are made canonical: every
/// denominator up to 100 alone (`pi/97`, degree 768), with thirds and quarters too (`pi/59`
/// with `pi/3`, 464), whole degrees (`pi/180`, 96), sevenths with ninths (144).
pub const DEFAULT_MAX_CYCLOTOMIC_DEGREE: u64 = 768;

/// A named set of limits: where the command line and the Python package start (`dqsym run`
/// and Python's `Session` from [`Preset::Script`], `dqsym fk` and Python's `Robot` from
/// [`Preset::Fk`]), each option then overriding one of them. [`Context::preset`] makes the
/// context; the other limits are the library's defaults.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Preset {
    /// Scripts, one-liners and the REPL: 20,000 terms (the paper's largest intermediate
    /// scalars have a few thousand, and a product of two scalars this size is still well under
    /// a second) and 3,000,000 units of work (over three times what the largest example, `fk`
    /// of `examples/robots/kuka_iiwa7.toml` with `--jacobian`, closed forms included, needs:
    /// a second or so of work on small terms).
    Script,
    /// Robot reports (`fk`, `ops`): 5,000 terms, past which the pose is a recurrence (the
    /// example robots need at most a few thousand, the KUKA iiwa's Jacobian; a chain whose
    /// terms multiply at every joint, 20 fully symbolic DH links, reaches this size in about a
    /// second, where 20,000 would take several), and the work budget of [`Preset::Script`].
    Fk,
}

impl Preset {
    /// The most terms of one scalar.
    pub const fn term_limit(self) -> usize {
        match self {
            Preset::Script => 20_000,
            Preset::Fk => 5_000,
        }
    }

    /// The work budget, in term operations.
    pub const fn work_budget(self) -> u64 {
        3_000_000
    }

    /// The largest exponent of `^`.
    pub const fn max_exponent(self) -> u64 {
        DEFAULT_MAX_EXPONENT
    }
}

/// The limits and the cancel flag of a computation (see the module docs).
#[derive(Clone, Debug)]
pub struct Context {
    term_limit: usize,
    max_exponent: u64,
    max_cyclotomic_degree: u64,
    max_digits: u64,
    max_angle_symbols: usize,
    work_budget: u64,
    /// The threads of parallel maps; 0 for the available cores ([`available_threads`]), read
    /// when a parallel map first asks: a context that never runs one (`dqsym -e 1`) never
    /// reads the cgroup files.
    threads: usize,
    cancel: Option<Arc<AtomicBool>>,
    /// For a context taken by [`Context::current`] (a parallel worker's): the budget of the
    /// context it was taken from as that one reports it, and the work done under it before.
    /// A [`ScalarError::Budget`] raised under this context then names the budget the user set
    /// and the work done in all, not what was left of it when a worker started (which depends
    /// on when the worker took its job).
    shown: Option<(u64, u64)>,
}

impl Default for Context {
    fn default() -> Context {
        Context {
            term_limit: DEFAULT_TERM_LIMIT,
            max_exponent: DEFAULT_MAX_EXPONENT,
            max_cyclotomic_degree: DEFAULT_MAX_CYCLOTOMIC_DEGREE,
            max_digits: DEFAULT_MAX_DIGITS,
            max_angle_symbols: DEFAULT_MAX_ANGLE_SYMBOLS,
            work_budget: u64::MAX,
            threads: 0,
            cancel: None,
            shown: None,
        }
    }
}

/// The available parallelism, at most 8 (read once: it reads cgroup files).
///
/// Measured per workload (`fk --jacobian` whole processes, release build, CPU ms with one /
/// two threads, `perf stat -r 3` on a shared 2-core machine): PUMA 560 9.3 / 11.8, iiwa 44 /
/// 42, Jaco-style 489 / 444, symbolic 4R 82 / 87, symbolic 6R 74 / 82, 20-joint symbolic
/// chain 52 / 59, `(x+y+z)^30` 32 / 33. A second thread costs at most 1.1x the CPU once the
/// `fk` expansions no longer race (it cost up to 3.9x: generic 6R 2,224 M against 573 M
/// instructions, `app/fk.rs`), and it shortens the wall time of the closed forms, which are
/// independent per entry; so the default stays every available core, and `par_map` and
/// `join` are the only places that use them.
fn available_threads() -> usize {
    static THREADS: OnceLock<usize> = OnceLock::new();
    *THREADS.get_or_init(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
            .min(8)
    })
}

impl Context {
    /// The default context: 200,000 terms, exponents up to [`DEFAULT_MAX_EXPONENT`], no work
    /// budget, the available cores (at most 8), no cancel flag.
    pub fn new() -> Context {
        Context::default()
    }

    /// The default context with the limits of `preset`.
    pub fn preset(preset: Preset) -> Context {
        Context::new()
            .with_term_limit(preset.term_limit())
            .with_max_exponent(preset.max_exponent())
            .with_work_budget(preset.work_budget())
    }

    /// The context entered on this thread (the default one if none is), with the budget that
    /// is left of it: what a computation started here may still spend.
    pub fn current() -> Context {
        STATE.with(|s| match &*s.borrow() {
            Some(st) => {
                let (limit, before) = st.ctx.shown.unwrap_or((st.ctx.work_budget, 0));
                Context {
                    work_budget: st.ctx.work_budget.saturating_sub(st.used),
                    shown: Some((limit, before.saturating_add(st.used))),
                    ..st.ctx.clone()
                }
            }
            None => Context::default(),
        })
    }

    /// The context entered on this thread as it was entered, its whole budget included: a new
    /// unit of work (a statement, a robot-file field) under the same limits.
    pub fn entered() -> Context {
        STATE.with(|s| match &*s.borrow() {
            Some(st) => st.ctx.clone(),
            None => Context::default(),
        })
    }

    /// Results with more terms than `n` (at least 1) become [`ScalarError::TooLarge`].
    pub fn with_term_limit(mut self, n: usize) -> Context {
        self.term_limit = n.max(1);
        self
    }

    /// `^` accepts exponents up to `n` in absolute value.
    pub fn with_max_exponent(mut self, n: u64) -> Context {
        self.max_exponent = n;
        self
    }

    /// Constants at rational multiples of pi are computed exactly in the cyclotomic field
    /// `Q(zeta_W)`, `W = lcm(24, 2 q1, 2 q2, ...)` for the denominators `q` of the pi offsets
    /// that meet in one sum; a field of degree `phi(W)` above `n` makes the result a
    /// [`ScalarError::CyclotomicDegree`] (never a non-canonical value). The work grows like the
    /// cube of the degree.
    pub fn with_max_cyclotomic_degree(mut self, n: u64) -> Context {
        self.max_cyclotomic_degree = n;
        self
    }

    /// A computed rational whose numerator or denominator has more than `n` decimal digits
    /// (at least 1) makes the result a [`ScalarError::TooManyDigits`]: products and sums
    /// check what they form, powers before they start.
    pub fn with_max_digits(mut self, n: u64) -> Context {
        self.max_digits = n.max(1);
        self
    }

    /// A result with more than `n` symbols (at least 1) inside one angle becomes a
    /// [`ScalarError::AngleSymbols`]: the term limit counts terms, not what is inside them.
    pub fn with_max_angle_symbols(mut self, n: usize) -> Context {
        self.max_angle_symbols = n.max(1);
        self
    }

    /// Once more than `units` term operations (one per term of a sum; one per pair of terms of
    /// a product, plus one per symbol of the pair's monomials) have been charged since the
    /// context was entered, every further operation yields [`ScalarError::Budget`]. The term
    /// limit bounds the size of one result; the budget the time of a whole evaluation made of
    /// many small operations.
    pub fn with_work_budget(mut self, units: u64) -> Context {
        self.work_budget = units;
        self.shown = None;
        self
    }

    /// Parallel maps use up to `n` threads (at least 1; 1 runs everything on the caller).
    pub fn with_threads(mut self, n: usize) -> Context {
        self.threads = n.max(1);
        self
    }

    /// Setting `flag` cancels every computation running in this context: each ends at its next
    /// charge of work with [`ScalarError::Cancelled`].
    pub fn with_cancel_flag(mut self, flag: Arc<AtomicBool>) -> Context {
        self.cancel = Some(flag);
        self
    }

    /// The term limit.
    pub fn term_limit(&self) -> usize {
        self.term_limit
    }

    /// The largest exponent `^` accepts.
    pub fn max_exponent(&self) -> u64 {
        self.max_exponent
    }

    /// The largest degree of a cyclotomic field the exact constants are computed in.
    pub fn max_cyclotomic_degree(&self) -> u64 {
        self.max_cyclotomic_degree
    }

    /// The largest number of decimal digits of a computed number.
    pub fn max_digits(&self) -> u64 {
        self.max_digits
    }

    /// The largest number of symbols inside one angle.
    pub fn max_angle_symbols(&self) -> usize {
        self.max_angle_symbols
    }

    /// The work budget, in term operations.
    pub fn work_budget(&self) -> u64 {
        self.work_budget
    }

    /// The threads parallel maps use.
    pub fn threads(&self) -> usize {
        match self.threads {
            0 => available_threads(),
            n => n,
        }
    }

    /// All the work charged on this thread so far, in every context entered on it (a unit's
    /// own counter starts at zero when it is entered and is gone when it ends); the work of
    /// worker threads counts once they finish. The difference of two readings is the
    /// deterministic cost of what ran between them: tests assert on it instead of on time.
    pub fn work_done() -> u64 {
        TOTAL.with(Cell::get)
    }

    /// `Err(Cancelled)` when the context entered on this thread is cancelled: for long loops
    /// that charge no work (the evaluator's, outside the engine).
    pub fn check_cancelled() -> Result<(), ScalarError> {
        check_cancelled()
    }

    /// Whether the cancel flag is set.
    pub fn is_cancelled(&self) -> bool {
        self.cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::Relaxed))
    }

    /// Installs this context on the calling thread, with no work charged yet, until the guard
    /// is dropped; the context that was there before comes back then (with its work count).
    pub fn enter(&self) -> Entered {
        let previous = STATE.with(|s| {
            s.borrow_mut().replace(State {
                ctx: self.clone(),
                used: 0,
            })
        });
        Entered {
            previous,
            _not_send: PhantomData,
        }
    }
}

/// A context entered on this thread; dropping it restores the previous one.
#[must_use = "the context applies only while the guard lives"]
pub struct Entered {
    previous: Option<State>,
    // The guard restores the state of the thread that created it.
    _not_send: PhantomData<*const ()>,
}

impl Entered {
    /// The term operations charged since the context was entered (on this thread, including
    /// the work of the worker threads it started).
    pub fn work_used(&self) -> u64 {
        work_used()
    }
}

impl Drop for Entered {
    fn drop(&mut self) {
        let previous = self.previous.take();
        STATE.with(|s| *s.borrow_mut() = previous);
    }
}

struct State {
    ctx: Context,
    used: u64,
}

thread_local! {
    static STATE: RefCell<Option<State>> = const { RefCell::new(None) };
    /// Every unit of work ever charged on this thread, whatever the context.
    static TOTAL: Cell<u64> = const { Cell::new(0) };
}

/// The term limit of the entered context.
pub(crate) fn term_limit() -> usize {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or(DEFAULT_TERM_LIMIT, |st| st.ctx.term_limit)
    })
}

/// The largest cyclotomic degree of the entered context.
pub(crate) fn max_cyclotomic_degree() -> u64 {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or(DEFAULT_MAX_CYCLOTOMIC_DEGREE, |st| {
                st.ctx.max_cyclotomic_degree
            })
    })
}

/// The largest number of decimal digits of a computed number in the entered context.
pub(crate) fn max_digits() -> u64 {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or(DEFAULT_MAX_DIGITS, |st| st.ctx.max_digits)
    })
}

/// The largest number of symbols inside one angle in the entered context.
pub(crate) fn max_angle_symbols() -> usize {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or(DEFAULT_MAX_ANGLE_SYMBOLS, |st| st.ctx.max_angle_symbols)
    })
}

/// The threads of the entered context.
pub(crate) fn threads() -> usize {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or_else(available_threads, |st| st.ctx.threads())
    })
}

/// The work charged to the entered context on this thread.
pub(crate) fn work_used() -> u64 {
    STATE.with(|s| s.borrow().as_ref().map_or(0, |st| st.used))
}

/// The work the entered context on this thread may still charge (`u64::MAX` without one).
pub(crate) fn work_left() -> u64 {
    STATE.with(|s| {
        s.borrow()
            .as_ref()
            .map_or(u64::MAX, |st| st.ctx.work_budget.saturating_sub(st.used))
    })
}

/// Counts `units` of work; the error to return when the computation is cancelled or the budget
/// is spent.
pub(crate) fn charge(units: u64) -> Result<(), ScalarError> {
    STATE.with(|s| {
        let mut s = s.borrow_mut();
        let Some(st) = s.as_mut() else {
            return Ok(());
        };
        if st.ctx.is_cancelled() {
            return Err(ScalarError::Cancelled);
        }
        TOTAL.with(|t| t.set(t.get().saturating_add(units)));
        st.used = st.used.saturating_add(units);
        if st.used > st.ctx.work_budget {
            let (limit, before) = st.ctx.shown.unwrap_or((st.ctx.work_budget, 0));
            return Err(ScalarError::Budget {
                used: before.saturating_add(st.used),
                limit,
            });
        }
        Ok(())
    })
}

/// `Err(Cancelled)` when the entered context is cancelled: for long loops that charge no work.
pub(crate) fn check_cancelled() -> Result<(), ScalarError> {
    #[cfg(test)]
    if test_hook::look() {
        return Err(ScalarError::Cancelled);
    }
    STATE.with(|s| match &*s.borrow() {
        Some(st) if st.ctx.is_cancelled() => Err(ScalarError::Cancelled),
        _ => Ok(()),
    })
}

/// How many steps of a long loop pass between two looks at the cancel flag. A step is one
/// term operation (a pair of a product, a term of a sum or of a sort's merge), which with
/// coefficients of dozens of digits costs microseconds (tens of them in a debug build): a
/// cancelled loop ends within a millisecond or so, and the look costs nothing measurable.
const POLL_STEPS: u32 = 64;

/// The cancel flag, looked at every [`POLL_STEPS`] steps of a long loop: a sum, a product, the
/// sort of a product's terms. Work is charged for such a loop before it starts (the budget
/// is known then); cancellation must be noticed inside it too, since one product of large
/// scalars runs for seconds.
#[derive(Default)]
pub(crate) struct Poll(u32);

impl Poll {
    /// One step of the loop; `Err(Cancelled)` once the context is cancelled.
    pub(crate) fn step(&mut self) -> Result<(), ScalarError> {
        self.0 += 1;
        if self.0 < POLL_STEPS {
            return Ok(());
        }
        self.0 = 0;
        check_cancelled()
    }
}

/// For tests: counts the looks at the cancel flag on this thread and cancels at a chosen one,
/// so that a test proves deterministically that a loop looks often enough and that its
/// cancellation reaches the result.
#[cfg(test)]
pub(crate) mod test_hook {
    use std::cell::Cell;

    thread_local! {
        static LOOKS: Cell<u64> = const { Cell::new(0) };
        static CANCEL_AT: Cell<Option<u64>> = const { Cell::new(None) };
    }

    /// Starts counting from zero; `cancel_at`: the look (1-based) from which on the context
    /// counts as cancelled.
    pub(crate) fn reset(cancel_at: Option<u64>) {
        LOOKS.with(|l| l.set(0));
        CANCEL_AT.with(|c| c.set(cancel_at));
    }

    /// The looks since [`reset`].
    pub(crate) fn looks() -> u64 {
        LOOKS.with(Cell::get)
    }

    /// Counts one look; whether it is cancelled.
    pub(crate) fn look() -> bool {
        let n = LOOKS.with(|l| {
            l.set(l.get() + 1);
            l.get()
        });
        CANCEL_AT.with(|c| c.get().is_some_and(|at| n >= at))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scalar;
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::Pow;

    #[test]
    fn entering_nests_and_restores() {
        let outer = Context::new().with_term_limit(7).with_work_budget(1000);
        let g = outer.enter();
        assert_eq!(term_limit(), 7);
        let _ = Scalar::sym("a") + Scalar::sym("b");
        let used = g.work_used();
        assert!(used > 0);
        {
            let _inner = Context::new().with_term_limit(3).enter();
            assert_eq!(term_limit(), 3);
            assert_eq!(work_used(), 0);
        }
        assert_eq!(term_limit(), 7);
        assert_eq!(g.work_used(), used);
        assert_eq!(Context::current().work_budget(), 1000 - used);
        drop(g);
        assert_eq!(term_limit(), DEFAULT_TERM_LIMIT);
    }

    /// A worker runs under [`Context::current`] (what is left of the budget); a budget it
    /// runs out of is still reported as the budget the user set, with the work done in all
    /// (an `ik` report at `--work-budget 5000` once said "over the budget of 1271" when a
    /// helper thread ran out, depending on when it took its job). A budget of its own (a
    /// bounded attempt) reports itself.
    #[test]
    fn a_worker_reports_the_budget_the_user_set() {
        let _in = Context::new().with_work_budget(1000).enter();
        charge(600).expect("within the budget");
        let worker = Context::current();
        assert_eq!(worker.work_budget(), 400);
        let first_error = |ctx: Context| {
            std::thread::spawn(move || {
                let _e = ctx.enter();
                (0..100).find_map(|_| charge(10).err())
            })
            .join()
            .expect("the worker ends")
        };
        assert_eq!(
            first_error(worker.clone()),
            Some(ScalarError::Budget {
                used: 1010,
                limit: 1000
            })
        );
        // A worker of a worker: the same.
        let nested = {
            let _w = worker.enter();
            charge(100).expect("within the budget");
            Context::current()
        };
        assert_eq!(nested.work_budget(), 300);
        assert_eq!(
            first_error(nested),
            Some(ScalarError::Budget {
                used: 1010,
                limit: 1000
            })
        );
        assert_eq!(
            first_error(worker.with_work_budget(50)),
            Some(ScalarError::Budget {
                used: 60,
                limit: 50
            })
        );
    }

    #[test]
    fn a_set_cancel_flag_stops_the_next_operation() {
        let flag = Arc::new(AtomicBool::new(false));
        let ctx = Context::new().with_cancel_flag(flag.clone());
        let _in = ctx.enter();
        let s = Scalar::sym("a") + Scalar::sym("b");
        assert!(s.as_error().is_none());
        flag.store(true, Ordering::Relaxed);
        let p = &s * &s;
        assert_eq!(p.as_error(), Some(&ScalarError::Cancelled));
        assert_eq!(check_cancelled(), Err(ScalarError::Cancelled));
    }
    #[test]
    fn a_large_product_and_the_sort_of_its_terms_look_at_the_cancel_flag_every_few_steps() {
        let _in = Context::new().with_term_limit(1_000_000).enter();
        let s = Scalar::sym("x") + Scalar::sym("y") + Scalar::sym("z");
        let (a, b) = (s.pow(15), s.pow(16));
        let pairs = (a.len() * b.len()) as u64;
        // More pairs than one sorted run holds: the terms are sorted in runs, then merged.
        assert!(pairs > 2 * super::super::RUN as u64, "{pairs} pairs");
        test_hook::reset(None);
        let p = &a * &b;
        let looks = test_hook::looks();
        // (x + y + z)^31: C(33, 2) terms; at x = y = z = 1 it is 3^31, at (1, 2, -1) 2^31.
        assert_eq!(p.len(), 528);
        let at = |v: [i64; 3]| {
            p.subs("x", &Scalar::int(v[0]))
                .subs("y", &Scalar::int(v[1]))
                .subs("z", &Scalar::int(v[2]))
        };
        let power =
            |n: i64| Scalar::rational(BigRational::from_integer(BigInt::from(n).pow(31u32)));
        assert_eq!(at([1, 1, 1]), power(3));
        assert_eq!(at([1, 2, -1]), power(2));
        // One look per 64 term pairs formed, then more while the pairs are sorted and merged:
        // no stretch of more than 64 steps goes unwatched.
        let product_looks = pairs / u64::from(POLL_STEPS);
        assert!(
            looks > product_looks + pairs / 2 / u64::from(POLL_STEPS),
            "{looks} looks at the cancel flag for {pairs} pairs"
        );
        // Cancelled at any of them, the product is the cancelled error value: at the first, in
        // the middle of forming the pairs, as the sort starts, and at the last look, which is
        // in the final merge of sorted runs.
        for cancel_at in [
            1,
            product_looks / 2,
            product_looks + 1,
            product_looks + 3,
            looks - 1,
            looks,
        ] {
            test_hook::reset(Some(cancel_at));
            let p = &a * &b;
            let seen = test_hook::looks();
            test_hook::reset(None);
            assert_eq!(
                p.as_error(),
                Some(&ScalarError::Cancelled),
                "cancelled at look {cancel_at}"
            );
            assert_eq!(
                seen, cancel_at,
                "the product stops at the look that sees the cancel"
            );
        }
        // A long sum looks too.
        let q = s.pow(30);
        test_hook::reset(Some(1));
        let sum = &p + &q;
        test_hook::reset(None);
        assert_eq!(sum.as_error(), Some(&ScalarError::Cancelled));
    }
}
