//! Independent exact computations on several threads, under the caller's context.
//!
//! A worker enters the caller's [`Context`] (term limit, exponent limit, threads, cancel flag)
//! with what is left of the caller's work budget; the work the workers did is charged to the
//! caller afterwards, so a parallel derivation spends one budget, as a sequential one would
//! (the workers together may overshoot it by at most one worker's budget before they stop).
//! Cancelling the context stops the workers too: they charge their work to the same flag.

use super::ctx::{charge, threads, Context};
use super::ScalarError;
use std::collections::VecDeque;
use std::marker::PhantomData;
use std::sync::atomic::{AtomicPtr, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex, MutexGuard};

/// The stack of a worker: closed-form searches recurse over expression depth.
const WORKER_STACK: usize = 64 << 20;

/// Runs `f` on this thread with a budget of its own, `units` term operations, and leaves this
/// thread's budget and the work counted against it as they were: for an optional attempt
/// (a form that may not fit) that must neither fail for lack of the caller's budget nor spend
/// it. The other limits and the cancel flag stay the caller's.
pub(crate) fn with_own_budget<R>(units: u64, f: impl FnOnce() -> R) -> R {
    let _own = Context::current().with_work_budget(units).enter();
    f()
}

/// `items.iter().map(f).collect()`, computed on up to [`Context::threads`] threads (the caller is one
/// of them). The result is in the order of `items` and does not depend on the number of
/// threads when `f` is a pure function of its argument.
pub fn par_map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let n = threads().min(items.len());
    if n <= 1 {
        return items.iter().map(&f).collect();
    }
    let ctx = Context::current();
    let next = AtomicUsize::new(0);
    let done: Mutex<Vec<(usize, R)>> = Mutex::new(Vec::with_capacity(items.len()));
    let spent = AtomicUsize::new(0);
    let work = |install: bool| {
        let entered = install.then(|| ctx.enter());
        let mut mine = Vec::new();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(x) = items.get(i) else { break };
            mine.push((i, f(x)));
        }
        if let Some(e) = entered {
            spent.fetch_add(
                usize::try_from(e.work_used()).unwrap_or(usize::MAX),
                Ordering::Relaxed,
            );
        }
        done.lock().unwrap_or_else(|e| e.into_inner()).extend(mine);
    };
    with_helpers(n - 1, &|| work(true), || work(false));
    // The workers' work counts against this thread's budget; an overrun shows up in the
    // next operation here, as it would have sequentially.
    let _: Result<(), ScalarError> = charge(spent.into_inner() as u64);
    let mut done = done.into_inner().unwrap_or_else(|e| e.into_inner());
    done.sort_unstable_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, r)| r).collect()
}

/// What each helper thread of the pool runs first, and keeps until the thread ends: set once
/// per process by [`on_helper_start`].
static HELPER_START: std::sync::OnceLock<fn() -> Box<dyn std::any::Any>> =
    std::sync::OnceLock::new();

/// Sets what each helper thread runs when it starts (the value it returns is kept for the
/// thread's life): for a program that sets up per-thread state the Rust runtime would
/// otherwise have set up, such as the `dqsym` binary's stack-overflow report, since it starts
/// without the runtime's start-up. Set once, before the first helper starts; whether it was
/// set by this call (false if a hook was already set).
pub fn on_helper_start(hook: fn() -> Box<dyn std::any::Any>) -> bool {
    HELPER_START.set(hook).is_ok()
}

/// Starts the helper threads the entered context's parallel maps use now, not at the first
/// one: a caller with serial work of its own before its parallel work (the command line's
/// `fk`, which reads its robot file and multiplies the matrices first) overlaps the helpers'
/// start-up (a thread, its stack and allocator heap, the start hook) with that work. The
/// first parallel stage then finds its helper waiting for jobs instead of running alone
/// while one starts.
pub fn start_helpers() {
    let k = threads().saturating_sub(1);
    if k > 0 {
        let pool = Pool::get();
        pool.start(&mut pool.lock(), k);
    }
}

/// Runs `a` on this thread and `b` on another one (under this thread's limits), and returns
/// both results. Without a second thread (one allowed, or none free) both run here.
pub fn join<A, B>(a: impl FnOnce() -> A, b: impl FnOnce() -> B + Send) -> (A, B)
where
    B: Send,
{
    let slot = Mutex::new(Some(b));
    let take = || slot.lock().unwrap_or_else(|e| e.into_inner()).take();
    if threads() <= 1 {
        let ra = a();
        let rb = take().map(|b| b());
        return (ra, rb.unwrap_or_else(|| unreachable!("b runs once")));
    }
    let ctx = Context::current();
    let other: Mutex<Option<(B, u64)>> = Mutex::new(None);
    let helper = || {
        let entered = ctx.enter();
        if let Some(b) = take() {
            let rb = b();
            *other.lock().unwrap_or_else(|e| e.into_inner()) = Some((rb, entered.work_used()));
        }
    };
    let ra = with_helpers(1, &helper, a);
    let rb = match other.into_inner().unwrap_or_else(|e| e.into_inner()) {
        Some((rb, used)) => {
            let _ = charge(used);
            rb
        }
        // No helper took `b` before `a` was done: it is still in its slot.
        None => take().map_or_else(|| unreachable!("b runs once"), |b| b()),
    };
    (ra, rb)
}

/// Runs `own` on this thread while up to `k` helper threads each run `job` once, and returns
/// once every helper that began `job` has ended it: the helpers are the process's persistent
/// ones ([`Pool`]), started when first needed and kept, not threads spawned per call (each
/// spawn mapped and touched a fresh 64 MB stack and set up a thread and its allocator heap:
/// the PUMA 560's `fk --jacobian` spawned four per run). A job no helper has begun when
/// `own` returns is taken back, never waited for, so a call never waits for a busy helper
/// (a `par_map` inside a job, or helpers that could not be started, run sequentially here).
/// A panic of `job` on a helper is resumed here once the others are done.
fn with_helpers<R>(k: usize, job: &(dyn Fn() + Sync), own: impl FnOnce() -> R) -> R {
    let pool = Pool::get();
    // SAFETY: the job's borrow is extended to `'static` only for the queue: the guard below
    // takes every unstarted copy back and waits for every started one to end before this
    // function returns or unwinds, so no helper uses it after its borrow ends.
    let erased: &'static (dyn Fn() + Sync) = unsafe { std::mem::transmute(job) };
    let call = pool.post(k, erased);
    let guard = Retract { pool, call };
    let r = own();
    drop(guard);
    if let Some(p) = pool.take_panic(call) {
        std::panic::resume_unwind(p);
    }
    r
}

/// Takes a call's unstarted jobs back and waits for its started ones, also when the caller
/// unwinds: the jobs borrow the caller's frame.
struct Retract {
    pool: &'static Pool,
    call: u64,
}

impl Drop for Retract {
    fn drop(&mut self) {
        self.pool.finish(self.call);
        // The caller's own panic is the one that goes on; a helper's is dropped.
        if std::thread::panicking() {
            drop(self.pool.take_panic(self.call));
        }
    }
}

/// A job in the queue: which call posted it and what it runs.
struct Job {
    call: u64,
    run: &'static (dyn Fn() + Sync),
}

/// The persistent helper threads and their queue of jobs.
struct Pool {
    state: Mutex<PoolState>,
    /// Helpers wait here for a job.
    posted: Condvar,
    /// Callers wait here for their started jobs to end.
    ended: Condvar,
    /// The calls posted so far, raised under the lock with each one: an idle helper watches
    /// it while it spins ([`spin_until`]) before it sleeps on `posted`.
    posts: AtomicU64,
    /// The calls whose started jobs all ended so far, raised under the lock with each one: a
    /// caller waiting for its jobs watches it while it spins before it sleeps on `ended`.
    ends: AtomicU64,
}

/// How long an idle helper spins for the next call's jobs, and a caller for its started jobs
/// to end, before sleeping on the pool's condition variables. Waking a sleeping thread took
/// 13-41 us here (a virtual machine's idle processor woken; PUMA 560 `fk --jacobian`, timed
/// from the post to the job's start and from the job's end to the caller's return: 1-3 us
/// with the spin), at the start and the end of each of the report's parallel stages, on the
/// process's critical path; the helper's gaps between two stages were 100-180 us. A measured
/// bound, not a proven one: a longer wait sleeps as before, so the bound caps the processor
/// time a spin costs. PUMA 560 `fk --jacobian` as a process (two threads, SCHED_FIFO, a loaded
/// machine, 300 interleaved runs each): wall minimum 4.16 -> 3.89 ms and 4.10 -> 3.84 ms,
/// median 4.46 -> 4.19 ms, for 0.13-0.18 ms more processor time (median 6.71 -> 6.89 ms).
const SPIN: std::time::Duration = std::time::Duration::from_micros(250);

/// Spins until `done` or for [`SPIN`]; whether `done` was seen. Between rounds of checks it
/// yields the processor: where there are more runnable threads than processors (a busy
/// machine, or more threads asked for than it has), the thread it waits for may be waiting
/// for this processor, and a spin that never yields would hold it off for the whole [`SPIN`].
fn spin_until(done: impl Fn() -> bool) -> bool {
    let start = std::time::Instant::now();
    loop {
        for _ in 0..64 {
            if done() {
                return true;
            }
            std::hint::spin_loop();
        }
        std::thread::yield_now();
        if start.elapsed() > SPIN {
            return done();
        }
    }
}

#[derive(Default)]
struct PoolState {
    queue: VecDeque<Job>,
    /// The calls with jobs begun and not ended, with their numbers of such jobs.
    running: Vec<(u64, usize)>,
    /// The panics of jobs, by call, until the call takes them.
    panics: Vec<(u64, Box<dyn std::any::Any + Send>)>,
    /// The helpers started (a failed start is not retried past this count).
    helpers: usize,
    next_call: u64,
}

impl Pool {
    /// This process's pool: a process forked from one that had a pool (Python's
    /// `multiprocessing`, `os.fork`) gets a new one ([`PerFork`]), with none of the parent's
    /// helpers, whose lock may have been held at the fork.
    fn get() -> &'static Pool {
        static POOL: PerFork<Pool> = PerFork::new();
        POOL.get_or(|| Pool {
            state: Mutex::new(PoolState::default()),
            posted: Condvar::new(),
            ended: Condvar::new(),
            posts: AtomicU64::new(0),
            ends: AtomicU64::new(0),
        })
    }

    fn lock(&self) -> MutexGuard<'_, PoolState> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Queues `k` copies of `run` (starting helpers up to `k`), and returns the call's number.
    fn post(&'static self, k: usize, run: &'static (dyn Fn() + Sync)) -> u64 {
        let mut st = self.lock();
        self.start(&mut st, k);
        let call = st.next_call;
        st.next_call += 1;
        st.queue.extend((0..k).map(|_| Job { call, run }));
        self.posts.fetch_add(1, Ordering::Release);
        drop(st);
        for _ in 0..k {
            self.posted.notify_one();
        }
        call
    }

    /// Starts helpers until there are `k` (fewer if a thread cannot be started).
    fn start(&'static self, st: &mut PoolState, k: usize) {
        while st.helpers < k {
            let started = std::thread::Builder::new()
                .name("dqsym-helper".to_owned())
                .stack_size(WORKER_STACK)
                .spawn(move || self.serve());
            if started.is_err() {
                break;
            }
            st.helpers += 1;
        }
    }

    /// A helper's life: runs the start hook ([`on_helper_start`]), then takes jobs from the
    /// queue and runs them, forever. With the queue empty it spins for a new call
    /// ([`spin_until`]), then sleeps until one is posted.
    fn serve(&self) {
        let _hook = HELPER_START.get().map(|start| start());
        let mut st = self.lock();
        loop {
            let Some(job) = st.queue.pop_front() else {
                let seen = self.posts.load(Ordering::Acquire);
                drop(st);
                let posted = spin_until(|| self.posts.load(Ordering::Acquire) != seen);
                st = self.lock();
                if !posted && st.queue.is_empty() {
                    st = self.posted.wait(st).unwrap_or_else(|e| e.into_inner());
                }
                continue;
            };
            match st.running.iter_mut().find(|(c, _)| *c == job.call) {
                Some((_, n)) => *n += 1,
                None => st.running.push((job.call, 1)),
            }
            drop(st);
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(job.run));
            st = self.lock();
            if let Err(p) = outcome {
                st.panics.push((job.call, p));
            }
            if let Some(i) = st.running.iter().position(|(c, _)| *c == job.call) {
                st.running[i].1 -= 1;
                if st.running[i].1 == 0 {
                    st.running.swap_remove(i);
                    self.ends.fetch_add(1, Ordering::Release);
                    self.ended.notify_all();
                }
            }
        }
    }

    /// Takes `call`'s unstarted jobs out of the queue and waits until its started ones ended:
    /// spinning first ([`spin_until`]) while no call ends, then sleeping.
    fn finish(&self, call: u64) {
        let mut st = self.lock();
        st.queue.retain(|j| j.call != call);
        while st.running.iter().any(|(c, _)| *c == call) {
            let seen = self.ends.load(Ordering::Acquire);
            drop(st);
            let ended = spin_until(|| self.ends.load(Ordering::Acquire) != seen);
            st = self.lock();
            if !ended && st.running.iter().any(|(c, _)| *c == call) {
                st = self.ended.wait(st).unwrap_or_else(|e| e.into_inner());
            }
        }
    }

    /// The first panic of `call`'s jobs, if one panicked (the others are dropped).
    fn take_panic(&self, call: u64) -> Option<Box<dyn std::any::Any + Send>> {
        let mut st = self.lock();
        let mut first = None;
        let mut i = 0;
        while i < st.panics.len() {
            if st.panics[i].0 == call {
                let (_, p) = st.panics.swap_remove(i);
                first.get_or_insert(p);
            } else {
                i += 1;
            }
        }
        first
    }
}

/// The forks this process descends from since it first asked, counted in the child of each
/// `fork` (a `pthread_atfork` handler): a pool made under another count is a parent's.
/// A value made once per process, and made again in a process forked from it (Python's
/// `multiprocessing`, `os.fork`): the child's copy of the parent's value may hold a lock, or a
/// `OnceLock` being filled, taken by a thread the child does not have, so the child never
/// touches it (it is left as it was, not freed: the parent's memory, copied). For the
/// process-wide pool and caches; a per-thread cache holding such values keeps the
/// fork count it was filled at and empties itself when the count differs ([`this_fork`]).
pub(crate) struct PerFork<T> {
    made: AtomicPtr<(u64, T)>,
    _owns: PhantomData<T>,
}

impl<T: Send + Sync> PerFork<T> {
    pub(crate) const fn new() -> Self {
        PerFork {
            made: AtomicPtr::new(std::ptr::null_mut()),
            _owns: PhantomData,
        }
    }

    /// This process's value, made by `make` the first time (two threads may both make one;
    /// one is kept, the other dropped unseen).
    pub(crate) fn get_or(&'static self, make: impl Fn() -> T) -> &'static T {
        loop {
            let seen = self.made.load(Ordering::Acquire);
            let forks = forks::seen();
            // SAFETY: a pointer stored in `made` comes from `Box::into_raw` below and is never
            // freed, so it is valid for the rest of the process (and of a forked child).
            if let Some((at, value)) = unsafe { seen.as_ref() } {
                if *at == forks {
                    return value;
                }
            }
            let fresh = Box::into_raw(Box::new((forks, make())));
            match self
                .made
                .compare_exchange(seen, fresh, Ordering::AcqRel, Ordering::Acquire)
            {
                // SAFETY: stored just now, and never freed (above).
                Ok(_) => return unsafe { &(*fresh).1 },
                // Another thread stored one first: this one was never shared.
                // SAFETY: `fresh` is the box made above, seen by no other thread.
                Err(_) => drop(unsafe { Box::from_raw(fresh) }),
            }
        }
    }
}

/// A per-thread cache (a map with the fork count it was filled at), emptied first in a
/// process forked since (see [`PerFork`]).
pub(crate) fn this_fork<M: Default>(cache: &mut (u64, M)) -> &mut M {
    let forks = forks::seen();
    if cache.0 != forks {
        *cache = (forks, M::default());
    }
    &mut cache.1
}

#[cfg(unix)]
mod forks {
    use std::ffi::c_int;
    use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

    /// Forks counted in this process.
    static FORKS: AtomicU64 = AtomicU64::new(0);
    /// Whether the handler is registered (a registration in a parent stays in its children).
    static REGISTERED: AtomicBool = AtomicBool::new(false);

    type Handler = Option<unsafe extern "C" fn()>;

    extern "C" {
        fn pthread_atfork(prepare: Handler, parent: Handler, child: Handler) -> c_int;
    }

    /// Runs in the child of every fork, before `fork` returns there; an atomic addition is
    /// all it does (async-signal-safe).
    unsafe extern "C" fn in_child() {
        FORKS.fetch_add(1, Ordering::AcqRel);
    }

    /// The forks counted so far. The handler is registered first, without a lock or a
    /// `Once` (a fork while another thread held either would leave the child waiting on it):
    /// two threads that both find it unregistered both register it, and the count then rises
    /// by two a fork, which changes it all the same. A thread goes on only once a
    /// registration is done, so every fork after a pool was made is counted.
    pub(super) fn seen() -> u64 {
        if !REGISTERED.load(Ordering::Acquire) {
            // SAFETY: registers a handler that only adds to an atomic; no pointer is passed.
            // A failed registration (out of memory) is tried again at the next call.
            if unsafe { pthread_atfork(None, None, Some(in_child)) } == 0 {
                REGISTERED.store(true, Ordering::Release);
            }
        }
        FORKS.load(Ordering::Acquire)
    }
}

/// Without `fork` no process inherits a pool.
#[cfg(not(unix))]
mod forks {
    pub(super) fn seen() -> u64 {
        0
    }
}

/// Runs `child` in a forked child of this process and `parent` in this one right after the
/// fork, and fails unless the child ends within 30 s with `child` true (a child that waits
/// forever on a lock is killed).
#[cfg(all(test, unix))]
pub(crate) fn in_forked_child(child: impl FnOnce() -> bool, parent: impl FnOnce()) {
    use std::ffi::c_int;
    extern "C" {
        fn fork() -> c_int;
        fn waitpid(pid: c_int, status: *mut c_int, options: c_int) -> c_int;
        fn kill(pid: c_int, sig: c_int) -> c_int;
        fn _exit(status: c_int) -> !;
    }
    const WNOHANG: c_int = 1;
    const SIGKILL: c_int = 9;
    // SAFETY: the child runs only this crate's code and `_exit`s, never returning into the
    // test harness; the parent waits for it below.
    let pid = unsafe { fork() };
    assert!(pid >= 0, "fork failed");
    if pid == 0 {
        let ok = std::panic::catch_unwind(std::panic::AssertUnwindSafe(child));
        // SAFETY: ends the child without running the harness's code in it.
        unsafe { _exit(if matches!(ok, Ok(true)) { 0 } else { 1 }) }
    }
    parent();
    let mut status: c_int = -1;
    let mut ended = false;
    for _ in 0..3000 {
        // SAFETY: waits for the child started above; `status` is a local.
        if unsafe { waitpid(pid, &mut status, WNOHANG) } == pid {
            ended = true;
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    if !ended {
        // SAFETY: the child started above, which has not been waited for.
        unsafe {
            kill(pid, SIGKILL);
            waitpid(pid, &mut status, 0);
        }
    }
    assert!(ended, "the forked child did not finish in 30 s");
    assert_eq!(status, 0, "the forked child's results were wrong");
}

#[cfg(test)]
mod tests {
    use super::super::ctx::work_used;
    use super::*;
    use crate::Scalar;

    fn sum_of(n: usize) -> Scalar {
        (0..n).fold(Scalar::int(0), |acc, i| acc + Scalar::sym(&format!("x{i}")))
    }

    #[test]
    fn results_keep_the_order_of_the_items() {
        let items: Vec<usize> = (0..50).collect();
        let out = par_map(&items, |&n| sum_of(n).len());
        assert_eq!(out, items);
    }

    #[test]
    fn workers_inherit_the_term_limit_and_charge_the_budget() {
        let small = Context::new().with_term_limit(10).with_threads(2).enter();
        let out = par_map(&[3usize, 30, 4, 40], |&n| sum_of(n).check().is_ok());
        assert_eq!(out, vec![true, false, true, false]);
        drop(small);
        let _big = Context::new().with_threads(2).enter();
        let before = work_used();
        let _ = par_map(&[20usize; 8], |&n| sum_of(n));
        assert!(
            work_used() > before,
            "the workers' work is charged to the caller"
        );
        let (a, b) = join(|| sum_of(2).len(), || sum_of(3).len());
        assert_eq!((a, b), (2, 3));
    }

    #[test]
    fn nested_maps_and_joins_finish_and_keep_the_order() {
        let _in = Context::new().with_threads(3).enter();
        let items: Vec<usize> = (0..12).collect();
        let out = par_map(&items, |&n| {
            let inner: Vec<usize> = (0..n).collect();
            let (a, b) = join(
                || par_map(&inner, |&k| sum_of(k).len()).iter().sum::<usize>(),
                || sum_of(n).len(),
            );
            a + b
        });
        let expected: Vec<usize> = items
            .iter()
            .map(|&n| n * n.saturating_sub(1) / 2 + n)
            .collect();
        assert_eq!(out, expected);
        // The helpers are kept: many calls start no more of them than the most threads a
        // call asks for (at most 8) less the caller.
        for _ in 0..50 {
            let _ = par_map(&items, |&n| n + 1);
        }
        assert!(Pool::get().lock().helpers < 8);
    }

    #[test]
    fn a_panic_on_a_helper_reaches_the_caller_and_the_helpers_stay() {
        let _in = Context::new().with_threads(2).enter();
        let items: Vec<usize> = (0..64).collect();
        let caught = std::panic::catch_unwind(|| {
            par_map(&items, |&n| {
                assert!(n != 40, "item 40");
                n
            })
        });
        assert!(caught.is_err());
        assert_eq!(par_map(&items, |&n| n * 2)[63], 126);
        let (a, b) = join(|| 1, || 2);
        assert_eq!((a, b), (1, 2));
    }

    thread_local! {
        /// Set by the start hook of the test below, on the thread that runs it.
        static HOOKED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    }

    /// A helper runs the hook set by `on_helper_start` before its first job (the `dqsym`
    /// binary's stack-overflow report of its helpers rests on it). In a forked child, whose
    /// pool is made there after the hook is set.
    #[cfg(unix)]
    #[test]
    fn helpers_run_the_start_hook_before_their_jobs() {
        in_forked_child(
            || {
                let set = on_helper_start(|| {
                    HOOKED.with(|h| h.set(true));
                    Box::new(())
                });
                let _in = Context::new().with_threads(2).enter();
                let began = std::sync::atomic::AtomicBool::new(false);
                let (_, on_helper) = join(
                    || {
                        // Waits (up to 10 s) for a helper to take `b`, so `b` does not run
                        // here.
                        let until = std::time::Instant::now() + std::time::Duration::from_secs(10);
                        while !began.load(std::sync::atomic::Ordering::SeqCst)
                            && std::time::Instant::now() < until
                        {
                            std::thread::yield_now();
                        }
                    },
                    || {
                        began.store(true, std::sync::atomic::Ordering::SeqCst);
                        HOOKED.with(std::cell::Cell::get)
                    },
                );
                set && on_helper && !HOOKED.with(std::cell::Cell::get)
            },
            || {},
        );
    }

    /// A child forked while the parent's pool is in use (its lock held, helpers started)
    /// makes a pool of its own and finishes its maps and joins: before, it waited forever on
    /// the lock, which no thread of the child would release.
    #[cfg(unix)]
    #[test]
    fn a_forked_child_gets_a_pool_of_its_own() {
        let _in = Context::new().with_threads(2).enter();
        let items: Vec<usize> = (0..40).collect();
        assert_eq!(par_map(&items, |&n| n * 3)[39], 117);
        let parents = Pool::get();
        let held = parents.lock();
        in_forked_child(
            || {
                let own = Pool::get();
                let out = par_map(&items, |&n| sum_of(n % 5).len());
                let (a, b) = join(|| sum_of(2).len(), || sum_of(3).len());
                !std::ptr::eq(own, parents)
                    && own.lock().helpers == 1
                    && out == items.iter().map(|n| n % 5).collect::<Vec<_>>()
                    && (a, b) == (2, 3)
            },
            move || drop(held),
        );
        // The parent's pool is still its own.
        assert!(std::ptr::eq(Pool::get(), parents));
        assert_eq!(par_map(&items, |&n| n + 1)[0], 1);
    }

    /// `spin_until` returns at the first call of its condition that is true, and ends (false)
    /// on one that never is. The true call is the 64th, the last of the first round of
    /// checks, which runs before any look at the clock or yield: how many calls fit in
    /// [`SPIN`] depends on the machine's load (the 1,000th call was not reached in one CI run
    /// with both cores busy once the spin yielded).
    #[test]
    fn spin_until_stops_at_the_first_true_and_ends_on_none() {
        let calls = std::cell::Cell::new(0);
        let seen = spin_until(|| {
            calls.set(calls.get() + 1);
            calls.get() == 64
        });
        assert!(seen);
        assert_eq!(calls.get(), 64);
        assert!(!spin_until(|| false));
    }

    /// Calls one after another, with gaps shorter than [`SPIN`] (the helper takes the next
    /// call while it spins) and longer (it sleeps and is woken), each keep every result in
    /// order, and run a join's second closure exactly once.
    #[test]
    fn calls_after_short_and_long_gaps_keep_their_results() {
        let _in = Context::new().with_threads(2).enter();
        let items: Vec<usize> = (0..16).collect();
        for round in 0..40usize {
            if round % 4 == 3 {
                std::thread::sleep(SPIN * 4);
            }
            let out = par_map(&items, |&n| sum_of(n + round % 3).len());
            let expected: Vec<usize> = items.iter().map(|n| n + round % 3).collect();
            assert_eq!(out, expected);
            let ran = AtomicUsize::new(0);
            let (a, b) = join(
                || sum_of(round % 5).len(),
                || {
                    ran.fetch_add(1, Ordering::Relaxed);
                    round
                },
            );
            assert_eq!((a, b, ran.into_inner()), (round % 5, round, 1));
        }
    }

    #[test]
    fn cancelling_stops_the_workers() {
        let flag = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
        let _in = Context::new()
            .with_threads(2)
            .with_cancel_flag(flag)
            .enter();
        let out = par_map(&[5usize; 4], |&n| sum_of(n).check());
        assert!(out.iter().all(|r| *r == Err(ScalarError::Cancelled)));
    }
}
