//! The transcendental operations of DQ Robotics, exact: `norm`, `rotation_angle`,
//! `rotation_axis`, `log`, `exp`, `pow`, and the screw (true) logarithm, power and ScLERP with
//! the body twist.
//!
//! # Which angle, which branch
//! The scalar layer takes cos and sin of angles that are linear in symbols (plus a rational
//! multiple of pi). An angle is read from a scalar part `w` by [`Scalar::as_cos_of_angle`]:
//! - a constant `w` gives `phi/2 = acos(w)` in `[0, pi]`, DQ Robotics' branch, exactly (for the
//!   values `cos(k pi/12)`; other constants have no exact angle here and are refused);
//! - `w = cos(x)` gives `phi/2 = x` as written, and `w = -cos(x)` gives `phi/2 = pi - x`, so that
//!   `sin(phi/2)` keeps the sign of `sin(x)`; both equal DQ Robotics' `acos` branch whenever `x`
//!   is in `[0, pi]`, and give the same rigid motion for every `x`.
//!
//! Zero rotation is exact: `sin(phi/2) = 0` identically (a constant `w = 1`) takes DQ
//! Robotics' convention (axis `k`, `log = ε t/2`). A full turn (`w = -1`) has no axis; `-q` is the
//! same pose and has a logarithm, so it is refused with that hint.
//!
//! # A power with a symbolic exponent
//! The rotation angle of `q^t` is `t phi`, a product of symbols, which is not an angle of the
//! scalar layer (`cos(t theta)` has no finite Fourier form in `t` and `theta`). The power
//! therefore takes the angle of the result as a *named symbol* `psi` with the defining relation
//! `psi = t phi` (`phi` the rotation angle of `q`): the result is exact and polynomial in `t`,
//! `cos(psi/2)` and `sin(psi/2)`, and code generated from it takes `psi` as an argument, which
//! the caller computes as `t * rotation_angle(q)`. The derivative in `t` is not `diff(x, t)` (that
//! misses `psi`'s dependence) but the closed form [`sclerp_derivative`]: `q0 (q0* q1)^t xi`.
//! When `t phi` is linear (a rational `t` and a symbolic `phi`), no name is needed.

use crate::algebra::dqr;
use crate::{DualQuat, Frac, Quat, Ring, Scalar, ScalarError};
use num_traits::{One, Zero};
use thiserror::Error;

/// Why an exact DQ Robotics operation could not be done.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DqError {
    /// The operation needs a unit dual quaternion.
    #[error("needs a unit dual quaternion (a rigid motion)")]
    NotUnit,
    /// `exp` is defined for pure dual quaternions only (as in DQ Robotics).
    #[error("exp is defined only for pure dual quaternions (Re(h) = 0), as in DQ Robotics")]
    NotPure,
    /// The rotation angle is not visibly an angle.
    #[error("cannot read the rotation angle: the scalar part {0} is not cos of an angle (symbols, or a multiple of pi/12)")]
    Angle(String),
    /// `|P(h)|` is not a linear form in the symbols.
    #[error("the norm of P(h) is sqrt({0}), not an angle linear in the symbols")]
    NotLinear(String),
    /// The rotation axis is not a polynomial.
    #[error("the rotation axis {0} / sin(phi/2) is not a polynomial in the symbols")]
    Axis(String),
    /// A rotation by 2 pi.
    #[error("q has P(q) = -1 (a full turn): its axis is undefined; -q is the same pose")]
    FullTurn,
    /// A symbolic power needs a name for the angle of the result.
    #[error("the rotation angle of q^{t} is {t} * ({phi}), not linear in the symbols: name it with a third argument (psi = {t} * ({phi}))")]
    NeedsAngle {
        /// The exponent, as written.
        t: String,
        /// The rotation angle of the base, as written.
        phi: String,
    },
    /// The norm of a non-unit symbolic primary part.
    #[error("norm: |P(h)|^2 = {0} has no exact square root here")]
    Norm(String),
    /// An exact operation failed.
    #[error(transparent)]
    Scalar(#[from] ScalarError),
}

type Result<T> = std::result::Result<T, DqError>;

fn text(s: &Scalar) -> String {
    crate::closed_form(s)
        .map(|e| {
            crate::plain(
                &e,
                &crate::PlainOptions {
                    shorthand: false,
                    decimals: false,
                },
            )
        })
        .unwrap_or_else(|_| s.to_string())
}

fn require_unit(h: &DualQuat<Scalar>) -> Result<()> {
    if h.unit_constraints().hold_exactly() {
        Ok(())
    } else {
        Err(DqError::NotUnit)
    }
}

/// Half the rotation angle of a unit quaternion's scalar part `w` (see the module docs for the
/// branch).
fn half_angle(w: &Scalar) -> Result<Scalar> {
    let Some(x) = w.as_cos_of_angle() else {
        return shifted_angle(w).ok_or_else(|| DqError::Angle(text(w)));
    };
    if w.is_constant() {
        return Ok(x);
    }
    // `-cos(y)` was read as `y + pi`; `pi - y` has the same cosine and the sine of `y`.
    let negative_cos = matches!(w.terms(), Ok([t]) if t.coef.is_negative() && !t.mode.sin);
    if negative_cos {
        return Ok(Scalar::pi() * Scalar::int(2) - x);
    }
    Ok(x)
}

/// An angle `y + k pi/12` with `cos` equal to `w`, `y` the angle of one of `w`'s modes: the
/// scalar layer expands `cos(theta/2 + pi/12)` into radicals times `cos(theta/2)` and
/// `sin(theta/2)`, which [`Scalar::as_cos_of_angle`] does not read back.
fn shifted_angle(w: &Scalar) -> Option<Scalar> {
    let terms = w.terms().ok()?;
    let mode = &terms.iter().find(|t| !t.mode.is_unit())?.mode;
    let y = crate::scalar::mode_angle(mode, None);
    (0..24)
        .map(|k| &y + Scalar::pi() * Scalar::from_ratio(k, 12))
        .find(|x| x.cos() == *w)
}

/// `norm(h) = sqrt(h* h)`, a dual number `|P| + ε (P · D)/|P|` (DQ Robotics' `norm`), exact when
/// `|P|²` is 1 or a non-negative rational.
pub fn norm(h: &DualQuat<Scalar>) -> Result<DualQuat<Scalar>> {
    let n2 = h.real.norm_squared();
    if n2.is_zero() {
        return Ok(DualQuat::from_real(Quat::zero()));
    }
    let r = if n2.is_one() {
        n2.clone()
    } else if n2.is_constant() {
        n2.sqrt().check()?
    } else {
        return Err(DqError::Norm(text(&n2)));
    };
    let du = h.real.dot(&h.dual).try_div(&r)?;
    Ok(DualQuat::from_real_and_dual(
        Quat::from_scalar(r),
        Quat::from_scalar(du),
    ))
}

/// DQ Robotics' `normalize(h) = h norm(h)^-1`, a unit DQ, exact when `norm` is (`|P(h)|²` 1
/// or a non-negative rational); the inverse of the dual number `a + ε b` is `1/a - ε b/a²`.
pub fn normalize(h: &DualQuat<Scalar>) -> Result<DualQuat<Scalar>> {
    let n = norm(h)?;
    let (a, b) = (&n.real.w, &n.dual.w);
    if a.is_zero() {
        return Err(DqError::Scalar(ScalarError::DivisionByZero));
    }
    let inv_a = Scalar::one().try_div(a)?;
    let inv = DualQuat::from_real_and_dual(
        Quat::from_scalar(inv_a.clone()),
        Quat::from_scalar(-(b * &inv_a * &inv_a)),
    );
    Ok(h * &inv)
}

/// `rotation_angle(h) = 2 acos(w)` of a unit DQ, exact (branch in the module docs).
pub fn rotation_angle(h: &DualQuat<Scalar>) -> Result<Scalar> {
    require_unit(h)?;
    Ok(half_angle(&h.real.w)? * Scalar::int(2))
}

/// `rotation_axis(h) = Im(P(h)) / sin(phi/2)`, a pure quaternion; `k` for zero rotation (DQ
/// Robotics' convention).
pub fn rotation_axis(h: &DualQuat<Scalar>) -> Result<Quat<Scalar>> {
    require_unit(h)?;
    let half = half_angle(&h.real.w)?;
    axis_of(&h.real, &half)
}

fn axis_of(r: &Quat<Scalar>, half: &Scalar) -> Result<Quat<Scalar>> {
    let s = half.sin().check()?;
    if s.is_zero() {
        if r.w == Scalar::int(-1) {
            return Err(DqError::FullTurn);
        }
        return Ok(Quat::vector(Scalar::zero(), Scalar::zero(), Scalar::one()));
    }
    let mut n = Vec::with_capacity(3);
    for v in r.vector_part() {
        match exact_div(&v, &s)? {
            Some(x) => n.push(x),
            None => return Err(DqError::Axis(text(&v))),
        }
    }
    Ok(Quat::vector(n[0].clone(), n[1].clone(), n[2].clone()))
}

/// DQ Robotics' `log(h) = (phi/2) n + ε translation(h)/2` of a unit DQ: the rotation and the
/// translation separately (not the screw logarithm; see [`screw_log`]).
pub fn log(h: &DualQuat<Scalar>) -> Result<DualQuat<Scalar>> {
    require_unit(h)?;
    let half = half_angle(&h.real.w)?;
    let n = axis_of(&h.real, &half)?;
    let t = dqr::translation(h);
    Ok(DualQuat::from_real_and_dual(
        n.scale(&half),
        t.scale(&Scalar::from_ratio(1, 2)),
    ))
}

/// `sqrt(x)` as a linear form `sum k_i x_i + c` with rational `k_i`, `c` (leading coefficient
/// positive), when `x` is the square of one.
pub fn linear_sqrt(x: &Scalar) -> Option<Scalar> {
    let syms: Vec<String> = x.symbols().iter().map(|s| s.name().to_owned()).collect();
    let at_zero = |y: &Scalar| {
        syms.iter()
            .fold(y.clone(), |acc, s| acc.subs(s, &Scalar::zero()))
    };
    let rational_sqrt = |y: &Scalar| -> Option<Scalar> {
        y.as_rational()?;
        let r = y.sqrt().check().ok()?;
        r.as_rational().map(|_| r)
    };
    let lead = syms.iter().find_map(|a| {
        let caa = x.diff(a).diff(a).try_div(&Scalar::int(2)).ok()?;
        (!caa.is_zero()).then(|| (a.clone(), caa))
    });
    let l = match lead {
        None => rational_sqrt(x)?,
        Some((a, caa)) => {
            let ka = rational_sqrt(&caa)?;
            let two_ka = &ka * Scalar::int(2);
            let mut l = Scalar::sym(&a) * &ka;
            for b in syms.iter().filter(|b| **b != a) {
                let cab = x.diff(&a).diff(b);
                if !cab.is_constant() {
                    return None;
                }
                l = l + Scalar::sym(b) * cab.try_div(&two_ka).ok()?;
            }
            let ca0 = at_zero(&x.diff(&a));
            l + ca0.try_div(&two_ka).ok()?
        }
    };
    (&l * &l == *x).then_some(l)
}

/// DQ Robotics' `exp(h)` of a pure DQ `h = r + ε d`: `e^r + ε d e^r` with
/// `e^r = cos|r| + sin|r| r/|r|` (1 when `r = 0`). `|r|` must be an angle linear in the symbols.
pub fn exp(h: &DualQuat<Scalar>) -> Result<DualQuat<Scalar>> {
    if !h.real.w.is_zero() || !h.dual.w.is_zero() {
        return Err(DqError::NotPure);
    }
    let prim = quat_exp(&h.real)?;
    Ok(DualQuat::from_real_and_dual(prim.clone(), &h.dual * &prim))
}

/// `e^r = cos|r| + sin|r| r/|r|` of a pure quaternion.
fn quat_exp(r: &Quat<Scalar>) -> Result<Quat<Scalar>> {
    let n2 = r.norm_squared();
    if n2.is_zero() {
        return Ok(Quat::identity());
    }
    let phi = linear_sqrt(&n2).ok_or_else(|| DqError::NotLinear(text(&n2)))?;
    let (c, s) = (phi.cos().check()?, phi.sin().check()?);
    let mut u = Vec::with_capacity(3);
    for v in r.vector_part() {
        match exact_div(&v, &phi)? {
            Some(x) => u.push(&s * x),
            None => return Err(DqError::Axis(text(&v))),
        }
    }
    Ok(Quat::new(c, u[0].clone(), u[1].clone(), u[2].clone()))
}

/// The angle `a phi/2` of a power, or the named one (see the module docs).
fn power_half_angle(half: &Scalar, a: &Scalar, name: Option<&Scalar>) -> Result<Scalar> {
    if let Some(psi) = name {
        return Ok(psi.clone() * Scalar::from_ratio(1, 2));
    }
    let x = a * half;
    if x.cos().check().is_ok() {
        return Ok(x);
    }
    Err(DqError::NeedsAngle {
        t: text(a),
        phi: text(&(half * Scalar::int(2))),
    })
}

/// DQ Robotics' `pow(h, a) = exp(a log(h))`: rotation `r^a`, translation `a t` (a straight-line
/// translation, not a screw; see [`screw_pow`]). `angle` names the rotation angle `a phi` of
/// the result when `a` is symbolic.
pub fn pow(h: &DualQuat<Scalar>, a: &Scalar, angle: Option<&Scalar>) -> Result<DualQuat<Scalar>> {
    require_unit(h)?;
    let half = half_angle(&h.real.w)?;
    let n = axis_of(&h.real, &half)?;
    let rot = if half.is_zero() {
        Quat::identity()
    } else {
        let y = power_half_angle(&half, a, angle)?;
        let (c, s) = (y.cos().check()?, y.sin().check()?);
        Quat::new(c, Scalar::zero(), Scalar::zero(), Scalar::zero()) + n.scale(&s)
    };
    let t = dqr::translation(h).scale(&(a * Scalar::from_ratio(1, 2)));
    Ok(DualQuat::from_real_and_dual(rot.clone(), &t * &rot))
}

/// The screw parameters as scalars: half angle, slide, axis, moment; `None` for a motion
/// without rotation.
struct Screw {
    half: Scalar,
    slide: Scalar,
    axis: [Scalar; 3],
    moment: [Scalar; 3],
}

/// The exact quotient `num / den` when it is a scalar (a polynomial in symbols and modes), found
/// without polynomial division: the symbols of `den` are set to a value where `den` is a
/// nonzero number (1, 2, pi, pi/2, pi/3), the candidate `num / den` there is kept when
/// `candidate * den == num` exactly. This finds every quotient that does not involve `den`'s
/// symbols (an axis `v / sin(theta/2)`, a slide, `r / |r|`); others are `None`.
pub fn exact_div(num: &Scalar, den: &Scalar) -> Result<Option<Scalar>> {
    if den.is_zero() {
        return Err(DqError::Scalar(ScalarError::DivisionByZero));
    }
    if num.is_zero() {
        return Ok(Some(Scalar::zero()));
    }
    let f = Frac::new(num.clone(), den.clone())?;
    if let Some(k) = f.as_scalar() {
        return Ok(Some(k.clone()));
    }
    let syms: Vec<String> = den
        .symbols()
        .iter()
        .filter(|s| !s.is_pi())
        .map(|s| s.name().to_owned())
        .collect();
    let pi = Scalar::pi();
    let values = [
        Scalar::one(),
        Scalar::int(2),
        pi.clone(),
        &pi * Scalar::from_ratio(1, 2),
        &pi * Scalar::from_ratio(1, 3),
        &pi * Scalar::from_ratio(2, 3),
    ];
    for v in &values {
        let at = |x: &Scalar| syms.iter().fold(x.clone(), |acc, n| acc.subs(n, v));
        let d = at(den);
        if d.is_zero() || !d.is_constant() || d.symbols().iter().any(crate::Sym::is_pi) {
            continue;
        }
        let Ok(k) = at(num).try_div(&d) else {
            continue;
        };
        if (&k * den).check()? == *num {
            return Ok(Some(k));
        }
    }
    Ok(None)
}

fn screw_of(q: &DualQuat<Scalar>) -> Result<Option<Screw>> {
    require_unit(q)?;
    let half = half_angle(&q.real.w)?;
    if half.sin().check()?.is_zero() {
        if q.real.w == Scalar::int(-1) {
            return Err(DqError::FullTurn);
        }
        return Ok(None);
    }
    // q = (c, s n) + eps (-(d/2) s, (d/2) c n + s m), c, s = cos, sin(half) (sec 4, eq 18).
    let (c, sn) = (half.cos().check()?, half.sin().check()?);
    let over_s = |x: Scalar| -> Result<Scalar> {
        exact_div(&x, &sn)?.ok_or_else(|| DqError::Axis(format!("({})/({})", text(&x), text(&sn))))
    };
    let v = q.real.vector_part();
    let axis = [
        over_s(v[0].clone())?,
        over_s(v[1].clone())?,
        over_s(v[2].clone())?,
    ];
    let slide = over_s(-(&q.dual.w * Scalar::int(2)))?;
    let ve = q.dual.vector_part();
    let hd = &slide * Scalar::from_ratio(1, 2);
    let mut moment = Vec::with_capacity(3);
    for k in 0..3 {
        moment.push(over_s(ve[k].clone() - &hd * &c * &axis[k])?);
    }
    Ok(Some(Screw {
        half,
        slide,
        axis,
        moment: [moment[0].clone(), moment[1].clone(), moment[2].clone()],
    }))
}

/// The screw logarithm `xi = (theta/2) n + ε ((d/2) n + (theta/2) m)` of a unit DQ
/// `q = exp(xi)` (the true dual-quaternion exponential), with angle `theta`, slide `d`, axis
/// `n`, moment `m`; `ε t/2` for a pure translation. `2 xi` is the constant body (and spatial)
/// twist of the screw motion `q^t`.
pub fn screw_log(q: &DualQuat<Scalar>) -> Result<DualQuat<Scalar>> {
    match screw_of(q)? {
        None => Ok(DualQuat::from_real_and_dual(
            Quat::zero(),
            dqr::translation(q).scale(&Scalar::from_ratio(1, 2)),
        )),
        Some(s) => {
            let n = Quat::from_vector(&s.axis);
            let m = Quat::from_vector(&s.moment);
            let hd = s.slide * Scalar::from_ratio(1, 2);
            Ok(DualQuat::from_real_and_dual(
                n.scale(&s.half),
                n.scale(&hd) + m.scale(&s.half),
            ))
        }
    }
}

/// The screw power `q^t = exp(t xi)`: rotation by `t theta` about the screw axis and slide
/// `t d` along it, `(c, s n) + ε (-(t d/2) s, (t d/2) c n + s m)` with `c, s` the cosine and sine
/// of `t theta/2`; `angle` names `t theta` when that is not linear (module docs).
pub fn screw_pow(
    q: &DualQuat<Scalar>,
    t: &Scalar,
    angle: Option<&Scalar>,
) -> Result<DualQuat<Scalar>> {
    match screw_of(q)? {
        None => {
            let w = if q.real.w == Scalar::int(-1) {
                -Scalar::one()
            } else {
                Scalar::one()
            };
            let tr = dqr::translation(q).scale(&(t * Scalar::from_ratio(1, 2)));
            Ok(DualQuat::from_real_and_dual(Quat::from_scalar(w), tr))
        }
        Some(s) => {
            let y = power_half_angle(&s.half, t, angle)?;
            let (c, sn) = (y.cos().check()?, y.sin().check()?);
            let n = Quat::from_vector(&s.axis);
            let m = Quat::from_vector(&s.moment);
            let htd = t * &s.slide * Scalar::from_ratio(1, 2);
            let real = Quat::from_scalar(c.clone()) + n.scale(&sn);
            let dual = Quat::from_scalar(-(&htd * &sn)) + n.scale(&(&htd * &c)) + m.scale(&sn);
            Ok(DualQuat::from_real_and_dual(real, dual))
        }
    }
}

/// ScLERP `q0 (q0* q1)^t` between two unit DQs (the screw power, constant speed along the
/// screw from `q0` at `t = 0` to `q1` at `t = 1`).
pub fn sclerp(
    q0: &DualQuat<Scalar>,
    q1: &DualQuat<Scalar>,
    t: &Scalar,
    angle: Option<&Scalar>,
) -> Result<DualQuat<Scalar>> {
    require_unit(q0)?;
    let rel = q0.conjugate() * q1;
    Ok(q0 * &screw_pow(&rel, t, angle)?)
}

/// `d/dt sclerp(q0, q1, t) = sclerp(q0, q1, t) xi` with `xi = screw_log(q0* q1)`: the body twist
/// of the interpolation is the constant `2 xi` (`q-dot = 1/2 q xi_body`).
pub fn sclerp_derivative(
    q0: &DualQuat<Scalar>,
    q1: &DualQuat<Scalar>,
    t: &Scalar,
    angle: Option<&Scalar>,
) -> Result<DualQuat<Scalar>> {
    let rel = q0.conjugate() * q1;
    let xi = screw_log(&rel)?;
    Ok(sclerp(q0, q1, t, angle)? * xi)
}

/// The twist `xi` with `q-dot = 1/2 xi q` (spatial, `body = false`) or `q-dot = 1/2 q xi`
/// (body, `body = true`) of a unit DQ `q = r + ε (1/2) t r` and its derivative: `2 q-dot q*` or
/// `2 q* q-dot`. The spatial twist is `omega + ε (t-dot + t × omega)` (DQ Robotics'
/// convention), so a column of the geometric Jacobian ([`crate::kin::geometric_jacobian`], rows
/// `(t-dot, omega)`) is read from it as `omega = P(xi)` and `t-dot = D(xi) − t × omega`; the body
/// twist is the spatial one expressed in the moving frame, `conj(q) xi q`.
pub fn twist(q: &DualQuat<Scalar>, q_dot: &DualQuat<Scalar>, body: bool) -> DualQuat<Scalar> {
    let two = Scalar::int(2);
    if body {
        (q.conjugate() * q_dot).scale(&two)
    } else {
        (q_dot * &q.conjugate()).scale(&two)
    }
}

/// `q-dot = 1/2 xi q` (spatial) or `1/2 q xi` (body) from a twist.
pub fn from_twist(q: &DualQuat<Scalar>, xi: &DualQuat<Scalar>, body: bool) -> DualQuat<Scalar> {
    let half = Scalar::from_ratio(1, 2);
    if body {
        (q * xi).scale(&half)
    } else {
        (xi * q).scale(&half)
    }
}
