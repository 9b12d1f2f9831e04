# The numeric core of a 4R2P chain with its slides three joints apart, in Python (NumPy): the
# algorithm of apart.rs (orientation by the four turns, position by the slides' plane, the
# resultant D(theta4) of degree 8), after core.py in the generated solver, whose helpers it
# uses.


class _Apart:
    # The canonical chain Tr(d0 v0) E1 E2 Tr(d3 v3) E4 E5 = H (see apart.rs).
    def __init__(self, j, h, perm):
        self.j, self.h, self.perm = j, h, perm
        self.rh, self.hp = h[:, :3], h[:, 3]
        w1, w2 = j[1][0], j[2][0]
        self.k12 = float(w1 @ w2)
        self.a = w2 - self.k12 * w1
        self.na = float(self.a @ self.a)

    def rot(self, i, th):
        return _rod(self.j[i][0], math.sin(th), math.cos(th))

    def q(self, t4, t5):
        return self.rh @ self.rot(5, t5).T @ self.rot(4, t4).T

    def cs1(self, q):
        w1 = self.j[1][0]
        b = q @ self.j[2][0] - self.k12 * w1
        return float(self.a @ b) / self.na, float(w1 @ np.cross(self.a, b)) / self.na

    def reach(self, t4, t5, q, c1, s1):
        j = self.j
        r1 = _rod(j[1][0], s1, c1)
        r4, r5 = self.rot(4, t4), self.rot(5, t5)
        t = (j[1][1] - r1 @ j[1][1] + r1 @ j[2][1] - q @ j[2][1]
             + q @ (j[4][1] - r4 @ j[4][1]) + self.rh @ (r5.T @ j[5][1] - j[5][1]))
        return self.hp - t, q @ j[3][0]

    def fp(self, t4, t5):
        q = self.q(t4, t5)
        c1, s1 = self.cs1(q)
        r, u = self.reach(t4, t5, q, c1, s1)
        n = np.cross(self.j[0][0], u)
        f = float(self.j[1][0] @ q @ self.j[2][0]) - self.k12
        return f, float(n @ r), float(np.linalg.norm(n) * np.linalg.norm(r)) + IK_GEN_MIN_POSITIVE

    def fcoef(self, t4):
        ths = IK_GEN_TAU * np.arange(3) / 3
        v = np.array([self.fp(t4, th)[0] for th in ths])
        return v.sum() / 3, 2 * (v * np.cos(ths)).sum() / 3, 2 * (v * np.sin(ths)).sum() / 3

    def sylvester(self, t4):
        f0, fc, fs = self.fcoef(t4)
        ths = IK_GEN_TAU * np.arange(5) / 5
        v = np.array([self.fp(t4, th)[1] for th in ths])
        p0 = v.sum() / 5
        c1, s1 = 2 * (v * np.cos(ths)).sum() / 5, 2 * (v * np.sin(ths)).sum() / 5
        c2, s2 = 2 * (v * np.cos(2 * ths)).sum() / 5, 2 * (v * np.sin(2 * ths)).sum() / 5
        f = [f0 + fc, 2 * fs, f0 - fc]
        p = [p0 + c1 + c2, 2 * s1 + 4 * s2, 2 * p0 - 6 * c2, 2 * s1 - 4 * s2, p0 - c1 + c2]
        s = np.zeros((6, 6))
        for i in range(4):
            s[i, i:i + 3] = f
        for i in range(2):
            s[4 + i, i:i + 5] = p
        return s

    def coefficients(self):
        n = IK_GEN_DET_SAMPLES
        step = IK_GEN_TAU / n
        d, good = [], 0.0
        for k in range(n):
            s = self.sylvester(k * step)
            d.append(np.linalg.det(s))
            sv = np.linalg.svd(s, compute_uv=False)
            good = max(good, sv[-1] / sv[0] if sv[0] > 0 else 0.0)
        d = np.array(d)
        scale = float(np.abs(d).max())
        if not (good > IK_GEN_SHIFT_GOOD and math.isfinite(scale)):
            return None
        f = np.fft.fft(d) / n
        c = np.concatenate([[f[0].real], 2 * f[1:IK_GEN_DET_DEGREE + 1]])
        half = 0.5 * step
        interp = float(np.sum((c * np.exp(1j * half * np.arange(len(c)))).real))
        check = np.linalg.det(self.sylvester(half))
        return c if abs(check - interp) <= IK_GEN_DET_CHECK * scale else None

    def joints(self, t4, t5):
        q = self.q(t4, t5)
        c1, s1 = self.cs1(q)
        t1 = math.atan2(s1, c1)
        w1, w2 = self.j[1][0], self.j[2][0]
        a2 = q.T @ w1 - self.k12 * w2
        b2 = w1 - self.k12 * w2
        t2 = math.atan2(float(w2 @ np.cross(a2, b2)), float(a2 @ b2))
        r, u = self.reach(t4, t5, q, math.cos(t1), math.sin(t1))
        v0 = self.j[0][0]
        k = float(v0 @ u)
        det = 1 - k * k
        r0, ru = float(v0 @ r), float(u @ r)
        singular = not det > IK_GEN_APART_PARALLEL
        d0, d3 = (r0, 0.0) if singular else ((r0 - k * ru) / det, (ru - k * r0) / det)
        return [d0, t1, t2, d3, t4, t5], singular

    def back(self, t4):
        f0, fc, fs = self.fcoef(t4)
        rho = math.hypot(fc, fs)
        flat = rho <= math.sqrt(IK_GEN_APART_PARALLEL) * (rho + abs(f0) + IK_GEN_MIN_POSITIVE)
        base = math.atan2(fs, fc)
        spread = 0.0 if flat else math.acos(min(1.0, max(-1.0, -f0 / rho)))
        cands = [base + spread, base - spread]
        ps = [self.fp(t4, t) for t in cands]
        best = 1 if abs(ps[1][1]) < abs(ps[0][1]) else 0
        out = []
        for i in (best, 1 - best):
            ok = i == best or abs(ps[i][1]) <= IK_GEN_APART_P_TOL * ps[i][2]
            if ok and (not out or spread > 0):
                q, sing = self.joints(t4, cands[i])
                out.append((q, sing or flat))
        return out


def _apart_eigen_roots(c):
    # The real roots of D where the certified search gives up (see apart_solver.rs,
    # apart_eigen_roots): the roots of (1 + x^2)^n D in x = tan((theta - phi)/2), by the
    # eigenvalues of its companion matrix (NumPy's polyroots).
    b0 = float(np.abs(c).sum())
    n = IK_GEN_DET_DEGREE
    while n > 0 and abs(c[n]) <= IK_GEN_DET_TRIM * b0:
        n -= 1
    if not (b0 > 0 and math.isfinite(b0)):
        return None
    if n == 0:
        return []
    js = np.arange(n + 1)
    best = (0.0, -1.0)
    for phi in IK_GEN_SHIFTS:
        ratio = abs(float(np.sum((c[:n + 1] * np.exp(1j * js * phi)).real * (-1.0) ** js))) / b0
        if ratio > best[1]:
            best = (phi, ratio)
        if ratio > IK_GEN_SHIFT_GOOD:
            break
    if not best[1] > 0:
        return None
    phi = best[0]
    poly = np.polynomial.polynomial
    p = np.zeros(2 * n + 1)
    for j in range(n + 1):
        term = poly.polymul(poly.polypow([1, 1j], n + j), poly.polypow([1, -1j], n - j))
        p += (c[j] * np.exp(1j * j * phi) * term).real
    roots = poly.polyroots(p)
    return [phi + 2 * math.atan(r.real) for r in roots
            if abs(r.imag) <= IK_GEN_NEAR_REAL * (1 + abs(r.real)) and math.isfinite(r.real)]


def _apart_arrangements(slides):
    s = [i for i in range(6) if slides[i]]
    if len(s) != 2 or s[1] - s[0] != 3:
        return None
    return [s[0], 6 + (5 - s[1])]


# The tests' hook: the eigenvalue route only (apart_solve_by's eigen_only) when set.
_APART_EIGEN_ONLY = False


def _apart_gen_solve(ax, home, target, length, pose_tol, keep_tol, first):
    ax = np.array(ax, dtype=float)
    ax[:, 4:7] /= length
    home = np.array(home, dtype=float)[:3].copy()
    home[:, 3] /= length
    tg = np.array(target, dtype=float)[:3].copy()
    tg[:, 3] /= length
    g = _compose(tg, _inv(home))
    slides = [a[0] != 0 for a in ax]
    js = [(a[1:4], a[4:7], a[0] != 0) for a in ax]
    sols = []
    arrs = _apart_arrangements(slides) or []
    # Both readings by the certified search, then (where it gave up in both) by the eigenvalues.
    searched = False
    for eigen, arr in [(e, a) for e in (False, True) for a in arrs]:
        if (eigen and searched) or (_APART_EIGEN_ONLY and not eigen):
            continue
        j, h, perm = _arranged(js, g, arr)
        ch = _Apart(j, h, perm)
        if not ch.na > IK_GEN_APART_PARALLEL:
            continue
        c = ch.coefficients()
        th = None if c is None else _apart_eigen_roots(c) if eigen else _trig_roots(c)
        if th is None:
            continue
        searched = searched or not eigen
        hit, roots = set(), 0
        for t4 in th:
            cands = ch.back(t4)
            roots += len(cands)
            for qa, sing in cands:
                q0 = [0.0] * 6
                for i in range(6):
                    q0[perm[i]] = qa[i]
                q, res = _refine(ax, home, tg, q0)
                if not res <= keep_tol:
                    continue
                q = [float(x) if sl else _wrap(float(x)) for x, sl in zip(q, slides)]
                at = next((i for i, s in enumerate(sols)
                           if _same(s[0], q, slides, IK_GEN_SAME_TOL)), None)
                if at is None and len(sols) < IK_GEN_MAX:
                    sols.append([q, res, sing])
                    at = len(sols) - 1
                elif at is not None:
                    if res < sols[at][1]:
                        sols[at][:2] = [q, res]
                    sols[at][2] = sols[at][2] or sing
                if at is not None and res <= pose_tol:
                    hit.add(at)
        if len(hit) == roots:
            break
    return [([x * length if sl else x for x, sl in zip(q, slides)], sing, not res <= pose_tol,
             float(res)) for q, res, sing in sols]
