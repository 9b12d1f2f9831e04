// The numeric core of the general 6R solver in JavaScript (the IK page's live table): a port of
// core.rs (Raghavan-Roth elimination in Manocha-Canny's matrix form), function by function,
// with the same operations in the same order. The constants IK_GEN_* (sample angles,
// tolerances) are written above this text by the emitter from core.rs, where they are defined
// and explained. Matrices are arrays of rows. Sums that core.rs writes with Rust's iterator sum
// start at -0, as that sum does.

// Rust's f64::max and min: a NaN argument gives the other one.
function ik_gen_fmax(a, b) {
    return a > b || b !== b ? a : b;
}

function ik_gen_fmin(a, b) {
    return a < b || b !== b ? a : b;
}

function ik_gen_zeros(...dims) {
    if (dims.length === 1) return new Array(dims[0]).fill(0);
    return Array.from({ length: dims[0] }, () => ik_gen_zeros(...dims.slice(1)));
}

function ik_gen_dot3(a, b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

function ik_gen_cross3(a, b) {
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

// Rodrigues: c I + s [w]x + (1 - c) w w^T.
function ik_gen_rodrigues(w, s, c) {
    const k = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]];
    const r = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
    for (let i = 0; i < 3; i++) {
        for (let j = 0; j < 3; j++) r[i][j] = (i === j ? c : 0) + s * k[i][j] + (1 - c) * w[i] * w[j];
    }
    return r;
}

function ik_gen_mv(r, v) {
    return [ik_gen_dot3(r[0], v), ik_gen_dot3(r[1], v), ik_gen_dot3(r[2], v)];
}

// [E x, R d] of joint j = {w, c} at the angle with sine s, cosine co.
function ik_gen_apply(j, s, co, x, d) {
    const r = ik_gen_rodrigues(j.w, s, co);
    const ry = ik_gen_mv(r, [x[0] - j.c[0], x[1] - j.c[1], x[2] - j.c[2]]);
    return [[ry[0] + j.c[0], ry[1] + j.c[1], ry[2] + j.c[2]], ik_gen_mv(r, d)];
}

// [E x, R d] of joint j = {w, c, prism} at sample k of its variable (inv: the inverse motion):
// a revolute joint at the angle 2 pi k / 3, a prismatic one at the length IK_GEN_SAMPLE_D[k].
function ik_gen_sample(j, k, inv, x, d) {
    const sg = inv ? -1 : 1;
    if (j.prism) {
        const t = sg * IK_GEN_SAMPLE_D[k];
        return [[x[0] + t * j.w[0], x[1] + t * j.w[1], x[2] + t * j.w[2]], d];
    }
    return ik_gen_apply(j, sg * IK_GEN_SAMPLE_S[k], IK_GEN_SAMPLE_C[k], x, d);
}

// The weights that turn three samples into the coefficients of the joint's basis: (1, cos,
// sin) for a revolute joint, (1, d, d^2) for a prismatic one.
function ik_gen_weights(j) {
    return j.prism ? IK_GEN_VANDER : IK_GEN_DFT;
}

// The fourteen Raghavan-Roth quantities of a point p and a direction l: l, p, p.p, p.l, p x l,
// (p.p) l - 2 (p.l) p.
function ik_gen_quantities(p, l) {
    const pp = ik_gen_dot3(p, p);
    const pl = ik_gen_dot3(p, l);
    const o = [...l, ...p, pp, pl, ...ik_gen_cross3(p, l)];
    for (let i = 0; i < 3; i++) o.push(pp * l[i] - 2 * pl * p[i]);
    return o;
}

// [R | t]^-1 = [R^T | -R^T t].
function ik_gen_inverse(g) {
    const o = [];
    for (let i = 0; i < 3; i++) {
        o.push([g[0][i], g[1][i], g[2][i], -(g[0][i] * g[0][3] + g[1][i] * g[1][3] + g[2][i] * g[2][3])]);
    }
    return o;
}

// A motion applied to a point and a direction: [point, direction].
function ik_gen_motion_apply(g, x, d) {
    const p = [0, 0, 0], v = [0, 0, 0];
    for (let i = 0; i < 3; i++) {
        p[i] = g[i][0] * x[0] + g[i][1] * x[1] + g[i][2] * x[2] + g[i][3];
        v[i] = g[i][0] * d[0] + g[i][1] * d[1] + g[i][2] * d[2];
    }
    return [p, v];
}

function ik_gen_compose(a, b) {
    const o = [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]];
    for (let r = 0; r < 3; r++) {
        for (let c = 0; c < 4; c++) {
            o[r][c] = (c === 3 ? a[r][3] : 0) + a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
    return o;
}

// The arranged problem E1 ... E6 = H (home pose the identity) for arr = shift + 6 reversed of
// the chain js (scaled) with the target g = T M^-1: {j, h, perm}, arranged joint i the arm's
// joint perm[i].
function ik_gen_arrange(js, g, arr) {
    const rev = arr >= 6, shift = arr % 6;
    let base = js, h = g, bperm = [0, 1, 2, 3, 4, 5];
    if (rev) {
        // E6^-1 ... E1^-1 = G^-1, and Ei^-1(q) turns about the reversed axis by q.
        base = js.map((_, i) => ({ w: js[5 - i].w.map((x) => -x), c: js[5 - i].c, prism: js[5 - i].prism }));
        bperm = bperm.map((i) => 5 - i);
        h = ik_gen_inverse(g);
    }
    // E_{s+1} ... E6 (H^-1 E1 H) ... (H^-1 Es H) = H.
    const hi = ik_gen_inverse(h);
    const j = [], perm = [];
    for (let i = 0; i < 6; i++) {
        const k = (shift + i) % 6;
        perm.push(bperm[k]);
        if (k < shift) {
            const [c, w] = ik_gen_motion_apply(hi, base[k].c, base[k].w);
            j.push({ w, c, prism: base[k].prism });
        } else {
            j.push(base[k]);
        }
    }
    return { j, h, perm };
}

function ik_gen_mono(i, j) {
    return 3 * i + j;
}

// The quantities on the 3 x 3 x 3 grid of sample angles (left: E3 E4 E5 applied to (p6, w6))
// and the 3 x 3 grid (right: E2^-1 E1^-1 H applied to it).
function ik_gen_samples(ar) {
    const p6 = ar.j[5].c, w6 = ar.j[5].w;
    const lhs = ik_gen_zeros(3, 3, 3, 0);
    for (let k5 = 0; k5 < 3; k5++) {
        const [x5, d5] = ik_gen_sample(ar.j[4], k5, false, p6, w6);
        for (let k4 = 0; k4 < 3; k4++) {
            const [x4, d4] = ik_gen_sample(ar.j[3], k4, false, x5, d5);
            for (let k3 = 0; k3 < 3; k3++) {
                const [x3, d3] = ik_gen_sample(ar.j[2], k3, false, x4, d4);
                lhs[k3][k4][k5] = ik_gen_quantities(x3, d3);
            }
        }
    }
    const [hp, hd] = ik_gen_motion_apply(ar.h, p6, w6);
    const rhs = ik_gen_zeros(3, 3, 0);
    for (let k1 = 0; k1 < 3; k1++) {
        const [y1, e1] = ik_gen_sample(ar.j[0], k1, true, hp, hd);
        for (let k2 = 0; k2 < 3; k2++) {
            const [y2, e2] = ik_gen_sample(ar.j[1], k2, true, y1, e1);
            rhs[k1][k2] = ik_gen_quantities(y2, e2);
        }
    }
    return [lhs, rhs];
}

// The left side's coefficients am[e][i3][mono(i4, i5)]: the 3-D transform as three 1-D passes.
function ik_gen_left_coefficients(ar, lhs) {
    const W = ar.j.map(ik_gen_weights), t1 = ik_gen_zeros(3, 3, 3, 14), t2 = ik_gen_zeros(3, 3, 3, 14);
    const am = ik_gen_zeros(14, 3, 9);
    for (let i5 = 0; i5 < 3; i5++) for (let k3 = 0; k3 < 3; k3++) for (let k4 = 0; k4 < 3; k4++) {
        for (let k5 = 0; k5 < 3; k5++) {
            const w = W[4][i5][k5];
            for (let e = 0; e < 14; e++) t1[k3][k4][i5][e] += w * lhs[k3][k4][k5][e];
        }
    }
    for (let i4 = 0; i4 < 3; i4++) for (let k3 = 0; k3 < 3; k3++) for (let k4 = 0; k4 < 3; k4++) {
        const w = W[3][i4][k4];
        for (let i5 = 0; i5 < 3; i5++) {
            for (let e = 0; e < 14; e++) t2[k3][i4][i5][e] += w * t1[k3][k4][i5][e];
        }
    }
    for (let i3 = 0; i3 < 3; i3++) for (let k3 = 0; k3 < 3; k3++) {
        const w = W[2][i3][k3];
        for (let i4 = 0; i4 < 3; i4++) for (let i5 = 0; i5 < 3; i5++) {
            for (let e = 0; e < 14; e++) am[e][i3][ik_gen_mono(i4, i5)] += w * t2[k3][i4][i5][e];
        }
    }
    return am;
}

// The elimination of one arrangement: Bm X12 = Am(th3) X45 (am), the QR of Bm (qt, r, piv,
// rank_ratio) and Sig = N Am in (1, cos th3, sin th3) with N the last six rows of Q^T.
function ik_gen_eliminate(ar) {
    const [lhs, rhs] = ik_gen_samples(ar);
    const W = ar.j.map(ik_gen_weights), am = ik_gen_left_coefficients(ar, lhs);
    const bm = ik_gen_zeros(14, 8);
    for (let e = 0; e < 14; e++) for (let i1 = 0; i1 < 3; i1++) for (let i2 = 0; i2 < 3; i2++) {
        let s = 0;
        for (let k1 = 0; k1 < 3; k1++) for (let k2 = 0; k2 < 3; k2++) {
            s += W[0][i1][k1] * W[1][i2][k2] * rhs[k1][k2][e];
        }
        const m = ik_gen_mono(i1, i2);
        if (m === 0) am[e][0][0] -= s;
        else bm[e][m - 1] = s;
    }
    const { qt, r, piv, ratio } = ik_gen_qr_pivot(bm);
    const sig = ik_gen_zeros(3, 6, 9);
    for (let k = 0; k < 3; k++) for (let row = 0; row < 6; row++) for (let m = 0; m < 9; m++) {
        let s = 0;
        for (let e = 0; e < 14; e++) s += qt[8 + row][e] * am[e][k][m];
        sig[k][row][m] = s;
    }
    ik_gen_prismatic_basis(ar, sig);
    return { am, qt, r, piv, rank_ratio: ratio, sig };
}

// The coefficients of prismatic joints 3, 4, 5 from (1, d, d^2) into the basis that
// ik_gen_matrix_poly's half-angle map turns into (1, d, d^2) again (IK_GEN_HALF_INV).
function ik_gen_prismatic_basis(ar, sig) {
    const conv = (v) => [0, 1, 2].map((k) => v.reduce((s, x, j) => s + x * IK_GEN_HALF_INV[j][k], -0));
    for (let row = 0; row < 6; row++) {
        if (ar.j[2].prism) {
            for (let m = 0; m < 9; m++) {
                const v = conv([sig[0][row][m], sig[1][row][m], sig[2][row][m]]);
                for (let k = 0; k < 3; k++) sig[k][row][m] = v[k];
            }
        }
        for (let k = 0; k < 3; k++) {
            if (ar.j[3].prism) {
                for (let i5 = 0; i5 < 3; i5++) {
                    const v = conv([0, 1, 2].map((i4) => sig[k][row][ik_gen_mono(i4, i5)]));
                    for (let i4 = 0; i4 < 3; i4++) sig[k][row][ik_gen_mono(i4, i5)] = v[i4];
                }
            }
            if (ar.j[4].prism) {
                for (let i4 = 0; i4 < 3; i4++) {
                    const v = conv([0, 1, 2].map((i5) => sig[k][row][ik_gen_mono(i4, i5)]));
                    for (let i5 = 0; i5 < 3; i5++) sig[k][row][ik_gen_mono(i4, i5)] = v[i5];
                }
            }
        }
    }
}

// Householder QR with column pivoting of the 14 x 8 matrix b: {qt: Q^T, r, piv, ratio: |r77| /
// |r00|}.
function ik_gen_qr_pivot(b) {
    const a = b.map((row) => row.slice());
    const qt = ik_gen_zeros(14, 14), piv = [0, 1, 2, 3, 4, 5, 6, 7];
    for (let i = 0; i < 14; i++) qt[i][i] = 1;
    for (let k = 0; k < 8; k++) {
        // The remaining column of largest norm first.
        let best = k, bn = -1;
        for (let c = k; c < 8; c++) {
            let n = -0;
            for (let r = k; r < 14; r++) n += a[r][c] * a[r][c];
            if (n > bn) {
                bn = n;
                best = c;
            }
        }
        if (best !== k) {
            for (let r = 0; r < 14; r++) [a[r][k], a[r][best]] = [a[r][best], a[r][k]];
            [piv[k], piv[best]] = [piv[best], piv[k]];
        }
        const norm = Math.sqrt(ik_gen_fmax(bn, 0));
        if (norm === 0) continue;
        const alpha = a[k][k] > 0 ? -norm : norm;
        const v = new Array(14).fill(0);
        for (let r = k; r < 14; r++) v[r] = a[r][k];
        v[k] -= alpha;
        let vn = -0;
        for (let r = k; r < 14; r++) vn += v[r] * v[r];
        if (vn === 0) continue;
        for (const m of [a, qt]) {
            for (let c = m === a ? k : 0; c < m[0].length; c++) {
                let s = -0;
                for (let r = k; r < 14; r++) s += v[r] * m[r][c];
                s = s * 2 / vn;
                for (let r = k; r < 14; r++) m[r][c] -= s * v[r];
            }
        }
    }
    const r = [0, 1, 2, 3, 4, 5, 6, 7].map((i) => a[i].map((x, j) => (j >= i ? x : 0)));
    const ratio = r[0][0] === 0 ? 0 : Math.abs(r[7][7] / r[0][0]);
    return { qt, r, piv, ratio };
}

// The 12 x 12 matrix polynomial M(x) = A x^2 + B x + C of x = tan((th3 - phi)/2) as [C, B, A].
function ik_gen_matrix_poly(sig, phi) {
    const sp = Math.sin(phi), cp = Math.cos(phi), H = IK_GEN_HALF;
    const out = ik_gen_zeros(3, 12, 12);
    for (let row = 0; row < 6; row++) for (let i4 = 0; i4 < 3; i4++) for (let i5 = 0; i5 < 3; i5++) {
        const m = ik_gen_mono(i4, i5);
        const s0 = sig[0][row][m];
        const sc = sig[1][row][m] * cp + sig[2][row][m] * sp;
        const ss = sig[2][row][m] * cp - sig[1][row][m] * sp;
        const coef = [s0 + sc, 2 * ss, s0 - sc];
        for (let a = 0; a < 3; a++) for (let b = 0; b < 3; b++) {
            const h = H[i4][a] * H[i5][b];
            if (h === 0) continue;
            for (let d = 0; d < 3; d++) {
                out[d][row][3 * a + b] += h * coef[d];
                out[d][row + 6][3 * (a + 1) + b] += h * coef[d];
            }
        }
    }
    return out;
}

// LU with partial pivoting of the square matrix a (in place): the pivot order and the smallest
// pivot over the largest entry.
function ik_gen_lu(a) {
    const n = a.length, p = [...Array(n).keys()];
    let amax = 0, minpiv = Infinity;
    for (const row of a) for (const x of row) amax = ik_gen_fmax(amax, Math.abs(x));
    for (let k = 0; k < n; k++) {
        let best = k;
        for (let r = k + 1; r < n; r++) if (Math.abs(a[r][k]) > Math.abs(a[best][k])) best = r;
        [a[k], a[best]] = [a[best], a[k]];
        [p[k], p[best]] = [p[best], p[k]];
        const d = a[k][k];
        minpiv = ik_gen_fmin(minpiv, Math.abs(d));
        if (d === 0) continue;
        for (let r = k + 1; r < n; r++) {
            const f = a[r][k] / d;
            a[r][k] = f;
            if (f !== 0) for (let c = k + 1; c < n; c++) a[r][c] -= f * a[k][c];
        }
    }
    return [p, amax > 0 ? minpiv / amax : 0];
}

// Solves LU x = b[p].
function ik_gen_lu_solve(lu, p, b) {
    const n = b.length, x = p.map((i) => b[i]);
    for (let i = 0; i < n; i++) for (let k = 0; k < i; k++) x[i] -= lu[i][k] * x[k];
    for (let i = n - 1; i >= 0; i--) {
        for (let k = i + 1; k < n; k++) x[i] -= lu[i][k] * x[k];
        x[i] /= lu[i][i];
    }
    return x;
}

// Deflates the spurious eigenvalues +-i of the 24 x 24 companion matrix k (see core.rs): the
// null vectors a + i b of M(i) = C - A + i B (elimination with complete pivoting) span with
// [a; -b], [b; a] an invariant subspace Z; Gaussian elimination with partial pivoting of Z
// gives the similarity whose trailing block k'22 - L2 L1^-1 k'12 (k' = P k P^T) has the other
// eigenvalues. Returns that block (k itself when nothing is deflated).
function ik_gen_deflate_spurious(m, k) {
    const re = ik_gen_zeros(12, 12), im = m[1].map((row) => row.slice());
    for (let r = 0; r < 12; r++) for (let c = 0; c < 12; c++) re[r][c] = m[0][r][c] - m[2][r][c];
    const cols = [...Array(12).keys()];
    let br = 0, bc = 0, bv = -1;
    for (let r = 0; r < 12; r++) {
        for (let c = 0; c < 12; c++) {
            const v = re[r][c] * re[r][c] + im[r][c] * im[r][c];
            if (v > bv) [br, bc, bv] = [r, c, v];
        }
    }
    const first = bv;
    let rank = 12;
    for (let s = 0; s < 12; s++) {
        if (!(bv > IK_GEN_SPURIOUS_RANK * IK_GEN_SPURIOUS_RANK * first)) {
            rank = s;
            break;
        }
        [re[s], re[br]] = [re[br], re[s]];
        [im[s], im[br]] = [im[br], im[s]];
        for (let r = 0; r < 12; r++) {
            [re[r][s], re[r][bc]] = [re[r][bc], re[r][s]];
            [im[r][s], im[r][bc]] = [im[r][bc], im[r][s]];
        }
        [cols[s], cols[bc]] = [cols[bc], cols[s]];
        const dr = re[s][s], di = im[s][s], d = bv, pr = re[s], pi = im[s];
        [br, bc, bv] = [s + 1, s + 1, -1];
        for (let r = s + 1; r < 12; r++) {
            const nr = re[r][s], ni = im[r][s];
            const fr = (nr * dr + ni * di) / d;
            const fi = (ni * dr - nr * di) / d;
            re[r][s] = 0;
            im[r][s] = 0;
            for (let c = s + 1; c < 12; c++) {
                const x = re[r][c] - (fr * pr[c] - fi * pi[c]);
                const y = im[r][c] - (fr * pi[c] + fi * pr[c]);
                re[r][c] = x;
                im[r][c] = y;
                const v = x * x + y * y;
                if (v > bv) [br, bc, bv] = [r, c, v];
            }
        }
    }
    const nullity = 12 - rank;
    if (nullity === 0 || nullity >= 12 || !(first > 0 && Number.isFinite(first))) return k;
    const z = ik_gen_zeros(24, 24);
    for (let f = 0; f < nullity; f++) {
        const yr = new Array(12).fill(0), yi = new Array(12).fill(0);
        yr[rank + f] = 1;
        for (let i = rank - 1; i >= 0; i--) {
            let sr = -re[i][rank + f], si = -im[i][rank + f];
            for (let c = i + 1; c < rank; c++) {
                sr -= re[i][c] * yr[c] - im[i][c] * yi[c];
                si -= re[i][c] * yi[c] + im[i][c] * yr[c];
            }
            const dr = re[i][i], di = im[i][i], d = dr * dr + di * di;
            yr[i] = (sr * dr + si * di) / d;
            yi[i] = (si * dr - sr * di) / d;
        }
        for (let i = 0; i < 12; i++) {
            const c = cols[i];
            z[2 * f][c] = yr[i];
            z[2 * f][12 + c] = -yi[i];
            z[2 * f + 1][c] = yi[i];
            z[2 * f + 1][12 + c] = yr[i];
        }
    }
    const nz = 2 * nullity, perm = [...Array(24).keys()];
    for (let j = 0; j < nz; j++) {
        let best = j;
        for (let r = j + 1; r < 24; r++) if (Math.abs(z[j][perm[r]]) > Math.abs(z[j][perm[best]])) best = r;
        [perm[j], perm[best]] = [perm[best], perm[j]];
        const d = z[j][perm[j]];
        if (!(d !== 0 && Number.isFinite(d))) return k;
        for (let r = j + 1; r < 24; r++) {
            const pr = perm[r], f = z[j][pr] / d;
            z[j][pr] = f;
            for (let c = j + 1; c < nz; c++) z[c][pr] -= f * z[c][perm[j]];
        }
    }
    const n = 24 - nz, x = [];
    for (let i = 0; i < nz; i++) {
        const row = [...Array(n).keys()].map((c) => k[perm[i]][perm[nz + c]]);
        for (let j = 0; j < i; j++) {
            const l = z[j][perm[i]];
            for (let c = 0; c < n; c++) row[c] -= l * x[j][c];
        }
        x.push(row);
    }
    const out = [];
    for (let r = 0; r < n; r++) {
        const pr = perm[nz + r];
        const row = [...Array(n).keys()].map((c) => k[pr][perm[nz + c]]);
        for (let j = 0; j < nz; j++) {
            const l = z[j][pr];
            for (let c = 0; c < n; c++) row[c] -= l * x[j][c];
        }
        out.push(row);
    }
    return out;
}

// The eigenvalues [re, im] of the companion linearisation [[0, I], [-A^-1 C, -A^-1 B]] of
// A x^2 + B x + C (A given as its LU a, p), less the eigenvalues +-i that
// ik_gen_deflate_spurious removes; null when the QR iteration does not converge.
function ik_gen_eigen_quadratic(m, a, p) {
    const k = ik_gen_zeros(24, 24);
    for (let i = 0; i < 12; i++) k[i][12 + i] = 1;
    for (let col = 0; col < 12; col++) {
        const xc = ik_gen_lu_solve(a, p, m[0].map((row) => row[col]));
        const xb = ik_gen_lu_solve(a, p, m[1].map((row) => row[col]));
        for (let r = 0; r < 12; r++) {
            k[12 + r][col] = -xc[r];
            k[12 + r][12 + col] = -xb[r];
        }
    }
    return ik_gen_eigenvalues(ik_gen_deflate_spurious(m, k));
}

// A null vector of the 12 x 12 matrix m (Gaussian elimination with complete pivoting, the last
// pivot taken as zero).
function ik_gen_null_vector(m) {
    const a = m.map((row) => row.slice()), cols = [...Array(12).keys()];
    for (let k = 0; k < 11; k++) {
        let br = k, bc = k, bv = -1;
        for (let r = k; r < 12; r++) for (let c = k; c < 12; c++) {
            if (Math.abs(a[r][c]) > bv) [br, bc, bv] = [r, c, Math.abs(a[r][c])];
        }
        const row = a[k];
        a[k] = a[br];
        a[br] = row;
        for (const r of a) {
            const t = r[k];
            r[k] = r[bc];
            r[bc] = t;
        }
        const ck = cols[k];
        cols[k] = cols[bc];
        cols[bc] = ck;
        const d = a[k][k];
        if (d === 0) continue;
        for (let r = k + 1; r < 12; r++) {
            const f = a[r][k] / d;
            for (let c = k; c < 12; c++) a[r][c] -= f * a[k][c];
        }
    }
    const y = new Array(12).fill(0);
    y[11] = 1;
    for (let i = 10; i >= 0; i--) {
        let s = 0;
        for (let c = i + 1; c < 12; c++) s -= a[i][c] * y[c];
        y[i] = a[i][i] === 0 ? 0 : s / a[i][i];
    }
    const v = new Array(12).fill(0);
    for (let i = 0; i < 12; i++) v[cols[i]] = y[i];
    return v;
}

// An angle in (-pi, pi].
function ik_gen_wrap(a) {
    // Already in (-pi, pi]: the remainder would return it unchanged.
    if (a > -IK_GEN_PI && a <= IK_GEN_PI) return a;
    let x = a % IK_GEN_TAU;
    if (x > IK_GEN_PI) x -= IK_GEN_TAU;
    else if (x <= -IK_GEN_PI) x += IK_GEN_TAU;
    return x;
}

// 2 atan2(num, den) of the pair [num, den] of largest size.
function ik_gen_angle_from(pairs) {
    let best = [0, 1], bn = -1;
    for (const [n, d] of pairs) {
        const s = n * n + d * d;
        if (s > bn) {
            bn = s;
            best = [n, d];
        }
    }
    return ik_gen_wrap(2 * Math.atan2(best[0], best[1]));
}

// th1, th2 from Bm X12 = Am(th3) X45 by the QR of Bm, given (1, cos, sin) of th3, th4, th5.
function ik_gen_first_two(ar, el, f3, f4, f5) {
    const rhs = el.am.map((ae) => {
        let s = 0;
        for (let k = 0; k < 3; k++) for (let i4 = 0; i4 < 3; i4++) for (let i5 = 0; i5 < 3; i5++) {
            s += ae[k][ik_gen_mono(i4, i5)] * f3[k] * f4[i4] * f5[i5];
        }
        return s;
    });
    const y = el.qt.slice(0, 8).map((row) => row.reduce((s, x, e) => s + x * rhs[e], -0));
    const z = new Array(8).fill(0);
    for (let i = 7; i >= 0; i--) {
        let s = y[i];
        for (let k = i + 1; k < 8; k++) s -= el.r[i][k] * z[k];
        z[i] = el.r[i][i] === 0 ? 0 : s / el.r[i][i];
    }
    const x12 = new Array(9).fill(0);
    x12[0] = 1;
    for (let i = 0; i < 8; i++) x12[el.piv[i] + 1] = z[i];
    // A prismatic th1 or th2 is its monomial d itself.
    return [ar.j[0].prism ? x12[ik_gen_mono(1, 0)] : Math.atan2(x12[ik_gen_mono(2, 0)], x12[ik_gen_mono(1, 0)]),
        ar.j[1].prism ? x12[ik_gen_mono(0, 1)] : Math.atan2(x12[ik_gen_mono(0, 2)], x12[ik_gen_mono(0, 1)])];
}

// th6 from the rest: E6 = (E1 ... E5)^-1 H, read about its axis.
function ik_gen_last(ar, t) {
    let rot = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
    for (let k = 0; k < 5; k++) {
        if (ar.j[k].prism) continue;
        const [co, si] = ik_gen_unit(t[k]);
        const r = ik_gen_rodrigues(ar.j[k].w, si, co);
        rot = [0, 1, 2].map((i) => [0, 1, 2].map((j) =>
            -0 + rot[i][0] * r[0][j] + rot[i][1] * r[1][j] + rot[i][2] * r[2][j]));
    }
    const w6 = ar.j[5].w;
    const u = ik_gen_cross3(w6, Math.abs(w6[0]) < 0.6 ? [1, 0, 0] : [0, 1, 0]);
    // v = R6 u with R6 = rot^T R_H.
    const hu = [0, 1, 2].map((i) => -0 + ar.h[i][0] * u[0] + ar.h[i][1] * u[1] + ar.h[i][2] * u[2]);
    const v = [0, 1, 2].map((i) => -0 + rot[0][i] * hu[0] + rot[1][i] * hu[1] + rot[2][i] * hu[2]);
    return Math.atan2(ik_gen_dot3(w6, ik_gen_cross3(u, v)), ik_gen_dot3(u, v));
}

// The joints of the arranged chain at a root of det M: v the null vector of M(x) (or of S(th))
// there, th3 the hidden joint's angle phi + 2 atan x.
function ik_gen_back_substitute(ar, el, v, th3) {
    const at = (a, b) => v[3 * a + b];
    const slide = (k, t) => (ar.j[k].prism ? Math.tan(0.5 * t) : t);
    const t3 = slide(2, th3);
    const p4 = [], p5 = [];
    for (let a = 0; a < 3; a++) for (let b = 0; b < 3; b++) p4.push([at(a + 1, b), at(a, b)]);
    for (let b = 0; b < 2; b++) for (let a = 0; a < 4; a++) p5.push([at(a, b + 1), at(a, b)]);
    // A prismatic joint's variable is the tangent of the half angle these formulas give.
    const t4 = slide(3, ik_gen_angle_from(p4)), t5 = slide(4, ik_gen_angle_from(p5));
    const f = (k, t) => (ar.j[k].prism ? [1, t, t * t] : [1, ...ik_gen_unit(t)]);
    const [t1, t2] = ik_gen_first_two(ar, el, f(2, t3), f(3, t4), f(4, t5));
    const t = [t1, t2, t3, t4, t5];
    return t.concat([ik_gen_last(ar, t)]);
}

// S(th) = T0 + T1 cos th + T2 sin th: the 12 x 12 matrix of matrix_poly at phi = 0 divided by
// 1 + x^2 (see core.rs, matrix_trig).
function ik_gen_matrix_trig(sig) {
    const H = IK_GEN_HALF, out = ik_gen_zeros(3, 12, 12);
    for (let row = 0; row < 6; row++) for (let i4 = 0; i4 < 3; i4++) for (let i5 = 0; i5 < 3; i5++) {
        const m = ik_gen_mono(i4, i5);
        for (let a = 0; a < 3; a++) for (let b = 0; b < 3; b++) {
            const h = H[i4][a] * H[i5][b];
            if (h === 0) continue;
            for (let d = 0; d < 3; d++) {
                out[d][row][3 * a + b] += h * sig[d][row][m];
                out[d][row + 6][3 * (a + 1) + b] += h * sig[d][row][m];
            }
        }
    }
    return out;
}

// One step of Gaussian elimination on whole rows: the rows below k less their multiple
// m[r][k] / d of row k (the columns left of k are never read again).
function ik_gen_eliminate_rows(m, k, d) {
    for (let r = k + 1; r < 12; r++) {
        const f = m[r][k] / d;
        if (f !== 0) for (let c = 0; c < 12; c++) m[r][c] -= f * m[k][c];
    }
}

// S(th) with its columns in the order IK_GEN_DET_COLS (see core.rs, DET_COLS).
function ik_gen_trig_at_cols(t, s, c) {
    return [...Array(12).keys()].map((r) => IK_GEN_DET_COLS.map((j) =>
        t[0][r][j] + c * t[1][r][j] + s * t[2][r][j]));
}

// [det S(th), smallest pivot over the largest] (LU with partial pivoting, the columns in the
// order IK_GEN_DET_COLS).
function ik_gen_det_trig(t, s, c) {
    const m = ik_gen_trig_at_cols(t, s, c);
    let det = 1, minpiv = Infinity, maxpiv = 0;
    for (let k = 0; k < 12; k++) {
        let best = k;
        for (let r = k + 1; r < 12; r++) if (Math.abs(m[r][k]) > Math.abs(m[best][k])) best = r;
        if (best !== k) {
            [m[k], m[best]] = [m[best], m[k]];
            det = -det;
        }
        const d = m[k][k];
        det *= d;
        if (Math.abs(d) < minpiv) minpiv = Math.abs(d);
        if (Math.abs(d) > maxpiv) maxpiv = Math.abs(d);
        if (d === 0) continue;
        ik_gen_eliminate_rows(m, k, d);
    }
    return [det, maxpiv > 0 ? minpiv / maxpiv : 0];
}

// [cos d, sin d] of a small angle, |d| <= pi/64, by Taylor polynomials (see core.rs,
// cos_sin_small).
function ik_gen_cos_sin_small(d) {
    const d2 = d * d;
    const s = d * (1 + d2 * (-1 / 6 + d2 * (1 / 120 + d2 * (-1 / 5040 + d2 * (1 / 362880)))));
    const c = 1 + d2 * (-0.5 + d2 * (1 / 24 + d2 * (-1 / 720 + d2 * (1 / 40320 + d2 * (-1 / 3628800)))));
    return [c, s];
}

// [cos th, sin th] without a library call: the nearest table angle b pi/32 turned by the rest
// (see core.rs, unit).
function ik_gen_unit(th) {
    const y = th / IK_GEN_GRID_STEP + 0.5;
    let b = Math.abs(y) < 1e15 ? Math.trunc(y) : 0;
    if (b > y) b -= 1;
    const [c, s] = ik_gen_cos_sin_small((th - b * IK_GEN_GRID_STEP_HI) - b * IK_GEN_GRID_STEP_LO);
    const k = ((b % 64) + 64) % 64;
    const sb = IK_GEN_GRID_SIN[k], cb = IK_GEN_GRID_SIN[(k + 16) % 64];
    return [cb * c - sb * s, sb * c + cb * s];
}

// D(th) = Re sum_j c_j e^(i j th) and its derivatives to the seventh.
function ik_gen_trig_eval(c, th) {
    const [co, s] = ik_gen_unit(th), out = new Array(IK_GEN_TAYLOR).fill(0);
    let zr = 1, zi = 0;
    for (let j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        const re = c[j][0] * zr - c[j][1] * zi;
        const im = c[j][0] * zi + c[j][1] * zr;
        const j1 = j, j2 = j1 * j1, j3 = j2 * j1, j4 = j2 * j2;
        out[0] += re;
        out[1] -= j1 * im;
        out[2] -= j2 * re;
        out[3] += j3 * im;
        out[4] += j4 * re;
        out[5] -= j4 * j1 * im;
        out[6] -= j4 * j2 * re;
        out[7] += j4 * j3 * im;
        [zr, zi] = [zr * co - zi * s, zr * s + zi * co];
    }
    return out;
}

// [D^(k), D^(k+1), D^(k+2)] at th for k 0 or 1 (see core.rs, trig_low).
function ik_gen_trig_low(c, k, th) {
    const [co, s] = ik_gen_unit(th);
    let zr = 1, zi = 0, d0 = 0, d1 = 0, d2 = 0, d3 = 0;
    for (let j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        const re = c[j][0] * zr - c[j][1] * zi;
        const im = c[j][0] * zi + c[j][1] * zr;
        const j2 = j * j;
        d0 += re;
        d1 -= j * im;
        d2 -= j2 * re;
        d3 += j2 * j * im;
        [zr, zi] = [zr * co - zi * s, zr * s + zi * co];
    }
    return k === 0 ? [d0, d1, d2] : [d1, d2, d3];
}

// The zero of D^(k) in [a, b] (fa, fb its values at the ends, of opposite signs, 0 counted as
// positive; D^(k) monotone there): Halley's method from the secant's zero, kept inside the
// bracket.
function ik_gen_bracketed(c, k, a, b, fa, fb) {
    const negA = fa < 0;
    let x = a + (b - a) * (fa / (fa - fb));
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    for (let it = 0; it < 60; it++) {
        const [v, dv, ddv] = ik_gen_trig_low(c, k, x);
        if (v === 0) return x;
        if ((v < 0) === negA) a = x;
        else b = x;
        const next = x - 2 * v * dv / (2 * dv * dv - v * ddv);
        if (next > a && next < b) {
            if (Math.abs(next - x) <= IK_GEN_BRACKET_TOL) return next;
            x = next;
        } else {
            x = 0.5 * (a + b);
        }
        if (b - a <= IK_GEN_BRACKET_WIDTH) return x;
    }
    return x;
}

// The real roots in [0, 2 pi) of D (see core.rs, trig_roots); null when the search gives up.
function ik_gen_trig_roots(c) {
    let b0 = 0, b8 = 0;
    for (let j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        const amp = Math.hypot(c[j][0], c[j][1]), j2 = j * j;
        b0 += amp;
        b8 += j2 * j2 * j2 * j2 * amp;
    }
    const margin = IK_GEN_ROOT_MARGIN * b0, nd = IK_GEN_DET_DEGREE;
    const h = IK_GEN_TAU / IK_GEN_ROOT_GRID, top = IK_GEN_ROOT_GRID * h;
    // The end 2 pi is read as 0, so that a root there is seen the same from both sides.
    const end = (x) => (x >= top ? 0 : x);
    const at = (x) => ik_gen_trig_eval(c, end(x));
    const stack = [];
    for (let k = IK_GEN_ROOT_GRID - 1; k >= 0; k--) stack.push([k * h, (k + 1) * h]);
    const out = [];
    let evals = 0;
    // A root of the monotone D^(k) on [a, b] if its ends differ in sign, else null.
    const mono = (a, b, k) => {
        const fa = ik_gen_trig_low(c, k, end(a))[0], fb = ik_gen_trig_low(c, k, end(b))[0];
        evals += 2;
        return (fa < 0) === (fb < 0) ? null : ik_gen_bracketed(c, k, a, b, fa, fb);
    };
    while (stack.length > 0) {
        const [a, b] = stack.pop();
        const m = 0.5 * (a + b), r = 0.5 * (b - a);
        const v = at(m);
        evals += 1;
        if (evals > IK_GEN_ROOT_EVALS || out.length + 2 > 24) return null;
        const moves = [0, 0, 0];
        for (let l = 0; l < 3; l++) {
            let term = 1;
            for (let k = l + 1; k < IK_GEN_TAYLOR; k++) {
                term *= r / (k - l);
                moves[l] += Math.abs(v[k]) * term;
            }
            moves[l] += b8 * term * r / (IK_GEN_TAYLOR - l);
        }
        if (Math.abs(v[0]) > moves[0] + margin) continue;
        if (Math.abs(v[1]) > moves[1] + nd * margin) {
            const x = mono(a, b, 0);
            if (x !== null) out.push(x);
            continue;
        }
        if (Math.abs(v[2]) > moves[2] + nd * nd * margin) {
            const e = mono(a, b, 1);
            if (e === null) {
                // D' keeps its sign: D is monotone after all.
                const x = mono(a, b, 0);
                if (x !== null) out.push(x);
                continue;
            }
            const left = mono(a, e, 0), right = mono(e, b, 0);
            if (left !== null) out.push(left);
            if (right !== null) out.push(right);
            if (left === null && right === null) {
                const w = at(e);
                if (2 * Math.abs(w[0]) <= IK_GEN_NEAR_REAL * IK_GEN_NEAR_REAL * Math.abs(w[2])) out.push(e, e);
            }
            continue;
        }
        // D and D' both zero to rounding, or nothing certified at the finest width: the
        // eigenvalue route decides.
        const flat = Math.abs(v[0]) <= margin && Math.abs(v[1]) <= nd * margin;
        if (flat || r <= IK_GEN_ROOT_LEAF || stack.length + 2 > 96) return null;
        stack.push([m, b], [a, m]);
    }
    return out;
}

// A null vector of m, singular to rounding, from its LU with partial pivoting: the smallest
// pivot u_kk taken as zero, y_k = 1 and the triangle above solved (see core.rs).
function ik_gen_null_vector_lu(m0) {
    const a = m0.map((row) => row.slice());
    let kmin = 11, pmin = Infinity;
    for (let k = 0; k < 12; k++) {
        let best = k;
        for (let r = k + 1; r < 12; r++) if (Math.abs(a[r][k]) > Math.abs(a[best][k])) best = r;
        [a[k], a[best]] = [a[best], a[k]];
        const d = a[k][k];
        if (Math.abs(d) < pmin) [kmin, pmin] = [k, Math.abs(d)];
        if (d === 0) continue;
        ik_gen_eliminate_rows(a, k, d);
    }
    const y = new Array(12).fill(0);
    y[kmin] = 1;
    for (let i = kmin - 1; i >= 0; i--) {
        let s = 0;
        for (let c = i + 1; c <= kmin; c++) s -= a[i][c] * y[c];
        y[i] = a[i][i] === 0 ? 0 : s / a[i][i];
    }
    // Partial pivoting need not reveal the rank: checked by the residual, else complete
    // pivoting.
    let ms = 0, ys = 0, res = 0;
    for (let r = 0; r < 12; r++) {
        let s = 0;
        for (let c = 0; c < 12; c++) {
            s += m0[r][c] * y[c];
            if (Math.abs(m0[r][c]) > ms) ms = Math.abs(m0[r][c]);
        }
        if (Math.abs(s) > res) res = Math.abs(s);
        if (Math.abs(y[r]) > ys) ys = Math.abs(y[r]);
    }
    return res <= IK_GEN_NULL_RESIDUAL * ms * ys ? y : ik_gen_null_vector(m0);
}

// The candidates of one arrangement by the determinant route (see core.rs, det_candidates);
// null when the eigenvalue route decides; {unconditioned: best} when no sample is conditioned
// (nearly degenerate here, GaveUp::Unconditioned).
function ik_gen_det_candidates(ar, el) {
    const tm = ik_gen_matrix_trig(el.sig), N = IK_GEN_DET_SAMPLES;
    const d = [];
    let scale = 0, good = 0;
    for (let k = 0; k < N; k++) {
        // The angle 2 pi k / 17 is (2k) pi / 17 of the tables.
        const [det, ratio] = ik_gen_det_trig(tm, IK_GEN_DET_SIN[2 * k], IK_GEN_DET_COS[2 * k]);
        d.push(det);
        if (Math.abs(det) > scale) scale = Math.abs(det);
        if (ratio > good) good = ratio;
    }
    if (!(good > IK_GEN_SHIFT_GOOD && Number.isFinite(scale))) return { unconditioned: good };
    // c_j = a_j - i b_j of D(th) = a_0 + sum a_j cos j th + b_j sin j th.
    const c = [];
    for (let j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        let a = 0, b = 0;
        for (let k = 0; k < N; k++) {
            const i = 2 * ((j * k) % N);
            a += d[k] * IK_GEN_DET_COS[i];
            b += d[k] * IK_GEN_DET_SIN[i];
        }
        const w = (j === 0 ? 1 : 2) / N;
        c.push([w * a, -(w * b)]);
    }
    // The check angle pi / 17: j pi / 17 of the tables.
    let interp = 0;
    for (let j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        interp += c[j][0] * IK_GEN_DET_COS[j] - c[j][1] * IK_GEN_DET_SIN[j];
    }
    const check = ik_gen_det_trig(tm, IK_GEN_DET_SIN[1], IK_GEN_DET_COS[1])[0];
    if (!(Math.abs(check - interp) <= IK_GEN_DET_CHECK * scale)) return null;
    let deg = IK_GEN_DET_DEGREE;
    while (deg > 0 && Math.hypot(c[deg][0], c[deg][1]) <= IK_GEN_DET_TRIM * scale) deg -= 1;
    const th = ik_gen_trig_roots(c);
    if (th === null) return null;
    const roots = th.map((t3) => {
        // The null vector with the columns in the order IK_GEN_DET_COLS, put back.
        const [co, si] = ik_gen_unit(t3);
        const y = ik_gen_null_vector_lu(ik_gen_trig_at_cols(tm, si, co));
        const v = new Array(12).fill(0);
        for (let i = 0; i < 12; i++) v[IK_GEN_DET_COLS[i]] = y[i];
        const t = ik_gen_back_substitute(ar, el, v, ik_gen_wrap(t3));
        const q = new Array(6).fill(0);
        for (let i = 0; i < 6; i++) q[ar.perm[i]] = t[i];
        return q;
    });
    return { roots, degree: 2 * deg };
}

// The candidates of one arrangement by the eigenvalue route (see core.rs, eigen_candidates):
// {roots (the arm's joint vectors, not yet refined), degree}; null when A is singular at
// every shift.
function ik_gen_eigen_candidates(ar, el) {
    // The shift phi that makes A best conditioned; its matrix polynomial and A's LU are kept.
    let best = [0, -1], mp = null, lu = null, piv = null;
    for (const phi of IK_GEN_SHIFTS) {
        const mps = ik_gen_matrix_poly(el.sig, phi);
        const a = mps[2].map((row) => row.slice());
        const [p, ratio] = ik_gen_lu(a);
        if (ratio > best[1]) [best, mp, lu, piv] = [[phi, ratio], mps, a, p];
        if (ratio > IK_GEN_SHIFT_GOOD) break;
    }
    if (best[1] < IK_GEN_SHIFT_SINGULAR) return null;
    const phi = best[0];
    const ev = ik_gen_eigen_quadratic(mp, lu, piv);
    if (ev === null) return null;
    const roots = [];
    let degree = 0;
    for (const [re, im] of ev) {
        // A prismatic hidden joint's roots at infinity are no solutions.
        if (ar.j[2].prism && Math.abs(Math.tan(0.5 * phi + Math.atan(re))) > IK_GEN_PRISM_FAR) continue;
        const spurious = (Math.abs(re) + Math.abs(Math.abs(im) - 1)) < IK_GEN_SPURIOUS_TOL;
        if (Number.isFinite(re) && Number.isFinite(im) && !spurious && Math.hypot(re, im) < IK_GEN_INFINITE_ROOT) {
            degree += 1;
        }
        // A real root, or a pair split by rounding: refinement and the check decide.
        if (Math.abs(im) <= IK_GEN_NEAR_REAL * (1 + Math.abs(re)) && Number.isFinite(re)) {
            const m = [...Array(12).keys()].map((r) => [...Array(12).keys()].map((c) =>
                (mp[2][r][c] * re + mp[1][r][c]) * re + mp[0][r][c]));
            const t = ik_gen_back_substitute(ar, el, ik_gen_null_vector(m), ik_gen_wrap(phi + 2 * Math.atan(re)));
            const q = new Array(6).fill(0);
            for (let i = 0; i < 6; i++) q[ar.perm[i]] = t[i];
            roots.push(q);
        }
    }
    return { roots, degree };
}

// The pose E1(q1) ... E6(q6) M and each joint's current axis [w, p] (scaled lengths).
function ik_gen_forward(ax, home, q) {
    let p = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]];
    const cur = [];
    for (let i = 0; i < 6; i++) {
        const a = ax[i], w = a.slice(1, 4), c = a.slice(4, 7);
        const [o, d] = ik_gen_motion_apply(p, c, w);
        cur.push([...d, ...o]);
        let m;
        if (a[0] !== 0) {
            m = [0, 1, 2].map((r) => [0, 1, 2].map((k) => (r === k ? 1 : 0)).concat([q[i] * w[r]]));
        } else {
            const r = ik_gen_rodrigues(w, Math.sin(q[i]), Math.cos(q[i]));
            m = r.map((row, k) => row.concat([c[k] - ik_gen_dot3(row, c)]));
        }
        p = ik_gen_compose(p, m);
    }
    return [ik_gen_compose(p, home), cur];
}

// T - F entry by entry, and its largest size (NaN when any is).
function ik_gen_error(f, t) {
    const e = [];
    let m = 0;
    for (let r = 0; r < 3; r++) for (let c = 0; c < 4; c++) {
        const d = t[r][c] - f[r][c];
        e.push(d);
        if (Number.isNaN(d)) m = NaN;
        else if (!Number.isNaN(m)) m = ik_gen_fmax(m, Math.abs(d));
    }
    return [e, m];
}

// The Jacobian's columns (d pose / d q_i, entries as the error's) at the pose f.
function ik_gen_jacobian(ax, f, cur) {
    return cur.map(([wx, wy, wz, px, py, pz], i) => {
        const col = new Array(12).fill(0);
        const cr = (v) => [wy * v[2] - wz * v[1], wz * v[0] - wx * v[2], wx * v[1] - wy * v[0]];
        if (ax[i][0] !== 0) {
            for (let r = 0; r < 3; r++) col[4 * r + 3] = [wx, wy, wz][r];
        } else {
            const dt = cr([f[0][3] - px, f[1][3] - py, f[2][3] - pz]);
            for (let k = 0; k < 3; k++) {
                const d = cr([f[0][k], f[1][k], f[2][k]]);
                for (let r = 0; r < 3; r++) col[4 * r + k] = d[r];
            }
            for (let r = 0; r < 3; r++) col[4 * r + 3] = dt[r];
        }
        return col;
    });
}

// Damped Gauss-Newton from q on the pose residual (scaled lengths): [q, residual].
function ik_gen_refine(ax, home, t, q) {
    let [f, cur] = ik_gen_forward(ax, home, q);
    let [e, res] = ik_gen_error(f, t);
    let lambda = IK_GEN_DAMP_START;
    for (let it = 0; it < IK_GEN_REFINE_ITERS; it++) {
        if (res <= IK_GEN_EXACT_TOL || Number.isNaN(res)) break;
        const cols = ik_gen_jacobian(ax, f, cur);
        const dot = (u, v) => u.reduce((s, x, k) => s + x * v[k], -0);
        const a = cols.map((ci) => cols.map((cj) => dot(ci, cj)));
        const g = cols.map((ci) => dot(ci, e));
        let tr = 0;
        for (let i = 0; i < 6; i++) tr += a[i][i];
        for (;;) {
            const m = a.map((row, i) => row.map((x, j) =>
                (i === j ? x + lambda * ik_gen_fmax(tr, IK_GEN_MIN_POSITIVE) : x)));
            const [p, ratio] = ik_gen_lu(m);
            if (ratio > 0 && Number.isFinite(ratio)) {
                const d = ik_gen_lu_solve(m, p, g);
                const next = q.map((x, i) => x + d[i]);
                const [f2, cur2] = ik_gen_forward(ax, home, next);
                const [e2, r2] = ik_gen_error(f2, t);
                if (r2 < res) {
                    [q, f, cur, e, res] = [next, f2, cur2, e2, r2];
                    lambda = ik_gen_fmax(lambda * 0.01, IK_GEN_DAMP_MIN);
                    break;
                }
            }
            lambda *= 100;
            if (lambda > IK_GEN_DAMP_MAX) return [q, res];
        }
    }
    return [q, res];
}

// Two joint vectors within radius of each other in every joint (angles compared on the circle).
function ik_gen_same(a, b, prismatic, radius) {
    return a.every((x, i) => Math.abs(prismatic[i] ? x - b[i] : ik_gen_wrap(x - b[i])) <= radius);
}

// Drops each solution of out that repeats another at its residual (core.rs, merge_repeats):
// one whose residual r is above IK_GEN_EXACT_TOL and that lies within IK_GEN_FOLD_REACH
// sqrt(r) of a solution of smaller residual (of equal residual and earlier).
function ik_gen_merge_repeats(out, prismatic) {
    for (let i = out.q.length - 1; i >= 0; i--) {
        const r = out.residual[i];
        if (r <= IK_GEN_EXACT_TOL) continue;
        const radius = IK_GEN_FOLD_REACH * Math.sqrt(r);
        const repeats = out.q.some((s, j) => {
            const rj = out.residual[j];
            return j !== i && (rj < r || (rj === r && j < i)) && ik_gen_same(s, out.q[i], prismatic, radius);
        });
        if (repeats) {
            out.q.splice(i, 1);
            out.residual.splice(i, 1);
        }
    }
}

// Adds the refined candidate q (residual res) to out, or improves the solution it repeats;
// returns its index, -1 when out is full.
function ik_gen_add(out, q, res, prismatic) {
    const at = out.q.findIndex((s) => ik_gen_same(s, q, prismatic, IK_GEN_SAME_TOL));
    if (at >= 0) {
        if (res < out.residual[at]) [out.q[at], out.residual[at]] = [q, res];
        return at;
    }
    if (out.q.length >= IK_GEN_MAX) return -1;
    out.q.push(q);
    out.residual.push(res);
    return out.q.length - 1;
}

// The chain and the target in the core's units (every length over the scale len): {ax, hm, tg
// (the target's top rows), prismatic, g = T M^-1, js (the joints)}.
function ik_gen_scale(axes, home, target, len) {
    const ax = axes.map((a) => a.map((x, k) => (k >= 4 ? x / len : x)));
    const hm = home.slice(0, 3).map((r) => r.map((x, c) => (c === 3 ? x / len : x)));
    const tg = target.slice(0, 3).map((r) => r.map((x, c) => (c === 3 ? x / len : x)));
    const prismatic = ax.map((a) => a[0] !== 0);
    const g = ik_gen_compose(tg, ik_gen_inverse(hm));
    const js = ax.map((a, i) => ({ w: a.slice(1, 4), c: a.slice(4, 7), prism: prismatic[i] }));
    return { ax, hm, tg, prismatic, g, js };
}

// Every solution of E1 ... E6 M = T for a 6R chain (axes [kind, w, p], home, target; lengths
// in the robot's, len its scale): {q, residual, degree, arrangements}, the arrangements tried
// from first on until one's roots all gave exact solutions of their own.
function ik_gen_solve(axes, home, target, len, tol, first) {
    const out = { q: [], residual: [], degree: 0, arrangements: [] };
    const { ax, hm, tg, prismatic, g, js } = ik_gen_scale(axes, home, target, len);
    // Refines the candidates of arrangement arr, adds the solutions; whether the set is
    // complete (every root gave its own exact solution).
    const take = (cand, arr) => {
        if (out.arrangements.length === 0) out.degree = cand.degree;
        out.arrangements.push(arr);
        const hit = new Set();
        for (const q0 of cand.roots) {
            let [q, res] = ik_gen_refine(ax, hm, tg, q0);
            if (Number.isNaN(res) || res > tol.keep) continue;
            q = q.map((x, i) => (prismatic[i] ? x : ik_gen_wrap(x)));
            const at = ik_gen_add(out, q, res, prismatic);
            if (at >= 0 && res <= tol.pose) hit.add(at);
        }
        return hit.size === cand.roots.length;
    };
    // The eigenvalue route of the first arrangement whose determinant route gives up waits for
    // the next arrangement's determinant route (see core.rs, gen_solve).
    let deferred = null, complete = false;
    // The arrangements whose determinant route found no conditioned sample: {good, arr}.
    const unconditioned = [];
    const f0 = first % 12;
    for (let k = 0; k < 12; k++) {
        const arr = k === 0 ? f0 : k <= f0 ? k - 1 : k;
        const ar = ik_gen_arrange(js, g, arr);
        // The last arranged joint is eliminated by a point of its axis, which a slide moves.
        if (prismatic[ar.perm[5]]) continue;
        const el = ik_gen_eliminate(ar);
        if (el.rank_ratio < IK_GEN_RANK_TOL) continue;
        let cand = ar.j[2].prism ? null : ik_gen_det_candidates(ar, el);
        if (cand !== null && cand.unconditioned !== undefined) {
            // Nearly degenerate here: kept for the end.
            unconditioned.push({ good: cand.unconditioned, arr });
            continue;
        }
        if (cand === null) {
            if (!ar.j[2].prism && deferred === null) {
                deferred = { ar, el, arr };
                continue;
            }
            if (deferred !== null) {
                const d = deferred;
                deferred = null;
                const dc = ik_gen_eigen_candidates(d.ar, d.el);
                if (dc !== null) {
                    complete = take(dc, d.arr);
                    if (complete) break;
                }
            }
            cand = ik_gen_eigen_candidates(ar, el);
        }
        if (cand === null) continue;
        complete = take(cand, arr);
        if (complete) break;
    }
    if (deferred !== null && !complete) {
        const dc = ik_gen_eigen_candidates(deferred.ar, deferred.el);
        if (dc !== null) complete = take(dc, deferred.arr);
    }
    // Still incomplete: the nearly degenerate arrangements' eigenvalue routes, the best
    // conditioned first (in the order tried among equals: the sort is stable).
    unconditioned.sort((a, b) => b.good - a.good);
    for (const u of unconditioned) {
        if (complete) break;
        const ar = ik_gen_arrange(js, g, u.arr);
        const cand = ik_gen_eigen_candidates(ar, ik_gen_eliminate(ar));
        if (cand !== null) complete = take(cand, u.arr);
    }
    ik_gen_merge_repeats(out, prismatic);
    // Prismatic variables back in the robot's length unit.
    out.q = out.q.map((q) => q.map((x, i) => (prismatic[i] ? x * len : x)));
    return out;
}

// Balancing (Parlett-Reinsch, powers of two).
function ik_gen_balance(a) {
    const RADIX = 2, n = a.length;
    let done = false, sweeps = 0;
    while (!done && sweeps < 100) {
        done = true;
        sweeps += 1;
        for (let i = 0; i < n; i++) {
            let c = 0, r = 0;
            for (let j = 0; j < n; j++) {
                if (j !== i) {
                    c += Math.abs(a[j][i]);
                    r += Math.abs(a[i][j]);
                }
            }
            if (c === 0 || r === 0 || !Number.isFinite(c + r)) continue;
            const s = c + r;
            let f = 1, g = r / RADIX;
            while (c < g) {
                f *= RADIX;
                c *= RADIX * RADIX;
            }
            g = r * RADIX;
            while (c > g) {
                f /= RADIX;
                c /= RADIX * RADIX;
            }
            if ((c + r) / f < 0.95 * s) {
                done = false;
                const gi = 1 / f;
                for (let j = 0; j < n; j++) a[i][j] *= gi;
                for (let j = 0; j < n; j++) a[j][i] *= f;
            }
        }
    }
}

// Reduction to upper Hessenberg form by stabilised elementary similarity transformations.
function ik_gen_hessenberg(a) {
    const n = a.length;
    for (let m = 1; m < n - 1; m++) {
        let x = 0, i = m;
        for (let j = m; j < n; j++) {
            if (Math.abs(a[j][m - 1]) > Math.abs(x)) {
                x = a[j][m - 1];
                i = j;
            }
        }
        if (i !== m) {
            for (let j = m - 1; j < n; j++) [a[i][j], a[m][j]] = [a[m][j], a[i][j]];
            for (let j = 0; j < n; j++) [a[j][i], a[j][m]] = [a[j][m], a[j][i]];
        }
        if (x !== 0) {
            for (let ii = m + 1; ii < n; ii++) {
                let y = a[ii][m - 1];
                if (y !== 0) {
                    y /= x;
                    a[ii][m - 1] = 0;
                    for (let j = m; j < n; j++) a[ii][j] -= y * a[m][j];
                    for (let j = 0; j < n; j++) a[j][m] += y * a[j][ii];
                }
            }
        }
    }
}

// One Francis double-shift QR sweep of rows and columns l..nn (1-based, A(i, j) = a[i-1][j-1])
// from row m with the shift's (p, q, r): the classical hqr's inner loop.
function ik_gen_qr_sweep(a, l, m, nn, p, q, r) {
    const A = (i, j) => a[i - 1][j - 1];
    const set = (i, j, v) => { a[i - 1][j - 1] = v; };
    let x = 0, y, z;
    for (let i = m + 2; i <= nn; i++) {
        set(i, i - 2, 0);
        if (i !== m + 2) set(i, i - 3, 0);
    }
    for (let k = m; k < nn; k++) {
        if (k !== m) {
            p = A(k, k - 1);
            q = A(k + 1, k - 1);
            r = 0;
            if (k !== nn - 1) r = A(k + 2, k - 1);
            x = Math.abs(p) + Math.abs(q) + Math.abs(r);
            if (x !== 0) {
                p /= x;
                q /= x;
                r /= x;
            }
        }
        const norm = Math.sqrt(p * p + q * q + r * r);
        const s = p >= 0 ? norm : -norm;
        if (s === 0) continue;
        if (k === m) {
            if (l !== m) set(k, k - 1, -A(k, k - 1));
        } else {
            set(k, k - 1, -s * x);
        }
        p += s;
        x = p / s;
        y = q / s;
        z = r / s;
        q /= p;
        r /= p;
        for (let j = k; j <= nn; j++) {
            p = A(k, j) + q * A(k + 1, j);
            if (k !== nn - 1) {
                p += r * A(k + 2, j);
                set(k + 2, j, A(k + 2, j) - p * z);
            }
            set(k + 1, j, A(k + 1, j) - p * y);
            set(k, j, A(k, j) - p * x);
        }
        const mmin = nn < k + 3 ? nn : k + 3;
        for (let i = l; i <= mmin; i++) {
            p = x * A(i, k) + y * A(i, k + 1);
            if (k !== nn - 1) {
                p += z * A(i, k + 2);
                set(i, k + 2, A(i, k + 2) - p * r);
            }
            set(i, k + 1, A(i, k + 1) - p * q);
            set(i, k, A(i, k) - p);
        }
    }
}

// The eigenvalues [re, im] of a real square matrix (destroyed): balancing, Hessenberg
// reduction and the Francis double-shift QR iteration (the classical hqr, 1-based indices);
// null when an eigenvalue takes more than 60 iterations.
function ik_gen_eigenvalues(a) {
    ik_gen_balance(a);
    ik_gen_hessenberg(a);
    const n = a.length;
    const A = (i, j) => a[i - 1][j - 1];
    const set = (i, j, v) => { a[i - 1][j - 1] = v; };
    const wr = new Array(n).fill(0), wi = new Array(n).fill(0);
    let anorm = 0;
    for (let i = 1; i <= n; i++) for (let j = Math.max(i - 1, 1); j <= n; j++) anorm += Math.abs(A(i, j));
    if (!Number.isFinite(anorm)) return null;
    let nn = n, t = 0, p = 0, q = 0, r = 0, s, w, x, y, z;
    while (nn >= 1) {
        let its = 0;
        for (;;) {
            let l;
            for (l = nn; l >= 2; l--) {
                s = Math.abs(A(l - 1, l - 1)) + Math.abs(A(l, l));
                if (s === 0) s = anorm;
                if (Math.abs(A(l, l - 1)) + s === s) {
                    set(l, l - 1, 0);
                    break;
                }
            }
            x = A(nn, nn);
            if (l === nn) {
                wr[nn - 1] = x + t;
                wi[nn - 1] = 0;
                nn -= 1;
                break;
            }
            y = A(nn - 1, nn - 1);
            w = A(nn, nn - 1) * A(nn - 1, nn);
            if (l === nn - 1) {
                p = 0.5 * (y - x);
                q = p * p + w;
                z = Math.sqrt(Math.abs(q));
                x += t;
                const i1 = nn - 2, i2 = nn - 1;
                if (q >= 0) {
                    z = p + (p >= 0 ? z : -z);
                    wr[i1] = x + z;
                    wr[i2] = x + z;
                    if (z !== 0) wr[i2] = x - w / z;
                    wi[i1] = 0;
                    wi[i2] = 0;
                } else {
                    wr[i1] = x + p;
                    wr[i2] = x + p;
                    wi[i1] = -z;
                    wi[i2] = z;
                }
                nn -= 2;
                break;
            }
            if (its === 60) return null;
            if (its === 10 || its === 20 || its === 40) {
                // An exceptional shift.
                t += x;
                for (let i = 1; i <= nn; i++) set(i, i, A(i, i) - x);
                s = Math.abs(A(nn, nn - 1)) + Math.abs(A(nn - 1, nn - 2));
                x = 0.75 * s;
                y = x;
                w = -0.4375 * s * s;
            }
            its += 1;
            let m;
            for (m = nn - 2; m >= l; m--) {
                z = A(m, m);
                r = x - z;
                s = y - z;
                p = (r * s - w) / A(m + 1, m) + A(m, m + 1);
                q = A(m + 1, m + 1) - z - r - s;
                r = A(m + 2, m + 1);
                s = Math.abs(p) + Math.abs(q) + Math.abs(r);
                p /= s;
                q /= s;
                r /= s;
                if (m === l) break;
                const u = Math.abs(A(m, m - 1)) * (Math.abs(q) + Math.abs(r));
                const v = Math.abs(p) * (Math.abs(A(m - 1, m - 1)) + Math.abs(z) + Math.abs(A(m + 1, m + 1)));
                if (u + v === v) break;
            }
            ik_gen_qr_sweep(a, l, m, nn, p, q, r);
            if (l >= nn - 1) break;
        }
    }
    return wr.map((re, i) => [re, wi[i]]);
}
