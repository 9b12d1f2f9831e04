//! Independent exact computations on several threads, under the caller's context.
//!
//! A worker enters the caller's [`Context`] (term limit, exponent limit, threads, cancel flag)
//! with what is left of the caller's work budget; the work the workers did is charged to the
//! caller afterwards, so a parallel derivation spends one budget, as a sequential one would
//! (the workers together may overshoot it by at most one worker's budget before they stop).
//! Cancelling the context stops the workers too: they charge their work to the same flag.

use super::ctx::{charge, threads, Context};
use super::ScalarError;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

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
    std::thread::scope(|s| {
        let helpers: Vec<_> = (1..n)
            .filter_map(|_| {
                std::thread::Builder::new()
                    .stack_size(WORKER_STACK)
                    .spawn_scoped(s, || work(true))
                    .ok()
            })
            .collect();
        work(false);
        for h in helpers {
            if let Err(p) = h.join() {
                std::panic::resume_unwind(p);
            }
        }
    });
    // The workers' work counts against this thread's budget; an overrun shows up in the
    // next operation here, as it would have sequentially.
    let _: Result<(), ScalarError> = charge(spent.into_inner() as u64);
    let mut done = done.into_inner().unwrap_or_else(|e| e.into_inner());
    done.sort_unstable_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, r)| r).collect()
}

/// Runs `a` on this thread and `b` on another one (under this thread's limits), and returns
/// both results. Without a second thread (one allowed, or none to be had) both run here.
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
    std::thread::scope(|s| {
        let other = std::thread::Builder::new()
            .stack_size(WORKER_STACK)
            .spawn_scoped(s, || {
                let entered = ctx.enter();
                let r = take().map(|b| b());
                (r, entered.work_used())
            });
        let ra = a();
        let (rb, used) = match other {
            Ok(h) => match h.join() {
                Ok(x) => x,
                Err(p) => std::panic::resume_unwind(p),
            },
            Err(_) => (None, 0),
        };
        let _ = charge(used);
        // The worker did not start: `b` is still in its slot.
        let rb = rb.or_else(|| take().map(|b| b()));
        (ra, rb.unwrap_or_else(|| unreachable!("b runs once")))
    })
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
