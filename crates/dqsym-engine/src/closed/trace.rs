//! A record of what the closed-form extraction did, for teaching: the expanded sum, each
//! angle-sum identity with the two terms it combined, and the factored result.
//!
//! Tracing observes the extraction and never steers it: [`closed_form_traced`] returns the
//! very expression [`closed_form`](super::closed_form) returns.

use super::expr::{Angle, Expr};
use super::factor::mon_expr;
use super::mon::{atom, Ctx, Mon};

/// The four angle-sum identities the recombination applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Identity {
    /// `cos a cos b - sin a sin b = cos(a + b)`.
    CosSum,
    /// `cos a cos b + sin a sin b = cos(a - b)`.
    CosDiff,
    /// `sin a cos b + cos a sin b = sin(a + b)`.
    SinSum,
    /// `sin a cos b - cos a sin b = sin(a - b)`.
    SinDiff,
}

impl Identity {
    /// The identity in words of `a` and `b`, plain text.
    pub fn text(self) -> &'static str {
        match self {
            Identity::CosSum => "cos a cos b - sin a sin b = cos(a + b)",
            Identity::CosDiff => "cos a cos b + sin a sin b = cos(a - b)",
            Identity::SinSum => "sin a cos b + cos a sin b = sin(a + b)",
            Identity::SinDiff => "sin a cos b - cos a sin b = sin(a - b)",
        }
    }

    /// The identity in LaTeX.
    pub fn latex(self) -> &'static str {
        match self {
            Identity::CosSum => r"\cos a \cos b - \sin a \sin b = \cos(a + b)",
            Identity::CosDiff => r"\cos a \cos b + \sin a \sin b = \cos(a - b)",
            Identity::SinSum => r"\sin a \cos b + \cos a \sin b = \sin(a + b)",
            Identity::SinDiff => r"\sin a \cos b - \cos a \sin b = \sin(a - b)",
        }
    }
}

/// One step of a traced closed-form extraction.
#[derive(Clone, Debug, PartialEq, Eq)]
// A few steps per traced closed form, read in place by the walkthrough renderers: not worth
// boxing the identity's angles and terms.
#[allow(clippy::large_enum_variant)]
pub enum TraceStep {
    /// The sum the following identities work on, term by term. In round 1 every angle sum of
    /// the canonical form is expanded into products of single-angle factors (the form a hand
    /// computation of the product reaches); in later rounds it is the previous round's result.
    /// The last `Sum` is the regrouped sum, before common factors are pulled out.
    Sum {
        /// 1 for the expanded sum.
        round: usize,
        /// The terms, numbered from 1 in the steps that refer to them.
        terms: Vec<Expr>,
    },
    /// An identity applied to two terms of the latest [`TraceStep::Sum`]:
    /// `cofactor (cos a cos b - sin a sin b) = result`.
    Identity {
        /// Which identity.
        identity: Identity,
        /// The angle `a`.
        a: Angle,
        /// The angle `b`.
        b: Angle,
        /// The two terms combined, numbered from 1 (`cos a cos b` or `sin a cos b` first).
        terms: [usize; 2],
        /// The common factor of the two terms, with the sign of the first.
        cofactor: Expr,
        /// The term that replaces them.
        result: Expr,
    },
    /// Common factors pulled out of the last sum: the closed form.
    Factored(Expr),
    /// The regrouped form was not cheaper than the canonical Fourier modes kept whole and
    /// factored, so those are the closed form; the identity steps above are not used.
    KeptWhole(Expr),
    /// A shorter equivalent form than both (the harmonic form `R cos(x - phi)`, a sum turned
    /// into a product, a polynomial in one cosine or sine factored by its roots): the closed
    /// form.
    Shorter(Expr),
}

/// One identity application as the recombination sees it: atoms of the first and second term
/// by interned angle id, before any renumbering.
pub(crate) struct AngleSum<'a> {
    pub(crate) sin: bool,
    pub(crate) sign: i64,
    pub(crate) a: u32,
    pub(crate) b: u32,
    pub(crate) terms: [usize; 2],
    pub(crate) cofactor: &'a Mon,
    /// The combined angle's id and whether it was negated; `None` for the zero angle.
    pub(crate) combined: Option<(u32, bool)>,
}

/// Collects [`TraceStep`]s during a recombination.
#[derive(Default)]
pub(crate) struct Recorder {
    pub(crate) steps: Vec<TraceStep>,
    pending: Vec<TraceStep>,
    rounds: usize,
}

impl Recorder {
    /// A round starts on `mons`.
    pub(crate) fn round(&mut self, ctx: &Ctx, mons: &[Mon]) {
        self.flush();
        self.rounds += 1;
        self.steps.push(TraceStep::Sum {
            round: self.rounds,
            terms: mons.iter().map(|m| mon_expr(m).to_expr(ctx)).collect(),
        });
    }

    /// An identity was applied.
    pub(crate) fn apply(&mut self, ctx: &Ctx, s: &AngleSum<'_>) {
        let identity = match (s.sin, s.sign) {
            (false, 1) => Identity::CosSum,
            (false, _) => Identity::CosDiff,
            (true, 1) => Identity::SinSum,
            (true, _) => Identity::SinDiff,
        };
        let cofactor = mon_expr(s.cofactor).to_expr(ctx);
        let result = match s.combined {
            None if s.sin => Expr::zero(),
            None => cofactor.clone(),
            Some((id, flipped)) => {
                // New angles keep their ids until the round ends, so the atom reads back.
                let mut m = s.cofactor.clone();
                m.atoms.push(atom(id, s.sin));
                if s.sin && flipped {
                    m.q = -&m.q;
                }
                mon_expr(&m).to_expr(ctx)
            }
        };
        self.pending.push(TraceStep::Identity {
            identity,
            a: ctx.angles[s.a as usize].clone(),
            b: ctx.angles[s.b as usize].clone(),
            terms: [s.terms[0] + 1, s.terms[1] + 1],
            cofactor,
            result,
        });
    }

    fn flush(&mut self) {
        // In reading order of the terms they combine.
        self.pending.sort_by_key(|s| match s {
            TraceStep::Identity { terms, .. } => terms[0].min(terms[1]),
            _ => 0,
        });
        self.steps.append(&mut self.pending);
    }

    /// The steps, ending with `last`.
    pub(crate) fn finish(mut self, last: TraceStep) -> Vec<TraceStep> {
        self.flush();
        self.steps.push(last);
        self.steps
    }
}
