# The numeric core of the general 6R solver in Python (NumPy): the algorithm of core.rs
# (Raghavan-Roth elimination in Manocha-Canny's 12 x 12 form), with NumPy's SVD for the left
# null space and the null vector, and np.linalg.eigvals for the companion matrix. Its
# constants IK_GEN_* (sample angles, tolerances) are written above this text from core.rs.

_SS = np.array(IK_GEN_SAMPLE_S)
_SC = np.array(IK_GEN_SAMPLE_C)
_DFT = np.array(IK_GEN_DFT)
_HALF = np.array(IK_GEN_HALF)
_SD = np.array(IK_GEN_SAMPLE_D)
_VANDER = np.array(IK_GEN_VANDER)
_HALF_INV = np.array(IK_GEN_HALF_INV)


def _rod(w, s, c):
    k = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
    return c * np.eye(3) + s * k + (1 - c) * np.outer(w, w)


def _apply(j, s, c, x, d):
    r = _rod(j[0], s, c)
    return j[1] + r @ (x - j[1]), r @ d


# A joint is (w, c, prism): a prismatic joint's variable is the length d of a slide along w,
# sampled at 0, 1, -1 and read in the basis (1, d, d^2) (see core.rs, SAMPLE_D and HALF_INV).
def _sample(j, k, inv, x, d):
    sg = -1.0 if inv else 1.0
    if j[2]:
        return x + sg * _SD[k] * j[0], d
    return _apply(j, sg * _SS[k], _SC[k], x, d)


def _weights(j):
    return _VANDER if j[2] else _DFT


def _quant(p, l):
    pp = p @ p
    pl = p @ l
    return np.concatenate([l, p, [pp, pl], np.cross(p, l), pp * l - 2 * pl * p])


def _inv(g):
    r = g[:, :3].T
    return np.hstack([r, (-r @ g[:, 3])[:, None]])


def _mapply(g, x, d):
    return g[:, :3] @ x + g[:, 3], g[:, :3] @ d


def _compose(a, b):
    return np.hstack([a[:, :3] @ b[:, :3], (a[:, :3] @ b[:, 3] + a[:, 3])[:, None]])


def _arranged(js, g, arr):
    rev, shift = arr >= 6, arr % 6
    base, h, bperm = list(js), g, list(range(6))
    if rev:
        base = [(-js[5 - i][0], js[5 - i][1], js[5 - i][2]) for i in range(6)]
        bperm = [5 - i for i in range(6)]
        h = _inv(g)
    hi = _inv(h)
    j, perm = [], []
    for i in range(6):
        k = (shift + i) % 6
        perm.append(bperm[k])
        if k < shift:
            c, w = _mapply(hi, base[k][1], base[k][0])
            j.append((w, c, base[k][2]))
        else:
            j.append(base[k])
    return j, h, perm


def _elim(j, h):
    w6, p6, _ = j[5]
    lhs = np.zeros((3, 3, 3, 14))
    for k5 in range(3):
        x5, d5 = _sample(j[4], k5, False, p6, w6)
        for k4 in range(3):
            x4, d4 = _sample(j[3], k4, False, x5, d5)
            for k3 in range(3):
                x3, d3 = _sample(j[2], k3, False, x4, d4)
                lhs[k3, k4, k5] = _quant(x3, d3)
    hp, hd = _mapply(h, p6, w6)
    rhs = np.zeros((3, 3, 14))
    for k1 in range(3):
        y1, e1 = _sample(j[0], k1, True, hp, hd)
        for k2 in range(3):
            y2, e2 = _sample(j[1], k2, True, y1, e1)
            rhs[k1, k2] = _quant(y2, e2)
    w = [_weights(x) for x in j]
    am = np.einsum('ia,jb,kc,abce->eijk', w[2], w[3], w[4], lhs).reshape(14, 3, 9).copy()
    r = np.einsum('ia,jb,abe->eij', w[0], w[1], rhs).reshape(14, 9)
    am[:, 0, 0] -= r[:, 0]
    bm = r[:, 1:]
    u, sv, _ = np.linalg.svd(bm)
    ratio = sv[7] / sv[0] if sv[0] > 0 else 0.0
    sig = np.einsum('re,ekm->krm', u[:, 8:].T, am)
    # Prismatic joints 3, 4, 5 into the basis the half-angle map turns into (1, d, d^2).
    s9 = sig.reshape(3, 6, 3, 3)
    if j[2][2]:
        s9 = np.einsum('krab,kc->crab', s9, _HALF_INV)
    if j[3][2]:
        s9 = np.einsum('krab,ac->krcb', s9, _HALF_INV)
    if j[4][2]:
        s9 = np.einsum('krab,bc->krac', s9, _HALF_INV)
    sig = s9.reshape(3, 6, 9)
    return am, bm, ratio, sig


def _mpoly(sig, phi):
    sp, cp = math.sin(phi), math.cos(phi)
    out = np.zeros((3, 12, 12))
    for i4 in range(3):
        for i5 in range(3):
            m = 3 * i4 + i5
            s0 = sig[0, :, m]
            sc = sig[1, :, m] * cp + sig[2, :, m] * sp
            ss = sig[2, :, m] * cp - sig[1, :, m] * sp
            coef = (s0 + sc, 2 * ss, s0 - sc)
            for a in range(3):
                for b in range(3):
                    hh = _HALF[i4, a] * _HALF[i5, b]
                    if hh == 0:
                        continue
                    for dd in range(3):
                        out[dd, :6, 3 * a + b] += hh * coef[dd]
                        out[dd, 6:, 3 * (a + 1) + b] += hh * coef[dd]
    return out


def _angle(pairs):
    n, d = max(pairs, key=lambda p: p[0] * p[0] + p[1] * p[1])
    return _wrap(2 * math.atan2(n, d))


def _wrap(a):
    x = math.fmod(a, IK_GEN_TAU)
    if x > IK_GEN_PI:
        x -= IK_GEN_TAU
    elif x <= -IK_GEN_PI:
        x += IK_GEN_TAU
    return x


def _back(j, h, am, bm, m, t3):
    # m: M(x) (or S(th)) at the root, t3 the hidden joint's angle phi + 2 atan x.
    v = np.linalg.svd(m)[2][-1]
    at = lambda a, b: v[3 * a + b]
    t4 = _angle([(at(a + 1, b), at(a, b)) for a in range(3) for b in range(3)])
    t5 = _angle([(at(a, b + 1), at(a, b)) for a in range(4) for b in range(2)])
    # A slide's variable is the tangent of the half angle these formulas give.
    t3, t4, t5 = [math.tan(0.5 * t) if j[k][2] else t for k, t in ((2, t3), (3, t4), (4, t5))]

    def f(k, t):
        if j[k][2]:
            return np.array([1.0, t, t * t])
        return np.array([1.0, math.cos(t), math.sin(t)])

    x45 = np.outer(f(3, t4), f(4, t5)).reshape(9)
    rhs = np.einsum('ekm,k,m->e', am, f(2, t3), x45)
    x12 = np.linalg.lstsq(bm, rhs, rcond=None)[0]
    t1 = x12[2] if j[0][2] else math.atan2(x12[5], x12[2])
    t2 = x12[0] if j[1][2] else math.atan2(x12[1], x12[0])
    rot = np.eye(3)
    for k, tk in enumerate([t1, t2, t3, t4, t5]):
        if not j[k][2]:
            rot = rot @ _rod(j[k][0], math.sin(tk), math.cos(tk))
    w6 = j[5][0]
    e = np.array([1.0, 0.0, 0.0]) if abs(w6[0]) < 0.6 else np.array([0.0, 1.0, 0.0])
    u = np.cross(w6, e)
    vv = rot.T @ (h[:, :3] @ u)
    t6 = math.atan2(w6 @ np.cross(u, vv), u @ vv)
    return [t1, t2, t3, t4, t5, t6]


def _deflate(mp, k):
    # The spurious eigenvalues +-i removed (see core.rs): the null vectors a + i b of M(i) give
    # the invariant subspace Z = span([a; -b], [b; a]) of k; with Q = [Z W] orthogonal, W^T k W
    # has the other eigenvalues.
    u, sv, vh = np.linalg.svd(mp[0] - mp[2] + 1j * mp[1])
    null = vh[sv <= IK_GEN_SPURIOUS_RANK * sv[0]].conj().T
    if not sv[0] > 0 or null.shape[1] == 0 or null.shape[1] >= 12:
        return k
    z = np.hstack([np.vstack([null.real, -null.imag]), np.vstack([null.imag, null.real])])
    q = np.linalg.qr(z, mode='complete')[0]
    w = q[:, z.shape[1]:]
    return w.T @ k @ w


def _mtrig(sig):
    # S(th) = T0 + T1 cos th + T2 sin th: M(x) of _mpoly at phi = 0 over 1 + x^2.
    out = np.zeros((3, 12, 12))
    for i4 in range(3):
        for i5 in range(3):
            m = 3 * i4 + i5
            for a in range(3):
                for b in range(3):
                    hh = _HALF[i4, a] * _HALF[i5, b]
                    if hh == 0:
                        continue
                    for dd in range(3):
                        out[dd, :6, 3 * a + b] += hh * sig[dd, :, m]
                        out[dd, 6:, 3 * (a + 1) + b] += hh * sig[dd, :, m]
    return out


def _trig_eval(c, th):
    # D(th) = Re sum_j c_j e^(i j th) and its derivatives to the seventh.
    z = c * np.exp(1j * th * np.arange(len(c)))
    jj = np.arange(len(c), dtype=float)
    return [float(np.sum(jj ** k * (1j ** k * z).real)) for k in range(IK_GEN_TAYLOR)]


def _bracketed(c, k, a, b, fa, fb):
    # Halley's method from the secant's zero, kept inside the bracket (see core.rs, bracketed).
    neg_a = fa < 0
    x = a + (b - a) * (fa / (fa - fb))
    if not (a < x < b):
        x = 0.5 * (a + b)
    for _ in range(60):
        v = _trig_eval(c, x)
        if v[k] == 0:
            return x
        if (v[k] < 0) == neg_a:
            a = x
        else:
            b = x
        den = 2 * v[k + 1] ** 2 - v[k] * v[k + 2]
        nxt = x - 2 * v[k] * v[k + 1] / den if den != 0 else math.nan
        if a < nxt < b:
            if abs(nxt - x) <= IK_GEN_BRACKET_TOL:
                return nxt
            x = nxt
        else:
            x = 0.5 * (a + b)
        if b - a <= IK_GEN_BRACKET_WIDTH:
            return x
    return x


def _trig_roots(c):
    # The real roots in [0, 2 pi) of D by interval search (see core.rs, trig_roots).
    amp = np.abs(c)
    jj = np.arange(len(c), dtype=float)
    b0, b8 = float(amp.sum()), float((jj ** IK_GEN_TAYLOR * amp).sum())
    margin, nd = IK_GEN_ROOT_MARGIN * b0, float(IK_GEN_DET_DEGREE)
    h = IK_GEN_TAU / IK_GEN_ROOT_GRID
    top = IK_GEN_ROOT_GRID * h
    at = lambda x: _trig_eval(c, 0.0 if x >= top else x)
    stack = [(k * h, (k + 1) * h) for k in reversed(range(IK_GEN_ROOT_GRID))]
    out, evals = [], 0

    def mono(a, b, k):
        nonlocal evals
        fa, fb = at(a)[k], at(b)[k]
        evals += 2
        return None if (fa < 0) == (fb < 0) else _bracketed(c, k, a, b, fa, fb)

    while stack:
        a, b = stack.pop()
        m, r = 0.5 * (a + b), 0.5 * (b - a)
        v = at(m)
        evals += 1
        if evals > IK_GEN_ROOT_EVALS or len(out) + 2 > 24:
            return None
        moves = []
        for l in range(3):
            mv, term = 0.0, 1.0
            for k in range(l + 1, IK_GEN_TAYLOR):
                term *= r / (k - l)
                mv += abs(v[k]) * term
            moves.append(mv + b8 * term * r / (IK_GEN_TAYLOR - l))
        if abs(v[0]) > moves[0] + margin:
            continue
        if abs(v[1]) > moves[1] + nd * margin:
            x = mono(a, b, 0)
            if x is not None:
                out.append(x)
            continue
        if abs(v[2]) > moves[2] + nd * nd * margin:
            e = mono(a, b, 1)
            if e is None:
                x = mono(a, b, 0)
                if x is not None:
                    out.append(x)
                continue
            left, right = mono(a, e, 0), mono(e, b, 0)
            out += [x for x in (left, right) if x is not None]
            if left is None and right is None:
                w = at(e)
                if 2 * abs(w[0]) <= IK_GEN_NEAR_REAL ** 2 * abs(w[2]):
                    out += [e, e]
            continue
        # D and D' both zero to rounding, or nothing certified at the finest width: the
        # eigenvalue route decides.
        flat = abs(v[0]) <= margin and abs(v[1]) <= nd * margin
        if flat or r <= IK_GEN_ROOT_LEAF or len(stack) + 2 > 96:
            return None
        stack += [(m, b), (a, m)]
    return out


def _det_candidates(j, h, perm, am, bm, sig):
    # The determinant route (see core.rs, det_candidates): det S(th) at IK_GEN_DET_SAMPLES
    # angles, its coefficients by the DFT, its real roots by interval search. None when the
    # eigenvalue route decides; ("unconditioned", best) when no sample is conditioned (nearly
    # degenerate here, GaveUp::Unconditioned).
    tm = _mtrig(sig)
    n = IK_GEN_DET_SAMPLES
    ths = IK_GEN_TAU * np.arange(n) / n
    d, good = [], 0.0
    for th in ths:
        s_ = tm[0] + math.cos(th) * tm[1] + math.sin(th) * tm[2]
        d.append(np.linalg.det(s_))
        sv = np.linalg.svd(s_, compute_uv=False)
        good = max(good, sv[-1] / sv[0] if sv[0] > 0 else 0.0)
    d = np.array(d)
    scale = float(np.abs(d).max())
    if not (good > IK_GEN_SHIFT_GOOD and math.isfinite(scale)):
        return ("unconditioned", good)
    f = np.fft.fft(d) / n
    # c_j = a_j - i b_j of D(th) = a_0 + sum a_j cos j th + b_j sin j th: 2 F_j (F_0 for j = 0).
    c = np.concatenate([[f[0].real], 2 * f[1:IK_GEN_DET_DEGREE + 1]])
    half = 0.5 * IK_GEN_TAU / n
    interp = float(np.sum((c * np.exp(1j * half * np.arange(len(c)))).real))
    check = np.linalg.det(tm[0] + math.cos(half) * tm[1] + math.sin(half) * tm[2])
    if not abs(check - interp) <= IK_GEN_DET_CHECK * scale:
        return None
    deg = IK_GEN_DET_DEGREE
    while deg > 0 and abs(c[deg]) <= IK_GEN_DET_TRIM * scale:
        deg -= 1
    th = _trig_roots(c)
    if th is None:
        return None
    out = []
    for t3 in th:
        t = _back(j, h, am, bm, tm[0] + math.cos(t3) * tm[1] + math.sin(t3) * tm[2], _wrap(t3))
        q = [0.0] * 6
        for i in range(6):
            q[perm[i]] = t[i]
        out.append(q)
    return out


def _eigen_candidates(j, h, perm, am, bm, sig):
    # The eigenvalue route (see core.rs, eigen_candidates); None when A is singular at every
    # shift.
    best = (0.0, -1.0)
    for phi in IK_GEN_SHIFTS:
        sv = np.linalg.svd(_mpoly(sig, phi)[2], compute_uv=False)
        ratio = sv[-1] / sv[0] if sv[0] > 0 else 0.0
        if ratio > best[1]:
            best = (phi, ratio)
        if ratio > IK_GEN_SHIFT_GOOD:
            break
    if best[1] < IK_GEN_SHIFT_SINGULAR:
        return None
    phi = best[0]
    mp = _mpoly(sig, phi)
    a_inv = np.linalg.inv(mp[2])
    k = np.zeros((24, 24))
    k[:12, 12:] = np.eye(12)
    k[12:, :12] = -a_inv @ mp[0]
    k[12:, 12:] = -a_inv @ mp[1]
    out = []
    for z in np.linalg.eigvals(_deflate(mp, k)):
        # A prismatic hidden joint's roots at infinity are no solutions.
        if j[2][2] and np.isfinite(z) and abs(math.tan(0.5 * phi + math.atan(z.real))) > IK_GEN_PRISM_FAR:
            continue
        if np.isfinite(z) and abs(z.imag) <= IK_GEN_NEAR_REAL * (1 + abs(z.real)):
            x = float(z.real)
            t = _back(j, h, am, bm, (mp[2] * x + mp[1]) * x + mp[0], _wrap(phi + 2 * math.atan(x)))
            q = [0.0] * 6
            for i in range(6):
                q[perm[i]] = t[i]
            out.append(q)
    return out


def _forward(ax, home, q):
    p = np.hstack([np.eye(3), np.zeros((3, 1))])
    cur = []
    for a, qi in zip(ax, q):
        w, c = a[1:4], a[4:7]
        o, d = _mapply(p, c, w)
        cur.append((d, o, a[0] != 0))
        if a[0] != 0:
            p = _compose(p, np.hstack([np.eye(3), (qi * w)[:, None]]))
        else:
            r = _rod(w, math.sin(qi), math.cos(qi))
            p = _compose(p, np.hstack([r, (c - r @ c)[:, None]]))
    return _compose(p, home), cur


def _refine(ax, home, t, q):
    q = np.array(q, dtype=float)
    f, cur = _forward(ax, home, q)
    e = (t - f).reshape(12)
    res = np.max(np.abs(e))
    lam = IK_GEN_DAMP_START
    for _ in range(IK_GEN_REFINE_ITERS):
        if not res > IK_GEN_EXACT_TOL:
            break
        cols = []
        for d, o, slide in cur:
            if slide:
                cols.append(np.hstack([np.zeros((3, 3)), d[:, None]]).reshape(12))
                continue
            dr = np.cross(d, f[:, :3].T).T
            dt = np.cross(d, f[:, 3] - o)
            cols.append(np.hstack([dr, dt[:, None]]).reshape(12))
        jm = np.array(cols).T
        a = jm.T @ jm
        g = jm.T @ e
        tr = np.trace(a)
        while True:
            step = np.linalg.solve(a + lam * max(tr, IK_GEN_MIN_POSITIVE) * np.eye(6), g)
            nxt = q + step
            f2, cur2 = _forward(ax, home, nxt)
            e2 = (t - f2).reshape(12)
            r2 = np.max(np.abs(e2))
            if r2 < res:
                q, f, cur, e, res = nxt, f2, cur2, e2, r2
                lam = max(lam * 0.01, IK_GEN_DAMP_MIN)
                break
            lam *= 100
            if lam > IK_GEN_DAMP_MAX:
                return q, res
    return q, res


def _same(a, b, slides, radius):
    return all(abs(x - y if sl else _wrap(x - y)) <= radius
               for x, y, sl in zip(a, b, slides))


def _merge_repeats(sols, slides):
    # Drops each solution that repeats another at its residual (core.rs, merge_repeats): one
    # whose residual r is above IK_GEN_EXACT_TOL and that lies within IK_GEN_FOLD_REACH sqrt(r)
    # of a solution of smaller residual (of equal residual and earlier).
    for i in range(len(sols) - 1, -1, -1):
        q, r = sols[i][0], sols[i][1]
        if r <= IK_GEN_EXACT_TOL:
            continue
        radius = IK_GEN_FOLD_REACH * math.sqrt(r)
        if any(j != i and (s[1] < r or (s[1] == r and j < i)) and _same(s[0], q, slides, radius)
               for j, s in enumerate(sols)):
            del sols[i]


def _gen_solve(ax, home, target, length, pose_tol, keep_tol, first):
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
    state = {"used": 0}

    def take(cands):
        # Refines the candidates, adds the solutions; whether the set is complete (every root
        # gave its own exact solution).
        state["used"] += 1
        hit = set()
        for q0 in cands:
            q, res = _refine(ax, home, tg, q0)
            if not res <= keep_tol:
                continue
            q = [float(x) if sl else _wrap(float(x)) for x, sl in zip(q, slides)]
            at = next((i for i, s in enumerate(sols) if _same(s[0], q, slides, IK_GEN_SAME_TOL)),
                      None)
            if at is None and len(sols) < IK_GEN_MAX:
                sols.append([q, res])
                at = len(sols) - 1
            elif at is not None and res < sols[at][1]:
                sols[at] = [q, res]
            if at is not None and res <= pose_tol:
                hit.add(at)
        return len(hit) == len(cands)

    # The eigenvalue route of the first arrangement whose determinant route gives up waits for
    # the next arrangement's determinant route (see core.rs, gen_solve).
    deferred = None
    # The arrangements whose determinant route found no conditioned sample: (best, arr).
    unconditioned = []
    complete = False
    order = [first % 12] + [k for k in range(12) if k != first % 12]
    for arr in order:
        if state["used"] == 12:
            break
        j, h, perm = _arranged(js, g, arr)
        # The last arranged joint is eliminated by a point of its axis, which a slide moves.
        if slides[perm[5]]:
            continue
        am, bm, ratio, sig = _elim(j, h)
        if ratio < IK_GEN_RANK_TOL:
            continue
        cands = None if j[2][2] else _det_candidates(j, h, perm, am, bm, sig)
        if isinstance(cands, tuple):
            # Nearly degenerate here: kept for the end.
            unconditioned.append((cands[1], arr))
            continue
        if cands is None:
            if not j[2][2] and deferred is None:
                deferred = (j, h, perm, am, bm, sig)
                continue
            if deferred is not None:
                d, deferred = deferred, None
                dc = _eigen_candidates(*d)
                if dc is not None:
                    complete = take(dc)
                    if complete or state["used"] == 12:
                        break
            cands = _eigen_candidates(j, h, perm, am, bm, sig)
        if cands is None:
            continue
        complete = take(cands)
        if complete:
            break
    if deferred is not None and not complete and state["used"] < 12:
        dc = _eigen_candidates(*deferred)
        if dc is not None:
            complete = take(dc)
    # Still incomplete: the nearly degenerate arrangements' eigenvalue routes, the best
    # conditioned first (in the order tried among equals: the sort is stable).
    for _, arr in sorted(unconditioned, key=lambda u: -u[0]):
        if complete or state["used"] == 12:
            break
        j, h, perm = _arranged(js, g, arr)
        am, bm, ratio, sig = _elim(j, h)
        cands = _eigen_candidates(j, h, perm, am, bm, sig)
        if cands is not None:
            complete = take(cands)
    _merge_repeats(sols, slides)
    # Slides back in the robot's length unit.
    return [([x * length if sl else x for x, sl in zip(q, slides)], False, not res <= pose_tol,
             float(res)) for q, res in sols]
