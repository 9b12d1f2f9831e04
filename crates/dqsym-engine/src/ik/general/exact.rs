//! The Raghavan–Roth equations of a general 6R chain, exactly: `Bm X12 = Am(θ3) X45` with
//! every coefficient a [`Scalar`] in the robot's parameters and the target's entries
//! ([`TARGET_SYMBOLS`]), and their half-angle form.
//!
//! The fourteen quantities of a point `p` and a direction `l` (with a fifteenth entry, the
//! constant 1) transform under a rigid motion by a 15 x 15 matrix: a rotation `R` acts as
//! `R` on `l`, `p`, `p × l` and `(p·p) l − 2 (p·l) p` and leaves `p·p`, `p·l` alone; a
//! translation by `t` as
//!
//! ```text
//! p' = p + t,  p·p' = p·p + 2 t·p + t·t,  p·l' = p·l + t·l,  (p × l)' = p × l + t × l,
//! ((p·p) l − 2 (p·l) p)' = (p·p) l − 2 (p·l) p − 2 t × (p × l) + (t·t) l − 2 (p·l) t − 2 (t·l) t
//! ```
//!
//! (the products of `p` and `l` from `2 (t·p) l − 2 (t·l) p` are `−2 t × (p × l)`). A joint
//! turn is a rotation `c I + s [w]× + (1 − c) w wᵀ` between the translations to and from a
//! point of its axis, so its matrix is `K₁ + c K_c + s K_s` with constant `K`s: each quantity
//! is of degree one in the cosine and sine of every joint, and the coefficients of the
//! products `(1, c3, s3) ⊗ (1, c4, s4) ⊗ (1, c5, s5)` come out of three such products applied
//! one joint at a time, by exact arithmetic (no sampling, no floating point).
//!
//! A prismatic joint's slide by `d w` is a translation: by the formulas above its matrix is
//! `K₁ + d K_d + d² K_dd` (`p·p` gains `2 d w·p + d² w·w`, the last three `d² (w·w) l − 2 d²
//! (w·l) w`), so the same construction runs in the basis `(1, d, d²)` of its variable, and the
//! half-angle form leaves `d` as it is. The loop is read so that its last joint turns (a point
//! of that axis is what the joint leaves fixed): forwards, or backwards when the last joint
//! slides; an arm whose first and last joints both slide has no such reading from joint 1.
//!
//! The target enters through the fourteen quantities of the point `u = H p6` and the
//! direction `v = H w6` alone (`H = G = T M⁻¹`, or `G⁻¹` when the loop is read backwards):
//! the equations name them `g1 … g14` and give their definitions apart.

use super::super::axes::{cross, dot, V3};
use super::super::{IkSolution, TARGET_SYMBOLS};
use super::GeneralInfo;
use crate::kin::JointKind;
use crate::{Scalar, ScalarError};

/// Fourteen quantities and the constant 1.
pub(crate) type Q15 = [Scalar; 15];

/// Why [`exact_equations`] gives no equations.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ExactError {
    /// The exact arithmetic failed (term limit, work budget, an interruption).
    #[error(transparent)]
    Scalar(#[from] ScalarError),
    /// The first and the last joint both slide: no reading of the loop from joint 1 ends with
    /// a joint that turns.
    #[error("the first and the last joint both slide, so no reading of the loop from the first joint ends with a turning joint")]
    SlideAtBothEnds,
    /// Two slides three joints apart: the arm is solved by `apart.rs` (orientation and
    /// position separated), whose equations `F`, `P` and resultant are computed numerically;
    /// the Raghavan–Roth equations here are degenerate for it.
    #[error("the slides are three joints apart: the Raghavan-Roth equations are degenerate for this arm, and the equations F, P of its elimination (orientation by the four turns, position by the slides' plane) are computed numerically, not derived exactly")]
    SlidesApart,
}

/// The exact equations of one arrangement of the loop.
#[derive(Clone, Debug)]
pub struct ExactEquations {
    /// The arrangement: `(reversed, shift)`, as [`GeneralInfo::arrangement`]; the exact
    /// equations are derived for `shift = 0` (see [`exact_equations`]).
    pub arrangement: (bool, usize),
    /// The arm's joint index (from 0) of each arranged joint.
    pub order: [usize; 6],
    /// Whether each arranged joint slides: its basis is `(1, d, d²)` where a turning joint's
    /// is `(1, cos, sin)`, in `am`, `bm` and the half-angle form.
    pub prismatic: [bool; 6],
    /// The names of the target's fourteen quantities (`g1 … g14` unless a parameter is
    /// called so).
    pub g_names: Vec<String>,
    /// Their definitions: the quantities of `u = H p6`, `v = H w6` in the target's entries.
    pub g: Vec<Scalar>,
    /// `am[e][k][m]`: equation `e`, `k` in `(1, c3, s3)`, `m = 3 i4 + i5` in `(1, c4, s4) ⊗
    /// (1, c5, s5)`; the constant `am[e][0][0]` holds the right side's constant, moved over.
    pub am: Vec<[[Scalar; 9]; 3]>,
    /// `bm[e][m − 1]`: `m = 3 i1 + i2` in `(1, c1, s1) ⊗ (1, c2, s2)` but the constant.
    pub bm: Vec<[Scalar; 8]>,
}

/// The degree in lengths of each of the fourteen quantities: `l`, `p`, `p·p`, `p·l`, `p × l`,
/// `(p·p) l − 2 (p·l) p`.
pub const LENGTH_DEGREE: [i32; 14] = [0, 0, 0, 1, 1, 1, 2, 1, 1, 1, 1, 2, 2, 2];

/// The quantity each equation is made of, for the report.
pub const QUANTITY_NAMES: [&str; 14] = [
    "l_x",
    "l_y",
    "l_z",
    "p_x",
    "p_y",
    "p_z",
    "p.p",
    "p.l",
    "(p x l)_x",
    "(p x l)_y",
    "(p x l)_z",
    "((p.p) l - 2 (p.l) p)_x",
    "((p.p) l - 2 (p.l) p)_y",
    "((p.p) l - 2 (p.l) p)_z",
];

fn v3(f: impl Fn(usize) -> Scalar) -> V3 {
    [f(0), f(1), f(2)]
}

fn sub3(a: &V3, b: &V3) -> V3 {
    v3(|i| &a[i] - &b[i])
}

fn scale3(a: &V3, k: &Scalar) -> V3 {
    v3(|i| &a[i] * k)
}

fn part(q: &Q15, at: usize) -> V3 {
    v3(|i| q[at + i].clone())
}

/// The fourteen quantities of `(p, l)` and the constant 1.
pub(crate) fn quantities(p: &V3, l: &V3) -> Q15 {
    let pp = dot(p, p);
    let pl = dot(p, l);
    let x = cross(p, l);
    let two = Scalar::int(2);
    let last = v3(|i| &pp * &l[i] - &two * &pl * &p[i]);
    assemble(l, p, pp, pl, &x, &last, Scalar::int(1))
}

fn assemble(l: &V3, p: &V3, pp: Scalar, pl: Scalar, x: &V3, last: &V3, one: Scalar) -> Q15 {
    [
        l[0].clone(),
        l[1].clone(),
        l[2].clone(),
        p[0].clone(),
        p[1].clone(),
        p[2].clone(),
        pp,
        pl,
        x[0].clone(),
        x[1].clone(),
        x[2].clone(),
        last[0].clone(),
        last[1].clone(),
        last[2].clone(),
        one,
    ]
}

/// The translation by `t` on the fifteen entries (linear: the constant carries `t`).
fn translate(q: &Q15, t: &V3) -> Q15 {
    let (l, p, x, last) = (part(q, 0), part(q, 3), part(q, 8), part(q, 11));
    let (pp, pl, one) = (&q[6], &q[7], &q[14]);
    let two = Scalar::int(2);
    let tt = dot(t, t);
    let tl = dot(t, &l);
    let p2 = v3(|i| &p[i] + &t[i] * one);
    let pp2 = pp + &two * dot(t, &p) + &tt * one;
    let pl2 = pl + &tl;
    let x2 = v3(|i| &x[i] + &cross(t, &l)[i]);
    let tx = cross(t, &x);
    let last2 =
        v3(|i| &last[i] - &two * &tx[i] + &tt * &l[i] - &two * &t[i] * pl - &two * &t[i] * &tl);
    assemble(&l, &p2, pp2, pl2, &x2, &last2, one.clone())
}

/// The three parts `K₁ q`, `K_c q`, `K_s q` of a rotation about the unit `w` through the
/// origin (`sign` −1 for the inverse turn): `w wᵀ` (and the scalars), `I − w wᵀ`, `±[w]×`.
fn rotate_parts(q: &Q15, w: &V3, sign: i64) -> [Q15; 3] {
    let zero = Scalar::int(0);
    let sg = Scalar::int(sign);
    let by = |f: &dyn Fn(&V3) -> V3| -> Q15 {
        let (l, p, x, last) = (
            f(&part(q, 0)),
            f(&part(q, 3)),
            f(&part(q, 8)),
            f(&part(q, 11)),
        );
        assemble(&l, &p, zero.clone(), zero.clone(), &x, &last, zero.clone())
    };
    let along = |a: &V3| scale3(w, &dot(w, a));
    let mut k1 = by(&along);
    k1[6] = q[6].clone();
    k1[7] = q[7].clone();
    k1[14] = q[14].clone();
    let kc = by(&|a: &V3| sub3(a, &along(a)));
    let ks = by(&|a: &V3| scale3(&cross(w, a), &sg));
    [k1, kc, ks]
}

/// A slide by `sign d w` applied to `q`, in parts `(1, d, d²)` (the translation's formulas with
/// `t = d w` sorted by powers of `d`).
fn slide_parts(q: &Q15, w: &V3, sign: i64) -> [Q15; 3] {
    let (l, p, x, last) = (part(q, 0), part(q, 3), part(q, 8), part(q, 11));
    let (pp, pl, one) = (&q[6], &q[7], &q[14]);
    let zero = Scalar::int(0);
    let sg = Scalar::int(sign);
    let two = Scalar::int(2);
    let ww = dot(w, w);
    let wl = dot(w, &l);
    let zv = v3(|_| zero.clone());
    // Power one (times sign): p + w, p·p + 2 w·p, p·l + w·l, p × l + w × l, last − 2 w × (p × l)
    // − 2 (p·l) w.
    let wxl = cross(w, &l);
    let wxx = cross(w, &x);
    let d1 = assemble(
        &zv,
        &v3(|i| &w[i] * one * &sg),
        &two * dot(w, &p) * &sg,
        &wl * &sg,
        &v3(|i| &wxl[i] * &sg),
        &v3(|i| (-&two * &wxx[i] - &two * pl * &w[i]) * &sg),
        zero.clone(),
    );
    // Power two (sign squared): p·p + w·w, last + (w·w) l − 2 (w·l) w.
    let d2 = assemble(
        &zv,
        &zv,
        &ww * one,
        zero.clone(),
        &zv,
        &v3(|i| &ww * &l[i] - &two * &wl * &w[i]),
        zero.clone(),
    );
    let d0 = assemble(&l, &p, pp.clone(), pl.clone(), &x, &last, one.clone());
    [d0, d1, d2]
}

/// A joint's motion applied to `q` in the parts of its variable's basis: a turn about the line
/// through `c` along `w` in `(1, cos, sin)` of its angle, a slide along `w` in `(1, d, d²)`
/// (`sign` −1: the inverse motion).
fn motion_parts(q: &Q15, (w, c, slide): &(V3, V3, bool), sign: i64) -> [Q15; 3] {
    if *slide {
        slide_parts(q, w, sign)
    } else {
        joint_parts(q, w, c, sign)
    }
}

/// A joint's turn about the line through `c` along `w` applied to `q`, in parts `(1, cos,
/// sin)` of its angle (`sign` −1: the inverse turn).
fn joint_parts(q: &Q15, w: &V3, c: &V3, sign: i64) -> [Q15; 3] {
    let neg = v3(|i| -&c[i]);
    let y = translate(q, &neg);
    rotate_parts(&y, w, sign).map(|z| translate(&z, c))
}

/// A rigid motion `[R | t]` (3 x 4, exact).
type Motion = [[Scalar; 4]; 3];

fn apply(g: &Motion, x: &V3, d: &V3) -> (V3, V3) {
    let p = v3(|i| &g[i][0] * &x[0] + &g[i][1] * &x[1] + &g[i][2] * &x[2] + &g[i][3]);
    let v = v3(|i| &g[i][0] * &d[0] + &g[i][1] * &d[1] + &g[i][2] * &d[2]);
    (p, v)
}

fn inverse(g: &Motion) -> Motion {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if j < 3 {
                g[j][i].clone()
            } else {
                -(&g[0][i] * &g[0][3] + &g[1][i] * &g[1][3] + &g[2][i] * &g[2][3])
            }
        })
    })
}

fn compose(a: &Motion, b: &Motion) -> Motion {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut s = (0..3).fold(Scalar::int(0), |s, k| s + &a[i][k] * &b[k][j]);
            if j == 3 {
                s = s + &a[i][3];
            }
            s
        })
    })
}

/// Names for the target's quantities that no parameter and no target entry takes.
fn g_names(sol: &IkSolution) -> Vec<String> {
    let taken = |n: &str| {
        sol.params.iter().any(|p| p.starts_with(n))
            || sol.variables.iter().any(|p| p.starts_with(n))
            || TARGET_SYMBOLS.iter().flatten().any(|p| p.starts_with(n))
    };
    let base = ["g", "h", "u", "w", "gq"]
        .into_iter()
        .find(|b| !taken(b))
        .unwrap_or("target_q");
    (1..=14).map(|i| format!("{base}{i}")).collect()
}

/// The exact equations of the arrangement read from joint 1, forwards or backwards as at the
/// derivation's generic target (`info.arrangement.0`), or the other way when that would end
/// with a joint that slides. An arrangement read from another joint (`shift > 0`, chosen when
/// these are degenerate) conjugates joints by the target and is not derived exactly; its
/// equations are the same construction with those axes moved.
///
/// # Errors
/// The exact arithmetic fails (term limit, work budget); the first and last joints both slide.
pub fn exact_equations(sol: &IkSolution, info: &GeneralInfo) -> Result<ExactEquations, ExactError> {
    if super::apart_chain(&sol.axes) {
        return Err(ExactError::SlidesApart);
    }
    let slides = |k: usize| {
        sol.axes
            .get(k)
            .is_some_and(|a| a.kind == JointKind::Prismatic)
    };
    let mut rev = info.arrangement.0;
    if slides(if rev { 0 } else { 5 }) {
        rev = !rev;
    }
    if slides(if rev { 0 } else { 5 }) {
        return Err(ExactError::SlideAtBothEnds);
    }
    let order: [usize; 6] = std::array::from_fn(|i| if rev { 5 - i } else { i });
    // The arranged axes: reversed directions when read backwards (`Ei⁻¹(q)` turns about the
    // reversed axis by `q`, and slides along it by `q`).
    let axis = |i: usize| -> (V3, V3, bool) {
        let a = &sol.axes[order[i]];
        let w = if rev {
            v3(|k| -&a.dir[k])
        } else {
            a.dir.clone()
        };
        (w, a.point.clone(), slides(order[i]))
    };
    // G = T M⁻¹ with T the symbolic target.
    let t: Motion =
        std::array::from_fn(|i| std::array::from_fn(|j| Scalar::sym(TARGET_SYMBOLS[i][j])));
    let m: Motion = std::array::from_fn(|i| std::array::from_fn(|j| sol.home.rows[i][j].clone()));
    let g = compose(&t, &inverse(&m));
    let h = if rev { inverse(&g) } else { g };
    let (w6, p6, _) = axis(5);
    let (u, v) = apply(&h, &p6, &w6);
    let defs = quantities(&u, &v);
    let names = g_names(sol);
    let mut gq: Q15 = std::array::from_fn(|i| {
        if i < 14 {
            Scalar::sym(&names[i])
        } else {
            Scalar::int(1)
        }
    });
    gq[14] = Scalar::int(1);
    // Left side: E3 E4 E5 applied to (p6, w6), one joint at a time.
    let q0 = quantities(&p6, &w6);
    let (j5, j4, j3) = (axis(4), axis(3), axis(2));
    let v5 = motion_parts(&q0, &j5, 1);
    let zero = || Scalar::int(0);
    let mut am: Vec<[[Scalar; 9]; 3]> = (0..14)
        .map(|_| std::array::from_fn(|_| std::array::from_fn(|_| zero())))
        .collect();
    for (i5, x5) in v5.iter().enumerate() {
        for (i4, x4) in motion_parts(x5, &j4, 1).iter().enumerate() {
            for (i3, x3) in motion_parts(x4, &j3, 1).iter().enumerate() {
                for e in 0..14 {
                    am[e][i3][3 * i4 + i5] = x3[e].clone().check()?;
                }
            }
        }
    }
    // Right side: E2⁻¹ E1⁻¹ applied to the target's (u, v), linear in its quantities.
    let (j1, j2) = (axis(0), axis(1));
    let mut bm: Vec<[Scalar; 8]> = (0..14).map(|_| std::array::from_fn(|_| zero())).collect();
    for (i1, y1) in motion_parts(&gq, &j1, -1).iter().enumerate() {
        for (i2, y2) in motion_parts(y1, &j2, -1).iter().enumerate() {
            let mono = 3 * i1 + i2;
            for e in 0..14 {
                let y = y2[e].clone().check()?;
                if mono == 0 {
                    am[e][0][0] = (&am[e][0][0] - &y).check()?;
                } else {
                    bm[e][mono - 1] = y;
                }
            }
        }
    }
    let g_defs = defs[..14]
        .iter()
        .map(|s| s.clone().check())
        .collect::<Result<Vec<_>, _>>()?;
    Ok(ExactEquations {
        arrangement: (rev, 0),
        order,
        prismatic: std::array::from_fn(|i| slides(order[i])),
        g_names: names,
        g: g_defs,
        am,
        bm,
    })
}

/// The half-angle weights: `(1, cos θ, sin θ) (1 + x²)` in powers `(1, x, x²)` of `x =
/// tan(θ/2)`, as the core's `HALF`.
pub const HALF: [[i64; 3]; 3] = [[1, 0, 1], [1, 0, -1], [0, 2, 0]];

impl ExactEquations {
    /// The half-angle form before the null space: `half[e][j][3 a + b]`, the coefficient of
    /// `x3^j x4^a x5^b` in `(1 + x3²)(1 + x4²)(1 + x5²)` times equation `e`'s left side minus
    /// right side's constant (the part `Am(θ3) X45`); a slide's `x` is its `d` itself, without
    /// the factor. `M(x3) = A x3² + B x3 + C` are `N` times
    /// these (and `x4` times them), `N` the left null space of `Bm` at the target (numeric).
    ///
    /// # Errors
    /// The exact arithmetic fails.
    pub fn half_angle(&self) -> Result<Vec<[[Scalar; 9]; 3]>, ScalarError> {
        self.am
            .iter()
            .map(|a| {
                let mut out: [[Scalar; 9]; 3] =
                    std::array::from_fn(|_| std::array::from_fn(|_| Scalar::int(0)));
                for (j, row) in out.iter_mut().enumerate() {
                    for (ab, x) in row.iter_mut().enumerate() {
                        let (pa, pb) = (ab / 3, ab % 3);
                        let mut s = Scalar::int(0);
                        for (k, ak) in a.iter().enumerate() {
                            for (m, c) in ak.iter().enumerate() {
                                let w = self.weight(2, k, j)
                                    * self.weight(3, m / 3, pa)
                                    * self.weight(4, m % 3, pb);
                                if w != 0 && !c.is_zero_value() {
                                    s = s + Scalar::int(w) * c;
                                }
                            }
                        }
                        *x = s.check()?;
                    }
                }
                Ok(out)
            })
            .collect()
    }

    /// The weight of basis function `k` of arranged joint `i` in power `j` of its half-angle
    /// variable: [`HALF`] for a turn, the identity for a slide.
    fn weight(&self, i: usize, k: usize, j: usize) -> i64 {
        if self.prismatic[i] {
            i64::from(k == j)
        } else {
            HALF[k][j]
        }
    }

    /// The equations at numbers: the target's quantities from `env` (parameters and target
    /// entries), then `(am, bm)`.
    ///
    /// # Errors
    /// A symbol without a value.
    #[allow(clippy::type_complexity)]
    pub fn eval(
        &self,
        env: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<([[[f64; 9]; 3]; 14], [[f64; 8]; 14]), ScalarError> {
        let gv = self
            .g
            .iter()
            .map(|s| s.eval(env))
            .collect::<Result<Vec<_>, _>>()?;
        let full = |n: &str| {
            self.g_names
                .iter()
                .position(|k| k == n)
                .map(|i| gv[i])
                .or_else(|| env(n))
        };
        let mut am = [[[0.0; 9]; 3]; 14];
        let mut bm = [[0.0; 8]; 14];
        for (e, (ar, br)) in am.iter_mut().zip(bm.iter_mut()).enumerate() {
            for (k, row) in ar.iter_mut().enumerate() {
                for (m, x) in row.iter_mut().enumerate() {
                    *x = self.am[e][k][m].eval(&full)?;
                }
            }
            for (m, x) in br.iter_mut().enumerate() {
                *x = self.bm[e][m].eval(&full)?;
            }
        }
        Ok((am, bm))
    }
}

/// One coefficient as the report and the walkthrough show it.
#[derive(Clone, Debug)]
pub struct Shown {
    /// Its name in plain text (`A3[cos q3 sin q5]`).
    pub label: String,
    /// Its name in LaTeX.
    pub tex: String,
    /// Its closed form.
    pub expr: crate::Expr,
}

/// A titled list of coefficients.
#[derive(Clone, Debug)]
pub struct ShownGroup {
    /// The title (plain text).
    pub title: String,
    /// The nonzero coefficients.
    pub items: Vec<Shown>,
}

/// A coefficient as shown: a constant as its expanded sum (`1/4 - 1/4 sqrt(5)`; the
/// closed-form search for products of constant cosines costs about a millisecond each and
/// these are hundreds), anything with symbols in closed form (factored over the parameters).
fn coefficient_form(s: &Scalar) -> Result<crate::Expr, ScalarError> {
    if s.is_constant() {
        crate::closed::expanded_form(s)
    } else {
        crate::closed_form(s)
    }
}

/// `(1, cos, sin)` of a variable, plain and LaTeX (`""` for the 1).
fn trig_factor(k: usize, var: &str) -> (String, String) {
    let tex = crate::emit::latex_symbol(var);
    match k {
        1 => (format!("cos {var}"), format!("\\cos {tex}")),
        2 => (format!("sin {var}"), format!("\\sin {tex}")),
        _ => (String::new(), String::new()),
    }
}

/// `d^p` of a slide's variable `d`.
fn slide_factor(p: usize, var: &str) -> (String, String) {
    let tex = crate::emit::latex_symbol(var);
    match p {
        1 => (var.to_string(), tex),
        2 => (format!("{var}^2"), format!("{tex}^{{2}}")),
        _ => (String::new(), String::new()),
    }
}

/// `x^p` of a half-angle tangent `x_var`.
fn power_factor(p: usize, var: &str) -> (String, String) {
    let tex = format!("x_{{{}}}", crate::emit::latex_symbol(var));
    match p {
        1 => (format!("x_{var}"), tex),
        2 => (format!("x_{var}^2"), format!("{tex}^{{2}}")),
        _ => (String::new(), String::new()),
    }
}

fn monomial(factors: &[(String, String)]) -> (String, String) {
    let plain: Vec<&str> = factors
        .iter()
        .map(|f| f.0.as_str())
        .filter(|s| !s.is_empty())
        .collect();
    let tex: Vec<&str> = factors
        .iter()
        .map(|f| f.1.as_str())
        .filter(|s| !s.is_empty())
        .collect();
    if plain.is_empty() {
        ("1".into(), "1".into())
    } else {
        (plain.join(" "), tex.join(" \\, "))
    }
}

/// Coefficients with their plain and LaTeX names.
type Named = Vec<(String, String, Scalar)>;

impl ExactEquations {
    /// Every nonzero coefficient in closed form, in groups: the target's quantities, then per
    /// equation its `Am` and `Bm` coefficients, then per equation its half-angle polynomial.
    ///
    /// # Errors
    /// A closed form that fails (term limit, work budget).
    pub fn shown(&self, sol: &IkSolution) -> Result<Vec<ShownGroup>, ScalarError> {
        let var = |i: usize| sol.variables[self.order[i]].as_str();
        // A slide's basis `(1, d, d²)` is its half-angle form too.
        let tf = |k: usize, i: usize| {
            if self.prismatic[i] {
                slide_factor(k, var(i))
            } else {
                trig_factor(k, var(i))
            }
        };
        let pf = |k: usize, i: usize| {
            if self.prismatic[i] {
                slide_factor(k, var(i))
            } else {
                power_factor(k, var(i))
            }
        };
        let mut raw: Vec<(String, Named)> = Vec::new();
        raw.push((
            "the target's quantities (u = H p6, v = H w6: the point and direction of the last axis carried by the target)".into(),
            self.g_names
                .iter()
                .zip(&self.g)
                .zip(QUANTITY_NAMES)
                .map(|((n, g), q)| {
                    (
                        format!("{n} ({q} of u, v)"),
                        crate::emit::latex_symbol(n),
                        g.clone(),
                    )
                })
                .collect(),
        ));
        for (e, quantity) in QUANTITY_NAMES.iter().enumerate() {
            let mut items = Vec::new();
            for k in 0..3 {
                for m in 0..9 {
                    let (p, t) = monomial(&[tf(k, 2), tf(m / 3, 3), tf(m % 3, 4)]);
                    items.push((
                        format!("A{}[{p}]", e + 1),
                        format!("A_{{{}}}[{t}]", e + 1),
                        self.am[e][k][m].clone(),
                    ));
                }
            }
            for m in 1..9 {
                let (p, t) = monomial(&[tf(m / 3, 0), tf(m % 3, 1)]);
                items.push((
                    format!("B{}[{p}]", e + 1),
                    format!("B_{{{}}}[{t}]", e + 1),
                    self.bm[e][m - 1].clone(),
                ));
            }
            raw.push((
                format!(
                    "equation {} ({quantity}): the Am and Bm coefficients",
                    e + 1
                ),
                items,
            ));
        }
        for (e, h) in self.half_angle()?.iter().enumerate() {
            let mut items = Vec::new();
            for (j, row) in h.iter().enumerate() {
                for (ab, c) in row.iter().enumerate() {
                    let (p, t) = monomial(&[pf(j, 2), pf(ab / 3, 3), pf(ab % 3, 4)]);
                    items.push((
                        format!("P{}[{p}]", e + 1),
                        format!("P_{{{}}}[{t}]", e + 1),
                        c.clone(),
                    ));
                }
            }
            raw.push((
                format!("equation {} in half-angle tangents: P{} = (1 + x^2) (1 + x^2) (1 + x^2) (Am X45)", e + 1, e + 1),
                items,
            ));
        }
        let mut out = Vec::new();
        for (title, items) in raw {
            let nonzero: Named = items
                .into_iter()
                .filter(|(_, _, s)| !s.is_zero_value())
                .collect();
            let forms = crate::scalar::par_map(&nonzero, |(_, _, s)| coefficient_form(s));
            let items = nonzero
                .into_iter()
                .zip(forms)
                .map(|((label, tex, _), f)| {
                    Ok(Shown {
                        label,
                        tex,
                        expr: f?,
                    })
                })
                .collect::<Result<Vec<_>, ScalarError>>()?;
            out.push(ShownGroup { title, items });
        }
        Ok(out)
    }
}
