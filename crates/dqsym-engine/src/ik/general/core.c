/* The numeric core of the general 6R solver in C99: a port of core.rs (Raghavan-Roth
   elimination in Manocha-Canny's matrix form), function by function, with the same operations
   in the same order, so that the C solver returns what the Rust reference solver returns. No
   allocation. The constants IK_GEN_* (sample angles, tolerances) are written above this text by
   the emitter from core.rs, where they are defined and explained. Every name starts with ik_
   (the solver's own names; a robot parameter never takes one). Sums that core.rs writes with
   Rust's iterator sum start at -0.0, as that sum does. */

typedef struct {
    double q[IK_GEN_MAX][6];
    double residual[IK_GEN_MAX];
    int n;
    int degree;
    int arrangements[3];
    int n_arr;
} ik_gen_out;

typedef struct {
    double pose, keep;
} ik_gen_tol;

/* One joint of an arranged chain: unit direction w, point c (scaled), whether it slides
   (prism: its variable is the length of a translation along w). */
typedef struct {
    double w[3], c[3];
    int prism;
} ik_gen_joint;

static double ik_gen_dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void ik_gen_cross3(const double a[3], const double b[3], double o[3]) {
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Rodrigues: c I + s [w]x + (1 - c) w w^T. */
static void ik_gen_rodrigues(const double w[3], double s, double c, double r[3][3]) {
    const double k[3][3] = {{0.0, -w[2], w[1]}, {w[2], 0.0, -w[0]}, {-w[1], w[0], 0.0}};
    int i, j;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            r[i][j] = (i == j ? c : 0.0) + s * k[i][j] + (1.0 - c) * w[i] * w[j];
        }
    }
}

static void ik_gen_mv(const double r[3][3], const double v[3], double o[3]) {
    o[0] = ik_gen_dot3(r[0], v);
    o[1] = ik_gen_dot3(r[1], v);
    o[2] = ik_gen_dot3(r[2], v);
}

/* (E x, R d) of joint j at the angle with sine s, cosine co. */
static void ik_gen_apply(const ik_gen_joint *j, double s, double co, const double x[3],
                         const double d[3], double xo[3], double dout[3]) {
    double r[3][3], y[3], ry[3];
    int i;
    ik_gen_rodrigues(j->w, s, co, r);
    for (i = 0; i < 3; i++) y[i] = x[i] - j->c[i];
    ik_gen_mv((const double (*)[3])r, y, ry);
    for (i = 0; i < 3; i++) xo[i] = ry[i] + j->c[i];
    ik_gen_mv((const double (*)[3])r, d, dout);
}

/* (E x, R d) of joint j at sample k of its variable (inv: the inverse motion): a revolute joint
   at the angle 2 pi k / 3, a prismatic one at the length IK_GEN_SAMPLE_D[k]. */
static void ik_gen_sample(const ik_gen_joint *j, int k, int inv, const double x[3],
                          const double d[3], double xo[3], double dout[3]) {
    const double sg = inv ? -1.0 : 1.0;
    int i;
    if (j->prism) {
        const double t = sg * IK_GEN_SAMPLE_D[k];
        for (i = 0; i < 3; i++) {
            xo[i] = x[i] + t * j->w[i];
            dout[i] = d[i];
        }
    } else {
        ik_gen_apply(j, sg * IK_GEN_SAMPLE_S[k], IK_GEN_SAMPLE_C[k], x, d, xo, dout);
    }
}

/* The weights that turn the three samples into the coefficients of the joint's basis:
   (1, cos, sin) for a revolute joint, (1, d, d^2) for a prismatic one. */
static const double (*ik_gen_weights(const ik_gen_joint *j))[3] {
    return j->prism ? IK_GEN_VANDER : IK_GEN_DFT;
}

/* The fourteen Raghavan-Roth quantities of a point p and a direction l: l, p, p.p, p.l,
   p x l, (p.p) l - 2 (p.l) p. */
static void ik_gen_quantities(const double p[3], const double l[3], double o[14]) {
    const double pp = ik_gen_dot3(p, p);
    const double pl = ik_gen_dot3(p, l);
    int i;
    for (i = 0; i < 3; i++) {
        o[i] = l[i];
        o[3 + i] = p[i];
    }
    o[6] = pp;
    o[7] = pl;
    ik_gen_cross3(p, l, o + 8);
    for (i = 0; i < 3; i++) o[11 + i] = pp * l[i] - 2.0 * pl * p[i];
}

/* [R | t]^-1 = [R^T | -R^T t]. */
static void ik_gen_inverse(const double g[3][4], double o[3][4]) {
    int i, j;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) o[i][j] = g[j][i];
        o[i][3] = -(g[0][i] * g[0][3] + g[1][i] * g[1][3] + g[2][i] * g[2][3]);
    }
}

/* A motion applied to a point x and a direction d. */
static void ik_gen_motion_apply(const double g[3][4], const double x[3], const double d[3],
                                double p[3], double v[3]) {
    int i;
    for (i = 0; i < 3; i++) {
        p[i] = g[i][0] * x[0] + g[i][1] * x[1] + g[i][2] * x[2] + g[i][3];
        v[i] = g[i][0] * d[0] + g[i][1] * d[1] + g[i][2] * d[2];
    }
}

static void ik_gen_compose(const double a[3][4], const double b[3][4], double o[3][4]) {
    int r, c;
    for (r = 0; r < 3; r++) {
        for (c = 0; c < 4; c++) {
            const double t = c == 3 ? a[r][3] : 0.0;
            o[r][c] = t + a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
}

/* The arranged problem E1 ... E6 = H (home pose the identity): joint i is the arm's perm[i]. */
typedef struct {
    ik_gen_joint j[6];
    double h[3][4];
    int perm[6];
} ik_gen_arranged;

/* arr = shift + 6 reversed of the chain ax (scaled) with the target g = T M^-1. */
static void ik_gen_arrange(const ik_gen_joint ax[6], const double g[3][4], int arr,
                           ik_gen_arranged *out) {
    const int rev = arr >= 6, shift = arr % 6;
    ik_gen_joint base[6];
    double hi[3][4];
    int bperm[6], i, k;
    for (i = 0; i < 6; i++) {
        base[i] = ax[i];
        bperm[i] = i;
    }
    memcpy(out->h, g, sizeof out->h);
    if (rev) {
        /* E6^-1 ... E1^-1 = G^-1, and Ei^-1(q) turns about the reversed axis by q. */
        for (i = 0; i < 6; i++) {
            for (k = 0; k < 3; k++) {
                base[i].w[k] = -ax[5 - i].w[k];
                base[i].c[k] = ax[5 - i].c[k];
            }
            base[i].prism = ax[5 - i].prism;
            bperm[i] = 5 - i;
        }
        ik_gen_inverse(g, out->h);
    }
    /* E_{s+1} ... E6 (H^-1 E1 H) ... (H^-1 Es H) = H. */
    ik_gen_inverse((const double (*)[4])out->h, hi);
    for (i = 0; i < 6; i++) {
        k = (shift + i) % 6;
        out->perm[i] = bperm[k];
        if (k < shift) {
            ik_gen_motion_apply((const double (*)[4])hi, base[k].c, base[k].w, out->j[i].c,
                                out->j[i].w);
            out->j[i].prism = base[k].prism;
        } else {
            out->j[i] = base[k];
        }
    }
}

/* The elimination of one arrangement: Bm X12 = Am(th3) X45 (14 equations), the Householder QR
   of Bm with column pivoting (qt = Q^T, r, piv), |r77| / |r00|, and Sig = N Am in the basis
   (1, cos th3, sin th3) with N the last six rows of Q^T. */
typedef struct {
    double am[14][3][9];
    double qt[14][14];
    double r[8][8];
    int piv[8];
    double rank_ratio;
    double sig[3][6][9];
} ik_gen_elim;

/* The monomial index of (i, j) with i, j in (1, cos, sin). */
static int ik_gen_mono(int i, int j) {
    return 3 * i + j;
}

/* The quantities on the 3 x 3 x 3 grid of the sample angles: left, E3 E4 E5 applied to (p6,
   w6); right (3 x 3), E2^-1 E1^-1 H applied to it. */
static void ik_gen_samples(const ik_gen_arranged *ar, double lhs[3][3][3][14],
                           double rhs[3][3][14]) {
    const double *p6 = ar->j[5].c, *w6 = ar->j[5].w;
    double x5[3], d5[3], x4[3], d4[3], x3[3], d3[3], hp[3], hd[3], y1[3], e1[3], y2[3], e2[3];
    int k1, k2, k3, k4, k5;
    /* (No left side when the caller has it: lhs NULL.) */
    for (k5 = 0; lhs && k5 < 3; k5++) {
        ik_gen_sample(&ar->j[4], k5, 0, p6, w6, x5, d5);
        for (k4 = 0; k4 < 3; k4++) {
            ik_gen_sample(&ar->j[3], k4, 0, x5, d5, x4, d4);
            for (k3 = 0; k3 < 3; k3++) {
                ik_gen_sample(&ar->j[2], k3, 0, x4, d4, x3, d3);
                ik_gen_quantities(x3, d3, lhs[k3][k4][k5]);
            }
        }
    }
    ik_gen_motion_apply((const double (*)[4])ar->h, p6, w6, hp, hd);
    for (k1 = 0; k1 < 3; k1++) {
        ik_gen_sample(&ar->j[0], k1, 1, hp, hd, y1, e1);
        for (k2 = 0; k2 < 3; k2++) {
            ik_gen_sample(&ar->j[1], k2, 1, y1, e1, y2, e2);
            ik_gen_quantities(y2, e2, rhs[k1][k2]);
        }
    }
}

/* The left side's coefficients: the 3-D transform as three 1-D passes. */
static void ik_gen_left_coefficients(const ik_gen_arranged *ar, double lhs[3][3][3][14],
                                     double am[14][3][9]) {
    const double (*w5)[3] = ik_gen_weights(&ar->j[4]);
    const double (*w4)[3] = ik_gen_weights(&ar->j[3]);
    const double (*w3)[3] = ik_gen_weights(&ar->j[2]);
    double t1[3][3][3][14], t2[3][3][3][14];
    int i3, i4, i5, k3, k4, k5, e;
    memset(t1, 0, sizeof t1);
    memset(t2, 0, sizeof t2);
    for (i5 = 0; i5 < 3; i5++)
        for (k3 = 0; k3 < 3; k3++)
            for (k4 = 0; k4 < 3; k4++)
                for (k5 = 0; k5 < 3; k5++) {
                    const double w = w5[i5][k5];
                    for (e = 0; e < 14; e++) t1[k3][k4][i5][e] += w * lhs[k3][k4][k5][e];
                }
    for (i4 = 0; i4 < 3; i4++)
        for (k3 = 0; k3 < 3; k3++)
            for (k4 = 0; k4 < 3; k4++) {
                const double w = w4[i4][k4];
                for (i5 = 0; i5 < 3; i5++)
                    for (e = 0; e < 14; e++) t2[k3][i4][i5][e] += w * t1[k3][k4][i5][e];
            }
    for (i3 = 0; i3 < 3; i3++)
        for (k3 = 0; k3 < 3; k3++) {
            const double w = w3[i3][k3];
            for (i4 = 0; i4 < 3; i4++)
                for (i5 = 0; i5 < 3; i5++)
                    for (e = 0; e < 14; e++)
                        am[e][i3][ik_gen_mono(i4, i5)] += w * t2[k3][i4][i5][e];
        }
}

static void ik_gen_qr_pivot(const double b[14][8], double qt[14][14], double r[8][8],
                            int piv[8], double *ratio);

/* v (coefficients of (1, d, d^2)) times IK_GEN_HALF_INV, in place. */
static void ik_gen_half_inv(double v[3]) {
    double o[3];
    int j, k;
    for (k = 0; k < 3; k++) {
        o[k] = -0.0;
        for (j = 0; j < 3; j++) o[k] += v[j] * IK_GEN_HALF_INV[j][k];
    }
    memcpy(v, o, sizeof o);
}

/* The coefficients of prismatic joints 3, 4, 5 from (1, d, d^2) into the basis that
   ik_gen_matrix_poly's half-angle map turns into (1, d, d^2) again (IK_GEN_HALF_INV). */
static void ik_gen_prismatic_basis(const ik_gen_arranged *ar, double sig[3][6][9]) {
    double v[3];
    int row, m, k, i4, i5;
    for (row = 0; row < 6; row++) {
        if (ar->j[2].prism) {
            for (m = 0; m < 9; m++) {
                for (k = 0; k < 3; k++) v[k] = sig[k][row][m];
                ik_gen_half_inv(v);
                for (k = 0; k < 3; k++) sig[k][row][m] = v[k];
            }
        }
        for (k = 0; k < 3; k++) {
            if (ar->j[3].prism) {
                for (i5 = 0; i5 < 3; i5++) {
                    for (i4 = 0; i4 < 3; i4++) v[i4] = sig[k][row][ik_gen_mono(i4, i5)];
                    ik_gen_half_inv(v);
                    for (i4 = 0; i4 < 3; i4++) sig[k][row][ik_gen_mono(i4, i5)] = v[i4];
                }
            }
            if (ar->j[4].prism) {
                for (i4 = 0; i4 < 3; i4++) {
                    for (i5 = 0; i5 < 3; i5++) v[i5] = sig[k][row][ik_gen_mono(i4, i5)];
                    ik_gen_half_inv(v);
                    for (i5 = 0; i5 < 3; i5++) sig[k][row][ik_gen_mono(i4, i5)] = v[i5];
                }
            }
        }
    }
}

/* The equations' coefficients by exact trigonometric interpolation (IK_GEN_DFT). */
static void ik_gen_eliminate(const ik_gen_arranged *ar, const double left[14][3][9],
                             ik_gen_elim *el) {
    double lhs[3][3][3][14], rhs[3][3][14], bm[14][8];
    int e, i1, i2, k1, k2, k, row, m;
    memset(bm, 0, sizeof bm);
    if (left) {
        /* The left side given (ik_gen_robot_left): the right side only. */
        ik_gen_samples(ar, NULL, rhs);
        memcpy(el->am, left, sizeof el->am);
    } else {
        ik_gen_samples(ar, lhs, rhs);
        memset(el->am, 0, sizeof el->am);
        ik_gen_left_coefficients(ar, lhs, el->am);
    }
    for (e = 0; e < 14; e++) {
        for (i1 = 0; i1 < 3; i1++) {
            for (i2 = 0; i2 < 3; i2++) {
                double s = 0.0;
                for (k1 = 0; k1 < 3; k1++)
                    for (k2 = 0; k2 < 3; k2++)
                        s += ik_gen_weights(&ar->j[0])[i1][k1] *
                             ik_gen_weights(&ar->j[1])[i2][k2] * rhs[k1][k2][e];
                m = ik_gen_mono(i1, i2);
                if (m == 0) {
                    el->am[e][0][0] -= s;
                } else {
                    bm[e][m - 1] = s;
                }
            }
        }
    }
    ik_gen_qr_pivot((const double (*)[8])bm, el->qt, el->r, el->piv, &el->rank_ratio);
    for (k = 0; k < 3; k++) {
        for (row = 0; row < 6; row++) {
            for (m = 0; m < 9; m++) {
                double s = 0.0;
                for (e = 0; e < 14; e++) s += el->qt[8 + row][e] * el->am[e][k][m];
                el->sig[k][row][m] = s;
            }
        }
    }
    ik_gen_prismatic_basis(ar, el->sig);
}

/* Householder QR with column pivoting of the 14 x 8 matrix b: Q^T, R, the column order and
   |r77| / |r00|; the last six rows of Q^T span the left null space when the ratio is not
   small. */
static void ik_gen_qr_pivot(const double b[14][8], double qt[14][14], double r[8][8],
                            int piv[8], double *ratio) {
    double a[14][8], v[14], norm, alpha, vn, bn, n, s, t;
    int i, k, c, rr, best, ti;
    memcpy(a, b, sizeof a);
    memset(qt, 0, 14 * sizeof qt[0]);
    for (i = 0; i < 14; i++) qt[i][i] = 1.0;
    for (i = 0; i < 8; i++) piv[i] = i;
    for (k = 0; k < 8; k++) {
        /* The remaining column of largest norm first. */
        best = k;
        bn = -1.0;
        for (c = k; c < 8; c++) {
            n = -0.0;
            for (rr = k; rr < 14; rr++) n += a[rr][c] * a[rr][c];
            if (n > bn) {
                bn = n;
                best = c;
            }
        }
        if (best != k) {
            for (rr = 0; rr < 14; rr++) {
                t = a[rr][k];
                a[rr][k] = a[rr][best];
                a[rr][best] = t;
            }
            ti = piv[k];
            piv[k] = piv[best];
            piv[best] = ti;
        }
        norm = sqrt(fmax(bn, 0.0));
        if (norm == 0.0) continue;
        alpha = a[k][k] > 0.0 ? -norm : norm;
        memset(v, 0, sizeof v);
        for (rr = k; rr < 14; rr++) v[rr] = a[rr][k];
        v[k] -= alpha;
        vn = -0.0;
        for (rr = k; rr < 14; rr++) vn += v[rr] * v[rr];
        if (vn == 0.0) continue;
        for (c = k; c < 8; c++) {
            s = -0.0;
            for (rr = k; rr < 14; rr++) s += v[rr] * a[rr][c];
            s = s * 2.0 / vn;
            for (rr = k; rr < 14; rr++) a[rr][c] -= s * v[rr];
        }
        for (c = 0; c < 14; c++) {
            s = -0.0;
            for (rr = k; rr < 14; rr++) s += v[rr] * qt[rr][c];
            s = s * 2.0 / vn;
            for (rr = k; rr < 14; rr++) qt[rr][c] -= s * v[rr];
        }
    }
    memset(r, 0, 8 * sizeof r[0]);
    for (i = 0; i < 8; i++)
        for (c = i; c < 8; c++) r[i][c] = a[i][c];
    *ratio = r[0][0] == 0.0 ? 0.0 : fabs(r[7][7] / r[0][0]);
}

/* The 12 x 12 matrix polynomial M(x) = A x^2 + B x + C of x = tan((th3 - phi)/2), as out[0] =
   C, out[1] = B, out[2] = A: the six equations Sig X45 = 0 with th4, th5 by their half-angle
   tangents, and the same times x4. */
static void ik_gen_matrix_poly(const double sig[3][6][9], double phi, double out[3][12][12]) {
    const double sp = sin(phi), cp = cos(phi);
    int row, i4, i5, a, b, d;
    memset(out, 0, 3 * sizeof out[0]);
    for (row = 0; row < 6; row++) {
        for (i4 = 0; i4 < 3; i4++) {
            for (i5 = 0; i5 < 3; i5++) {
                const int m = ik_gen_mono(i4, i5);
                const double s0 = sig[0][row][m];
                const double sc = sig[1][row][m] * cp + sig[2][row][m] * sp;
                const double ss = sig[2][row][m] * cp - sig[1][row][m] * sp;
                const double coef[3] = {s0 + sc, 2.0 * ss, s0 - sc};
                for (a = 0; a < 3; a++) {
                    for (b = 0; b < 3; b++) {
                        const double h = IK_GEN_HALF[i4][a] * IK_GEN_HALF[i5][b];
                        if (h == 0.0) continue;
                        for (d = 0; d < 3; d++) {
                            out[d][row][3 * a + b] += h * coef[d];
                            out[d][row + 6][3 * (a + 1) + b] += h * coef[d];
                        }
                    }
                }
            }
        }
    }
}

/* LU with partial pivoting of the n x n matrix a (row-major, in place), the pivot order in p;
   returns the smallest pivot over the largest entry. */
static double ik_gen_lu(double *a, int n, int *p) {
    double amax = 0.0, minpiv = HUGE_VAL, d, f, t;
    int i, k, r, c, best;
    for (i = 0; i < n * n; i++) amax = fmax(amax, fabs(a[i]));
    for (i = 0; i < n; i++) p[i] = i;
    for (k = 0; k < n; k++) {
        best = k;
        for (r = k + 1; r < n; r++) {
            if (fabs(a[r * n + k]) > fabs(a[best * n + k])) best = r;
        }
        for (c = 0; c < n; c++) {
            t = a[k * n + c];
            a[k * n + c] = a[best * n + c];
            a[best * n + c] = t;
        }
        i = p[k];
        p[k] = p[best];
        p[best] = i;
        d = a[k * n + k];
        minpiv = fmin(minpiv, fabs(d));
        if (d == 0.0) continue;
        for (r = k + 1; r < n; r++) {
            f = a[r * n + k] / d;
            a[r * n + k] = f;
            if (f != 0.0) {
                for (c = k + 1; c < n; c++) a[r * n + c] -= f * a[k * n + c];
            }
        }
    }
    return amax > 0.0 ? minpiv / amax : 0.0;
}

/* Solves LU x = b[p]. */
static void ik_gen_lu_solve(const double *lu, int n, const int *p, const double *b, double *x) {
    int i, k;
    for (i = 0; i < n; i++) x[i] = b[p[i]];
    for (i = 0; i < n; i++)
        for (k = 0; k < i; k++) x[i] -= lu[i * n + k] * x[k];
    for (i = n - 1; i >= 0; i--) {
        for (k = i + 1; k < n; k++) x[i] -= lu[i * n + k] * x[k];
        x[i] /= lu[i * n + i];
    }
}

static int ik_gen_eigenvalues(double a[24][24], int n, double wr[24], double wi[24]);

/* Deflates the spurious eigenvalues +-i of the companion matrix k (see core.rs): the null
   vectors a + i b of M(i) = C - A + i B (elimination with complete pivoting) span with [a; -b],
   [b; a] an invariant subspace Z; Gaussian elimination with partial pivoting of Z gives the
   similarity whose trailing block k'22 - L2 L1^-1 k'12 (k' = P k P^T) has the other
   eigenvalues. It is left in the leading rows and columns of k; returns its size (24 when
   nothing is deflated). */
static int ik_gen_deflate_spurious(const double m[3][12][12], double k[24][24]) {
    double re[12][12], im[12][12], yr[12], yi[12], pr[12], pi[12], z[24][24], xx[24][24];
    double out[24][24], row[24];
    double bv, first, dr, di, d, nr, ni, fr, fi, x, y, v, sr, si, l, f;
    int cols[12], perm[24], r, c, s, br, bc, rank, nullity, fidx, i, j, best, nz, n, t;
    for (r = 0; r < 12; r++)
        for (c = 0; c < 12; c++) {
            re[r][c] = m[0][r][c] - m[2][r][c];
            im[r][c] = m[1][r][c];
        }
    for (i = 0; i < 12; i++) cols[i] = i;
    br = 0;
    bc = 0;
    bv = -1.0;
    for (r = 0; r < 12; r++)
        for (c = 0; c < 12; c++) {
            v = re[r][c] * re[r][c] + im[r][c] * im[r][c];
            if (v > bv) {
                br = r;
                bc = c;
                bv = v;
            }
        }
    first = bv;
    rank = 12;
    for (s = 0; s < 12; s++) {
        if (!(bv > IK_GEN_SPURIOUS_RANK * IK_GEN_SPURIOUS_RANK * first)) {
            rank = s;
            break;
        }
        for (c = 0; c < 12; c++) {
            x = re[s][c];
            re[s][c] = re[br][c];
            re[br][c] = x;
            x = im[s][c];
            im[s][c] = im[br][c];
            im[br][c] = x;
        }
        for (r = 0; r < 12; r++) {
            x = re[r][s];
            re[r][s] = re[r][bc];
            re[r][bc] = x;
            x = im[r][s];
            im[r][s] = im[r][bc];
            im[r][bc] = x;
        }
        t = cols[s];
        cols[s] = cols[bc];
        cols[bc] = t;
        dr = re[s][s];
        di = im[s][s];
        d = bv;
        memcpy(pr, re[s], sizeof pr);
        memcpy(pi, im[s], sizeof pi);
        br = s + 1;
        bc = s + 1;
        bv = -1.0;
        for (r = s + 1; r < 12; r++) {
            nr = re[r][s];
            ni = im[r][s];
            fr = (nr * dr + ni * di) / d;
            fi = (ni * dr - nr * di) / d;
            re[r][s] = 0.0;
            im[r][s] = 0.0;
            for (c = s + 1; c < 12; c++) {
                x = re[r][c] - (fr * pr[c] - fi * pi[c]);
                y = im[r][c] - (fr * pi[c] + fi * pr[c]);
                re[r][c] = x;
                im[r][c] = y;
                v = x * x + y * y;
                if (v > bv) {
                    br = r;
                    bc = c;
                    bv = v;
                }
            }
        }
    }
    nullity = 12 - rank;
    if (nullity == 0 || nullity >= 12 || !(first > 0.0 && isfinite(first))) return 24;
    memset(z, 0, sizeof z);
    for (fidx = 0; fidx < nullity; fidx++) {
        memset(yr, 0, sizeof yr);
        memset(yi, 0, sizeof yi);
        yr[rank + fidx] = 1.0;
        for (i = rank - 1; i >= 0; i--) {
            sr = -re[i][rank + fidx];
            si = -im[i][rank + fidx];
            for (c = i + 1; c < rank; c++) {
                sr -= re[i][c] * yr[c] - im[i][c] * yi[c];
                si -= re[i][c] * yi[c] + im[i][c] * yr[c];
            }
            dr = re[i][i];
            di = im[i][i];
            d = dr * dr + di * di;
            yr[i] = (sr * dr + si * di) / d;
            yi[i] = (si * dr - sr * di) / d;
        }
        for (i = 0; i < 12; i++) {
            c = cols[i];
            z[2 * fidx][c] = yr[i];
            z[2 * fidx][12 + c] = -yi[i];
            z[2 * fidx + 1][c] = yi[i];
            z[2 * fidx + 1][12 + c] = yr[i];
        }
    }
    nz = 2 * nullity;
    for (i = 0; i < 24; i++) perm[i] = i;
    for (j = 0; j < nz; j++) {
        best = j;
        for (r = j + 1; r < 24; r++) {
            if (fabs(z[j][perm[r]]) > fabs(z[j][perm[best]])) best = r;
        }
        t = perm[j];
        perm[j] = perm[best];
        perm[best] = t;
        d = z[j][perm[j]];
        if (!(d != 0.0 && isfinite(d))) return 24;
        for (r = j + 1; r < 24; r++) {
            const int q = perm[r];
            f = z[j][q] / d;
            z[j][q] = f;
            for (c = j + 1; c < nz; c++) z[c][q] -= f * z[c][perm[j]];
        }
    }
    n = 24 - nz;
    memset(xx, 0, sizeof xx);
    for (i = 0; i < nz; i++) {
        for (c = 0; c < 24; c++) row[c] = c < n ? k[perm[i]][perm[nz + c]] : 0.0;
        for (j = 0; j < i; j++) {
            l = z[j][perm[i]];
            for (c = 0; c < n; c++) row[c] -= l * xx[j][c];
        }
        memcpy(xx[i], row, sizeof row);
    }
    memset(out, 0, sizeof out);
    for (r = 0; r < n; r++) {
        const int q = perm[nz + r];
        for (c = 0; c < 24; c++) row[c] = c < n ? k[q][perm[nz + c]] : 0.0;
        for (j = 0; j < nz; j++) {
            l = z[j][q];
            for (c = 0; c < n; c++) row[c] -= l * xx[j][c];
        }
        memcpy(out[r], row, sizeof row);
    }
    memcpy(k, out, sizeof out);
    return n;
}

/* The eigenvalues of the 24 x 24 companion linearisation of A x^2 + B x + C: [[0, I], [-A^-1
   C, -A^-1 B]] (A invertible, given as its LU a, p), less the eigenvalues +-i that
   ik_gen_deflate_spurious removes; their number in *n. 0 when the QR iteration does not
   converge. */
static int ik_gen_eigen_quadratic(const double m[3][12][12], const double a[12][12],
                                  const int p[12], double wr[24], double wi[24], int *n) {
    double k[24][24], cc[12], cb[12], xc[12], xb[12];
    int i, r, col;
    memset(k, 0, sizeof k);
    for (i = 0; i < 12; i++) k[i][12 + i] = 1.0;
    for (col = 0; col < 12; col++) {
        for (r = 0; r < 12; r++) {
            cc[r] = m[0][r][col];
            cb[r] = m[1][r][col];
        }
        ik_gen_lu_solve(&a[0][0], 12, p, cc, xc);
        ik_gen_lu_solve(&a[0][0], 12, p, cb, xb);
        for (r = 0; r < 12; r++) {
            k[12 + r][col] = -xc[r];
            k[12 + r][12 + col] = -xb[r];
        }
    }
    *n = ik_gen_deflate_spurious(m, k);
    return ik_gen_eigenvalues(k, *n, wr, wi);
}

/* A null vector of the 12 x 12 matrix m (Gaussian elimination with complete pivoting, the
   last pivot taken as zero). */
static void ik_gen_null_vector(const double m[12][12], double v[12]) {
    double a[12][12], y[12], bv, d, f, s, t, x;
    int cols[12], i, k, r, c, br, bc;
    memcpy(a, m, sizeof a);
    for (i = 0; i < 12; i++) cols[i] = i;
    /* The largest entry of the remaining block, tracked while it is updated (the same choice
       as a search of the block after each step). */
    br = 0;
    bc = 0;
    bv = -1.0;
    for (r = 0; r < 12; r++) {
        for (c = 0; c < 12; c++) {
            if (fabs(a[r][c]) > bv) {
                br = r;
                bc = c;
                bv = fabs(a[r][c]);
            }
        }
    }
    for (k = 0; k < 11; k++) {
        for (c = 0; c < 12; c++) {
            t = a[k][c];
            a[k][c] = a[br][c];
            a[br][c] = t;
        }
        for (r = 0; r < 12; r++) {
            t = a[r][k];
            a[r][k] = a[r][bc];
            a[r][bc] = t;
        }
        i = cols[k];
        cols[k] = cols[bc];
        cols[bc] = i;
        d = a[k][k];
        br = k + 1;
        bc = k + 1;
        bv = -1.0;
        if (d == 0.0) {
            for (r = k + 1; r < 12; r++) {
                for (c = k + 1; c < 12; c++) {
                    if (fabs(a[r][c]) > bv) {
                        br = r;
                        bc = c;
                        bv = fabs(a[r][c]);
                    }
                }
            }
            continue;
        }
        for (r = k + 1; r < 12; r++) {
            f = a[r][k] / d;
            a[r][k] -= f * a[k][k];
            for (c = k + 1; c < 12; c++) {
                x = a[r][c] - f * a[k][c];
                a[r][c] = x;
                if (fabs(x) > bv) {
                    br = r;
                    bc = c;
                    bv = fabs(x);
                }
            }
        }
    }
    y[11] = 1.0;
    for (i = 10; i >= 0; i--) {
        s = 0.0;
        for (c = i + 1; c < 12; c++) s -= a[i][c] * y[c];
        y[i] = a[i][i] == 0.0 ? 0.0 : s / a[i][i];
    }
    for (i = 0; i < 12; i++) v[cols[i]] = y[i];
}

/* An angle in (-pi, pi]. */
static double ik_gen_wrap(double a) {
    /* Already in (-pi, pi]: the remainder would return it unchanged. */
    if (a > -IK_GEN_PI && a <= IK_GEN_PI) {
        return a;
    }
    double x = fmod(a, IK_GEN_TAU);
    if (x > IK_GEN_PI) {
        x -= IK_GEN_TAU;
    } else if (x <= -IK_GEN_PI) {
        x += IK_GEN_TAU;
    }
    return x;
}

/* 2 atan2(num, den) of the pair (num[k], den[k]) of largest size: the half-angle tangent's
   ratio, well-conditioned for any angle. */
static double ik_gen_angle_from(const double *num, const double *den, int n) {
    double bn = -1.0, bnum = 0.0, bden = 1.0, s;
    int k;
    for (k = 0; k < n; k++) {
        s = num[k] * num[k] + den[k] * den[k];
        if (s > bn) {
            bn = s;
            bnum = num[k];
            bden = den[k];
        }
    }
    return ik_gen_wrap(2.0 * atan2(bnum, bden));
}

/* th1, th2 from Bm X12 = Am(th3) X45 by the QR of Bm, given (1, cos, sin) of th3, th4, th5. */
static void ik_gen_first_two(const ik_gen_arranged *ar, const ik_gen_elim *el,
                             const double f3[3], const double f4[3], const double f5[3],
                             double *t1, double *t2) {
    double rhs[14], g[3][9], y[8], z[8], x12[9], s;
    int e, k, i4, i5, i;
    /* The 27 products of the three joints' bases once, in am's order (k, i4, i5). */
    for (k = 0; k < 3; k++)
        for (i4 = 0; i4 < 3; i4++)
            for (i5 = 0; i5 < 3; i5++) g[k][ik_gen_mono(i4, i5)] = f3[k] * f4[i4] * f5[i5];
    for (e = 0; e < 14; e++) {
        s = 0.0;
        for (k = 0; k < 3; k++)
            for (i = 0; i < 9; i++) s += el->am[e][k][i] * g[k][i];
        rhs[e] = s;
    }
    for (i = 0; i < 8; i++) {
        y[i] = -0.0;
        for (e = 0; e < 14; e++) y[i] += el->qt[i][e] * rhs[e];
    }
    for (i = 7; i >= 0; i--) {
        s = y[i];
        for (k = i + 1; k < 8; k++) s -= el->r[i][k] * z[k];
        z[i] = el->r[i][i] == 0.0 ? 0.0 : s / el->r[i][i];
    }
    x12[0] = 1.0;
    for (i = 0; i < 8; i++) x12[el->piv[i] + 1] = z[i];
    /* A prismatic th1 or th2 is its monomial d itself. */
    *t1 = ar->j[0].prism ? x12[ik_gen_mono(1, 0)]
                         : atan2(x12[ik_gen_mono(2, 0)], x12[ik_gen_mono(1, 0)]);
    *t2 = ar->j[1].prism ? x12[ik_gen_mono(0, 1)]
                         : atan2(x12[ik_gen_mono(0, 2)], x12[ik_gen_mono(0, 1)]);
}

/* cos and sin of a small angle, |d| <= pi/64, by Taylor polynomials (see core.rs,
   cos_sin_small). */
static void ik_gen_cos_sin_small(double d, double *co, double *si) {
    const double d2 = d * d;
    *si = d * (1.0 + d2 * (-1.0 / 6.0 + d2 * (1.0 / 120.0 + d2 * (-1.0 / 5040.0 +
                                                                  d2 * (1.0 / 362880.0)))));
    *co = 1.0 + d2 * (-0.5 + d2 * (1.0 / 24.0 + d2 * (-1.0 / 720.0 + d2 * (1.0 / 40320.0 +
                                                                         d2 * (-1.0 / 3628800.0)))));
}

/* cos th and sin th without a library call: the nearest table angle b pi/32 turned by the rest
   (see core.rs, unit). */
static void ik_gen_unit(double th, double *co, double *si) {
    const double y = th / IK_GEN_GRID_STEP + 0.5;
    long long b = fabs(y) < 1e15 ? (long long)y : 0;
    double c, s, sb, cb;
    int k;
    if ((double)b > y) b -= 1;
    ik_gen_cos_sin_small((th - (double)b * IK_GEN_GRID_STEP_HI) - (double)b * IK_GEN_GRID_STEP_LO,
                         &c, &s);
    k = (int)(((b % 64) + 64) % 64);
    sb = IK_GEN_GRID_SIN[k];
    cb = IK_GEN_GRID_SIN[(k + 16) % 64];
    *co = cb * c - sb * s;
    *si = sb * c + cb * s;
}

/* th6 from the rest: E6 = (E1 ... E5)^-1 H, read about its axis: R6 u = R5^T ... R1^T R_H u
   for a unit vector u normal to axis 6, each R^T by Rodrigues applied to the vector. */
static double ik_gen_last(const ik_gen_arranged *ar, const double t[5], const double *fk[3]) {
    double u[3], v[3], x[3], uv[3], co, si, f;
    const double ex[3] = {1.0, 0.0, 0.0}, ey[3] = {0.0, 1.0, 0.0};
    const double *w6 = ar->j[5].w, *w;
    int k, i, l;
    ik_gen_cross3(w6, fabs(w6[0]) < 0.6 ? ex : ey, u);
    for (i = 0; i < 3; i++) {
        v[i] = -0.0;
        for (l = 0; l < 3; l++) v[i] += ar->h[i][l] * u[l];
    }
    for (k = 0; k < 5; k++) {
        if (ar->j[k].prism) continue;
        /* (Joints 3 to 5 turning have their cosine and sine in their bases already.) */
        if (k >= 2) {
            co = fk[k - 2][1];
            si = fk[k - 2][2];
        } else {
            ik_gen_unit(t[k], &co, &si);
        }
        w = ar->j[k].w;
        /* R^T v = c v - s w x v + (1 - c) (w . v) w. */
        ik_gen_cross3(w, v, x);
        f = (1.0 - co) * ik_gen_dot3(w, v);
        for (i = 0; i < 3; i++) v[i] = co * v[i] - si * x[i] + f * w[i];
    }
    ik_gen_cross3(u, v, uv);
    return atan2(ik_gen_dot3(w6, uv), ik_gen_dot3(u, v));
}

/* The joint's basis at its value t: (1, cos t, sin t), or (1, t, t^2) for a slide. */
static void ik_gen_basis(const ik_gen_joint *j, double t, double f[3]) {
    f[0] = 1.0;
    if (j->prism) {
        f[1] = t;
        f[2] = t * t;
    } else {
        ik_gen_unit(t, &f[1], &f[2]);
    }
}

/* The joints of the arranged chain at a root of det M: v the null vector of M(x) (or of S(th))
   there, t3 the hidden joint's angle phi + 2 atan x. */
static void ik_gen_back_substitute(const ik_gen_arranged *ar, const ik_gen_elim *el,
                                   const double v[12], double t3, double out[6]) {
    double num[9], den[9], f3[3], f4[3], f5[3];
    const double *fk[3];
    int a, b, k;
    out[2] = t3;
    /* th4: the pairs (x4^(a+1) x5^b, x4^a x5^b), a = 0..2, b = 0..2. */
    for (k = 0, a = 0; a < 3; a++)
        for (b = 0; b < 3; b++, k++) {
            num[k] = v[3 * (a + 1) + b];
            den[k] = v[3 * a + b];
        }
    out[3] = ik_gen_angle_from(num, den, 9);
    /* th5: the pairs (x4^a x5^(b+1), x4^a x5^b), b = 0..1, a = 0..3. */
    for (k = 0, b = 0; b < 2; b++)
        for (a = 0; a < 4; a++, k++) {
            num[k] = v[3 * a + b + 1];
            den[k] = v[3 * a + b];
        }
    out[4] = ik_gen_angle_from(num, den, 8);
    /* A prismatic joint's variable is the tangent of the half angle these formulas give. */
    for (k = 2; k < 5; k++)
        if (ar->j[k].prism) out[k] = tan(0.5 * out[k]);
    ik_gen_basis(&ar->j[2], out[2], f3);
    ik_gen_basis(&ar->j[3], out[3], f4);
    ik_gen_basis(&ar->j[4], out[4], f5);
    ik_gen_first_two(ar, el, f3, f4, f5, &out[0], &out[1]);
    fk[0] = f3;
    fk[1] = f4;
    fk[2] = f5;
    out[5] = ik_gen_last(ar, out, fk);
}

/* S(th) = T0 + T1 cos th + T2 sin th: the 12 x 12 matrix of matrix_poly at phi = 0 divided by
   1 + x^2 (see core.rs, matrix_trig). */
static void ik_gen_matrix_trig(const double sig[3][6][9], double out[3][12][12]) {
    int row, i4, i5, a, b, d, m;
    double h;
    memset(out, 0, 3 * 12 * 12 * sizeof(double));
    for (row = 0; row < 6; row++)
        for (i4 = 0; i4 < 3; i4++)
            for (i5 = 0; i5 < 3; i5++) {
                m = ik_gen_mono(i4, i5);
                for (a = 0; a < 3; a++)
                    for (b = 0; b < 3; b++) {
                        h = IK_GEN_HALF[i4][a] * IK_GEN_HALF[i5][b];
                        if (h == 0.0) continue;
                        for (d = 0; d < 3; d++) {
                            out[d][row][3 * a + b] += h * sig[d][row][m];
                            out[d][row + 6][3 * (a + 1) + b] += h * sig[d][row][m];
                        }
                    }
            }
}

/* One step of Gaussian elimination on whole rows: the rows below k less their multiple
   m[r][k] / d of row k (the columns left of k are never read again). */
static void ik_gen_eliminate_rows(double m[12][12], int k, double d) {
    double f, p[12];
    int r, c;
    /* The pivot row copied: the compiler then knows the rows below do not alias it. */
    memcpy(p, m[k], sizeof p);
    for (r = k + 1; r < 12; r++) {
        f = m[r][k] / d;
        if (f != 0.0)
            for (c = 0; c < 12; c++) m[r][c] -= f * p[c];
    }
}

/* S(th) with its columns in the order IK_GEN_DET_COLS (see core.rs, DET_COLS). */
static void ik_gen_trig_at_cols(const double t[3][12][12], double s, double c, double m[12][12]) {
    int r, k, j, cols[12];
    for (k = 0; k < 12; k++) cols[k] = (int)IK_GEN_DET_COLS[k];
    for (r = 0; r < 12; r++)
        for (k = 0; k < 12; k++) {
            j = cols[k];
            m[r][k] = t[0][r][j] + c * t[1][r][j] + s * t[2][r][j];
        }
}

/* det S(th) (LU with partial pivoting, the columns in the order IK_GEN_DET_COLS) and the
   smallest pivot over the largest in *ratio, on the nonzero blocks only (see core.rs,
   block_lu): an equation's row [a = 0 | a = 1 | a = 2] (S's rows 0-5, columns 0-8), its
   copy times x4 [a = 3 | a = 1 | a = 2]; columns 0-2 among the equations' rows, 3-5 among
   the copies', then a 6 x 6 block. The same pivots, products and bits as the whole matrix'. */
static double ik_gen_det_trig(const double t[3][12][12], double s, double c, double *ratio) {
    double m[6][9], low[6][9], b[6][6], row[9], det = 1.0, minpiv = HUGE_VAL, maxpiv = 0.0, d,
        f, bv;
    int k, r, i, j, best, from[6];
    for (r = 0; r < 6; r++)
        for (j = 0; j < 9; j++) m[r][j] = t[0][r][j] + c * t[1][r][j] + s * t[2][r][j];
    for (r = 0; r < 6; r++)
        for (j = 0; j < 9; j++) low[r][j] = m[r][(j + 6) % 9];
#define IK_GEN_PIVOT(x)                         \
    do {                                        \
        det *= (x);                             \
        if (fabs(x) < minpiv) minpiv = fabs(x); \
        if (fabs(x) > maxpiv) maxpiv = fabs(x); \
    } while (0)
    /* Columns 0-2, among the equations' rows. */
    for (k = 0; k < 3; k++) {
        best = k;
        for (r = k + 1; r < 6; r++)
            if (fabs(m[r][k]) > fabs(m[best][k])) best = r;
        if (best != k) {
            memcpy(row, m[k], sizeof row);
            memcpy(m[k], m[best], sizeof row);
            memcpy(m[best], row, sizeof row);
            det = -det;
        }
        d = m[k][k];
        IK_GEN_PIVOT(d);
        if (d == 0.0) continue;
        for (r = k + 1; r < 6; r++) {
            f = m[r][k] / d;
            if (f != 0.0)
                for (j = 0; j < 9; j++) m[r][j] -= f * m[k][j];
        }
    }
    /* Columns 3-5, among the copies' rows (positions 6-11): a copy taken as pivot k trades
       places with the equation's row k; from[i] is the row at position 6 + i. */
    for (i = 0; i < 6; i++) from[i] = 6 + i;
    for (k = 3; k < 6; k++) {
        best = -1;
        bv = 0.0;
        for (i = 0; i < 6; i++)
            if (from[i] >= 6 && fabs(low[i][k - 3]) > bv) {
                best = i;
                bv = fabs(low[i][k - 3]);
            }
        if (best < 0) {
            IK_GEN_PIVOT(0.0);
            continue;
        }
        det = -det;
        from[best] = k;
        memcpy(row, low[best], sizeof row);
        d = row[k - 3];
        IK_GEN_PIVOT(d);
        for (i = 0; i < 6; i++)
            if (from[i] >= 6) {
                f = low[i][k - 3] / d;
                if (f != 0.0)
                    for (j = 0; j < 9; j++) low[i][j] -= f * row[j];
            }
    }
    /* The last six columns: a 6 x 6 block. */
    for (i = 0; i < 6; i++)
        for (j = 0; j < 6; j++) b[i][j] = from[i] >= 6 ? low[i][3 + j] : m[from[i]][3 + j];
    for (k = 0; k < 6; k++) {
        best = k;
        for (r = k + 1; r < 6; r++)
            if (fabs(b[r][k]) > fabs(b[best][k])) best = r;
        if (best != k) {
            memcpy(row, b[k], 6 * sizeof(double));
            memcpy(b[k], b[best], 6 * sizeof(double));
            memcpy(b[best], row, 6 * sizeof(double));
            det = -det;
        }
        d = b[k][k];
        IK_GEN_PIVOT(d);
        if (d == 0.0) continue;
        for (r = k + 1; r < 6; r++) {
            f = b[r][k] / d;
            if (f != 0.0)
                for (j = 0; j < 6; j++) b[r][j] -= f * b[k][j];
        }
    }
#undef IK_GEN_PIVOT
    *ratio = maxpiv > 0.0 ? minpiv / maxpiv : 0.0;
    return det;
}

/* D(th) = Re sum_j c_j e^(i j th) prepared for evaluation with its derivatives: D^(k)(th) =
   sum_j u[j][k] cos j th + v[j][k] sin j th (see core.rs, TrigTable). */
typedef struct {
    double u[IK_GEN_DET_DEGREE + 1][IK_GEN_TAYLOR], v[IK_GEN_DET_DEGREE + 1][IK_GEN_TAYLOR];
} ik_gen_trig_table;

static void ik_gen_trig_table_of(const double c[IK_GEN_DET_DEGREE + 1][2], ik_gen_trig_table *t) {
    double p, a, b, u, v;
    int j, k;
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        a = c[j][0];
        b = c[j][1];
        p = 1.0;
        for (k = 0; k < IK_GEN_TAYLOR; k++) {
            switch (k % 4) {
            case 0: u = a; v = -b; break;
            case 1: u = -b; v = -a; break;
            case 2: u = -a; v = b; break;
            default: u = b; v = a; break;
            }
            t->u[j][k] = p * u;
            t->v[j][k] = p * v;
            p *= (double)j;
        }
    }
}

/* D(th) and its derivatives to the seventh. */
static void ik_gen_trig_eval(const ik_gen_trig_table *t, double th, double out[IK_GEN_TAYLOR]) {
    double s, co, zr = 1.0, zi = 0.0, nz, acc[IK_GEN_TAYLOR];
    int j, k;
    ik_gen_unit(th, &co, &s);
    /* Sums in a local array (no aliasing with the table: the compiler may run them side by
       side). */
    for (k = 0; k < IK_GEN_TAYLOR; k++) acc[k] = 0.0;
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        for (k = 0; k < IK_GEN_TAYLOR; k++) acc[k] += t->u[j][k] * zr + t->v[j][k] * zi;
        nz = zr * co - zi * s;
        zi = zr * s + zi * co;
        zr = nz;
    }
    for (k = 0; k < IK_GEN_TAYLOR; k++) out[k] = acc[k];
}

/* D^(k), D^(k+1), D^(k+2) at th for k 0 or 1 (see core.rs, trig_low). */
static void ik_gen_trig_low(const ik_gen_trig_table *t, int k, double th, double v[3]) {
    double s, co, zr = 1.0, zi = 0.0, nz, out[4] = {0.0, 0.0, 0.0, 0.0};
    int j, l;
    ik_gen_unit(th, &co, &s);
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        for (l = 0; l < 4; l++) out[l] += t->u[j][l] * zr + t->v[j][l] * zi;
        nz = zr * co - zi * s;
        zi = zr * s + zi * co;
        zr = nz;
    }
    v[0] = out[k];
    v[1] = out[k + 1];
    v[2] = out[k + 2];
}

/* The zero of D^(k) in [a, b] (fa, fb its values at the ends, of opposite signs, 0 counted as
   positive; D^(k) monotone there): Halley's method from the secant's zero, kept inside the
   bracket. */
static double ik_gen_bracketed(const ik_gen_trig_table *c, int k, double a,
                               double b, double fa, double start) {
    double v[3], x = start, next;
    const int neg_a = fa < 0.0;
    int it;
    for (it = 0; it < 60; it++) {
        ik_gen_trig_low(c, k, x, v);
        if (v[0] == 0.0) return x;
        if ((v[0] < 0.0) == neg_a)
            a = x;
        else
            b = x;
        next = x - 2.0 * v[0] * v[1] / (2.0 * v[1] * v[1] - v[0] * v[2]);
        if (next > a && next < b) {
            if (fabs(next - x) <= IK_GEN_BRACKET_TOL) return next;
            x = next;
        } else {
            x = 0.5 * (a + b);
        }
        if (b - a <= IK_GEN_BRACKET_WIDTH) return x;
    }
    return x;
}

/* Where ik_gen_bracketed starts on [a, b] inside an interval with midpoint m and Taylor data v
   there: the zero of the Taylor polynomial of D^(k) at m by Newton's method from the secant's
   zero; the secant's zero where Newton's leaves the bracket (see core.rs, taylor_start). */
static double ik_gen_taylor_start(const double v[IK_GEN_TAYLOR], int k, double m, double a,
                                  double b, double fa, double fb) {
    static const double inv_fact[IK_GEN_TAYLOR] = {1.0,         1.0,         0.5,
                                                   1.0 / 6.0,   1.0 / 24.0,  1.0 / 120.0,
                                                   1.0 / 720.0, 1.0 / 5040.0};
    double x = a + (b - a) * (fa / (fa - fb)), h, p, dp, step, y;
    int it, j;
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    h = x - m;
    for (it = 0; it < 8; it++) {
        p = v[IK_GEN_TAYLOR - 1] * inv_fact[IK_GEN_TAYLOR - 1 - k];
        dp = 0.0;
        for (j = IK_GEN_TAYLOR - 2 - k; j >= 0; j--) {
            dp = dp * h + p;
            p = p * h + v[k + j] * inv_fact[j];
        }
        step = p / dp;
        if (!isfinite(step)) return x;
        h -= step;
        if (fabs(step) <= 1e-15) break;
    }
    y = m + h;
    return y > a && y < b ? y : x;
}

/* D^(l) at m + h by Taylor's formula at m (v) into *val when its sign is certified: the value
   beyond the rest b8 |h|^(8 - l) / (8 - l)! and the margin tol (see core.rs, trig_roots). */
static int ik_gen_certified(const double v[IK_GEN_TAYLOR], int l, double h, double tol,
                            double b8, double *val) {
    double s = 0.0, term = 1.0, rest;
    int k;
    for (k = l; k < IK_GEN_TAYLOR; k++) {
        if (k > l) term *= h / (double)(k - l);
        s += v[k] * term;
    }
    rest = b8 * fabs(term * h / (double)(IK_GEN_TAYLOR - l)) + tol;
    *val = s;
    return s > rest || s < -rest;
}

/* A root of the monotone D^(k) on [a, b] (at m + ha, m + hb inside the interval with midpoint
   m and Taylor data v) into *x if its ends differ in sign; 1 when found. An end whose sign
   Taylor's formula certifies is not evaluated. The end top (2 pi) is read as 0, so that a root
   there is seen the same from both sides. */
static int ik_gen_mono_root(const ik_gen_trig_table *c, double a, double b, double ha, double hb,
                            int k, double m, const double v[IK_GEN_TAYLOR], double b8,
                            double tol, double top, int *evals, double *x) {
    double va[3], vb[3], fa, fb;
    if (!ik_gen_certified(v, k, ha, tol, b8, &fa)) {
        ik_gen_trig_low(c, k, a >= top ? 0.0 : a, va);
        fa = va[0];
    }
    if (!ik_gen_certified(v, k, hb, tol, b8, &fb)) {
        ik_gen_trig_low(c, k, b >= top ? 0.0 : b, vb);
        fb = vb[0];
    }
    *evals += 2;
    if ((fa < 0.0) == (fb < 0.0)) return 0;
    *x = ik_gen_bracketed(c, k, a, b, fa, ik_gen_taylor_start(v, k, m, a, b, fa, fb));
    return 1;
}

/* D and its derivatives at the midpoints of the IK_GEN_ROOT_GRID base intervals, eight at a
   time (see core.rs, grid_values): from the powers e^(i j m) at the first half quarter's
   midpoints m, the sums by j mod 4 of the cosine and sine parts give the values at m + r pi/2
   and, the cosine part even and the sine part odd, at -(m + r pi/2) too. */
static void ik_gen_grid_values(const ik_gen_trig_table *t,
                               double out[IK_GEN_ROOT_GRID][IK_GEN_TAYLOR]) {
    const int quarter = IK_GEN_ROOT_GRID / 4;
    const double h = IK_GEN_TAU / (double)IK_GEN_ROOT_GRID;
    double s, co, zr, zi, nz, pv[4][IK_GEN_TAYLOR], rv[4][IK_GEN_TAYLOR], qv[2][IK_GEN_TAYLOR],
        wv[2][IK_GEN_TAYLOR], ce, cn, cd, cq, se, sn, sd, sw, part[4][2];
    int g, j, k, q, i;
    for (g = 0; g < quarter / 2; g++) {
        ik_gen_unit(0.5 * ((double)g * h + (double)(g + 1) * h), &co, &s);
        zr = 1.0;
        zi = 0.0;
        for (q = 0; q < 4; q++)
            for (k = 0; k < IK_GEN_TAYLOR; k++) pv[q][k] = rv[q][k] = 0.0;
        for (q = 0; q < 2; q++)
            for (k = 0; k < IK_GEN_TAYLOR; k++) qv[q][k] = wv[q][k] = 0.0;
        for (j = 0; j <= IK_GEN_DET_DEGREE; j++) {
            q = j % 4;
            for (k = 0; k < IK_GEN_TAYLOR; k++) {
                pv[q][k] += t->u[j][k] * zr;
                rv[q][k] += t->v[j][k] * zi;
            }
            if (q % 2 == 1)
                for (k = 0; k < IK_GEN_TAYLOR; k++) {
                    qv[q / 2][k] += t->u[j][k] * zi;
                    wv[q / 2][k] += t->v[j][k] * zr;
                }
            nz = zr * co - zi * s;
            zi = zr * s + zi * co;
            zr = nz;
        }
        for (k = 0; k < IK_GEN_TAYLOR; k++) {
            ce = pv[0][k] + pv[2][k];
            cn = pv[1][k] + pv[3][k];
            cd = pv[0][k] - pv[2][k];
            cq = qv[1][k] - qv[0][k];
            se = rv[0][k] + rv[2][k];
            sn = rv[1][k] + rv[3][k];
            sd = rv[0][k] - rv[2][k];
            sw = wv[0][k] - wv[1][k];
            part[0][0] = ce + cn;
            part[0][1] = se + sn;
            part[1][0] = cd + cq;
            part[1][1] = sd + sw;
            part[2][0] = ce - cn;
            part[2][1] = se - sn;
            part[3][0] = cd - cq;
            part[3][1] = sd - sw;
            for (i = 0; i < 4; i++) {
                out[g + i * quarter][k] = part[i][0] + part[i][1];
                /* -(m + i pi/2): interval quarter - 1 - g's midpoint plus (3 - i) pi/2. */
                out[quarter - 1 - g + (3 - i) * quarter][k] = part[i][0] - part[i][1];
            }
        }
    }
}

/* The real roots in [0, 2 pi) of D (see core.rs, trig_roots) into out, their number in *n;
   0 when the search gives up. */
static int ik_gen_trig_roots(const double c[IK_GEN_DET_DEGREE + 1][2], double out[24], int *n) {
    double b0 = 0.0, b8 = 0.0, margin, nd = (double)IK_GEN_DET_DEGREE, h, top, a, b, m, r, term,
        x, e, moves[3], v[IK_GEN_TAYLOR], w[IK_GEN_TAYLOR], stack[96][2],
        base[IK_GEN_ROOT_GRID][IK_GEN_TAYLOR];
    /* Each interval's index in the base grid (IK_GEN_ROOT_GRID for the halves). */
    int grid[96];
    int j, k, l, depth = 0, evals = 0, left, right, flat;
    ik_gen_trig_table tt;
    double xl = 0.0, xr = 0.0;
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        const double amp = hypot(c[j][0], c[j][1]), j2 = (double)(j * j);
        b0 += amp;
        b8 += j2 * j2 * j2 * j2 * amp;
    }
    ik_gen_trig_table_of(c, &tt);
    ik_gen_grid_values(&tt, base);
    margin = IK_GEN_ROOT_MARGIN * b0;
    h = IK_GEN_TAU / (double)IK_GEN_ROOT_GRID;
    top = (double)IK_GEN_ROOT_GRID * h;
    for (k = IK_GEN_ROOT_GRID - 1; k >= 0; k--) {
        stack[depth][0] = (double)k * h;
        stack[depth][1] = (double)(k + 1) * h;
        grid[depth] = k;
        depth++;
    }
    *n = 0;
    while (depth > 0) {
        depth--;
        a = stack[depth][0];
        b = stack[depth][1];
        m = 0.5 * (a + b);
        r = 0.5 * (b - a);
        if (grid[depth] < IK_GEN_ROOT_GRID)
            memcpy(v, base[grid[depth]], sizeof v);
        else
            ik_gen_trig_eval(&tt, m >= top ? 0.0 : m, v);
        evals++;
        if (evals > IK_GEN_ROOT_EVALS || *n + 2 > 24) return 0;
        for (l = 0; l < 3; l++) {
            moves[l] = 0.0;
            term = 1.0;
            for (k = l + 1; k < IK_GEN_TAYLOR; k++) {
                term *= r / (double)(k - l);
                moves[l] += fabs(v[k]) * term;
            }
            moves[l] += b8 * term * r / (double)(IK_GEN_TAYLOR - l);
        }
        if (fabs(v[0]) > moves[0] + margin) continue;
        if (fabs(v[1]) > moves[1] + nd * margin) {
            if (ik_gen_mono_root(&tt, a, b, -r, r, 0, m, v, b8, margin, top, &evals, &x))
                out[(*n)++] = x;
            continue;
        }
        if (fabs(v[2]) > moves[2] + nd * nd * margin) {
            if (!ik_gen_mono_root(&tt, a, b, -r, r, 1, m, v, b8, nd * margin, top, &evals, &e)) {
                /* D' keeps its sign: D is monotone after all. */
                if (ik_gen_mono_root(&tt, a, b, -r, r, 0, m, v, b8, margin, top, &evals, &x))
                    out[(*n)++] = x;
                continue;
            }
            left = ik_gen_mono_root(&tt, a, e, -r, e - m, 0, m, v, b8, margin, top, &evals, &xl);
            right = ik_gen_mono_root(&tt, e, b, e - m, r, 0, m, v, b8, margin, top, &evals, &xr);
            if (left) out[(*n)++] = xl;
            if (right) out[(*n)++] = xr;
            if (!left && !right) {
                ik_gen_trig_eval(&tt, e >= top ? 0.0 : e, w);
                if (2.0 * fabs(w[0]) <= IK_GEN_NEAR_REAL * IK_GEN_NEAR_REAL * fabs(w[2])) {
                    out[(*n)++] = e;
                    out[(*n)++] = e;
                }
            }
            continue;
        }
        /* D and D' both zero to rounding, or nothing certified at the finest width: the
           eigenvalue route decides. */
        flat = fabs(v[0]) <= margin && fabs(v[1]) <= nd * margin;
        if (flat || r <= IK_GEN_ROOT_LEAF || depth + 2 > 96) return 0;
        stack[depth][0] = m;
        stack[depth][1] = b;
        stack[depth + 1][0] = a;
        stack[depth + 1][1] = m;
        grid[depth] = IK_GEN_ROOT_GRID;
        grid[depth + 1] = IK_GEN_ROOT_GRID;
        depth += 2;
    }
    return 1;
}

/* A null vector of m, singular to rounding, from its LU with partial pivoting: the smallest
   pivot u_kk taken as zero, y_k = 1 and the triangle above solved (see core.rs). */
static void ik_gen_null_vector_lu(const double m[12][12], double y[12]) {
    double a[12][12], row[12], pmin = HUGE_VAL, d, s, ms = 0.0, ys = 0.0, res = 0.0;
    int k, r, c, i, best, kmin = 11;
    memcpy(a, m, sizeof a);
    for (k = 0; k < 12; k++) {
        best = k;
        for (r = k + 1; r < 12; r++)
            if (fabs(a[r][k]) > fabs(a[best][k])) best = r;
        if (best != k) {
            memcpy(row, a[k], sizeof row);
            memcpy(a[k], a[best], sizeof row);
            memcpy(a[best], row, sizeof row);
        }
        d = a[k][k];
        if (fabs(d) < pmin) {
            kmin = k;
            pmin = fabs(d);
        }
        if (d == 0.0) continue;
        ik_gen_eliminate_rows(a, k, d);
    }
    for (i = 0; i < 12; i++) y[i] = 0.0;
    y[kmin] = 1.0;
    for (i = kmin - 1; i >= 0; i--) {
        s = 0.0;
        for (c = i + 1; c <= kmin; c++) s -= a[i][c] * y[c];
        y[i] = a[i][i] == 0.0 ? 0.0 : s / a[i][i];
    }
    /* Partial pivoting need not reveal the rank: checked by the residual, else complete
       pivoting. */
    for (r = 0; r < 12; r++) {
        s = 0.0;
        for (c = 0; c < 12; c++) {
            s += m[r][c] * y[c];
            if (fabs(m[r][c]) > ms) ms = fabs(m[r][c]);
        }
        if (fabs(s) > res) res = fabs(s);
        if (fabs(y[r]) > ys) ys = fabs(y[r]);
    }
    if (!(res <= IK_GEN_NULL_RESIDUAL * ms * ys)) ik_gen_null_vector(m, y);
}

/* The candidates of one arrangement by the determinant route (see core.rs, det_candidates):
   1 with the roots; 0 when the eigenvalue route decides; -1 when no sample is conditioned
   (GaveUp::Unconditioned: nearly degenerate here), the best sample's pivot ratio in *best. */
static int ik_gen_det_candidates(const ik_gen_arranged *ar, const ik_gen_elim *el,
                                 double roots[24][6], int *n, int *degree, double *best) {
    double tm[3][12][12], m[12][12], v[12], y[12], t[6], d[IK_GEN_DET_SAMPLES],
        c[IK_GEN_DET_DEGREE + 1][2], th[24], even[IK_GEN_DET_DEGREE + 1],
        odd[IK_GEN_DET_DEGREE + 1], scale = 0.0, good = 0.0, ratio, a, b, w,
        interp = 0.0, check, t3, co, si;
    int k, j, i, deg, count;
    ik_gen_matrix_trig((const double (*)[6][9])el->sig, tm);
    /* The angle 2 pi k / 17 is (2k) pi / 17 of the tables. */
    for (k = 0; k < IK_GEN_DET_SAMPLES; k++) {
        d[k] = ik_gen_det_trig((const double (*)[12][12])tm, IK_GEN_DET_SIN[2 * k],
                               IK_GEN_DET_COS[2 * k], &ratio);
        if (fabs(d[k]) > scale) scale = fabs(d[k]);
        if (ratio > good) good = ratio;
    }
    if (!(good > IK_GEN_SHIFT_GOOD && isfinite(scale))) {
        *best = good;
        return -1;
    }
    /* c_j = a_j - i b_j of D(th) = a_0 + sum a_j cos j th + b_j sin j th; the samples at
       +-th paired (cos j th even, sin j th odd). */
    for (k = 1; k <= IK_GEN_DET_DEGREE; k++) {
        even[k] = d[k] + d[IK_GEN_DET_SAMPLES - k];
        odd[k] = d[k] - d[IK_GEN_DET_SAMPLES - k];
    }
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        a = d[0];
        b = 0.0;
        for (k = 1; k <= IK_GEN_DET_DEGREE; k++) {
            const int idx = 2 * ((j * k) % IK_GEN_DET_SAMPLES);
            a += even[k] * IK_GEN_DET_COS[idx];
            b += odd[k] * IK_GEN_DET_SIN[idx];
        }
        w = (j == 0 ? 1.0 : 2.0) / (double)IK_GEN_DET_SAMPLES;
        c[j][0] = w * a;
        c[j][1] = -(w * b);
    }
    /* The check angle pi / 17: j pi / 17 of the tables. */
    for (j = 0; j <= IK_GEN_DET_DEGREE; j++)
        interp += c[j][0] * IK_GEN_DET_COS[j] - c[j][1] * IK_GEN_DET_SIN[j];
    check = ik_gen_det_trig((const double (*)[12][12])tm, IK_GEN_DET_SIN[1], IK_GEN_DET_COS[1],
                            &ratio);
    if (!(fabs(check - interp) <= IK_GEN_DET_CHECK * scale)) return 0;
    deg = IK_GEN_DET_DEGREE;
    while (deg > 0 && hypot(c[deg][0], c[deg][1]) <= IK_GEN_DET_TRIM * scale) deg--;
    if (!ik_gen_trig_roots((const double (*)[2])c, th, &count)) return 0;
    *n = 0;
    for (k = 0; k < count; k++) {
        /* The null vector with the columns in the order IK_GEN_DET_COLS, put back. */
        t3 = th[k];
        ik_gen_unit(t3, &co, &si);
        ik_gen_trig_at_cols((const double (*)[12][12])tm, si, co, m);
        ik_gen_null_vector_lu((const double (*)[12])m, y);
        for (i = 0; i < 12; i++) v[(int)IK_GEN_DET_COLS[i]] = y[i];
        ik_gen_back_substitute(ar, el, v, ik_gen_wrap(t3), t);
        for (i = 0; i < 6; i++) roots[*n][ar->perm[i]] = t[i];
        *n += 1;
    }
    *degree = 2 * deg;
    return 1;
}

/* The candidates of one arrangement by the eigenvalue route (see core.rs, eigen_candidates):
   its real roots, each with the arm's joint vector (not yet refined) in roots, their number
   in *n and the degree reached in *degree; 0 when A is singular at every shift. */
static int ik_gen_eigen_candidates(const ik_gen_arranged *ar, const ik_gen_elim *el,
                                   double roots[24][6], int *n, int *degree) {
    double mp[3][12][12], mps[3][12][12], m[12][12], v[12];
    double a[12][12], a_s[12][12], wr[24], wi[24], t[6], best_phi = 0.0, best = -1.0, ratio, re,
        im, phi;
    int p[12], ps[12], k, i, n_ev;
    /* The shift phi of the hidden joint that makes A best conditioned; its matrix polynomial
       and the LU of its A are kept. */
    for (k = 0; k < (int)(sizeof IK_GEN_SHIFTS / sizeof IK_GEN_SHIFTS[0]); k++) {
        ik_gen_matrix_poly((const double (*)[6][9])el->sig, IK_GEN_SHIFTS[k], mps);
        memcpy(a_s, mps[2], sizeof a_s);
        ratio = ik_gen_lu(&a_s[0][0], 12, ps);
        if (ratio > best) {
            best_phi = IK_GEN_SHIFTS[k];
            best = ratio;
            memcpy(mp, mps, sizeof mp);
            memcpy(a, a_s, sizeof a);
            memcpy(p, ps, sizeof p);
        }
        if (ratio > IK_GEN_SHIFT_GOOD) break;
    }
    if (best < IK_GEN_SHIFT_SINGULAR) return 0;
    phi = best_phi;
    if (!ik_gen_eigen_quadratic((const double (*)[12][12])mp, (const double (*)[12])a, p, wr, wi,
                                &n_ev))
        return 0;
    *n = 0;
    *degree = 0;
    for (k = 0; k < n_ev; k++) {
        const int spurious = (fabs(wr[k]) + fabs(fabs(wi[k]) - 1.0)) < IK_GEN_SPURIOUS_TOL;
        re = wr[k];
        im = wi[k];
        /* A prismatic hidden joint's roots at infinity are no solutions. */
        if (ar->j[2].prism && fabs(tan(0.5 * phi + atan(re))) > IK_GEN_PRISM_FAR) continue;
        if (isfinite(re) && isfinite(im) && !spurious && hypot(re, im) < IK_GEN_INFINITE_ROOT) {
            *degree += 1;
        }
        /* A real root, or a pair split by rounding (a double root near a singular set): the
           refinement and the check by forward kinematics decide. */
        if (fabs(im) <= IK_GEN_NEAR_REAL * (1.0 + fabs(re)) && isfinite(re)) {
            int r, c;
            for (r = 0; r < 12; r++)
                for (c = 0; c < 12; c++)
                    m[r][c] = (mp[2][r][c] * re + mp[1][r][c]) * re + mp[0][r][c];
            ik_gen_null_vector((const double (*)[12])m, v);
            ik_gen_back_substitute(ar, el, v, ik_gen_wrap(phi + 2.0 * atan(re)), t);
            for (i = 0; i < 6; i++) roots[*n][ar->perm[i]] = t[i];
            *n += 1;
        }
    }
    return 1;
}

/* The chain prepared for the forward kinematics (see core.rs, Chain): E1(q1) ... E6(q6) M =
   F1 Z(q1) L1 ... Z(q6) L6 with Fi a frame of joint i's axis, Li = Fi^-1 Fi+1, L6 = F6^-1 M. */
typedef struct {
    double base[3][4], link[6][3][4];
    int prism[6];
} ik_gen_chain;

/* A frame of the axis through c along w: z the unit direction, x a unit normal, y = z x x. */
static void ik_gen_axis_frame(const double w[3], const double c[3], double f[3][4]) {
    const double n = sqrt(ik_gen_dot3(w, w));
    const double ex[3] = {1.0, 0.0, 0.0}, ey[3] = {0.0, 1.0, 0.0};
    double z[3], x0[3], x[3], y[3], m;
    int r;
    for (r = 0; r < 3; r++) z[r] = w[r] / n;
    ik_gen_cross3(z, fabs(z[0]) < 0.6 ? ex : ey, x0);
    m = sqrt(ik_gen_dot3(x0, x0));
    for (r = 0; r < 3; r++) x[r] = x0[r] / m;
    ik_gen_cross3(z, x, y);
    for (r = 0; r < 3; r++) {
        f[r][0] = x[r];
        f[r][1] = y[r];
        f[r][2] = z[r];
        f[r][3] = c[r];
    }
}

/* The chain of the axes ax and the home pose home (scaled). */
static void ik_gen_chain_of(const double ax[6][7], const double home[3][4], ik_gen_chain *ch) {
    double fr[6][3][4], inv[3][4];
    int i;
    for (i = 0; i < 6; i++) {
        ik_gen_axis_frame(ax[i] + 1, ax[i] + 4, fr[i]);
        ch->prism[i] = ax[i][0] != 0.0;
    }
    memcpy(ch->base, fr[0], sizeof ch->base);
    for (i = 0; i < 6; i++) {
        ik_gen_inverse((const double (*)[4])fr[i], inv);
        ik_gen_compose((const double (*)[4])inv, i < 5 ? (const double (*)[4])fr[i + 1] : home,
                       ch->link[i]);
    }
}

/* a b for rigid motions (no term for the zero bottom row of b's rotation columns). */
static void ik_gen_then(const double a[3][4], const double b[3][4], double o[3][4]) {
    int r, c;
    for (r = 0; r < 3; r++) {
        for (c = 0; c < 3; c++) o[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        o[r][3] = a[r][0] * b[0][3] + a[r][1] * b[1][3] + a[r][2] * b[2][3] + a[r][3];
    }
}

/* The pose E1(q1) ... E6(q6) M and each joint's current axis (w, p) (scaled lengths): the
   product so far is joint i's frame. */
static void ik_gen_forward(const ik_gen_chain *ch, const double q[6], double pose[3][4],
                           double cur[6][6]) {
    double p[3][4], np[3][4], co, si, x, y;
    int i, r;
    memcpy(p, ch->base, sizeof p);
    for (i = 0; i < 6; i++) {
        for (r = 0; r < 3; r++) {
            cur[i][r] = p[r][2];
            cur[i][3 + r] = p[r][3];
        }
        if (ch->prism[i]) {
            for (r = 0; r < 3; r++) p[r][3] += q[i] * p[r][2];
        } else {
            ik_gen_unit(q[i], &co, &si);
            for (r = 0; r < 3; r++) {
                x = p[r][0];
                y = p[r][1];
                p[r][0] = co * x + si * y;
                p[r][1] = co * y - si * x;
            }
        }
        ik_gen_then((const double (*)[4])p, (const double (*)[4])ch->link[i], np);
        memcpy(p, np, sizeof p);
    }
    memcpy(pose, p, sizeof p);
}

/* T - F entry by entry, and its largest size (NaN when any is). */
static double ik_gen_error(const double f[3][4], const double t[3][4], double e[12]) {
    double m = 0.0, d;
    int r, c;
    for (r = 0; r < 3; r++) {
        for (c = 0; c < 4; c++) {
            d = t[r][c] - f[r][c];
            e[4 * r + c] = d;
            if (isnan(d)) {
                m = NAN;
            } else if (!isnan(m)) {
                m = fmax(m, fabs(d));
            }
        }
    }
    return m;
}

/* The normal matrix a and gradient g of Gauss-Newton at the pose f with the current axes cur
   and the error e, without the Jacobian's columns (see core.rs, refine): joint i's column is
   [w]x [F | t - p] (a slide's [0 | w]), so with F a rotation its rotation part gives 2 wi.wj
   and wi.u, u = sum_k f_k x e_k; the translation part (wi x (t - pi)).(wj x (t - pj)) and its
   product with e_t. Returns the trace. */
static double ik_gen_normal(const ik_gen_chain *ch, const double f[3][4], const double cur[6][6],
                            const double e[12], double a[6][6], double g[6]) {
    double u[3] = {0.0, 0.0, 0.0}, x[3], col[3], ek[3], et[3], rel[3], rot[6][3], tra[6][3],
        tr = 0.0, v;
    int i, j, k, r;
    for (k = 0; k < 3; k++) {
        for (r = 0; r < 3; r++) {
            col[r] = f[r][k];
            ek[r] = e[4 * r + k];
        }
        ik_gen_cross3(col, ek, x);
        for (r = 0; r < 3; r++) u[r] += x[r];
    }
    for (r = 0; r < 3; r++) et[r] = e[4 * r + 3];
    for (i = 0; i < 6; i++) {
        const double *w = cur[i], *p = cur[i] + 3;
        if (ch->prism[i]) {
            for (r = 0; r < 3; r++) {
                rot[i][r] = 0.0;
                tra[i][r] = w[r];
            }
        } else {
            for (r = 0; r < 3; r++) {
                rot[i][r] = w[r];
                rel[r] = f[r][3] - p[r];
            }
            ik_gen_cross3(w, rel, tra[i]);
        }
    }
    for (i = 0; i < 6; i++) {
        for (j = i; j < 6; j++) {
            v = 2.0 * ik_gen_dot3(rot[i], rot[j]) + ik_gen_dot3(tra[i], tra[j]);
            a[i][j] = v;
            a[j][i] = v;
        }
        g[i] = ik_gen_dot3(rot[i], u) + ik_gen_dot3(tra[i], et);
        tr += a[i][i];
    }
    return tr;
}

/* Solves m d = g by Cholesky's factorization m = L L^T (the damped normal matrix is symmetric
   positive definite; see core.rs, cholesky_solve); 0 where a pivot is not positive and finite. */
static int ik_gen_cholesky_solve(const double m[6][6], const double g[6], double d[6]) {
    double l[6][6], inv[6], y[6], s, ir, t;
    int i, j, k;
    for (j = 0; j < 6; j++) {
        s = m[j][j];
        for (k = 0; k < j; k++) s -= l[j][k] * l[j][k];
        if (!(s > 0.0 && isfinite(s))) return 0;
        ir = 1.0 / sqrt(s);
        inv[j] = ir;
        for (i = j + 1; i < 6; i++) {
            t = m[i][j];
            for (k = 0; k < j; k++) t -= l[i][k] * l[j][k];
            l[i][j] = t * ir;
        }
    }
    for (i = 0; i < 6; i++) {
        t = g[i];
        for (k = 0; k < i; k++) t -= l[i][k] * y[k];
        y[i] = t * inv[i];
    }
    for (i = 5; i >= 0; i--) {
        t = y[i];
        for (k = i + 1; k < 6; k++) t -= l[k][i] * d[k];
        d[i] = t * inv[i];
    }
    return 1;
}

/* Damped Gauss-Newton from q on the pose residual (scaled lengths); returns the final
   residual. */
static double ik_gen_refine(const ik_gen_chain *ch, const double t[3][4], double q[6]) {
    double f[3][4], cur[6][6], e[12], f2[3][4], cur2[6][6], e2[12];
    double a[6][6], m[6][6], g[6], d[6], next[6], res, r2, tr, lambda = IK_GEN_DAMP_START;
    int it, i, done;
    ik_gen_forward(ch, q, f, cur);
    res = ik_gen_error((const double (*)[4])f, t, e);
    for (it = 0; it < IK_GEN_REFINE_ITERS; it++) {
        if (res <= IK_GEN_EXACT_TOL || isnan(res)) break;
        tr = ik_gen_normal(ch, (const double (*)[4])f, (const double (*)[6])cur, e, a, g);
        for (done = 0; !done;) {
            memcpy(m, a, sizeof m);
            for (i = 0; i < 6; i++) m[i][i] += lambda * fmax(tr, IK_GEN_MIN_POSITIVE);
            if (ik_gen_cholesky_solve((const double (*)[6])m, g, d)) {
                for (i = 0; i < 6; i++) next[i] = q[i] + d[i];
                ik_gen_forward(ch, next, f2, cur2);
                r2 = ik_gen_error((const double (*)[4])f2, t, e2);
                if (r2 < res) {
                    memcpy(q, next, 6 * sizeof q[0]);
                    memcpy(f, f2, sizeof f);
                    memcpy(cur, cur2, sizeof cur);
                    memcpy(e, e2, sizeof e);
                    res = r2;
                    lambda = fmax(lambda * 0.01, IK_GEN_DAMP_MIN);
                    done = 1;
                    continue;
                }
            }
            lambda *= 100.0;
            if (lambda > IK_GEN_DAMP_MAX) return res;
        }
    }
    return res;
}

/* Two joint vectors within radius of each other in every joint (angles compared on the
   circle). */
static int ik_gen_same(const double a[6], const double b[6], const int prismatic[6],
                       double radius) {
    int i;
    for (i = 0; i < 6; i++) {
        const double d = prismatic[i] ? a[i] - b[i] : ik_gen_wrap(a[i] - b[i]);
        if (!(fabs(d) <= radius)) return 0;
    }
    return 1;
}

/* Drops each solution of out that repeats another at its residual (core.rs, merge_repeats):
   one whose residual r is above IK_GEN_EXACT_TOL and that lies within IK_GEN_FOLD_REACH
   sqrt(r) of a solution of smaller residual (of equal residual and earlier). */
static void ik_gen_merge_repeats(ik_gen_out *out, const int prismatic[6]) {
    int i = out->n, j, k, repeats;
    double r, rj, radius;
    while (i > 0) {
        i -= 1;
        r = out->residual[i];
        if (r <= IK_GEN_EXACT_TOL) continue;
        radius = IK_GEN_FOLD_REACH * sqrt(r);
        repeats = 0;
        for (j = 0; j < out->n && !repeats; j++) {
            rj = out->residual[j];
            repeats = j != i && (rj < r || (rj == r && j < i)) &&
                      ik_gen_same(out->q[j], out->q[i], prismatic, radius);
        }
        if (repeats) {
            for (k = i; k < out->n - 1; k++) {
                memcpy(out->q[k], out->q[k + 1], 6 * sizeof out->q[k][0]);
                out->residual[k] = out->residual[k + 1];
            }
            out->n -= 1;
        }
    }
}

/* Adds the refined candidate q (residual res) to out, or improves the solution it repeats;
   returns its index, -1 when out is full. */
static int ik_gen_add(ik_gen_out *out, const double q[6], double res, const int prismatic[6]) {
    int i;
    for (i = 0; i < out->n; i++) {
        if (ik_gen_same(out->q[i], q, prismatic, IK_GEN_SAME_TOL)) {
            if (res < out->residual[i]) {
                memcpy(out->q[i], q, 6 * sizeof q[0]);
                out->residual[i] = res;
            }
            return i;
        }
    }
    if (out->n < IK_GEN_MAX) {
        memcpy(out->q[out->n], q, 6 * sizeof q[0]);
        out->residual[out->n] = res;
        out->n += 1;
        return out->n - 1;
    }
    return -1;
}

/* The chain and the target in the core's units (every length over the scale len): the axes,
   the home pose and the target's top rows, G = T M^-1, the joints and which of them slide. */
typedef struct {
    double ax[6][7], hm[3][4], tg[3][4], g[3][4];
    ik_gen_joint js[6];
    ik_gen_chain chain;
    int prismatic[6];
} ik_gen_scaled;

static void ik_gen_scale(const double axes[6][7], const double home[3][4],
                         const double target[4][4], double len, ik_gen_scaled *s) {
    double ihm[3][4];
    int i, k;
    memcpy(s->ax, axes, sizeof s->ax);
    memcpy(s->hm, home, sizeof s->hm);
    memcpy(s->tg, target, sizeof s->tg);
    for (i = 0; i < 6; i++)
        for (k = 4; k < 7; k++) s->ax[i][k] /= len;
    for (i = 0; i < 3; i++) {
        s->hm[i][3] /= len;
        s->tg[i][3] /= len;
    }
    for (i = 0; i < 6; i++) s->prismatic[i] = s->ax[i][0] != 0.0;
    ik_gen_chain_of((const double (*)[7])s->ax, (const double (*)[4])s->hm, &s->chain);
    ik_gen_inverse((const double (*)[4])s->hm, ihm);
    ik_gen_compose((const double (*)[4])s->tg, (const double (*)[4])ihm, s->g);
    for (i = 0; i < 6; i++) {
        for (k = 0; k < 3; k++) {
            s->js[i].w[k] = s->ax[i][1 + k];
            s->js[i].c[k] = s->ax[i][4 + k];
        }
        s->js[i].prism = s->prismatic[i];
    }
}

/* The degree in length of each of the fourteen quantities (l, p, p.p, p.l, p x l,
   (p.p) l - 2 (p.l) p): computed from lengths in the robot's units, equation e of the left side
   is len^IK_GEN_LEFT_DEG[e] times the one from lengths over len. */
static const int IK_GEN_LEFT_DEG[14] = {0, 0, 0, 1, 1, 1, 2, 1, 1, 1, 1, 2, 2, 2};

/* The left side of arrangement arr (0 or 6, joints 3 to 5 turning: a constant of the arm) from
   the axes in the robot's units, each equation times 1 / len to its degree (the Rust solver
   keeps the unscaled one per arm; the same numbers). */
static void ik_gen_robot_left(const double axes[6][7], int arr, double len,
                              double am[14][3][9]) {
    static const double id[3][4] = {{1.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0},
                                     {0.0, 0.0, 1.0, 0.0}};
    ik_gen_joint js[6];
    ik_gen_arranged ar;
    double lhs[3][3][3][14], rhs[3][3][14], s = 1.0 / len, f[3];
    int i, k, m;
    for (i = 0; i < 6; i++) {
        for (k = 0; k < 3; k++) {
            js[i].w[k] = axes[i][1 + k];
            js[i].c[k] = axes[i][4 + k];
        }
        js[i].prism = axes[i][0] != 0.0;
    }
    ik_gen_arrange(js, id, arr, &ar);
    ik_gen_samples(&ar, lhs, rhs);
    memset(am, 0, 14 * sizeof am[0]);
    ik_gen_left_coefficients(&ar, lhs, am);
    f[0] = 1.0;
    f[1] = s;
    f[2] = s * s;
    for (i = 0; i < 14; i++)
        for (k = 0; k < 3; k++)
            for (m = 0; m < 9; m++) am[i][k][m] *= f[IK_GEN_LEFT_DEG[i]];
}

/* Refines the n candidates of arrangement arr (degree reached: degree), adds the solutions to
   out; 1 when the set is complete (every root gave its own exact solution). */
static int ik_gen_take(ik_gen_out *out, const ik_gen_scaled *sc, double roots[24][6], int n,
                       int degree, int arr, ik_gen_tol tol) {
    int hit[IK_GEN_MAX], i, j, at, hits;
    double q[6], res;
    if (out->n_arr == 0) out->degree = degree;
    if (out->n_arr < 3) out->arrangements[out->n_arr] = arr;
    out->n_arr += 1;
    /* The solutions this arrangement's roots reached (exactly). */
    memset(hit, 0, sizeof hit);
    for (i = 0; i < n; i++) {
        memcpy(q, roots[i], sizeof q);
        res = ik_gen_refine(&sc->chain, (const double (*)[4])sc->tg, q);
        if (isnan(res) || res > tol.keep) continue;
        for (j = 0; j < 6; j++)
            if (!sc->prismatic[j]) q[j] = ik_gen_wrap(q[j]);
        at = ik_gen_add(out, q, res, sc->prismatic);
        if (at >= 0) hit[at] |= res <= tol.pose;
    }
    for (hits = 0, i = 0; i < IK_GEN_MAX; i++) hits += hit[i];
    return hits == n;
}

/* Every solution of E1 ... E6 M = T for a 6R chain (axes [kind, w, p], home and target
   positions in the robot's lengths, len its scale): the arrangements are tried in order from
   first; each nondegenerate one gives its real roots, each back-substituted, refined and
   checked by forward kinematics, until one arrangement's roots all gave exact solutions of
   their own. The eigenvalue route of the first arrangement whose determinant route gives up
   is deferred by one arrangement (see core.rs, gen_solve). */
static void ik_gen_elim_of(const double axes[6][7], double len, const ik_gen_arranged *ar,
                           int arr, ik_gen_elim *el) {
    double left[14][3][9];
    /* The left side from the arm's constants where it is one, else from the arranged
       joints. */
    if (arr % 6 == 0 && !ar->j[2].prism && !ar->j[3].prism && !ar->j[4].prism) {
        ik_gen_robot_left(axes, arr, len, left);
        ik_gen_eliminate(ar, (const double (*)[3][9])left, el);
    } else {
        ik_gen_eliminate(ar, NULL, el);
    }
}

static void ik_gen_solve(const double axes[6][7], const double home[3][4],
                         const double target[4][4], double len, ik_gen_tol tol, int first,
                         ik_gen_out *out) {
    double roots[24][6], good, unc_good[12], tg;
    ik_gen_elim el, del;
    ik_gen_scaled sc;
    ik_gen_arranged ar, dar;
    const int *prismatic = sc.prismatic;
    int i, j, k, n, degree, arr, darr = -1, complete = 0, found, unc_arr[12], n_unc = 0, ta;
    memset(out, 0, sizeof *out);
    ik_gen_scale(axes, home, target, len, &sc);
    /* The arrangement that served at the derivation's generic target first, then the others. */
    for (k = 0; k < 12; k++) {
        arr = k == 0 ? first % 12 : k <= first % 12 ? k - 1 : k;
        if (out->n_arr == 12) break;
        ik_gen_arrange(sc.js, (const double (*)[4])sc.g, arr, &ar);
        /* The last arranged joint is eliminated by a point of its axis, which a slide moves. */
        if (prismatic[ar.perm[5]]) continue;
        ik_gen_elim_of(axes, len, &ar, arr, &el);
        if (el.rank_ratio < IK_GEN_RANK_TOL) continue;
        /* A turning hidden joint: the determinant route first. */
        found = ar.j[2].prism ? 0
                              : ik_gen_det_candidates(&ar, &el, roots, &n, &degree, &good);
        /* Nearly degenerate here: kept for the end. */
        if (found < 0) {
            unc_good[n_unc] = good;
            unc_arr[n_unc] = arr;
            n_unc += 1;
            continue;
        }
        if (!found) {
            /* The first to give up waits for the next arrangement's determinant route. */
            if (!ar.j[2].prism && darr < 0) {
                dar = ar;
                del = el;
                darr = arr;
                continue;
            }
            /* A second gave up (or the hidden joint slides): the deferred eigenvalue route
               decides first, then this arrangement's. */
            if (darr >= 0) {
                const int d = darr;
                darr = -1;
                if (ik_gen_eigen_candidates(&dar, &del, roots, &n, &degree)) {
                    complete = ik_gen_take(out, &sc, roots, n, degree, d, tol);
                    if (complete || out->n_arr == 12) break;
                }
            }
            found = ik_gen_eigen_candidates(&ar, &el, roots, &n, &degree);
        }
        if (!found) continue;
        complete = ik_gen_take(out, &sc, roots, n, degree, arr, tol);
        if (complete) break;
    }
    /* The loop ended with an arrangement deferred and the set incomplete: its eigenvalue
       route. */
    if (darr >= 0 && !complete && out->n_arr < 12 &&
        ik_gen_eigen_candidates(&dar, &del, roots, &n, &degree))
        complete = ik_gen_take(out, &sc, roots, n, degree, darr, tol);
    /* Still incomplete: the nearly degenerate arrangements' eigenvalue routes, the best
       conditioned first (in the order tried among equals). */
    for (i = 1; i < n_unc; i++)
        for (k = i; k > 0 && unc_good[k - 1] < unc_good[k]; k--) {
            tg = unc_good[k - 1];
            unc_good[k - 1] = unc_good[k];
            unc_good[k] = tg;
            ta = unc_arr[k - 1];
            unc_arr[k - 1] = unc_arr[k];
            unc_arr[k] = ta;
        }
    for (i = 0; i < n_unc; i++) {
        if (complete || out->n_arr == 12) break;
        ik_gen_arrange(sc.js, (const double (*)[4])sc.g, unc_arr[i], &ar);
        ik_gen_elim_of(axes, len, &ar, unc_arr[i], &el);
        if (ik_gen_eigen_candidates(&ar, &el, roots, &n, &degree))
            complete = ik_gen_take(out, &sc, roots, n, degree, unc_arr[i], tol);
    }
    ik_gen_merge_repeats(out, prismatic);
    /* Prismatic variables back in the robot's length unit. */
    for (i = 0; i < out->n; i++)
        for (j = 0; j < 6; j++)
            if (prismatic[j]) out->q[i][j] *= len;
}

/* Balancing (Parlett-Reinsch, powers of two): a similar matrix with rows and columns of
   comparable norm. */
static void ik_gen_balance(double a[24][24], int n) {
    const double radix = 2.0;
    int done = 0, sweeps = 0, i, j;
    double c, r, s, f, g, gi;
    while (!done && sweeps < 100) {
        done = 1;
        sweeps += 1;
        for (i = 0; i < n; i++) {
            c = 0.0;
            r = 0.0;
            for (j = 0; j < n; j++) {
                if (j != i) {
                    c += fabs(a[j][i]);
                    r += fabs(a[i][j]);
                }
            }
            if (c == 0.0 || r == 0.0 || !isfinite(c + r)) continue;
            s = c + r;
            f = 1.0;
            g = r / radix;
            while (c < g) {
                f *= radix;
                c *= radix * radix;
            }
            g = r * radix;
            while (c > g) {
                f /= radix;
                c /= radix * radix;
            }
            if ((c + r) / f < 0.95 * s) {
                done = 0;
                gi = 1.0 / f;
                for (j = 0; j < n; j++) a[i][j] *= gi;
                for (j = 0; j < n; j++) a[j][i] *= f;
            }
        }
    }
}

/* Reduction to upper Hessenberg form by stabilised elementary similarity transformations (of
   the leading n x n block). */
static void ik_gen_hessenberg(double a[24][24], int n) {
    int m, i, j, ii;
    double x, y, t;
    for (m = 1; m < n - 1; m++) {
        x = 0.0;
        i = m;
        for (j = m; j < n; j++) {
            if (fabs(a[j][m - 1]) > fabs(x)) {
                x = a[j][m - 1];
                i = j;
            }
        }
        if (i != m) {
            for (j = m - 1; j < n; j++) {
                t = a[i][j];
                a[i][j] = a[m][j];
                a[m][j] = t;
            }
            for (j = 0; j < n; j++) {
                t = a[j][i];
                a[j][i] = a[j][m];
                a[j][m] = t;
            }
        }
        if (x != 0.0) {
            for (ii = m + 1; ii < n; ii++) {
                y = a[ii][m - 1];
                if (y != 0.0) {
                    y /= x;
                    a[ii][m - 1] = 0.0;
                    for (j = m; j < n; j++) a[ii][j] -= y * a[m][j];
                    for (j = 0; j < n; j++) a[j][m] += y * a[j][ii];
                }
            }
        }
    }
}

/* One Francis double-shift QR sweep of rows and columns l..nn (1-based) from row m, with the
   shift's (p, q, r) given: the classical hqr's inner loop. */
static void ik_gen_qr_sweep(double a[24][24], int l, int m, int nn, double p, double q,
                            double r) {
#define IK_GEN_A(i, j) a[(i) - 1][(j) - 1]
    double s, x = 0.0, y, z, norm;
    int i, j, k, mmin;
    for (i = m + 2; i <= nn; i++) {
        IK_GEN_A(i, i - 2) = 0.0;
        if (i != m + 2) IK_GEN_A(i, i - 3) = 0.0;
    }
    for (k = m; k < nn; k++) {
        if (k != m) {
            p = IK_GEN_A(k, k - 1);
            q = IK_GEN_A(k + 1, k - 1);
            r = 0.0;
            if (k != nn - 1) r = IK_GEN_A(k + 2, k - 1);
            x = fabs(p) + fabs(q) + fabs(r);
            if (x != 0.0) {
                p /= x;
                q /= x;
                r /= x;
            }
        }
        norm = sqrt(p * p + q * q + r * r);
        s = p >= 0.0 ? norm : -norm;
        if (s == 0.0) continue;
        if (k == m) {
            if (l != m) IK_GEN_A(k, k - 1) = -IK_GEN_A(k, k - 1);
        } else {
            IK_GEN_A(k, k - 1) = -s * x;
        }
        p += s;
        x = p / s;
        y = q / s;
        z = r / s;
        q /= p;
        r /= p;
        mmin = nn < k + 3 ? nn : k + 3;
        if (k != nn - 1) {
            double *r0 = a[k - 1], *r1 = a[k], *r2 = a[k + 1];
            for (j = k - 1; j < nn; j++) {
                p = r0[j] + q * r1[j] + r * r2[j];
                r2[j] -= p * z;
                r1[j] -= p * y;
                r0[j] -= p * x;
            }
            for (i = l - 1; i < mmin; i++) {
                double *ci = a[i] + (k - 1);
                p = x * ci[0] + y * ci[1] + z * ci[2];
                ci[2] -= p * r;
                ci[1] -= p * q;
                ci[0] -= p;
            }
        } else {
            double *r0 = a[k - 1], *r1 = a[k];
            for (j = k - 1; j < nn; j++) {
                p = r0[j] + q * r1[j];
                r1[j] -= p * y;
                r0[j] -= p * x;
            }
            for (i = l - 1; i < mmin; i++) {
                double *ci = a[i] + (k - 1);
                p = x * ci[0] + y * ci[1];
                ci[1] -= p * q;
                ci[0] -= p;
            }
        }
    }
#undef IK_GEN_A
}

/* The eigenvalues (wr + i wi) of the leading n x n block of a real matrix (destroyed):
   balancing, Hessenberg reduction and the Francis double-shift QR iteration (the classical
   hqr, 1-based indices); 0 when an eigenvalue takes more than 60 iterations. */
static int ik_gen_eigenvalues(double a[24][24], int n, double wr[24], double wi[24]) {
#define IK_GEN_A(i, j) a[(i) - 1][(j) - 1]
    double anorm = 0.0, t = 0.0, p = 0.0, q = 0.0, r = 0.0, s, w, x, y, z, u, v;
    int nn, its, l, m, i, j, i1, i2;
    ik_gen_balance(a, n);
    ik_gen_hessenberg(a, n);
    for (i = 1; i <= n; i++)
        for (j = i - 1 > 1 ? i - 1 : 1; j <= n; j++) anorm += fabs(IK_GEN_A(i, j));
    if (!isfinite(anorm)) return 0;
    nn = n;
    while (nn >= 1) {
        its = 0;
        for (;;) {
            for (l = nn; l >= 2; l--) {
                s = fabs(IK_GEN_A(l - 1, l - 1)) + fabs(IK_GEN_A(l, l));
                if (s == 0.0) s = anorm;
                if (fabs(IK_GEN_A(l, l - 1)) + s == s) {
                    IK_GEN_A(l, l - 1) = 0.0;
                    break;
                }
            }
            x = IK_GEN_A(nn, nn);
            if (l == nn) {
                wr[nn - 1] = x + t;
                wi[nn - 1] = 0.0;
                nn -= 1;
                break;
            }
            y = IK_GEN_A(nn - 1, nn - 1);
            w = IK_GEN_A(nn, nn - 1) * IK_GEN_A(nn - 1, nn);
            if (l == nn - 1) {
                p = 0.5 * (y - x);
                q = p * p + w;
                z = sqrt(fabs(q));
                x += t;
                i1 = nn - 2;
                i2 = nn - 1;
                if (q >= 0.0) {
                    z = p + (p >= 0.0 ? z : -z);
                    wr[i1] = x + z;
                    wr[i2] = x + z;
                    if (z != 0.0) wr[i2] = x - w / z;
                    wi[i1] = 0.0;
                    wi[i2] = 0.0;
                } else {
                    wr[i1] = x + p;
                    wr[i2] = x + p;
                    wi[i1] = -z;
                    wi[i2] = z;
                }
                nn -= 2;
                break;
            }
            if (its == 60) return 0;
            if (its == 10 || its == 20 || its == 40) {
                /* An exceptional shift. */
                t += x;
                for (i = 1; i <= nn; i++) IK_GEN_A(i, i) -= x;
                s = fabs(IK_GEN_A(nn, nn - 1)) + fabs(IK_GEN_A(nn - 1, nn - 2));
                x = 0.75 * s;
                y = x;
                w = -0.4375 * s * s;
            }
            its += 1;
            for (m = nn - 2; m >= l; m--) {
                z = IK_GEN_A(m, m);
                r = x - z;
                s = y - z;
                p = (r * s - w) / IK_GEN_A(m + 1, m) + IK_GEN_A(m, m + 1);
                q = IK_GEN_A(m + 1, m + 1) - z - r - s;
                r = IK_GEN_A(m + 2, m + 1);
                s = fabs(p) + fabs(q) + fabs(r);
                p /= s;
                q /= s;
                r /= s;
                if (m == l) break;
                u = fabs(IK_GEN_A(m, m - 1)) * (fabs(q) + fabs(r));
                v = fabs(p) *
                    (fabs(IK_GEN_A(m - 1, m - 1)) + fabs(z) + fabs(IK_GEN_A(m + 1, m + 1)));
                if (u + v == v) break;
            }
            ik_gen_qr_sweep(a, l, m, nn, p, q, r);
            if (l >= nn - 1) break;
        }
    }
    return 1;
#undef IK_GEN_A
}
