//@ ik_cands: always
// The candidates of one step from its parts v (rounded by sg): [value, singular, checked,
// sampled] each.
function ik_cands(kind, v, sg) {
    const any = (first) => {
        const out = [];
        for (let k = -5; k <= 6; k++) out.push([k * Math.PI / 6, true, true, first]);
        return out;
    };
    const radicand = (rad, n, nu) => {
        if (rad < -IK_REACH_TOL * n - nu) return null;
        if (rad <= nu) return [0, true, true];
        return [rad, false, nu * nu > 4 * IK_CHECK_TOL * IK_CHECK_TOL * rad * n];
    };
    if (kind === "atan2") {
        const [y, x] = v, h2 = y * y + x * x;
        if (h2 <= sg * sg) {
            return (h2 > 0 ? [[Math.atan2(y, x), true, true, false]] : []).concat(any(h2 > 0));
        }
        return [[Math.atan2(y, x), false, sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2, false]];
    }
    if (kind === "value") return [[v[0], false, false, false]];
    if (kind === "linear") {
        // a q = b, q a length: b rounded by sg = IK_ZERO_TOL L, a dimensionless (rounded by
        // IK_ZERO_TOL); singular where |a| <= IK_ZERO_TOL (b / a kept while a != 0).
        const [a, b] = v, q = a === 0 ? 0 : b / a;
        if (Math.abs(a) <= IK_ZERO_TOL) return [[q, true, true, false]];
        return [[q, false, (sg + Math.abs(q) * IK_ZERO_TOL) / Math.abs(a) * IK_ZERO_TOL > IK_CHECK_TOL * sg, false]];
    }
    if (kind === "trig") {
        const [a, b, c] = v, n = a * a + b * b;
        if (n <= sg * sg) return Math.abs(c) <= sg ? [[0, true, true, false]] : [];
        const nu = 2 * sg * (Math.abs(a) + Math.abs(b) + Math.abs(c)) + 4 * IK_EPS * n;
        const r = radicand(n - c * c, n, nu);
        if (r === null) return [];
        // atan2(b, a) +- atan2(w, c) as atan2(b c +- a w, a c -+ b w), as the solvers do.
        const w = Math.sqrt(r[0]);
        if (r[1]) {
            // Beside the double root, the pair of the radicand nu (sampled: kept where
            // refinement takes it onto the pose).
            const e = Math.sqrt(nu);
            return [[Math.atan2(b * c, a * c), true, true, false],
                [Math.atan2(b * c + a * e, a * c - b * e), true, true, true],
                [Math.atan2(b * c - a * e, a * c + b * e), true, true, true]];
        }
        return [[Math.atan2(b * c + a * w, a * c - b * w), r[1], r[2], false],
            [Math.atan2(b * c - a * w, a * c + b * w), r[1], r[2], false]];
    }
    const [b, g] = v, s = Math.max(Math.abs(b), Math.sqrt(Math.abs(g)));
    const nu = sg + 2 * Math.sqrt(sg * IK_ZERO_TOL) * (2 * Math.abs(b) + s) + 4 * IK_EPS * (b * b + Math.abs(g));
    const r = radicand(b * b - g, Math.max(b * b, Math.abs(g)), nu);
    if (r === null) return [];
    const w = Math.sqrt(r[0]);
    return [[-b + w, r[1], r[2], false], [-b - w, r[1], r[2], false]];
}

//@ ik_scale: always
// The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
// position or the target position.
function ik_scale(ax, home, T) {
    const n1 = (v) => Math.abs(v[0]) + Math.abs(v[1]) + Math.abs(v[2]);
    let l = Math.max(n1(home.map((r) => r[3])), n1(T.map((r) => r[3])));
    for (const a of ax) l = Math.max(l, n1(a.slice(4)));
    return l > 0 && l < Infinity ? l : 1;
}

//@ ik_fk: always
// The pose E1(q1) ... En(qn) M (3 x 4) and each joint's current axis [w, p].
function ik_fk(ax, home, q) {
    const compose = (a, b) => [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) =>
        a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c] + (c === 3 ? a[r][3] : 0)));
    let p = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]];
    const cur = [];
    ax.forEach((a, i) => {
        const w = [a[1], a[2], a[3]];
        cur.push([0, 1, 2].map((r) => p[r][0] * a[1] + p[r][1] * a[2] + p[r][2] * a[3])
            .concat([0, 1, 2].map((r) => p[r][0] * a[4] + p[r][1] * a[5] + p[r][2] * a[6] + p[r][3])));
        let m;
        if (a[0] !== 0) {
            m = [0, 1, 2].map((r) => [0, 1, 2].map((c) => (r === c ? 1 : 0)).concat([q[i] * w[r]]));
        } else {
            const s = Math.sin(q[i]), c = Math.cos(q[i]);
            const k = [[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]];
            m = [0, 1, 2].map((r) => [0, 1, 2].map((j) =>
                (r === j ? c : 0) + s * k[r][j] + (1 - c) * w[r] * w[j]));
            m.forEach((row, r) => row.push(a[4 + r] - (row[0] * a[4] + row[1] * a[5] + row[2] * a[6])));
        }
        p = compose(p, m);
    });
    return [compose(p, home), cur];
}

//@ ik_error: always
// T - F: rotation entries, then positions over the scale (positions only for a position-only
// solver).
function ik_error(f, T, len, po) {
    const e = [];
    for (let r = 0; r < 3; r++) for (let c = 0; c < 4; c++) {
        if (c === 3) e.push((T[r][3] - f[r][3]) / len);
        else if (!po) e.push(T[r][c] - f[r][c]);
    }
    return e;
}

//@ ik_max_abs: always
function ik_max_abs(e) {
    return e.reduce((m, x) => (Math.abs(x) > m || Number.isNaN(x) ? Math.abs(x) : m), 0);
}

//@ ik_cholesky: always
// Solves h x = b for a symmetric positive definite h (Cholesky); null when it is not.
function ik_cholesky(h, b) {
    const n = b.length, l = h.map((r) => r.slice()), x = b.slice();
    for (let j = 0; j < n; j++) {
        let d = l[j][j];
        for (let k = 0; k < j; k++) d -= l[j][k] * l[j][k];
        if (!(d > 0)) return null;
        d = Math.sqrt(d);
        l[j][j] = d;
        for (let i = j + 1; i < n; i++) {
            let s = l[i][j];
            for (let k = 0; k < j; k++) s -= l[i][k] * l[j][k];
            l[i][j] = s / d;
        }
    }
    for (let i = 0; i < n; i++) {
        for (let k = 0; k < i; k++) x[i] -= l[i][k] * x[k];
        x[i] /= l[i][i];
    }
    for (let i = n - 1; i >= 0; i--) {
        for (let k = i + 1; k < n; k++) x[i] -= l[k][i] * x[k];
        x[i] /= l[i][i];
    }
    return x;
}

//@ ik_refine: always
// Damped Gauss-Newton on the pose residual from q: at most IK_REFINE_STEPS steps, each kept
// only when it lowers the residual (else the damping grows a hundredfold); [q, residual].
function ik_refine(ax, home, T, len, po, q) {
    let [f, cur] = ik_fk(ax, home, q), e = ik_error(f, T, len, po), res = ik_max_abs(e);
    let lambda = 1e-12;
    for (let it = 0; it < IK_REFINE_STEPS && res > IK_CHECK_TOL * 1e-3; it++) {
        // Jacobian columns: d(R)/dqi = [wi]x R, d(t)/dqi = wi x (t - pi) (revolute), wi
        // (prismatic); the same entries and scaling as the residual.
        const cols = ax.map((a, i) => {
            const w = cur[i].slice(0, 3), p = cur[i].slice(3);
            const cross = (v) => [w[1] * v[2] - w[2] * v[1], w[2] * v[0] - w[0] * v[2], w[0] * v[1] - w[1] * v[0]];
            const zero = [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0]];
            const d = zero.map((row) => row.slice());
            const dt = a[0] !== 0 ? w : cross([0, 1, 2].map((r) => f[r][3] - p[r]));
            for (let c = 0; c < 3; c++) {
                const v = a[0] !== 0 ? [0, 0, 0] : cross([f[0][c], f[1][c], f[2][c]]);
                for (let r = 0; r < 3; r++) d[r][c] = -v[r];
            }
            for (let r = 0; r < 3; r++) d[r][3] = -dt[r];
            return ik_error(d, zero, len, po);
        });
        const n = q.length, m = e.length;
        const A = [], g = [];
        let tr = 0;
        for (let i = 0; i < n; i++) {
            A.push([]);
            for (let j = 0; j < n; j++) {
                let s = 0;
                for (let k = 0; k < m; k++) s += cols[i][k] * cols[j][k];
                A[i].push(s);
            }
            let s = 0;
            for (let k = 0; k < m; k++) s += cols[i][k] * e[k];
            g.push(s);
            tr += A[i][i];
        }
        for (;;) {
            const d = ik_cholesky(A.map((row, i) => row.map((x, j) =>
                x + (i === j ? lambda * Math.max(tr, Number.MIN_VALUE) : 0))), g);
            if (d !== null) {
                const next = q.map((x, i) => x + d[i]);
                const [f2, cur2] = ik_fk(ax, home, next), e2 = ik_error(f2, T, len, po);
                const r2 = ik_max_abs(e2);
                if (r2 < res) {
                    [q, f, cur, e, res] = [next, f2, cur2, e2, r2];
                    lambda = Math.max(lambda * 0.01, 1e-15);
                    break;
                }
            }
            lambda *= 100;
            if (lambda > 1) return [q, res];
        }
    }
    return [q, res];
}

//@ ik_push: always
// Adds a solution [q, singular, approximate, residual] to out; one a step asks to check is
// checked by forward kinematics: refined where its residual exceeds IK_REFINE_TOL, flagged
// approximate where it stays above IK_POSE_TOL, dropped when it is a sample off the pose or a
// singular duplicate.
function ik_push(out, q, sg, ck, smp, ax, home, T, len, po) {
    let res = 0;
    if (sg || ck) {
        res = ik_max_abs(ik_error(ik_fk(ax, home, q)[0], T, len, po));
        if (res > IK_REFINE_TOL) {
            const [r, rr] = ik_refine(ax, home, T, len, po, q);
            if (rr < res) [q, res] = [r, rr];
        }
        if (smp && res > IK_POSE_TOL) return;
        const same = (a, b) => a.every((x, i) =>
            Math.abs(x - b[i]) <= 4 * IK_EPS * Math.max(Math.abs(x), Math.abs(b[i]), 1));
        if (sg && out.some(([p, psg]) => psg && same(p, q))) return;
    }
    out.push([q, sg, !(res <= IK_POSE_TOL), res]);
}
