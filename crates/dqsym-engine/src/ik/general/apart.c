/* The numeric core of a 4R2P chain with its slides three joints apart in C99: a port of
   apart_solver.rs (orientation by the four turns, position by the slides' plane, the resultant
   D(theta4) of degree 8), function by function, with the same operations in the same order,
   after core.c in the generated solver, whose helpers it uses. The canonical chain is
   Tr(d0 v0) E1 E2 Tr(d3 v3) E4 E5 = H (see apart_solver.rs). Sums that apart_solver.rs writes
   with Rust's iterator sum start at -0.0, as that sum does. */

/* The arranged chain and what it keeps: R_H, h, w1 . w2, a = w2 - (w1 . w2) w1 and |a|^2. */
typedef struct {
    ik_gen_arranged ar;
    double rh[3][3], h[3], k12, a[3], na;
} ik_gen_apart;

static void ik_gen_apart_mt(const double r[3][3], double o[3][3]) {
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) o[i][j] = r[j][i];
}

static void ik_gen_apart_mm(const double a[3][3], const double b[3][3], double o[3][3]) {
    int i, j, k;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            o[i][j] = -0.0;
            for (k = 0; k < 3; k++) o[i][j] += a[i][k] * b[k][j];
        }
    }
}

/* o = a - f b. */
static void ik_gen_apart_sub(const double a[3], const double b[3], double o[3]) {
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}

static void ik_gen_apart_scaled(double f, const double v[3], double o[3]) {
    o[0] = f * v[0];
    o[1] = f * v[1];
    o[2] = f * v[2];
}

/* The chain of the arrangement ar; 0 when turns 1 and 2 are about parallel axes (this reading
   cannot serve). */
static int ik_gen_apart_new(const ik_gen_arranged *ar, ik_gen_apart *ch) {
    const double *w1 = ar->j[1].w, *w2 = ar->j[2].w;
    double kw[3];
    int i, k;
    ch->ar = *ar;
    for (i = 0; i < 3; i++) {
        for (k = 0; k < 3; k++) ch->rh[i][k] = ar->h[i][k];
        ch->h[i] = ar->h[i][3];
    }
    ch->k12 = ik_gen_dot3(w1, w2);
    ik_gen_apart_scaled(ch->k12, w1, kw);
    ik_gen_apart_sub(w2, kw, ch->a);
    ch->na = ik_gen_dot3(ch->a, ch->a);
    return ch->na > IK_GEN_APART_PARALLEL;
}

static void ik_gen_apart_rot(const ik_gen_apart *ch, int i, double th, double r[3][3]) {
    ik_gen_rodrigues(ch->ar.j[i].w, sin(th), cos(th), r);
}

/* Q = R_H R5^T R4^T. */
static void ik_gen_apart_q(const ik_gen_apart *ch, double t4, double t5, double q[3][3]) {
    double r[3][3], rt[3][3], m[3][3];
    ik_gen_apart_rot(ch, 5, t5, r);
    ik_gen_apart_mt((const double (*)[3])r, rt);
    ik_gen_apart_mm((const double (*)[3])ch->rh, (const double (*)[3])rt, m);
    ik_gen_apart_rot(ch, 4, t4, r);
    ik_gen_apart_mt((const double (*)[3])r, rt);
    ik_gen_apart_mm((const double (*)[3])m, (const double (*)[3])rt, q);
}

static double ik_gen_apart_f(const ik_gen_apart *ch, const double q[3][3]) {
    double qw[3];
    ik_gen_mv(q, ch->ar.j[2].w, qw);
    return ik_gen_dot3(ch->ar.j[1].w, qw) - ch->k12;
}

/* (cos th1, sin th1) as subproblem 1 gives them, linear in Q. */
static void ik_gen_apart_cs1(const ik_gen_apart *ch, const double q[3][3], double *c1,
                             double *s1) {
    const double *w1 = ch->ar.j[1].w;
    double qw[3], kw[3], b[3], x[3];
    ik_gen_mv(q, ch->ar.j[2].w, qw);
    ik_gen_apart_scaled(ch->k12, w1, kw);
    ik_gen_apart_sub(qw, kw, b);
    ik_gen_cross3(ch->a, b, x);
    *c1 = ik_gen_dot3(ch->a, b) / ch->na;
    *s1 = ik_gen_dot3(w1, x) / ch->na;
}

/* h - t(E1 E2 E4 E5) into r and Q v3 into u, with R1 from (c1, s1). */
static void ik_gen_apart_reach(const ik_gen_apart *ch, double t4, double t5, const double q[3][3],
                               double c1, double s1, double r[3], double u[3]) {
    const ik_gen_joint *j = ch->ar.j;
    double r1[3][3], r4[3][3], r5[3][3], r5t[3][3], x[3], y[3], z[3], t1[3], t2[3], t4v[3],
        t5v[3], a[3], b[3];
    int i;
    ik_gen_rodrigues(j[1].w, s1, c1, r1);
    ik_gen_apart_rot(ch, 4, t4, r4);
    ik_gen_apart_rot(ch, 5, t5, r5);
    ik_gen_mv((const double (*)[3])r1, j[1].c, x);
    ik_gen_apart_sub(j[1].c, x, t1);
    ik_gen_mv((const double (*)[3])r1, j[2].c, x);
    ik_gen_mv(q, j[2].c, y);
    ik_gen_apart_sub(x, y, t2);
    ik_gen_mv((const double (*)[3])r4, j[4].c, x);
    ik_gen_apart_sub(j[4].c, x, y);
    ik_gen_mv(q, y, t4v);
    ik_gen_apart_mt((const double (*)[3])r5, r5t);
    ik_gen_mv((const double (*)[3])r5t, j[5].c, x);
    ik_gen_apart_sub(x, j[5].c, y);
    ik_gen_mv((const double (*)[3])ch->rh, y, t5v);
    for (i = 0; i < 3; i++) {
        a[i] = t1[i] + t2[i];
        b[i] = t4v[i] + t5v[i];
    }
    for (i = 0; i < 3; i++) z[i] = a[i] + b[i];
    ik_gen_apart_sub(ch->h, z, r);
    ik_gen_mv(q, j[3].w, u);
}

/* (F, P, size of P's terms) at (th4, th5) into fp. */
static void ik_gen_apart_fp(const ik_gen_apart *ch, double t4, double t5, double fp[3]) {
    double q[3][3], c1, s1, r[3], u[3], n[3];
    ik_gen_apart_q(ch, t4, t5, q);
    ik_gen_apart_cs1(ch, (const double (*)[3])q, &c1, &s1);
    ik_gen_apart_reach(ch, t4, t5, (const double (*)[3])q, c1, s1, r, u);
    ik_gen_cross3(ch->ar.j[0].w, u, n);
    fp[0] = ik_gen_apart_f(ch, (const double (*)[3])q);
    fp[1] = ik_gen_dot3(n, r);
    fp[2] = sqrt(ik_gen_dot3(n, n)) * sqrt(ik_gen_dot3(r, r)) + IK_GEN_MIN_POSITIVE;
}

/* F's coefficients of (1, cos th5, sin th5) at th4, from three samples. */
static void ik_gen_apart_fcoef(const ik_gen_apart *ch, double t4, double *f0, double *fc,
                               double *fs) {
    double fp[3], th, v;
    int k;
    *f0 = 0.0;
    *fc = 0.0;
    *fs = 0.0;
    for (k = 0; k < 3; k++) {
        th = IK_GEN_TAU * (double)k / 3.0;
        ik_gen_apart_fp(ch, t4, th, fp);
        v = fp[0];
        *f0 += v / 3.0;
        *fc += 2.0 * v * cos(th) / 3.0;
        *fs += 2.0 * v * sin(th) / 3.0;
    }
}

/* (1 + x^2) F and (1 + x^2)^2 P in x = tan(th5/2) at th4 (ascending coefficients). */
static void ik_gen_apart_polys(const ik_gen_apart *ch, double t4, double f[3], double p[5]) {
    double f0, fc, fs, pc[5] = {0.0, 0.0, 0.0, 0.0, 0.0}, fp[3], th, v;
    int k, m;
    ik_gen_apart_fcoef(ch, t4, &f0, &fc, &fs);
    for (k = 0; k < 5; k++) {
        th = IK_GEN_TAU * (double)k / 5.0;
        ik_gen_apart_fp(ch, t4, th, fp);
        v = fp[1];
        pc[0] += v / 5.0;
        for (m = 1; m < 3; m++) {
            pc[2 * m - 1] += 2.0 * v * cos((double)m * th) / 5.0;
            pc[2 * m] += 2.0 * v * sin((double)m * th) / 5.0;
        }
    }
    f[0] = f0 + fc;
    f[1] = 2.0 * fs;
    f[2] = f0 - fc;
    p[0] = pc[0] + pc[1] + pc[3];
    p[1] = 2.0 * pc[2] + 4.0 * pc[4];
    p[2] = 2.0 * pc[0] - 6.0 * pc[3];
    p[3] = 2.0 * pc[2] - 4.0 * pc[4];
    p[4] = pc[0] - pc[1] + pc[3];
}

/* D(th4), the determinant of the Sylvester matrix; *ratio how well its LU is conditioned. */
static double ik_gen_apart_resultant(const ik_gen_apart *ch, double t4, double *ratio) {
    double f[3], p[5], s[6][6], d = 1.0;
    int perm[6], seen[6] = {0, 0, 0, 0, 0, 0}, i, k, len;
    ik_gen_apart_polys(ch, t4, f, p);
    memset(s, 0, sizeof s);
    for (i = 0; i < 4; i++)
        for (k = 0; k < 3; k++) s[i][i + k] = f[k];
    for (i = 0; i < 2; i++)
        for (k = 0; k < 5; k++) s[4 + i][i + k] = p[k];
    *ratio = ik_gen_lu(&s[0][0], 6, perm);
    for (i = 0; i < 6; i++) d *= s[i][i];
    /* The sign of the row permutation. */
    for (i = 0; i < 6; i++) {
        if (seen[i]) continue;
        for (k = i, len = 0; !seen[k]; len++) {
            seen[k] = 1;
            k = perm[k];
        }
        if (len % 2 == 0) d = -d;
    }
    return d;
}

/* The trigonometric coefficients of D into c; 0 when the check angle disagrees or no sample is
   conditioned. */
static int ik_gen_apart_coefficients(const ik_gen_apart *ch, double c[IK_GEN_DET_DEGREE + 1][2]) {
    const double step = IK_GEN_TAU / (double)IK_GEN_DET_SAMPLES, half = 0.5 * step;
    double d[IK_GEN_DET_SAMPLES], scale = 0.0, good = 0.0, ratio, a, b, w, interp = -0.0, check;
    int j, k;
    for (k = 0; k < IK_GEN_DET_SAMPLES; k++) {
        d[k] = ik_gen_apart_resultant(ch, (double)k * step, &ratio);
        scale = fmax(scale, fabs(d[k]));
        good = fmax(good, ratio);
    }
    if (!(good > IK_GEN_SHIFT_GOOD && isfinite(scale))) return 0;
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        a = 0.0;
        b = 0.0;
        for (k = 0; k < IK_GEN_DET_SAMPLES; k++) {
            a += d[k] * cos((double)(j * k) * step);
            b += d[k] * sin((double)(j * k) * step);
        }
        w = (j == 0 ? 1.0 : 2.0) / (double)IK_GEN_DET_SAMPLES;
        c[j][0] = w * a;
        c[j][1] = -(w * b);
    }
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++)
        interp += c[j][0] * cos((double)j * half) - c[j][1] * sin((double)j * half);
    check = ik_gen_apart_resultant(ch, half, &ratio);
    return fabs(check - interp) <= IK_GEN_DET_CHECK * scale;
}

/* Every joint (arranged order) from th4, th5. */
static void ik_gen_apart_joints(const ik_gen_apart *ch, double t4, double t5, double out[6]) {
    const double *w1 = ch->ar.j[1].w, *w2 = ch->ar.j[2].w, *v0 = ch->ar.j[0].w;
    double q[3][3], qt[3][3], c1, s1, t1, t2, kw[3], x[3], a2[3], b2[3], r[3], u[3], k, det,
        r0, ru;
    ik_gen_apart_q(ch, t4, t5, q);
    ik_gen_apart_cs1(ch, (const double (*)[3])q, &c1, &s1);
    t1 = atan2(s1, c1);
    ik_gen_apart_mt((const double (*)[3])q, qt);
    ik_gen_apart_scaled(ch->k12, w2, kw);
    ik_gen_mv((const double (*)[3])qt, w1, x);
    ik_gen_apart_sub(x, kw, a2);
    ik_gen_apart_sub(w1, kw, b2);
    ik_gen_cross3(a2, b2, x);
    t2 = atan2(ik_gen_dot3(w2, x), ik_gen_dot3(a2, b2));
    ik_gen_apart_reach(ch, t4, t5, (const double (*)[3])q, cos(t1), sin(t1), r, u);
    /* Least squares of r = d0 v0 + d3 u (unit directions): the normal equations; where they
       degenerate (a line of solutions), the one with d3 = 0. */
    k = ik_gen_dot3(v0, u);
    det = 1.0 - k * k;
    r0 = ik_gen_dot3(v0, r);
    ru = ik_gen_dot3(u, r);
    if (isnan(det) || det <= IK_GEN_APART_PARALLEL) {
        out[0] = r0;
        out[3] = 0.0;
    } else {
        out[0] = (r0 - k * ru) / det;
        out[3] = (ru - k * r0) / det;
    }
    out[1] = t1;
    out[2] = t2;
    out[4] = t4;
    out[5] = t5;
}

/* The joints (arranged order) at a root th4: one or two candidates (the roots of F = 0 in th5
   where P vanishes); returns how many. */
static int ik_gen_apart_back(const ik_gen_apart *ch, double t4, double out[2][6]) {
    double f0, fc, fs, rho, base, spread, cands[2], ps[2][3];
    int flat, best, n = 0, i, pass;
    ik_gen_apart_fcoef(ch, t4, &f0, &fc, &fs);
    rho = hypot(fc, fs);
    flat = rho <= sqrt(IK_GEN_APART_PARALLEL) * (rho + fabs(f0) + IK_GEN_MIN_POSITIVE);
    base = atan2(fs, fc);
    if (flat) {
        spread = 0.0;
    } else {
        /* -f0 / rho clamped to [-1, 1] (a NaN stays). */
        spread = -f0 / rho;
        if (spread < -1.0) spread = -1.0;
        if (spread > 1.0) spread = 1.0;
        spread = acos(spread);
    }
    cands[0] = base + spread;
    cands[1] = base - spread;
    ik_gen_apart_fp(ch, t4, cands[0], ps[0]);
    ik_gen_apart_fp(ch, t4, cands[1], ps[1]);
    best = fabs(ps[1][1]) < fabs(ps[0][1]);
    for (pass = 0; pass < 2; pass++) {
        i = pass == 0 ? best : 1 - best;
        if ((i == best || fabs(ps[i][1]) <= IK_GEN_APART_P_TOL * ps[i][2]) &&
            (n == 0 || spread > 0.0)) {
            ik_gen_apart_joints(ch, t4, cands[i], out[n]);
            n++;
        }
    }
    return n;
}

/* The real roots of D (see apart_solver.rs, apart_eigen_roots) into out, their number in *n,
   where the certified search gives up: the eigenvalues of the companion matrix of D in x =
   tan((th - phi)/2); 0 when D vanishes to rounding or the QR iteration does not converge. */
static int ik_gen_apart_eigen_roots(const double c[IK_GEN_DET_DEGREE + 1][2], double out[24],
                                    int *n) {
    double b0 = 0.0, best_phi = 0.0, best = -1.0, phi, lead, s, co, re, ratio, a, b, sg, r0, i0,
        p[2 * IK_GEN_DET_DEGREE + 1], pr[2 * IK_GEN_DET_DEGREE + 1],
        pi[2 * IK_GEN_DET_DEGREE + 1], k[24][24], wr[24], wi[24];
    int deg = IK_GEN_DET_DEGREE, j, l, kk, m, sh;
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++) b0 += hypot(c[j][0], c[j][1]);
    while (deg > 0 && hypot(c[deg][0], c[deg][1]) <= IK_GEN_DET_TRIM * b0) deg--;
    *n = 0;
    if (!(b0 > 0.0 && isfinite(b0))) return 0;
    /* A nonzero constant: no root. */
    if (deg == 0) return 1;
    /* The shift: |D(phi + pi)| large. */
    for (sh = 0; sh < 5; sh++) {
        phi = IK_GEN_SHIFTS[sh];
        lead = 0.0;
        for (j = 0; j <= deg; j++) {
            s = sin((double)j * phi);
            co = cos((double)j * phi);
            re = c[j][0] * co - c[j][1] * s;
            lead += j % 2 == 0 ? re : -re;
        }
        ratio = fabs(lead) / b0;
        if (ratio > best) {
            best_phi = phi;
            best = ratio;
        }
        if (ratio > IK_GEN_SHIFT_GOOD) break;
    }
    if (!(best > 0.0)) return 0;
    phi = best_phi;
    /* The polynomial's coefficients (ascending): (1 + ix)^(n+j) (1 - ix)^(n-j) expanded, its
       product with c_j e^(ij phi) taken real. */
    m = 2 * deg;
    for (l = 0; l <= m; l++) p[l] = 0.0;
    for (j = 0; j <= deg; j++) {
        s = sin((double)j * phi);
        co = cos((double)j * phi);
        a = c[j][0] * co - c[j][1] * s;
        b = c[j][0] * s + c[j][1] * co;
        for (l = 0; l <= m; l++) {
            pr[l] = 0.0;
            pi[l] = 0.0;
        }
        pr[0] = 1.0;
        for (kk = 0; kk < m; kk++) {
            sg = kk < deg + j ? 1.0 : -1.0;
            for (l = kk + 1; l >= 1; l--) {
                r0 = pr[l];
                i0 = pi[l];
                pr[l] = r0 - sg * pi[l - 1];
                pi[l] = i0 + sg * pr[l - 1];
            }
        }
        for (l = 0; l <= m; l++) p[l] += a * pr[l] - b * pi[l];
    }
    /* The companion matrix of the monic polynomial. */
    memset(k, 0, sizeof k);
    for (l = 0; l < m; l++) k[0][l] = -p[m - 1 - l] / p[m];
    for (l = 1; l < m; l++) k[l][l - 1] = 1.0;
    if (!ik_gen_eigenvalues(k, m, wr, wi)) return 0;
    for (l = 0; l < m; l++) {
        if (fabs(wi[l]) <= IK_GEN_NEAR_REAL * (1.0 + fabs(wr[l])) && isfinite(wr[l])) {
            out[*n] = phi + 2.0 * atan(wr[l]);
            *n += 1;
        }
    }
    return 1;
}

/* The two slides three joints apart: the arrangements (shift + 6 reversed) that put them at
   arranged joints 0 and 3, forwards and backwards, into arrs; 0 for any other chain. */
static int ik_gen_apart_arrangements(const int prismatic[6], int arrs[2]) {
    int found[2] = {0, 0}, n = 0, i;
    for (i = 0; i < 6; i++) {
        if (prismatic[i]) {
            if (n == 2) return 0;
            found[n++] = i;
        }
    }
    if (n != 2 || found[1] - found[0] != 3) return 0;
    arrs[0] = found[0];
    arrs[1] = 6 + (5 - found[1]);
    return 1;
}

/* Every solution of a 4R2P chain with its slides three joints apart (see apart_solver.rs,
   apart_solve), with the signature of ik_gen_solve (first unused here): both readings by the
   certified search, then, where it gave up in both, by the companion matrix; the backward
   reading only when a root of the forward one gave no new exact solution. */
static void ik_gen_apart_solve(const double axes[6][7], const double home[3][4],
                               const double target[4][4], double len, ik_gen_tol tol, int first,
                               ik_gen_out *out) {
    double q[6], cands[2][6], res, c[IK_GEN_DET_DEGREE + 1][2], th[24];
    ik_gen_scaled sc;
    ik_gen_arranged ar;
    ik_gen_apart ch;
    const int *prismatic = sc.prismatic;
    int arrs[2], hit[IK_GEN_MAX], route, eigen, arr, searched = 0, count, found, roots, hits, i,
        j, k, m, at;
    memset(out, 0, sizeof *out);
    ik_gen_scale(axes, home, target, len, &sc);
    /* Any other chain by the core's elimination (no generated solver calls this entry for one;
       so the core's entry stays in use, as -Wunused-function wants). */
    if (!ik_gen_apart_arrangements(prismatic, arrs)) {
        ik_gen_solve(axes, home, target, len, tol, first, out);
        return;
    }
    for (route = 0; route < 4; route++) {
        eigen = route >= 2;
        arr = arrs[route % 2];
        if (eigen && searched) continue;
#ifdef IK_GEN_APART_EIGEN_ONLY
        /* The tests' hook: the eigenvalue route only (apart_solve_by's eigen_only). */
        if (!eigen) continue;
#endif
        ik_gen_arrange(sc.js, (const double (*)[4])sc.g, arr, &ar);
        if (!ik_gen_apart_new(&ar, &ch)) continue;
        if (!ik_gen_apart_coefficients(&ch, c)) continue;
        found = eigen ? ik_gen_apart_eigen_roots((const double (*)[2])c, th, &count)
                      : ik_gen_trig_roots((const double (*)[2])c, th, &count);
        if (!found) continue;
        searched |= !eigen;
        if (out->n_arr == 0) out->degree = 2 * IK_GEN_DET_DEGREE;
        if (out->n_arr < 3) out->arrangements[out->n_arr] = arr;
        out->n_arr += 1;
        memset(hit, 0, sizeof hit);
        roots = 0;
        for (i = 0; i < count; i++) {
            m = ik_gen_apart_back(&ch, th[i], cands);
            roots += m;
            for (j = 0; j < m; j++) {
                for (k = 0; k < 6; k++) q[ch.ar.perm[k]] = cands[j][k];
                res = ik_gen_refine(&sc.chain, (const double (*)[4])sc.tg, q);
                if (isnan(res) || res > tol.keep) continue;
                for (k = 0; k < 6; k++)
                    if (!prismatic[k]) q[k] = ik_gen_wrap(q[k]);
                at = ik_gen_add(out, q, res, prismatic);
                if (at >= 0) hit[at] |= res <= tol.pose;
            }
        }
        for (hits = 0, i = 0; i < IK_GEN_MAX; i++) hits += hit[i];
        if (hits == roots) break;
    }
    /* Prismatic variables back in the robot's length unit. */
    for (i = 0; i < out->n; i++)
        for (j = 0; j < 6; j++)
            if (prismatic[j]) out->q[i][j] *= len;
}
