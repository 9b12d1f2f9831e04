//! A walkthrough of a `.dq` script: the script runs in a fresh [`Session`] that reports each
//! motion built, product taken and point transformed; this module turns the reports into steps.

use super::motion::{is_point, Motion, Words};
use super::{ComponentTrace, HalfAngle, Mechanism, Step, WalkError, Walkthrough};
use crate::lang::{Event, Observer};
use crate::{
    closed::closed_form_traced,
    lang::{BindingKind, StmtKind},
    parse, DualQuat, Scalar, Session, Trig, Value,
};
use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};

/// The evaluation's events of one statement, in order.
#[derive(Default)]
struct Recorder(RefCell<Vec<Event>>);

impl Observer for Recorder {
    fn observe(&self, event: Event) {
        self.0.borrow_mut().push(event);
    }
}

/// The walkthrough of the script `src`; `title` names it (the file name).
///
/// # Errors
/// When the script does not parse or a statement fails (the message has the caret), or a
/// value cannot be shown.
pub fn walk_script(src: &str, title: &str) -> Result<Walkthrough, WalkError> {
    let program = parse(src).map_err(|e| WalkError::Script(e.to_string()))?;
    let mut session = Session::new();
    let mut w = ScriptWalk::default();
    for stmt in &program.statements {
        let rec = Recorder::default();
        let shown = session
            .exec_observed(stmt, &rec)
            .map_err(|e| WalkError::Script(e.render(src)))?;
        let name = match &stmt.kind {
            StmtKind::Assign { name, .. } => Some(name.name.clone()),
            StmtKind::HalfAngle { cos, sin, .. } => {
                w.notation(&session, &cos.name, &sin.name);
                continue;
            }
            _ => None,
        };
        let value = match (&name, &shown) {
            (Some(n), _) => session.get(n).cloned(),
            (None, Some(d)) => Some(d.value.clone()),
            (None, None) => session.get("ans").cloned(),
        };
        let label = match (&name, &shown) {
            (Some(n), _) => n.clone(),
            (None, Some(d)) => d.label.clone(),
            (None, None) => "ans".to_owned(),
        };
        w.half_names = half_angle_names(&session);
        for e in rec.0.into_inner() {
            w.event(e, &label, value.as_ref())?;
        }
        if let Some(v) = value {
            w.after(&label, name.is_some(), &v);
            if shown.is_some() {
                w.last_shown = Some((label, v));
            }
        }
    }
    Ok(w.finish(title))
}

/// The names `halfangle` gave the cosine and sine of each symbol's half angle.
fn half_angle_names(session: &Session) -> BTreeMap<String, (String, String)> {
    let mut cos: Vec<(Scalar, String)> = Vec::new();
    let mut sin: Vec<(Scalar, String)> = Vec::new();
    for (name, b) in session.bindings() {
        if let (BindingKind::HalfAngle { f, .. }, Value::Scalar(v)) = (&b.kind, &b.value) {
            let map = match f {
                Trig::Cos => &mut cos,
                Trig::Sin => &mut sin,
            };
            map.push((v.clone(), name.clone()));
        }
    }
    let mut out = BTreeMap::new();
    for (name, b) in session.bindings() {
        if b.kind == BindingKind::Symbol {
            let half = Scalar::sym(name).half_angle();
            let find = |m: &[(Scalar, String)], x: &Scalar| {
                m.iter().find(|(v, _)| v == x).map(|(_, n)| n.clone())
            };
            if let (Some(c), Some(s)) = (find(&cos, &half.cos()), find(&sin, &half.sin())) {
                out.insert(name.clone(), (c.clone(), s.clone()));
            }
        }
    }
    out
}

trait HalfAngleOf {
    fn half_angle(&self) -> Scalar;
}

impl HalfAngleOf for Scalar {
    fn half_angle(&self) -> Scalar {
        self * Scalar::rational(num_rational::BigRational::new(1.into(), 2.into()))
    }
}

/// The value as a dual quaternion, when it is a quaternion or one.
pub(crate) fn as_dq(v: &Value) -> Option<DualQuat<Scalar>> {
    match v {
        Value::DualQuat(d) => Some(d.clone()),
        Value::Quat(q) => Some(DualQuat::from_real(q.clone())),
        _ => None,
    }
}

/// The symbols that occur at a fractional frequency (a half angle) in `q`.
pub(crate) fn half_angle_symbols(q: &DualQuat<Scalar>) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for c in q.components() {
        out.extend(c.fractional_angle_symbols());
    }
    out
}

/// The traces of the non-constant coordinates of a point.
pub(crate) fn traces(label: &str, p: &[Scalar; 3]) -> Result<Vec<ComponentTrace>, WalkError> {
    let mut out = Vec::new();
    for (k, c) in ["x", "y", "z"].iter().zip(p) {
        if c.is_constant() {
            continue;
        }
        let (_, steps) = closed_form_traced(c)?;
        out.push(ComponentTrace {
            label: format!("{label}.{k}"),
            steps,
        });
    }
    Ok(out)
}

/// A point to check: the chain's motions, the home point, its image, the label.
type PointCheck = (Vec<Motion>, [Scalar; 3], [Scalar; 3], String);

/// The walkthrough being built.
#[derive(Default)]
struct ScriptWalk {
    steps: Vec<Step>,
    /// Known values with the motions they are products of.
    motions: Vec<(DualQuat<Scalar>, Vec<Motion>)>,
    /// Named factors, for recognizing conjugates.
    named: Vec<(DualQuat<Scalar>, String)>,
    /// Product labels already shown.
    shown_products: BTreeSet<String>,
    half_names: BTreeMap<String, (String, String)>,
    /// Transforms whose motion is a known chain: (motions, home point, image, label).
    checks: Vec<PointCheck>,
    last_shown: Option<(String, Value)>,
    /// The value the last transform step produced.
    last_image: Option<Value>,
}

impl ScriptWalk {
    fn notation(&mut self, session: &Session, c: &str, s: &str) {
        let meaning = |n: &str| {
            session
                .bindings()
                .get(n)
                .and_then(|b| b.kind.half_angle_meaning())
                .unwrap_or_default()
        };
        self.steps.push(Step::Notation {
            names: vec![c.to_owned(), s.to_owned()],
            meaning: format!("{c} = {}, {s} = {}", meaning(c), meaning(s)),
        });
    }

    fn motions_of(&self, q: &DualQuat<Scalar>) -> Option<&Vec<Motion>> {
        self.motions.iter().find(|(v, _)| v == q).map(|(_, m)| m)
    }

    fn register(&mut self, q: DualQuat<Scalar>, m: Vec<Motion>) {
        if self.motions_of(&q).is_none() {
            self.motions.push((q, m));
        }
    }

    fn event(&mut self, e: Event, label: &str, value: Option<&Value>) -> Result<(), WalkError> {
        match e {
            Event::Built {
                func,
                args,
                value: v,
            } => {
                let name = if value == Some(&v) {
                    label.to_owned()
                } else {
                    let a: Vec<&str> = args.iter().map(|(t, _)| t.as_str()).collect();
                    format!("{func}({})", a.join(", "))
                };
                if let Some(meaning) = velocity_words(func, &args, &v) {
                    if let Some(q) = as_dq(&v) {
                        self.named.push((q, name.clone()));
                    }
                    self.steps.push(Step::Define {
                        name,
                        value: v,
                        meaning,
                    });
                    return Ok(());
                }
                let Some(q) = as_dq(&v) else { return Ok(()) };
                if func == "point" {
                    self.steps.push(Step::Define {
                        name,
                        value: v,
                        meaning: Words::text("a point, 1 + eps (0; v)"),
                    });
                    return Ok(());
                }
                let m = built_motion(func, &args).or_else(|| Motion::of_dual_quat(&q));
                let meaning = m.as_ref().map(Motion::describe).unwrap_or_default();
                if let Some(m) = m {
                    self.register(q.clone(), vec![m]);
                }
                self.named.push((q, name.clone()));
                self.steps.push(Step::Factor {
                    name,
                    value: v,
                    meaning,
                });
            }
            Event::Chain { factors, partials } => {
                for (k, p) in partials.iter().enumerate() {
                    let left: Vec<&str> = factors[..=k].iter().map(|(t, _)| t.as_str()).collect();
                    let left = left.join("*");
                    let right = factors[k + 1].0.clone();
                    let full = format!("{left}*{right}");
                    let composed = {
                        let prefix = if k == 0 {
                            as_dq(&factors[0].1).and_then(|q| self.motions_of(&q).cloned())
                        } else {
                            as_dq(&partials[k - 1]).and_then(|q| self.motions_of(&q).cloned())
                        };
                        let next =
                            as_dq(&factors[k + 1].1).and_then(|q| self.motions_of(&q).cloned());
                        prefix.zip(next).map(|(mut a, b)| {
                            a.extend(b);
                            a
                        })
                    };
                    if let (Some(m), Some(q)) = (composed, as_dq(p)) {
                        self.register(q, m);
                    }
                    if self.shown_products.insert(full) {
                        self.steps.push(Step::Product {
                            left,
                            right,
                            value: p.clone(),
                        });
                    }
                }
                // q v q‾*: a point carried by a motion (eq 10).
                if let ([(qt, qv), (vt, vv), (_, cv)], Some(image)) =
                    (factors.as_slice(), partials.last())
                {
                    let (q, v, c) = (as_dq(qv), as_dq(vv), as_dq(cv));
                    if let (Some(q), Some(v), Some(c)) = (q, v, c) {
                        if is_point(&v) && !is_point(&q) && c == q.combined_conjugate() {
                            let name = if value == Some(image) { label } else { "ans" };
                            self.transform(name, qt, &q, vt, &v.dual.vector_part(), image)?;
                        }
                    }
                }
            }
            Event::Transform { q, v, value: image } => {
                let point = match &v.1 {
                    Value::Vector(p) => Some(p.clone()),
                    Value::DualQuat(d) if is_point(d) => Some(d.dual.vector_part()),
                    _ => None,
                };
                if let (Some(qd), Some(p)) = (as_dq(&q.1), point) {
                    let name = if value == Some(&image) { label } else { "ans" };
                    self.transform(name, &q.0, &qd, &v.0, &p, &image)?;
                }
            }
        }
        Ok(())
    }

    fn transform(
        &mut self,
        label: &str,
        qt: &str,
        q: &DualQuat<Scalar>,
        vt: &str,
        v: &[Scalar; 3],
        image: &Value,
    ) -> Result<(), WalkError> {
        let p = match image {
            Value::Vector(p) => p.clone(),
            Value::DualQuat(d) => d.dual.vector_part(),
            _ => return Ok(()),
        };
        let half_angles = half_angle_symbols(q)
            .into_iter()
            .map(|s| HalfAngle {
                names: self.half_names.get(&s).cloned(),
                symbol: s,
            })
            .collect();
        if let Some(m) = self.motions_of(q) {
            self.checks
                .push((m.clone(), v.clone(), p.clone(), label.to_owned()));
        }
        self.steps.push(Step::Transform {
            label: label.to_owned(),
            q: qt.to_owned(),
            v: vt.to_owned(),
            value: image.clone(),
            half_angles,
            traces: traces(if is_name(label) { label } else { "ans" }, &p)?,
        });
        self.last_image = Some(image.clone());
        Ok(())
    }

    /// After a statement bound or showed `v`: a factor or a point given as a tuple.
    fn after(&mut self, label: &str, assigned: bool, v: &Value) {
        if !assigned || self.last_image.as_ref() == Some(v) {
            return;
        }
        let Some(q) = as_dq(v) else { return };
        if self.motions_of(&q).is_some() || self.named.iter().any(|(x, _)| *x == q) {
            return;
        }
        if is_point(&q) {
            self.steps.push(Step::Define {
                name: label.to_owned(),
                value: v.clone(),
                meaning: Words::text("the point ").then_tuple(&q.dual.vector_part()),
            });
            return;
        }
        let conj = self
            .named
            .iter()
            .find(|(x, _)| x.combined_conjugate() == q)
            .map(|(_, n)| n.clone());
        if let Some(n) = conj {
            self.named.push((q, label.to_owned()));
            self.steps.push(Step::Define {
                name: label.to_owned(),
                value: v.clone(),
                meaning: Words::text(&format!(
                    "the combined conjugate of {n} (eq 9), which carries points back in q v q*"
                )),
            });
            return;
        }
        let m = Motion::of_dual_quat(&q);
        let meaning = match &m {
            Some(m) => m.describe(),
            None if q.unit_constraints().hold_exactly() => Words::text("a rigid motion"),
            None => Words::text("a dual quaternion that is not a rigid motion"),
        };
        if let Some(m) = m {
            self.register(q.clone(), vec![m]);
        }
        self.named.push((q, label.to_owned()));
        self.steps.push(Step::Factor {
            name: label.to_owned(),
            value: v.clone(),
            meaning,
        });
    }

    fn finish(mut self, title: &str) -> Walkthrough {
        if let Some((label, value)) = self.last_shown.take() {
            self.steps.push(Step::Result { label, value });
        }
        let mut mechanism = None;
        if let Some((motions, v, image, label)) = self.checks.last() {
            if let Some(step) = super::check::check(motions, v, image, label) {
                self.steps.push(step);
            }
            mechanism = Some(Mechanism {
                motions: motions.clone(),
                tool: Some(v.clone()),
                values: Vec::new(),
            });
        }
        let mut w = Walkthrough {
            title: title.to_owned(),
            steps: self.steps,
            mechanism,
            forms: super::Forms::default(),
        };
        w.prepare();
        w
    }
}

impl Words {
    fn then_tuple(mut self, v: &[Scalar]) -> Words {
        self.0.push(super::Word::Tuple(v.to_vec()));
        self
    }
}

/// What a twist or velocity built-in's result is, in words with its exact parts: the spatial
/// twist `xi = 2 qdot q* = omega + eps (t-dot + t x omega)` and the geometric Jacobian column
/// `(t-dot; omega)` it gives, the body twist `2 q* qdot = omega_b + eps r* t-dot r`, `qdot =
/// 1/2 xi q`, ScLERP and its derivative with the constant body twist `2 screwlog(q0* q1)`.
fn velocity_words(func: &str, args: &[(String, Value)], v: &Value) -> Option<Words> {
    use super::Word::{Text, Tuple};
    let text = |s: &str| Text(s.to_owned());
    let arg = |k: usize| args.get(k).map_or("", |a| a.0.as_str());
    let cross = |a: &[Scalar; 3], b: &[Scalar; 3]| -> [Scalar; 3] {
        [
            &a[1] * &b[2] - &a[2] * &b[1],
            &a[2] * &b[0] - &a[0] * &b[2],
            &a[0] * &b[1] - &a[1] * &b[0],
        ]
    };
    let words = match func {
        "twist" => {
            let q = as_dq(&args.first()?.1)?;
            let xi = as_dq(v)?;
            let omega = xi.real.vector_part();
            let t = crate::algebra::dqr::translation(&q).vector_part();
            let txo = cross(&t, &omega);
            let d = xi.dual.vector_part();
            let tdot: Vec<Scalar> = (0..3).map(|k| &d[k] - &txo[k]).collect();
            vec![
                text(&format!(
                    "the spatial twist xi = 2 qdot q* of the motion {} moving at qdot = {} (so qdot = 1/2 xi q): the angular velocity omega = P(xi) = ",
                    arg(0),
                    arg(1)
                )),
                Tuple(omega.to_vec()),
                text(", and D(xi) = t-dot + t x omega (t = translation(q)), so the velocity of the moving frame's origin is t-dot = D(xi) - t x omega = "),
                Tuple(tdot),
                text("; when qdot is the derivative of a pose by one joint variable, (t-dot; omega) is that joint's column of the geometric Jacobian (gjacobian)"),
            ]
        }
        "bodytwist" => {
            let xi = as_dq(v)?;
            vec![
                text(&format!(
                    "the body twist xi_b = 2 q* qdot of the motion {} moving at qdot = {} (so qdot = 1/2 q xi_b; xi_b = q* xi q for the spatial twist xi): the angular velocity in the moving frame P(xi_b) = ",
                    arg(0),
                    arg(1)
                )),
                Tuple(xi.real.vector_part().to_vec()),
                text(", and D(xi_b) = r* t-dot r, the velocity of the moving frame's origin in the moving frame, = "),
                Tuple(xi.dual.vector_part().to_vec()),
            ]
        }
        "qdot" => vec![text(&format!(
            "the derivative qdot = 1/2 xi q of the motion {} under the spatial twist {} (twist(q, qdot) gives the twist back)",
            arg(0),
            arg(1)
        ))],
        "sclerp" => {
            let (a, b, t) = (arg(0), arg(1), arg(2));
            let named = match args.get(3) {
                Some(p) => format!(", {} = {t} * rotation_angle({a}* {b})", p.0),
                None => String::new(),
            };
            vec![text(&format!(
                "ScLERP {a} ({a}* {b})^{t}: the screw motion about the axis of {a}* {b} from {a} ({t} = 0) to {b} ({t} = 1) at constant speed{named}"
            ))]
        }
        "sclerpdot" => {
            let (q0, q1) = (as_dq(&args.first()?.1)?, as_dq(&args.get(1)?.1)?);
            let xi = crate::kin::dqexp::screw_log(&(q0.conjugate() * q1)).ok()?;
            let two = Scalar::int(2);
            let body: Vec<Scalar> = xi.components().iter().map(|c| c * &two).collect();
            vec![
                text(&format!(
                    "the derivative by {t} of sclerp({a}, {b}, {t}) = {a} ({a}* {b})^{t}: sclerp({a}, {b}, {t}) xi with xi = screwlog({a}* {b}); its body twist 2 q* qdot = 2 xi = ",
                    a = arg(0),
                    b = arg(1),
                    t = arg(2),
                )),
                Tuple(body),
                text(" (w, x, y, z, w_e, x_e, y_e, z_e) does not depend on t: a screw motion at constant speed"),
            ]
        }
        _ => return None,
    };
    Some(Words(words))
}

/// The motion of a built-in call from its arguments.
fn built_motion(func: &str, args: &[(String, Value)]) -> Option<Motion> {
    let sc = |k: usize| match args.get(k).map(|a| &a.1) {
        Some(Value::Scalar(s)) => Some(s.clone()),
        _ => None,
    };
    let vec = |k: usize| match args.get(k).map(|a| &a.1) {
        Some(Value::Vector(v)) => Some(v.clone()),
        _ => None,
    };
    let zero = || [Scalar::int(0), Scalar::int(0), Scalar::int(0)];
    Some(match func {
        "rot" => Motion::Screw {
            axis: vec(0)?,
            point: if args.len() > 2 { vec(2)? } else { zero() },
            angle: sc(1)?,
            slide: Scalar::int(0),
        },
        "screw" => Motion::Screw {
            axis: vec(0)?,
            point: vec(1)?,
            angle: sc(2)?,
            slide: sc(3)?,
        },
        "trans" => Motion::Translation { t: vec(0)? },
        "dh" => Motion::Dh {
            theta: sc(0)?,
            d: sc(1)?,
            a: sc(2)?,
            alpha: sc(3)?,
        },
        "mdh" => Motion::Mdh {
            alpha: sc(0)?,
            a: sc(1)?,
            theta: sc(2)?,
            d: sc(3)?,
        },
        _ => return None,
    })
}

fn is_name(label: &str) -> bool {
    label.chars().next().is_some_and(|c| c.is_alphabetic())
        && label.chars().all(|c| c.is_alphanumeric() || c == '_')
}
