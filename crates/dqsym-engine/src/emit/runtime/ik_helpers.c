//@ ik_roots: always
/* The roots of one step: n joint values with their sines and cosines, and the flags
   (singular, checked); n = 12 on a singular set of an atan2 (any value: k pi/6, k = -5..6),
   n = 13 with the atan2 value first. */
typedef struct {
    int n;
    double q[3], s[3], c[3];
    int sg, ck, smp;
} ik_roots;

static ik_roots ik_none(void) {
    ik_roots r = {0, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, 0, 0, 99};
    return r;
}

static void ik_root(const ik_roots *r, int i, double *q, double *s, double *c) {
    if (r->n >= 12 && i + 12 >= r->n) {
        *q = (i + 12 - r->n - 5) * (M_PI / 6);
        *s = sin(*q);
        *c = cos(*q);
    } else {
        *q = r->q[i];
        *s = r->s[i];
        *c = r->c[i];
    }
}

//@ ik_memo: atan2
/* A step's last atan2, reused by the next call of the step: the same arguments give the same
   root, exactly negated ones the angle plus pi with the sine and cosine negated. */
typedef struct {
    double y, x;
    ik_roots r;
} ik_memo;

static ik_memo ik_memo_new(void) {
    ik_memo m;
    m.y = m.x = NAN;
    m.r = ik_none();
    return m;
}

//@ ik_atan2: atan2
/* atan2(y, x) for arguments rounded by sg: where both are zero within it, any value (and
   atan2 itself where not exactly 0/0). */
static ik_roots ik_atan2(double y, double x, double sg, ik_memo *m) {
    ik_roots r = ik_none();
    double h2, h;
    if (m->r.n == 1 && y == m->y && x == m->x) return m->r;
    if (m->r.n == 1 && y == -m->y && x == -m->x) {
        const double q = m->r.q[0];
        m->r.q[0] = q > 0.0 ? q - M_PI : q + M_PI;
        m->r.s[0] = -m->r.s[0];
        m->r.c[0] = -m->r.c[0];
        m->y = y;
        m->x = x;
        return m->r;
    }
    h2 = y * y + x * x;
    if (h2 <= sg * sg) {
        r.sg = 1;
        r.ck = 1;
        r.n = 12;
        if (h2 > 0.0) {
            h = sqrt(h2);
            r.n = 13;
            r.smp = 1;
            r.q[0] = atan2(y, x);
            r.s[0] = y / h;
            r.c[0] = x / h;
        }
        return r;
    }
    h = sqrt(h2);
    r.n = 1;
    r.q[0] = atan2(y, x);
    r.s[0] = y / h;
    r.c[0] = x / h;
    r.ck = sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2;
    m->y = y;
    m->x = x;
    m->r = r;
    return r;
}

//@ ik_radicand: trig quadratic
/* A radicand of scale n rounded by nu: 0 out of reach (below -IK_REACH_TOL n), a double root
   within nu of zero (singular), else itself (checked where its roots err by more than
   IK_CHECK_TOL). */
static int ik_radicand(double *rad, double n, double nu, int *sg, int *ck) {
    if (*rad < -IK_REACH_TOL * n - nu) return 0;
    if (*rad <= nu) {
        *sg = 1;
        *ck = 1;
        *rad = 0.0;
    } else {
        *ck = nu * nu > 4.0 * IK_CHECK_TOL * IK_CHECK_TOL * *rad * n;
    }
    return 1;
}

//@ ik_trig: trig
static ik_roots ik_trig(double a, double b, double c, double sg) {
    ik_roots r = ik_none();
    const double n = a * a + b * b;
    double rad, nu, w, d, y0, x0, y1, x1;
    if (n <= sg * sg) {
        if (fabs(c) <= sg) {
            r.n = 1;
            r.sg = 1;
            r.ck = 1;
        }
        return r;
    }
    rad = n - c * c;
    nu = 2.0 * sg * (fabs(a) + fabs(b) + fabs(c)) + 4.0 * DBL_EPSILON * n;
    if (!ik_radicand(&rad, n, nu, &r.sg, &r.ck)) return r;
    w = sqrt(rad);
    d = r.sg ? sqrt(n * (c * c + rad)) : n;
    y0 = b * c + a * w; x0 = a * c - b * w; y1 = b * c - a * w; x1 = a * c + b * w;
    r.n = 2;
    r.q[0] = atan2(y0, x0);
    r.q[1] = b == 0.0 ? -r.q[0] : a == 0.0 ? copysign(M_PI, y0) - r.q[0] : atan2(y1, x1);
    r.s[0] = y0 / d; r.s[1] = y1 / d;
    r.c[0] = x0 / d; r.c[1] = x1 / d;
    if (r.sg) {
        /* Beside the double root, the pair of the radicand nu (sampled: kept where refinement
           takes it onto the pose). */
        const double wn = sqrt(nu), e = sqrt(n * (c * c + nu));
        const double y2 = b * c + a * wn, x2 = a * c - b * wn, y3 = b * c - a * wn, x3 = a * c + b * wn;
        r.n = 3;
        r.smp = 1;
        r.q[1] = atan2(y2, x2); r.s[1] = y2 / e; r.c[1] = x2 / e;
        r.q[2] = atan2(y3, x3); r.s[2] = y3 / e; r.c[2] = x3 / e;
    }
    return r;
}

//@ ik_exact: trig
/* Beside the double root of ik_trig(...): a solution from `from` on reproduces the pose. */
static int ik_exact(const ik_solutions *out, int from) {
    int i;
    for (i = from; i < out->n; i++)
        if (!out->approximate[i]) return 1;
    return 0;
}

//@ ik_quadratic: quadratic
static ik_roots ik_quadratic(double beta, double gamma, double sg) {
    ik_roots r = ik_none();
    double rad = beta * beta - gamma, w;
    const double s = fmax(fabs(beta), sqrt(fabs(gamma)));
    const double nu = sg + 2.0 * sqrt(sg * IK_ZERO_TOL) * (2.0 * fabs(beta) + s) + 4.0 * DBL_EPSILON * (beta * beta + fabs(gamma));
    if (!ik_radicand(&rad, fmax(beta * beta, fabs(gamma)), nu, &r.sg, &r.ck)) return r;
    w = sqrt(rad);
    r.n = 2;
    r.q[0] = -beta + w; r.q[1] = -beta - w;
    return r;
}

//@ ik_linear: linear
/* a q = b, q a length (b rounded by sg = IK_ZERO_TOL L, a dimensionless, rounded by
   IK_ZERO_TOL): q = b / a; singular where |a| <= IK_ZERO_TOL (b / a kept while a != 0, else 0);
   checked where its error (sg + |q| IK_ZERO_TOL) / |a| exceeds IK_CHECK_TOL L. */
static ik_roots ik_linear(double a, double b, double sg) {
    ik_roots r = ik_none();
    const double q = a == 0.0 ? 0.0 : b / a;
    r.n = 1;
    r.q[0] = q;
    if (fabs(a) <= IK_ZERO_TOL) {
        r.sg = 1;
        r.ck = 1;
        return r;
    }
    r.ck = (sg + fabs(q) * IK_ZERO_TOL) / fabs(a) * IK_ZERO_TOL > IK_CHECK_TOL * sg;
    return r;
}

//@ ik_chain: always
/* What the check of a solution needs: the joint axes in the home pose {kind, w, p} (kind 1:
   prismatic), the home pose, the target and the robot's scale. */
typedef struct {
    double ax[IK_DOF][7];
    double home[3][4];
    const double (*t)[4];
    double len;
} ik_chain;

//@ ik_scale: always
/* The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
   position or the target position. */
static double ik_scale(const ik_chain *ch) {
    double l = fmax(fabs(ch->home[0][3]) + fabs(ch->home[1][3]) + fabs(ch->home[2][3]),
                    fabs(ch->t[0][3]) + fabs(ch->t[1][3]) + fabs(ch->t[2][3]));
    int i;
    for (i = 0; i < IK_DOF; i++) l = fmax(l, fabs(ch->ax[i][4]) + fabs(ch->ax[i][5]) + fabs(ch->ax[i][6]));
    return l > 0.0 && l < HUGE_VAL ? l : 1.0;
}

//@ ik_compose: always
/* a b for rigid motions as 3 x 4 blocks (m may not be a or b). */
static void ik_compose(const double a[3][4], const double b[3][4], double m[3][4]) {
    int r, c;
    for (r = 0; r < 3; r++)
        for (c = 0; c < 4; c++)
            m[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + (c == 3 ? a[r][3] : 0.0);
}

//@ ik_motion: always
/* Joint motion at q about (along) a home axis: R = c I + s [w]x + (1 - c) w w^T,
   t = (I - R) p. */
static void ik_motion(const double a[7], double q, double m[3][4]) {
    const double w[3] = {a[1], a[2], a[3]};
    const double k[3][3] = {{0.0, -a[3], a[2]}, {a[3], 0.0, -a[1]}, {-a[2], a[1], 0.0}};
    const double s = sin(q), c = cos(q);
    int r, j;
    for (r = 0; r < 3; r++) {
        for (j = 0; j < 3; j++)
            m[r][j] = a[0] != 0.0 ? (r == j ? 1.0 : 0.0) : (r == j ? c : 0.0) + s * k[r][j] + (1.0 - c) * w[r] * w[j];
        m[r][3] = a[0] != 0.0 ? q * w[r] : a[4 + r] - (m[r][0] * a[4] + m[r][1] * a[5] + m[r][2] * a[6]);
    }
}

//@ ik_fk: always
/* The pose E1(q1) ... En(qn) M (into f) and each joint's current axis (w, p). */
static void ik_fk(const ik_chain *ch, const double q[IK_DOF], double cur[IK_DOF][6], double f[3][4]) {
    double p[3][4] = {{1.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}}, e[3][4], m[3][4];
    int i, r, c;
    for (i = 0; i < IK_DOF; i++) {
        const double *a = ch->ax[i];
        for (r = 0; r < 3; r++) {
            cur[i][r] = p[r][0] * a[1] + p[r][1] * a[2] + p[r][2] * a[3];
            cur[i][3 + r] = p[r][0] * a[4] + p[r][1] * a[5] + p[r][2] * a[6] + p[r][3];
        }
        ik_motion(a, q[i], e);
        ik_compose((const double (*)[4])p, (const double (*)[4])e, m);
        for (r = 0; r < 3; r++)
            for (c = 0; c < 4; c++) p[r][c] = m[r][c];
    }
    ik_compose((const double (*)[4])p, ch->home, f);
}

//@ ik_error: always
/* T - F (rotation entries, then positions over the scale; positions only for a
   position-only solver); returns its length. */
static int ik_error(const ik_chain *ch, const double f[3][4], double e[12]) {
    int k = 0, r, c;
    for (r = 0; r < 3; r++)
        for (c = 0; c < 4; c++) {
            if (c == 3) e[k++] = (ch->t[r][3] - f[r][3]) / ch->len;
            else if (!IK_POSITION_ONLY) e[k++] = ch->t[r][c] - f[r][c];
        }
    return k;
}

//@ ik_max_abs: always
static double ik_max_abs(const double *e, int m) {
    double x = 0.0;
    int k;
    for (k = 0; k < m; k++)
        if (fabs(e[k]) > x || e[k] != e[k]) x = fabs(e[k]);
    return x;
}

//@ ik_residual: always
/* The residual of q: the largest entry of T - F(q), positions over the scale. */
static double ik_residual(const ik_chain *ch, const double q[IK_DOF]) {
    double cur[IK_DOF][6], f[3][4], e[12];
    int m;
    ik_fk(ch, q, cur, f);
    m = ik_error(ch, (const double (*)[4])f, e);
    return ik_max_abs(e, m);
}

//@ ik_cholesky: always
/* Solves h x = b in place (b becomes x) for a symmetric positive definite h; 0 when it is
   not. */
static int ik_cholesky(double h[IK_DOF][IK_DOF], double b[IK_DOF]) {
    int i, j, k;
    for (j = 0; j < IK_DOF; j++) {
        double d = h[j][j];
        for (k = 0; k < j; k++) d -= h[j][k] * h[j][k];
        if (!(d > 0.0)) return 0;
        d = sqrt(d);
        h[j][j] = d;
        for (i = j + 1; i < IK_DOF; i++) {
            double s = h[i][j];
            for (k = 0; k < j; k++) s -= h[i][k] * h[j][k];
            h[i][j] = s / d;
        }
    }
    for (i = 0; i < IK_DOF; i++) {
        for (k = 0; k < i; k++) b[i] -= h[i][k] * b[k];
        b[i] /= h[i][i];
    }
    for (i = IK_DOF - 1; i >= 0; i--) {
        for (k = i + 1; k < IK_DOF; k++) b[i] -= h[k][i] * b[k];
        b[i] /= h[i][i];
    }
    return 1;
}

//@ ik_refine: always
/* Damped Gauss-Newton on the pose residual from q (updated in place): at most
   IK_REFINE_STEPS steps, each kept only when it lowers the residual (else the damping grows a
   hundredfold). Returns the final residual. */
static double ik_refine(const ik_chain *ch, double q[IK_DOF]) {
    double cur[IK_DOF][6], f[3][4], e[12], jac[IK_DOF][12], a[IK_DOF][IK_DOF], g[IK_DOF];
    double lambda = 1e-12, res;
    int m, it, i, j, k, r, c;
    ik_fk(ch, q, cur, f);
    m = ik_error(ch, (const double (*)[4])f, e);
    res = ik_max_abs(e, m);
    for (it = 0; it < IK_REFINE_STEPS && res > IK_CHECK_TOL * 1e-3; it++) {
        double tr = 0.0;
        /* Jacobian columns: d(R)/dqi = [wi]x R, d(t)/dqi = wi x (t - pi) (revolute), wi
           (prismatic); the same entries and scaling as the residual. */
        for (i = 0; i < IK_DOF; i++) {
            const double *w = cur[i];
            const int pri = ch->ax[i][0] != 0.0;
            const double v[3] = {f[0][3] - cur[i][3], f[1][3] - cur[i][4], f[2][3] - cur[i][5]};
            double dt[3], dr[3][3];
            dt[0] = pri ? w[0] : w[1] * v[2] - w[2] * v[1];
            dt[1] = pri ? w[1] : w[2] * v[0] - w[0] * v[2];
            dt[2] = pri ? w[2] : w[0] * v[1] - w[1] * v[0];
            for (c = 0; c < 3; c++) {
                dr[0][c] = pri ? 0.0 : w[1] * f[2][c] - w[2] * f[1][c];
                dr[1][c] = pri ? 0.0 : w[2] * f[0][c] - w[0] * f[2][c];
                dr[2][c] = pri ? 0.0 : w[0] * f[1][c] - w[1] * f[0][c];
            }
            k = 0;
            for (r = 0; r < 3; r++)
                for (c = 0; c < 4; c++) {
                    if (c == 3) jac[i][k++] = dt[r] / ch->len;
                    else if (!IK_POSITION_ONLY) jac[i][k++] = dr[r][c];
                }
        }
        for (i = 0; i < IK_DOF; i++) {
            for (j = 0; j < IK_DOF; j++) {
                a[i][j] = 0.0;
                for (k = 0; k < m; k++) a[i][j] += jac[i][k] * jac[j][k];
            }
            g[i] = 0.0;
            for (k = 0; k < m; k++) g[i] += jac[i][k] * e[k];
            tr += a[i][i];
        }
        for (;;) {
            double h[IK_DOF][IK_DOF], d[IK_DOF];
            for (i = 0; i < IK_DOF; i++) {
                for (j = 0; j < IK_DOF; j++) h[i][j] = a[i][j];
                h[i][i] += lambda * (tr > DBL_MIN ? tr : DBL_MIN);
                d[i] = g[i];
            }
            if (ik_cholesky(h, d)) {
                double next[IK_DOF], cur2[IK_DOF][6], f2[3][4], e2[12], r2;
                for (i = 0; i < IK_DOF; i++) next[i] = q[i] + d[i];
                ik_fk(ch, next, cur2, f2);
                ik_error(ch, (const double (*)[4])f2, e2);
                r2 = ik_max_abs(e2, m);
                if (r2 < res) {
                    for (i = 0; i < IK_DOF; i++) q[i] = next[i];
                    for (i = 0; i < IK_DOF; i++)
                        for (j = 0; j < 6; j++) cur[i][j] = cur2[i][j];
                    for (r = 0; r < 3; r++)
                        for (c = 0; c < 4; c++) f[r][c] = f2[r][c];
                    for (k = 0; k < 12; k++) e[k] = e2[k];
                    res = r2;
                    lambda = lambda * 0.01 > 1e-15 ? lambda * 0.01 : 1e-15;
                    break;
                }
            }
            lambda *= 100.0;
            if (lambda > 1.0) return res;
        }
    }
    return res;
}

//@ ik_same: always
static int ik_same(const double *a, const double *b) {
    int i;
    for (i = 0; i < IK_DOF; i++) {
        const double s = fmax(fmax(fabs(a[i]), fabs(b[i])), 1.0);
        if (fabs(a[i] - b[i]) > 4.0 * DBL_EPSILON * s) return 0;
    }
    return 1;
}

//@ ik_push: always
/* Writes a solution; one a step asks to check is checked by forward kinematics: refined
   where its residual exceeds IK_REFINE_TOL, flagged approximate where it stays above
   IK_POSE_TOL, dropped when it is a sample off the pose or a singular duplicate. */
static void ik_push(ik_solutions *out, const double q0[IK_DOF], int sg, int ck, int smp, const ik_chain *ch) {
    double q[IK_DOF], res = 0.0;
    int i;
    for (i = 0; i < IK_DOF; i++) q[i] = q0[i];
    if (sg || ck) {
        res = ik_residual(ch, q);
        if (res > IK_REFINE_TOL) {
            double r[IK_DOF], rr;
            for (i = 0; i < IK_DOF; i++) r[i] = q[i];
            rr = ik_refine(ch, r);
            if (rr < res) {
                for (i = 0; i < IK_DOF; i++) q[i] = r[i];
                res = rr;
            }
        }
        if (smp && res > IK_POSE_TOL) return;
        if (sg)
            for (i = 0; i < out->n; i++)
                if (out->singular[i] && ik_same(out->q[i], q)) return;
    }
    for (i = 0; i < IK_DOF; i++) out->q[out->n][i] = q[i];
    out->singular[out->n] = sg;
    out->approximate[out->n] = !(res <= IK_POSE_TOL);
    out->residual[out->n] = res;
    out->n += 1;
}

//@ ik_dq_matrix: always
static void ik_dq_matrix(const double q[8], double T[4][4]) {
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double a = q[4], b = q[5], c = q[6], d = q[7];
    T[0][0] = w * w + x * x - y * y - z * z; T[0][1] = 2 * (x * y - w * z); T[0][2] = 2 * (x * z + w * y);
    T[1][0] = 2 * (x * y + w * z); T[1][1] = w * w - x * x + y * y - z * z; T[1][2] = 2 * (y * z - w * x);
    T[2][0] = 2 * (x * z - w * y); T[2][1] = 2 * (y * z + w * x); T[2][2] = w * w - x * x - y * y + z * z;
    T[0][3] = 2 * (-a * x + b * w - c * z + d * y);
    T[1][3] = 2 * (-a * y + b * z + c * w - d * x);
    T[2][3] = 2 * (-a * z - b * y + c * x + d * w);
    T[3][0] = T[3][1] = T[3][2] = 0.0; T[3][3] = 1.0;
}
