//@ IkRoots: always
/// The roots of one step: `n` joint values with their sines and cosines (known without a
/// call), and the flags (singular, checked); `n = 12` on a singular set of an atan2 (the
/// samples of `ik_any`), `n = 13` with the atan2 value first; roots from `smp` on are samples
/// beside a kept value.
#[derive(Clone, Copy)]
struct IkRoots {
    n: usize,
    q: [f64; 3],
    s: [f64; 3],
    c: [f64; 3],
    sg: bool,
    ck: bool,
    smp: usize,
}

impl IkRoots {
    const NONE: IkRoots = IkRoots { n: 0, q: [0.0; 3], s: [0.0; 3], c: [1.0; 3], sg: false, ck: false, smp: 99 };
    /// Root `i`: `(q, sin q, cos q)`.
    #[inline(always)]
    fn root(&self, i: usize) -> (f64, f64, f64) {
        if self.n >= 12 && i + 12 >= self.n {
            ik_any(i + 12 - self.n)
        } else {
            (self.q[i], self.s[i], self.c[i])
        }
    }
    /// Root `i` is a sample beside the kept atan2 value (dropped when it stays off the pose).
    #[inline(always)]
    #[allow(dead_code)]
    fn sampled(&self, i: usize) -> bool {
        i >= self.smp
    }
}

//@ ik_any: always
/// A joint free on a singular set: value `i` of twelve, k pi/6, k = -5..6, so that a later
/// joint can still reach.
#[cold]
#[inline(never)]
fn ik_any(i: usize) -> (f64, f64, f64) {
    let q = (i as f64 - 5.0) * std::f64::consts::FRAC_PI_6;
    let (s, c) = q.sin_cos();
    (q, s, c)
}

//@ IkMemo: atan2
/// A step's last atan2 (`y`, `x` and the root `q`, `sin q`, `cos q`), reused by the next call
/// of the step: the same arguments give the same root, exactly negated ones the angle plus pi
/// with the sine and cosine negated (the wrist flip theta4 + pi, theta6 + pi of the sibling
/// branch).
#[derive(Clone, Copy)]
struct IkMemo {
    y: f64,
    x: f64,
    q: f64,
    s: f64,
    c: f64,
    ck: bool,
}

impl IkMemo {
    const NEW: IkMemo = IkMemo { y: f64::NAN, x: f64::NAN, q: 0.0, s: 0.0, c: 1.0, ck: false };
}

//@ ik_atan2: atan2
/// `atan2(y, x)`, its sine `y / h` and cosine `x / h`, for arguments rounded by `sg`: where
/// both are zero within it, any value (and atan2 itself where not exactly 0/0).
#[inline(always)]
fn ik_atan2(y: f64, x: f64, sg: f64, m: &mut IkMemo) -> IkRoots {
    if y == -m.y && x == -m.x {
        m.q = if m.q > 0.0 { m.q - std::f64::consts::PI } else { m.q + std::f64::consts::PI };
        m.s = -m.s;
        m.c = -m.c;
        m.y = y;
        m.x = x;
    } else if y != m.y || x != m.x {
        let h2 = y * y + x * x;
        if h2 <= sg * sg {
            return ik_atan2_singular(y, x, h2);
        }
        let h = h2.sqrt();
        let ck = sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2;
        *m = IkMemo { y, x, q: y.atan2(x), s: y / h, c: x / h, ck };
    }
    IkRoots { n: 1, q: [m.q, 0.0, 0.0], s: [m.s, 0.0, 0.0], c: [m.c, 1.0, 1.0], sg: false, ck: m.ck, smp: 99 }
}

//@ ik_atan2_singular: atan2
#[cold]
#[inline(never)]
fn ik_atan2_singular(y: f64, x: f64, h2: f64) -> IkRoots {
    if h2 > 0.0 {
        let h = h2.sqrt();
        return IkRoots { n: 13, q: [y.atan2(x), 0.0, 0.0], s: [y / h, 0.0, 0.0], c: [x / h, 1.0, 1.0], sg: true, ck: true, smp: 1 };
    }
    IkRoots { n: 12, sg: true, ck: true, ..IkRoots::NONE }
}

//@ ik_radicand: trig quadratic
/// A radicand `rad` of scale `n` rounded by `nu`: none out of reach (below -IK_REACH_TOL n),
/// a double root within `nu` of zero (singular), else itself (checked where its roots err by
/// more than IK_CHECK_TOL).
#[inline(always)]
fn ik_radicand(rad: f64, n: f64, nu: f64) -> Option<(f64, bool, bool)> {
    if rad < -IK_REACH_TOL * n - nu {
        None
    } else if rad <= nu {
        Some((0.0, true, true))
    } else {
        Some((rad, false, nu * nu > 4.0 * IK_CHECK_TOL * IK_CHECK_TOL * rad * n))
    }
}

//@ ik_trig: trig
/// `a cos q + b sin q = c` (parts rounded by `sg`): `q = atan2(b, a) +- atan2(r, c)`, `r =
/// sqrt(a^2 + b^2 - c^2)`, as `atan2(b c +- a r, a c -+ b r)`, whose sine and cosine are those
/// over `a^2 + b^2`. Where `b = 0` the roots are `+-q` (`atan2` is odd in `y`), where `a = 0`
/// they are `q` and `pi - q`.
#[inline(always)]
fn ik_trig(a: f64, b: f64, c: f64, sg: f64) -> IkRoots {
    let n = a * a + b * b;
    if n <= sg * sg {
        return if c.abs() <= sg { IkRoots { n: 1, sg: true, ck: true, ..IkRoots::NONE } } else { IkRoots::NONE };
    }
    let nu = 2.0 * sg * (a.abs() + b.abs() + c.abs()) + 4.0 * f64::EPSILON * n;
    let Some((rad, sg, ck)) = ik_radicand(n - c * c, n, nu) else {
        return IkRoots::NONE;
    };
    let r = rad.sqrt();
    // r^2 + c^2 = n, unless the radicand was clamped.
    let d = if sg { (n * (c * c + rad)).sqrt() } else { n };
    let (y0, x0, y1, x1) = (b * c + a * r, a * c - b * r, b * c - a * r, a * c + b * r);
    let q0 = y0.atan2(x0);
    let q1 = if b == 0.0 {
        -q0
    } else if a == 0.0 {
        std::f64::consts::PI.copysign(y0) - q0
    } else {
        y1.atan2(x1)
    };
    if sg {
        // Beside the double root, the pair of the radicand nu (sampled: kept where refinement
        // takes it onto the pose, which the double root may miss when the pose is only near).
        let w = nu.sqrt();
        let e = (n * (c * c + nu)).sqrt();
        let (y1, x1, y2, x2) = (b * c + a * w, a * c - b * w, b * c - a * w, a * c + b * w);
        return IkRoots { n: 3, q: [q0, y1.atan2(x1), y2.atan2(x2)], s: [y0 / d, y1 / e, y2 / e], c: [x0 / d, x1 / e, x2 / e], sg, ck, smp: 1 };
    }
    IkRoots { n: 2, q: [q0, q1, 0.0], s: [y0 / d, y1 / d, 0.0], c: [x0 / d, x1 / d, 1.0], sg, ck, smp: 99 }
}

//@ ik_exact: trig
/// Beside the double root of `ik_trig(...)`: a solution from `from` on reproduces the pose.
fn ik_exact(out: &IkSolutions, from: usize) -> bool {
    out.approximate[from..out.n].iter().any(|a| !a)
}

//@ ik_quadratic: quadratic
/// `q^2 + 2 beta q + gamma = 0` (`gamma` rounded by `sg`, `beta` by `sqrt(sg IK_ZERO_TOL)`):
/// up to two roots.
#[inline(always)]
fn ik_quadratic(beta: f64, gamma: f64, sg: f64) -> IkRoots {
    let s = beta.abs().max(gamma.abs().sqrt());
    let nu = sg + 2.0 * (sg * IK_ZERO_TOL).sqrt() * (2.0 * beta.abs() + s) + 4.0 * f64::EPSILON * (beta * beta + gamma.abs());
    let Some((rad, sg, ck)) = ik_radicand(beta * beta - gamma, (beta * beta).max(gamma.abs()), nu) else {
        return IkRoots::NONE;
    };
    let r = rad.sqrt();
    IkRoots { n: 2, q: [-beta + r, -beta - r, 0.0], sg, ck, ..IkRoots::NONE }
}

//@ ik_linear: linear
/// `a q = b`, `q` a length (`b` rounded by `sg = IK_ZERO_TOL L`, `a` dimensionless, rounded by
/// `IK_ZERO_TOL`): `q = b / a`; singular where `|a| <= IK_ZERO_TOL` (`b / a` kept while `a != 0`,
/// else 0); checked where its error `(sg + |q| IK_ZERO_TOL) / |a|` exceeds `IK_CHECK_TOL L`.
#[inline(always)]
fn ik_linear(a: f64, b: f64, sg: f64) -> IkRoots {
    let q = if a == 0.0 { 0.0 } else { b / a };
    if a.abs() <= IK_ZERO_TOL {
        return IkRoots { n: 1, q: [q, 0.0, 0.0], sg: true, ck: true, ..IkRoots::NONE };
    }
    let ck = (sg + q.abs() * IK_ZERO_TOL) / a.abs() * IK_ZERO_TOL > IK_CHECK_TOL * sg;
    IkRoots { n: 1, q: [q, 0.0, 0.0], ck, ..IkRoots::NONE }
}

//@ IkChain: always
/// What the check of a solution needs: the joint axes in the home pose `[kind, w, p]` (kind 1:
/// prismatic), the home pose, the target and the robot's scale.
struct IkChain<'a> {
    ax: [[f64; 7]; IK_DOF],
    home: [[f64; 4]; 3],
    t: &'a [[f64; 4]; 4],
    len: f64,
}

//@ ik_scale: always
/// The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
/// position or the target position.
fn ik_scale(ch: &IkChain) -> f64 {
    let n1 = |x: f64, y: f64, z: f64| x.abs() + y.abs() + z.abs();
    let mut l = n1(ch.home[0][3], ch.home[1][3], ch.home[2][3]).max(n1(ch.t[0][3], ch.t[1][3], ch.t[2][3]));
    for a in &ch.ax {
        l = l.max(n1(a[4], a[5], a[6]));
    }
    if l > 0.0 && l.is_finite() { l } else { 1.0 }
}

//@ ik_push: always
/// Writes a solution; one a step asks to check goes through `ik_checked`.
#[inline(always)]
fn ik_push(out: &mut IkSolutions, q: [f64; IK_DOF], sg: bool, ck: bool, smp: bool, ch: &IkChain) {
    if sg || ck {
        ik_checked(out, q, sg, smp, ch);
        return;
    }
    out.q[out.n] = q;
    out.singular[out.n] = false;
    out.approximate[out.n] = false;
    out.residual[out.n] = 0.0;
    out.n += 1;
}

//@ ik_checked: always
/// A solution checked by forward kinematics: refined where its residual exceeds
/// IK_REFINE_TOL, flagged approximate where it stays above IK_POSE_TOL, dropped when it is a
/// sample off the pose or a singular duplicate.
#[cold]
#[inline(never)]
#[allow(clippy::needless_range_loop)]
fn ik_checked(out: &mut IkSolutions, mut q: [f64; IK_DOF], sg: bool, smp: bool, ch: &IkChain) {
    let mut res = ik_residual(ch, &q);
    if res > IK_REFINE_TOL {
        let mut r = q;
        let rr = ik_refine(ch, &mut r);
        if rr < res {
            q = r;
            res = rr;
        }
    }
    if smp && res > IK_POSE_TOL {
        return;
    }
    if sg {
        for i in 0..out.n {
            if out.singular[i] && ik_same(&out.q[i], &q) {
                return;
            }
        }
    }
    out.q[out.n] = q;
    out.singular[out.n] = sg;
    out.approximate[out.n] = res > IK_POSE_TOL || res.is_nan();
    out.residual[out.n] = res;
    out.n += 1;
}

//@ ik_same: always
/// Equal to a few units in the last place.
fn ik_same(a: &[f64; IK_DOF], b: &[f64; IK_DOF]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 4.0 * f64::EPSILON * x.abs().max(y.abs()).max(1.0))
}

//@ ik_compose: always
/// `a b` for rigid motions as 3 x 4 blocks.
fn ik_compose(a: &[[f64; 4]; 3], b: &[[f64; 4]; 3]) -> [[f64; 4]; 3] {
    let mut m = [[0.0; 4]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + if c == 3 { a[r][3] } else { 0.0 };
        }
    }
    m
}

//@ ik_motion: always
/// Joint motion at `q` about (along) a home axis: `R = c I + s [w]x + (1 - c) w w^T`, `t = (I
/// - R) p`.
#[allow(clippy::needless_range_loop)]
fn ik_motion(a: &[f64; 7], q: f64) -> [[f64; 4]; 3] {
    let w = [a[1], a[2], a[3]];
    if a[0] != 0.0 {
        return [[1.0, 0.0, 0.0, q * w[0]], [0.0, 1.0, 0.0, q * w[1]], [0.0, 0.0, 1.0, q * w[2]]];
    }
    let (s, c) = q.sin_cos();
    let k = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
    let mut m = [[0.0; 4]; 3];
    for r in 0..3 {
        for j in 0..3 {
            m[r][j] = if r == j { c } else { 0.0 } + s * k[r][j] + (1.0 - c) * w[r] * w[j];
        }
    }
    for r in 0..3 {
        m[r][3] = a[4 + r] - (m[r][0] * a[4] + m[r][1] * a[5] + m[r][2] * a[6]);
    }
    m
}

//@ ik_fk: always
/// The pose `E1(q1) ... En(qn) M` and each joint's current axis `(w, p)`.
#[allow(clippy::needless_range_loop)]
fn ik_fk(ch: &IkChain, q: &[f64; IK_DOF], cur: &mut [[f64; 6]; IK_DOF]) -> [[f64; 4]; 3] {
    let mut p = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]];
    for ((a, qi), cu) in ch.ax.iter().zip(q).zip(cur.iter_mut()) {
        for r in 0..3 {
            cu[r] = p[r][0] * a[1] + p[r][1] * a[2] + p[r][2] * a[3];
            cu[3 + r] = p[r][0] * a[4] + p[r][1] * a[5] + p[r][2] * a[6] + p[r][3];
        }
        p = ik_compose(&p, &ik_motion(a, *qi));
    }
    ik_compose(&p, &ch.home)
}

//@ ik_error: always
/// `T - F` (rotation entries, then positions over the scale; positions only for a
/// position-only solver); its length.
#[allow(clippy::needless_range_loop)]
fn ik_error(ch: &IkChain, f: &[[f64; 4]; 3], e: &mut [f64; 12]) -> usize {
    let mut k = 0;
    for r in 0..3 {
        for c in 0..4 {
            if c == 3 {
                e[k] = (ch.t[r][3] - f[r][3]) / ch.len;
                k += 1;
            } else if !IK_POSITION_ONLY {
                e[k] = ch.t[r][c] - f[r][c];
                k += 1;
            }
        }
    }
    k
}

//@ ik_max_abs: always
/// The largest entry (NaN for a NaN).
fn ik_max_abs(e: &[f64]) -> f64 {
    e.iter().fold(0.0, |m: f64, x| if x.abs() > m || x.is_nan() { x.abs() } else { m })
}

//@ ik_residual: always
/// The residual of `q`: the largest entry of `T - F(q)`, positions over the scale.
fn ik_residual(ch: &IkChain, q: &[f64; IK_DOF]) -> f64 {
    let mut cur = [[0.0; 6]; IK_DOF];
    let f = ik_fk(ch, q, &mut cur);
    let mut e = [0.0; 12];
    let k = ik_error(ch, &f, &mut e);
    ik_max_abs(&e[..k])
}

//@ ik_refine: always
/// Damped Gauss-Newton on the pose residual from `q` (updated in place): at most
/// IK_REFINE_STEPS steps, each kept only when it lowers the residual (else the damping grows a
/// hundredfold). Returns the final residual.
#[allow(clippy::needless_range_loop)]
fn ik_refine(ch: &IkChain, q: &mut [f64; IK_DOF]) -> f64 {
    let mut cur = [[0.0; 6]; IK_DOF];
    let mut f = ik_fk(ch, q, &mut cur);
    let mut e = [0.0; 12];
    let m = ik_error(ch, &f, &mut e);
    let mut res = ik_max_abs(&e[..m]);
    let mut lambda = 1e-12;
    for _ in 0..IK_REFINE_STEPS {
        if res <= IK_CHECK_TOL * 1e-3 {
            break;
        }
        // Jacobian columns: d(R)/dqi = [wi]x R, d(t)/dqi = wi x (t - pi) (revolute), wi
        // (prismatic); the same entries and scaling as the residual.
        let mut jac = [[0.0; 12]; IK_DOF];
        for i in 0..IK_DOF {
            let w = [cur[i][0], cur[i][1], cur[i][2]];
            let cross = |v: [f64; 3]| [w[1] * v[2] - w[2] * v[1], w[2] * v[0] - w[0] * v[2], w[0] * v[1] - w[1] * v[0]];
            let pri = ch.ax[i][0] != 0.0;
            let dt = if pri { w } else { cross([f[0][3] - cur[i][3], f[1][3] - cur[i][4], f[2][3] - cur[i][5]]) };
            let mut dr = [[0.0; 3]; 3];
            if !pri {
                for c in 0..3 {
                    let v = cross([f[0][c], f[1][c], f[2][c]]);
                    for r in 0..3 {
                        dr[r][c] = v[r];
                    }
                }
            }
            let mut k = 0;
            for r in 0..3 {
                for c in 0..4 {
                    if c == 3 {
                        jac[i][k] = dt[r] / ch.len;
                        k += 1;
                    } else if !IK_POSITION_ONLY {
                        jac[i][k] = dr[r][c];
                        k += 1;
                    }
                }
            }
        }
        let mut a = [[0.0; IK_DOF]; IK_DOF];
        let mut g = [0.0; IK_DOF];
        let mut tr = 0.0;
        for i in 0..IK_DOF {
            for j in 0..IK_DOF {
                a[i][j] = (0..m).map(|k| jac[i][k] * jac[j][k]).sum();
            }
            g[i] = (0..m).map(|k| jac[i][k] * e[k]).sum();
            tr += a[i][i];
        }
        loop {
            let mut h = a;
            for i in 0..IK_DOF {
                h[i][i] += lambda * tr.max(f64::MIN_POSITIVE);
            }
            let mut d = g;
            if ik_cholesky(&mut h, &mut d) {
                let mut next = *q;
                for i in 0..IK_DOF {
                    next[i] += d[i];
                }
                let mut cur2 = [[0.0; 6]; IK_DOF];
                let f2 = ik_fk(ch, &next, &mut cur2);
                let mut e2 = [0.0; 12];
                ik_error(ch, &f2, &mut e2);
                let r2 = ik_max_abs(&e2[..m]);
                if r2 < res {
                    *q = next;
                    f = f2;
                    cur = cur2;
                    e = e2;
                    res = r2;
                    lambda = (lambda * 0.01).max(1e-15);
                    break;
                }
            }
            lambda *= 100.0;
            if lambda > 1.0 {
                return res;
            }
        }
    }
    res
}

//@ ik_cholesky: always
/// Solves `h x = b` in place (`b` becomes `x`) for a symmetric positive definite `h`; false
/// when it is not.
#[allow(clippy::needless_range_loop)]
fn ik_cholesky(h: &mut [[f64; IK_DOF]; IK_DOF], b: &mut [f64; IK_DOF]) -> bool {
    for j in 0..IK_DOF {
        let mut d = h[j][j];
        for k in 0..j {
            d -= h[j][k] * h[j][k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        h[j][j] = d;
        for i in j + 1..IK_DOF {
            let mut s = h[i][j];
            for k in 0..j {
                s -= h[i][k] * h[j][k];
            }
            h[i][j] = s / d;
        }
    }
    for i in 0..IK_DOF {
        for k in 0..i {
            b[i] -= h[i][k] * b[k];
        }
        b[i] /= h[i][i];
    }
    for i in (0..IK_DOF).rev() {
        for k in i + 1..IK_DOF {
            b[i] -= h[k][i] * b[k];
        }
        b[i] /= h[i][i];
    }
    true
}

//@ ik_dq_matrix: always
/// The homogeneous matrix of a unit dual quaternion (Appendix I).
fn ik_dq_matrix(q: &[f64; 8]) -> [[f64; 4]; 4] {
    let [w, x, y, z, a, b, c, d] = *q;
    // t = 2 q_eps q* (vector part)
    let tx = 2.0 * (-a * x + b * w - c * z + d * y);
    let ty = 2.0 * (-a * y + b * z + c * w - d * x);
    let tz = 2.0 * (-a * z - b * y + c * x + d * w);
    [
        [w * w + x * x - y * y - z * z, 2.0 * (x * y - w * z), 2.0 * (x * z + w * y), tx],
        [2.0 * (x * y + w * z), w * w - x * x + y * y - z * z, 2.0 * (y * z - w * x), ty],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), w * w - x * x - y * y + z * z, tz],
        [0.0, 0.0, 0.0, 1.0],
    ]
}
