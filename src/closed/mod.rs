//! Closed forms: the display layer between canonical scalars and printed text.
//!
//! The canonical form is a Fourier series; a kinematician reads products of cosines and sines
//! of grouped angles. [`closed_form`] tries two shapes and keeps the cheaper by [`Cost`]:
//! (a) every mode split into single-symbol atoms, then regrouped by the angle-sum identities
//! (`recombine.rs`) and factored (`factor.rs`); (b) the Fourier modes kept whole and factored.
//! The result is re-canonicalized and compared with the input before it is returned.

mod expr;
mod factor;
mod mon;
mod recombine;
mod trace;

pub use expr::{Angle, Cost, Expr};
pub use trace::{Identity, TraceStep};

use crate::{Scalar, ScalarError};

/// The largest number of monomials the split shape may have before it is skipped.
const SPLIT_LIMIT: usize = 100_000;

/// The most readable equivalent form of `x`: fewest operations, then fewest calls.
///
/// # Errors
/// When `x` is an error value, and when the search or the check of its result against `x`
/// runs out of the work budget or over the term limit (see [`crate::set_work_budget`]).
pub fn closed_form(x: &Scalar) -> Result<Expr, ScalarError> {
    if let Err(e) = x.terms() {
        return Err(e.clone());
    }
    let (wctx, wmons) = mon::whole_modes(x);
    let (whole, wc) = factor::build(&wmons)?;
    let split_size: usize = x
        .terms()
        .map(|t| t.iter().map(|t| 1usize << t.mode.freq.len().min(30)).sum())
        .unwrap_or(0);
    if split_size > SPLIT_LIMIT {
        return Ok(whole.to_expr(&wctx));
    }
    let (mut sctx, smons) = mon::split_modes(x);
    let smons = recombine::recombine(&mut sctx, smons);
    let (split, sc) = factor::build(&smons)?;
    // Prefer the regrouped shape on ties: it is the one textbooks print.
    let best = if sc <= wc {
        split.to_expr(&sctx)
    } else {
        whole.to_expr(&wctx)
    };
    let value = best.to_scalar();
    if let Some(e) = value.as_error() {
        // The check ran out of the budget or the term limit: no verified form to give.
        return Err(e.clone());
    }
    if value == *x {
        Ok(best)
    } else {
        debug_assert!(false, "closed form does not equal its input");
        Ok(whole.to_expr(&wctx))
    }
}

/// [`closed_form`] with a record of how it was reached: the expanded sum, every angle-sum
/// identity applied (with the numbers of the terms it combined), each regrouped sum, and the
/// factored result. The expression is the one [`closed_form`] returns.
///
/// # Errors
/// When `x` is an error value, or the work budget runs out.
pub fn closed_form_traced(x: &Scalar) -> Result<(Expr, Vec<TraceStep>), ScalarError> {
    if let Err(e) = x.terms() {
        return Err(e.clone());
    }
    let (wctx, wmons) = mon::whole_modes(x);
    let (whole, wc) = factor::build(&wmons)?;
    let split_size: usize = x
        .terms()
        .map(|t| t.iter().map(|t| 1usize << t.mode.freq.len().min(30)).sum())
        .unwrap_or(0);
    if split_size > SPLIT_LIMIT {
        let e = whole.to_expr(&wctx);
        return Ok((e.clone(), vec![TraceStep::KeptWhole(e)]));
    }
    let (mut sctx, smons) = mon::split_modes(x);
    let mut rec = trace::Recorder::default();
    let smons = recombine::recombine_traced(&mut sctx, smons, &mut Some(&mut rec));
    let (split, sc) = factor::build(&smons)?;
    let (best, last) = if sc <= wc {
        let e = split.to_expr(&sctx);
        (e.clone(), TraceStep::Factored(e))
    } else {
        let e = whole.to_expr(&wctx);
        (e.clone(), TraceStep::KeptWhole(e))
    };
    if best.to_scalar() == *x {
        Ok((best, rec.finish(last)))
    } else {
        debug_assert!(false, "closed form does not equal its input");
        let e = whole.to_expr(&wctx);
        Ok((e.clone(), vec![TraceStep::KeptWhole(e)]))
    }
}
