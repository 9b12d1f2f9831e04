//! Points that divide by a symbolic expression: the point where two axes meet when a free
//! joint's value turns one of them, carried as `N λ` and multiplied out of each step.

use super::*;

/// The name of `λ = 1/D` in the steps built on a point `N λ` (see [`meet`]); [`Builder::push`]
/// multiplies it out, so it never reaches a formula.
pub(super) const INV_SCALE: &str = "ik__inverse_scale";

/// The point where two intersecting, non-parallel axes meet: exact when the parameters allow
/// (a numeric divisor), else `N λ` with `λ = 1/D`, `D = |d1 × d2|²`, recorded in the builder.
/// `D` is positive wherever the axes are not parallel (a free joint's value can make them
/// parallel: there the steps built on the point vanish, a singular set).
pub(super) fn meet(b: &mut Builder, a: &Axis, c: &Axis) -> Result<V3, PlanError> {
    if let Some(p) = intersection(a, c) {
        return Ok(p);
    }
    let n = cross(&a.dir, &c.dir);
    let d = dot(&n, &n);
    let t = dot(&cross(&sub(&c.point, &a.point), &c.dir), &n);
    let num = add(&scale(&d, &a.point), &scale(&t, &a.dir));
    first_error(num.iter().chain([&d]))?;
    if b.scale.as_ref().is_some_and(|s| *s != d) {
        return Err(PlanError::NotExact(
            "a second point with a symbolic divisor",
        ));
    }
    b.scale = Some(d);
    Ok(scale(&Scalar::sym(INV_SCALE), &num))
}

/// The parts of a formula, to rewrite in place.
pub(super) fn parts_mut(f: &mut Formula) -> Vec<&mut Scalar> {
    match f {
        Formula::Atan2 { y, x } => vec![y, x],
        Formula::Trig { a, b, c } => vec![a, b, c],
        Formula::Value { v } => vec![v],
        Formula::Linear { a, b } => vec![a, b],
        Formula::Quadratic { beta, gamma } => vec![beta, gamma],
    }
}

/// A formula on a point `N λ` multiplied through by `D^k`, `k` the highest power of `λ = 1/D`
/// in its parts: each part `Σ pᵢ λⁱ` becomes `Σ pᵢ D^(k−i)`, a polynomial again. The solution
/// is unchanged because `D > 0`: `atan2(y, x)` and `a cos q + b sin q = c` (with its radicand
/// `a² + b² − c²` and `atan2(sqrt(.), c)`) are invariant under one positive factor on every
/// part. A quadratic's parts are not (its leading coefficient is 1): refused.
pub(super) fn homogenize(f: &mut Formula, d: &Scalar) -> Result<(), PlanError> {
    if matches!(f, Formula::Quadratic { .. } | Formula::Value { .. }) {
        return Err(PlanError::NotExact(
            "a slide on a point with a symbolic divisor",
        ));
    }
    let zero = Scalar::int(0);
    let mut coefs: Vec<Vec<Scalar>> = Vec::new();
    for p in parts_mut(f) {
        // pᵢ = (dⁱ p / dλⁱ)(0) / i!; the parts are polynomials of degree at most 4 in λ (a
        // squared distance to the point, times a distance), so the loop ends.
        let mut cs = Vec::new();
        let mut q = p.clone();
        let mut fact = 1i64;
        while !q.is_zero_value() {
            first_error([&q])?;
            if cs.len() > 8 {
                return Err(PlanError::NotExact(
                    "a step on a point with a symbolic divisor",
                ));
            }
            let c = q.subs(INV_SCALE, &zero);
            cs.push(c.try_div(&Scalar::int(fact))?);
            q = q.diff(INV_SCALE);
            fact *= cs.len() as i64;
        }
        coefs.push(cs);
    }
    let k = coefs
        .iter()
        .map(Vec::len)
        .max()
        .unwrap_or(0)
        .saturating_sub(1);
    for (p, cs) in parts_mut(f).into_iter().zip(coefs) {
        let mut acc = Scalar::int(0);
        for (i, c) in cs.iter().enumerate() {
            let mut t = c.clone();
            for _ in i..k {
                t = &t * d;
            }
            acc = &acc + &t;
        }
        *p = acc;
    }
    Ok(())
}

/// Whether a point (`N λ` when it has a symbolic divisor, see [`meet`]) lies on the axis.
pub(super) fn on_line_scaled(b: &Builder, p: &V3, a: &Axis) -> bool {
    match &b.scale {
        Some(d)
            if p.iter()
                .any(|x| x.symbols().iter().any(|s| s.name() == INV_SCALE)) =>
        {
            let one = Scalar::int(1);
            let n: V3 = std::array::from_fn(|i| p[i].subs(INV_SCALE, &one));
            is_zero3(&cross(&sub(&n, &scale(d, &a.point)), &a.dir))
        }
        _ => on_line(p, a),
    }
}
