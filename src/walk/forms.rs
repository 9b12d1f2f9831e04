//! The display values of a walkthrough: the closed form of every scalar a renderer shows,
//! computed once by the builder ([`Walkthrough::prepare`]) so that the renderers only look them
//! up and print them (they never simplify).

use super::notation::scalars;
use super::svg::Scene;
use super::{Config, Step, WalkError, Walkthrough, Word};
use crate::{closed::TraceStep, closed_form, Expr, Scalar, ScalarError};
use std::collections::HashMap;

/// The closed forms of the scalars of a walkthrough, each computed once (or why it failed).
#[derive(Clone, Debug, Default)]
pub struct Forms(HashMap<Scalar, Result<Expr, ScalarError>>);

impl Forms {
    /// Computes the closed form of `x` unless it is known.
    pub(crate) fn add(&mut self, x: &Scalar) {
        if !self.0.contains_key(x) {
            self.0.insert(x.clone(), closed_form(x));
        }
    }

    /// The closed form of `x`.
    ///
    /// # Errors
    /// When its closed form failed (over the term limit or the work budget), and when `x` is
    /// not a scalar of the walkthrough (it was edited after [`Walkthrough::prepare`]).
    pub fn of(&self, x: &Scalar) -> Result<&Expr, WalkError> {
        match self.0.get(x) {
            Some(Ok(e)) => Ok(e),
            Some(Err(e)) => Err(WalkError::Scalar(e.clone())),
            None => Err(WalkError::Unprepared),
        }
    }
}

/// `theta/2`.
pub(crate) fn half(t: &Scalar) -> Scalar {
    t * Scalar::rational(num_rational::BigRational::new(1.into(), 2.into()))
}

impl Walkthrough {
    /// Computes the display values of every step: the closed forms of its values and words,
    /// of the half-angle identities it states, and of the angles of its identities. The
    /// builders call it; call it again after editing the steps.
    pub fn prepare(&mut self) {
        let mut f = Forms::default();
        for step in &self.steps {
            match step {
                Step::Factor { value, meaning, .. } | Step::Define { value, meaning, .. } => {
                    scalars(value).into_iter().for_each(|x| f.add(x));
                    for w in &meaning.0 {
                        match w {
                            Word::Text(_) => {}
                            Word::Scalar(x) => f.add(x),
                            Word::Tuple(v) => v.iter().for_each(|x| f.add(x)),
                        }
                    }
                }
                Step::Product { value, .. } | Step::Result { value, .. } => {
                    scalars(value).into_iter().for_each(|x| f.add(x));
                }
                Step::Transform {
                    value,
                    half_angles,
                    traces,
                    ..
                } => {
                    scalars(value).into_iter().for_each(|x| f.add(x));
                    for a in half_angles {
                        let t = Scalar::sym(&a.symbol);
                        let h = half(&t);
                        for x in [h.cos(), h.sin(), t.cos(), t.sin()] {
                            f.add(&x);
                        }
                    }
                    for t in traces {
                        for s in &t.steps {
                            if let TraceStep::Identity { a, b, .. } = s {
                                f.add(&a.to_scalar());
                                f.add(&b.to_scalar());
                            }
                        }
                    }
                }
                Step::Notation { .. }
                | Step::Check { .. }
                | Step::Explain { .. }
                | Step::Legend(_)
                | Step::Solutions { .. } => {}
            }
        }
        // The exact scene of the page's drawing and live function (its symbolic parts do not
        // depend on the configuration drawn).
        if let Some(scene) = self
            .mechanism
            .as_ref()
            .and_then(|m| Scene::new(m, &Config::default()).ok())
        {
            for x in scene.scalars() {
                f.add(x);
            }
        }
        self.forms = f;
    }
}
