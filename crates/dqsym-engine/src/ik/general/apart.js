// The numeric core of a 4R2P chain with its slides three joints apart in JavaScript (the IK
// page's live table): a port of apart_solver.rs (orientation by the four turns, position by the
// slides' plane, the resultant D(theta4) of degree 8), function by function, after core.js,
// whose helpers it uses. The canonical chain is Tr(d0 v0) E1 E2 Tr(d3 v3) E4 E5 = H (see
// apart_solver.rs). Matrices are arrays of rows.

function ik_gen_apart_mt(r) {
    return [0, 1, 2].map((i) => [r[0][i], r[1][i], r[2][i]]);
}

function ik_gen_apart_mm(a, b) {
    return [0, 1, 2].map((i) => [0, 1, 2].map((j) => -0 + a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j]));
}

function ik_gen_apart_sub(a, b) {
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
}

function ik_gen_apart_scaled(f, v) {
    return [f * v[0], f * v[1], f * v[2]];
}

// The chain of the arrangement ar: {ar, rh, h, k12, a, na}; null when turns 1 and 2 are about
// parallel axes (this reading cannot serve).
function ik_gen_apart_new(ar) {
    const w1 = ar.j[1].w, w2 = ar.j[2].w;
    const k12 = ik_gen_dot3(w1, w2);
    const a = ik_gen_apart_sub(w2, ik_gen_apart_scaled(k12, w1));
    const na = ik_gen_dot3(a, a);
    if (!(na > IK_GEN_APART_PARALLEL)) return null;
    return { ar, rh: ar.h.map((row) => row.slice(0, 3)), h: ar.h.map((row) => row[3]), k12, a, na };
}

function ik_gen_apart_rot(ch, i, th) {
    return ik_gen_rodrigues(ch.ar.j[i].w, Math.sin(th), Math.cos(th));
}

// Q = R_H R5^T R4^T.
function ik_gen_apart_q(ch, t4, t5) {
    const m = ik_gen_apart_mm(ch.rh, ik_gen_apart_mt(ik_gen_apart_rot(ch, 5, t5)));
    return ik_gen_apart_mm(m, ik_gen_apart_mt(ik_gen_apart_rot(ch, 4, t4)));
}

// [cos th1, sin th1] as subproblem 1 gives them, linear in Q.
function ik_gen_apart_cs1(ch, q) {
    const w1 = ch.ar.j[1].w;
    const b = ik_gen_apart_sub(ik_gen_mv(q, ch.ar.j[2].w), ik_gen_apart_scaled(ch.k12, w1));
    return [ik_gen_dot3(ch.a, b) / ch.na, ik_gen_dot3(w1, ik_gen_cross3(ch.a, b)) / ch.na];
}

// [h - t(E1 E2 E4 E5), Q v3] with R1 from (c1, s1).
function ik_gen_apart_reach(ch, t4, t5, q, c1, s1) {
    const j = ch.ar.j, sub = ik_gen_apart_sub, mv = ik_gen_mv;
    const r1 = ik_gen_rodrigues(j[1].w, s1, c1);
    const r4 = ik_gen_apart_rot(ch, 4, t4), r5 = ik_gen_apart_rot(ch, 5, t5);
    const t1 = sub(j[1].c, mv(r1, j[1].c));
    const t2 = sub(mv(r1, j[2].c), mv(q, j[2].c));
    const t4v = mv(q, sub(j[4].c, mv(r4, j[4].c)));
    const t5v = mv(ch.rh, sub(mv(ik_gen_apart_mt(r5), j[5].c), j[5].c));
    const t = [0, 1, 2].map((i) => (t1[i] + t2[i]) + (t4v[i] + t5v[i]));
    return [sub(ch.h, t), mv(q, j[3].w)];
}

// [F, P, size of P's terms] at (th4, th5).
function ik_gen_apart_fp(ch, t4, t5) {
    const q = ik_gen_apart_q(ch, t4, t5);
    const [c1, s1] = ik_gen_apart_cs1(ch, q);
    const [r, u] = ik_gen_apart_reach(ch, t4, t5, q, c1, s1);
    const n = ik_gen_cross3(ch.ar.j[0].w, u);
    const f = ik_gen_dot3(ch.ar.j[1].w, ik_gen_mv(q, ch.ar.j[2].w)) - ch.k12;
    return [f, ik_gen_dot3(n, r), Math.sqrt(ik_gen_dot3(n, n)) * Math.sqrt(ik_gen_dot3(r, r)) + IK_GEN_MIN_POSITIVE];
}

// F's coefficients [1, cos th5, sin th5] at th4, from three samples.
function ik_gen_apart_fcoef(ch, t4) {
    let f0 = 0, fc = 0, fs = 0;
    for (let k = 0; k < 3; k++) {
        const th = IK_GEN_TAU * k / 3;
        const v = ik_gen_apart_fp(ch, t4, th)[0];
        f0 += v / 3;
        fc += 2 * v * Math.cos(th) / 3;
        fs += 2 * v * Math.sin(th) / 3;
    }
    return [f0, fc, fs];
}

// D(th4), the determinant of the Sylvester matrix of (1 + x^2) F and (1 + x^2)^2 P in x =
// tan(th5/2), and how well its LU is conditioned: [d, ratio].
function ik_gen_apart_resultant(ch, t4) {
    const [f0, fc, fs] = ik_gen_apart_fcoef(ch, t4);
    const pc = [0, 0, 0, 0, 0];
    for (let k = 0; k < 5; k++) {
        const th = IK_GEN_TAU * k / 5;
        const v = ik_gen_apart_fp(ch, t4, th)[1];
        pc[0] += v / 5;
        for (let m = 1; m < 3; m++) {
            pc[2 * m - 1] += 2 * v * Math.cos(m * th) / 5;
            pc[2 * m] += 2 * v * Math.sin(m * th) / 5;
        }
    }
    const [p0, c1, s1, c2, s2] = pc;
    const f = [f0 + fc, 2 * fs, f0 - fc];
    const p = [p0 + c1 + c2, 2 * s1 + 4 * s2, 2 * p0 - 6 * c2, 2 * s1 - 4 * s2, p0 - c1 + c2];
    const s = ik_gen_zeros(6, 6);
    for (let i = 0; i < 4; i++) for (let k = 0; k < 3; k++) s[i][i + k] = f[k];
    for (let i = 0; i < 2; i++) for (let k = 0; k < 5; k++) s[4 + i][i + k] = p[k];
    const [perm, ratio] = ik_gen_lu(s);
    let d = 1;
    for (let i = 0; i < 6; i++) d *= s[i][i];
    // The sign of the row permutation.
    const seen = new Array(6).fill(false);
    for (let i = 0; i < 6; i++) {
        if (seen[i]) continue;
        let len = 0;
        for (let k = i; !seen[k]; k = perm[k], len++) seen[k] = true;
        if (len % 2 === 0) d = -d;
    }
    return [d, ratio];
}

// The trigonometric coefficients [a, b] of D; null when the check angle disagrees or no sample
// is conditioned.
function ik_gen_apart_coefficients(ch) {
    const n = IK_GEN_DET_SAMPLES, step = IK_GEN_TAU / n, half = 0.5 * step;
    const d = [];
    let scale = 0, good = 0;
    for (let k = 0; k < n; k++) {
        const [v, ratio] = ik_gen_apart_resultant(ch, k * step);
        d.push(v);
        scale = ik_gen_fmax(scale, Math.abs(v));
        good = ik_gen_fmax(good, ratio);
    }
    if (!(good > IK_GEN_SHIFT_GOOD && Number.isFinite(scale))) return null;
    const c = [];
    for (let j = 0; j <= IK_GEN_DET_DEGREE; j++) {
        let a = 0, b = 0;
        for (let k = 0; k < n; k++) {
            a += d[k] * Math.cos(j * k * step);
            b += d[k] * Math.sin(j * k * step);
        }
        const w = (j === 0 ? 1 : 2) / n;
        c.push([w * a, -(w * b)]);
    }
    let interp = -0;
    for (let j = 0; j <= IK_GEN_DET_DEGREE; j++) interp += c[j][0] * Math.cos(j * half) - c[j][1] * Math.sin(j * half);
    return Math.abs(ik_gen_apart_resultant(ch, half)[0] - interp) <= IK_GEN_DET_CHECK * scale ? c : null;
}

// Every joint (arranged order) from th4, th5.
function ik_gen_apart_joints(ch, t4, t5) {
    const w1 = ch.ar.j[1].w, w2 = ch.ar.j[2].w, v0 = ch.ar.j[0].w;
    const q = ik_gen_apart_q(ch, t4, t5);
    const [c1, s1] = ik_gen_apart_cs1(ch, q);
    const t1 = Math.atan2(s1, c1);
    const kw = ik_gen_apart_scaled(ch.k12, w2);
    const a2 = ik_gen_apart_sub(ik_gen_mv(ik_gen_apart_mt(q), w1), kw);
    const b2 = ik_gen_apart_sub(w1, kw);
    const t2 = Math.atan2(ik_gen_dot3(w2, ik_gen_cross3(a2, b2)), ik_gen_dot3(a2, b2));
    const [r, u] = ik_gen_apart_reach(ch, t4, t5, q, Math.cos(t1), Math.sin(t1));
    // Least squares of r = d0 v0 + d3 u (unit directions): the normal equations; where they
    // degenerate (a line of solutions), the one with d3 = 0.
    const k = ik_gen_dot3(v0, u), det = 1 - k * k;
    const r0 = ik_gen_dot3(v0, r), ru = ik_gen_dot3(u, r);
    const singular = !(det > IK_GEN_APART_PARALLEL);
    const [d0, d3] = singular ? [r0, 0] : [(r0 - k * ru) / det, (ru - k * r0) / det];
    return [d0, t1, t2, d3, t4, t5];
}

// The joints (arranged order) at a root th4: one or two candidates (the roots of F = 0 in th5
// where P vanishes).
function ik_gen_apart_back(ch, t4) {
    const [f0, fc, fs] = ik_gen_apart_fcoef(ch, t4);
    const rho = Math.hypot(fc, fs);
    const flat = rho <= Math.sqrt(IK_GEN_APART_PARALLEL) * (rho + Math.abs(f0) + IK_GEN_MIN_POSITIVE);
    const base = Math.atan2(fs, fc);
    const spread = flat ? 0 : Math.acos(Math.min(1, Math.max(-1, -f0 / rho)));
    const cands = [base + spread, base - spread];
    const ps = cands.map((t) => ik_gen_apart_fp(ch, t4, t));
    const best = Math.abs(ps[1][1]) < Math.abs(ps[0][1]) ? 1 : 0;
    const out = [];
    for (const i of [best, 1 - best]) {
        const ok = i === best || Math.abs(ps[i][1]) <= IK_GEN_APART_P_TOL * ps[i][2];
        if (ok && (out.length === 0 || spread > 0)) out.push(ik_gen_apart_joints(ch, t4, cands[i]));
    }
    return out;
}

// The real roots of D where the certified search gives up (see apart_solver.rs,
// apart_eigen_roots): the eigenvalues of the companion matrix of D in x = tan((th - phi)/2);
// null when D vanishes to rounding or the QR iteration does not converge.
function ik_gen_apart_eigen_roots(c) {
    let b0 = 0;
    for (const [a, b] of c) b0 += Math.hypot(a, b);
    let n = IK_GEN_DET_DEGREE;
    while (n > 0 && Math.hypot(c[n][0], c[n][1]) <= IK_GEN_DET_TRIM * b0) n -= 1;
    if (!(b0 > 0 && Number.isFinite(b0))) return null;
    // A nonzero constant: no root.
    if (n === 0) return [];
    // The shift: |D(phi + pi)| large.
    let best = [0, -1];
    for (const phi of IK_GEN_SHIFTS) {
        let lead = 0;
        for (let j = 0; j <= n; j++) {
            const re = c[j][0] * Math.cos(j * phi) - c[j][1] * Math.sin(j * phi);
            lead += j % 2 === 0 ? re : -re;
        }
        const ratio = Math.abs(lead) / b0;
        if (ratio > best[1]) best = [phi, ratio];
        if (ratio > IK_GEN_SHIFT_GOOD) break;
    }
    if (!(best[1] > 0)) return null;
    const phi = best[0], m = 2 * n;
    // The polynomial's coefficients (ascending): (1 + ix)^(n+j) (1 - ix)^(n-j) expanded, its
    // product with c_j e^(ij phi) taken real.
    const p = new Array(m + 1).fill(0);
    for (let j = 0; j <= n; j++) {
        const s = Math.sin(j * phi), co = Math.cos(j * phi);
        const a = c[j][0] * co - c[j][1] * s, b = c[j][0] * s + c[j][1] * co;
        const pr = new Array(m + 1).fill(0), pi = new Array(m + 1).fill(0);
        pr[0] = 1;
        for (let k = 0; k < m; k++) {
            const sg = k < n + j ? 1 : -1;
            for (let l = k + 1; l >= 1; l--) {
                const r0 = pr[l], i0 = pi[l];
                pr[l] = r0 - sg * pi[l - 1];
                pi[l] = i0 + sg * pr[l - 1];
            }
        }
        for (let l = 0; l <= m; l++) p[l] += a * pr[l] - b * pi[l];
    }
    // The companion matrix of the monic polynomial.
    const k = ik_gen_zeros(m, m);
    for (let l = 0; l < m; l++) k[0][l] = -p[m - 1 - l] / p[m];
    for (let l = 1; l < m; l++) k[l][l - 1] = 1;
    const ev = ik_gen_eigenvalues(k);
    if (ev === null) return null;
    return ev.filter(([re, im]) => Math.abs(im) <= IK_GEN_NEAR_REAL * (1 + Math.abs(re)) && Number.isFinite(re))
        .map(([re]) => phi + 2 * Math.atan(re));
}

// The two slides three joints apart: the arrangements (shift + 6 reversed) that put them at
// arranged joints 0 and 3, forwards and backwards; null for any other chain.
function ik_gen_apart_arrangements(prismatic) {
    const s = [0, 1, 2, 3, 4, 5].filter((i) => prismatic[i]);
    if (s.length !== 2 || s[1] - s[0] !== 3) return null;
    return [s[0], 6 + (5 - s[1])];
}

// Every solution of a 4R2P chain with its slides three joints apart (see apart_solver.rs,
// apart_solve), as ik_gen_solve returns them (first unused): both readings by the certified
// search, then, where it gave up in both, by the companion matrix; the backward reading only
// when a root of the forward one gave no new exact solution.
// The tests' hook: the eigenvalue route only (apart_solve_by's eigen_only) when set.
let ik_gen_apart_eigen_only = false;

function ik_gen_apart_solve(axes, home, target, len, tol, first) {
    const out = { q: [], residual: [], degree: 0, arrangements: [] };
    const { ax, hm, tg, prismatic, g, js } = ik_gen_scale(axes, home, target, len);
    const arrs = ik_gen_apart_arrangements(prismatic);
    if (arrs === null) return out;
    let searched = false;
    for (const [eigen, arr] of [[false, arrs[0]], [false, arrs[1]], [true, arrs[0]], [true, arrs[1]]]) {
        if ((eigen && searched) || (ik_gen_apart_eigen_only && !eigen)) continue;
        const ch = ik_gen_apart_new(ik_gen_arrange(js, g, arr));
        if (ch === null) continue;
        const c = ik_gen_apart_coefficients(ch);
        if (c === null) continue;
        const th = eigen ? ik_gen_apart_eigen_roots(c) : ik_gen_trig_roots(c);
        if (th === null) continue;
        searched = searched || !eigen;
        if (out.arrangements.length === 0) out.degree = 2 * IK_GEN_DET_DEGREE;
        out.arrangements.push(arr);
        const hit = new Set();
        let roots = 0;
        for (const t4 of th) {
            const cands = ik_gen_apart_back(ch, t4);
            roots += cands.length;
            for (const qa of cands) {
                const q0 = new Array(6).fill(0);
                for (let i = 0; i < 6; i++) q0[ch.ar.perm[i]] = qa[i];
                let [q, res] = ik_gen_refine(ax, hm, tg, q0);
                if (Number.isNaN(res) || res > tol.keep) continue;
                q = q.map((x, i) => (prismatic[i] ? x : ik_gen_wrap(x)));
                const at = ik_gen_add(out, q, res, prismatic);
                if (at >= 0 && res <= tol.pose) hit.add(at);
            }
        }
        if (hit.size === roots) break;
    }
    // Prismatic variables back in the robot's length unit.
    out.q = out.q.map((q) => q.map((x, i) => (prismatic[i] ? x * len : x)));
    return out;
}
