#@ _ik_radicand: trig quadratic
def _ik_radicand(rad, n, nu):
    # A radicand of scale n rounded by nu: None out of reach (below -IK_REACH_TOL n), a double
    # root within nu of zero (singular), else itself (checked where its roots err by more than
    # IK_CHECK_TOL): (rad, singular, checked).
    if rad < -IK_REACH_TOL * n - nu:
        return None
    if rad <= nu:
        return 0.0, True, True
    return rad, False, nu * nu > 4.0 * IK_CHECK_TOL * IK_CHECK_TOL * rad * n


#@ _ik_any: always
def _ik_any(first):
    # A joint free on a singular set: twelve values k pi/6, k = -5..6; sampled beside a kept
    # atan2 value when `first`.
    qs = [k * math.pi / 6 for k in range(-5, 7)]
    return [(q, math.sin(q), math.cos(q), first) for q in qs]


#@ _ik_atan2: atan2
def _ik_atan2(y, x, sg, m):
    # The roots [(q, sin q, cos q, sampled)], singular, checked, for arguments rounded by sg.
    # m: the step's last [y, x, roots]: the same arguments give the same root, exactly negated
    # ones q + pi (the wrist flip).
    if m and len(m[2][0]) == 1 and y == m[0] and x == m[1]:
        return m[2]
    if m and len(m[2][0]) == 1 and y == -m[0] and x == -m[1]:
        q, s, c, _ = m[2][0][0]
        m[:] = [y, x, ([(q - math.pi if q > 0 else q + math.pi, -s, -c, False)], False, m[2][2])]
        return m[2]
    h2 = y * y + x * x
    if h2 <= sg * sg:
        if h2 > 0.0:
            h = math.sqrt(h2)
            return [(math.atan2(y, x), y / h, x / h, False)] + _ik_any(True), True, True
        return _ik_any(False), True, True
    h = math.sqrt(h2)
    ck = sg * sg > IK_CHECK_TOL * IK_CHECK_TOL * h2
    m[:] = [y, x, ([(math.atan2(y, x), y / h, x / h, False)], False, ck)]
    return m[2]


#@ _ik_trig: trig
def _ik_trig(a, b, c, sg):
    n = a * a + b * b
    if n <= sg * sg:
        return ([(0.0, 0.0, 1.0, False)] if abs(c) <= sg else []), True, True
    nu = 2.0 * sg * (abs(a) + abs(b) + abs(c)) + 4.0 * IK_EPS * n
    r = _ik_radicand(n - c * c, n, nu)
    if r is None:
        return [], False, False
    rad, sing, ck = r
    w = math.sqrt(rad)
    d = math.sqrt(n * (c * c + rad)) if sing else n
    y0, x0, y1, x1 = b * c + a * w, a * c - b * w, b * c - a * w, a * c + b * w
    q0 = math.atan2(y0, x0)
    if b == 0.0:
        q1 = -q0
    elif a == 0.0:
        q1 = math.copysign(math.pi, y0) - q0
    else:
        q1 = math.atan2(y1, x1)
    roots = [(q0, y0 / d, x0 / d, False), (q1, y1 / d, x1 / d, False)]
    if sing:
        # Beside the double root, the pair of the radicand nu (sampled: kept where refinement
        # takes it onto the pose).
        w, e = math.sqrt(nu), math.sqrt(n * (c * c + nu))
        y2, x2, y3, x3 = b * c + a * w, a * c - b * w, b * c - a * w, a * c + b * w
        roots = [roots[0], (math.atan2(y2, x2), y2 / e, x2 / e, True),
                 (math.atan2(y3, x3), y3 / e, x3 / e, True)]
    return roots, sing, ck


#@ _ik_quadratic: quadratic
def _ik_quadratic(beta, gamma, sg):
    s = max(abs(beta), math.sqrt(abs(gamma)))
    nu = sg + 2.0 * math.sqrt(sg * IK_ZERO_TOL) * (2.0 * abs(beta) + s) + 4.0 * IK_EPS * (beta * beta + abs(gamma))
    r = _ik_radicand(beta * beta - gamma, max(beta * beta, abs(gamma)), nu)
    if r is None:
        return [], False, False
    rad, sing, ck = r
    w = math.sqrt(rad)
    return [(-beta + w, 0.0, 1.0, False), (-beta - w, 0.0, 1.0, False)], sing, ck


#@ _ik_linear: linear
def _ik_linear(a, b, sg):
    # a q = b, q a length (b rounded by sg = IK_ZERO_TOL L, a dimensionless, rounded by
    # IK_ZERO_TOL): q = b / a; singular where |a| <= IK_ZERO_TOL (b / a kept while a != 0, else
    # 0); checked where its error (sg + |q| IK_ZERO_TOL) / |a| exceeds IK_CHECK_TOL L.
    q = 0.0 if a == 0.0 else b / a
    if abs(a) <= IK_ZERO_TOL:
        return [(q, 0.0, 1.0, False)], True, True
    ck = (sg + abs(q) * IK_ZERO_TOL) / abs(a) * IK_ZERO_TOL > IK_CHECK_TOL * sg
    return [(q, 0.0, 1.0, False)], False, ck


#@ _ik_scale: always
def _ik_scale(ax, home, T):
    # The robot's scale: the largest sum of absolute coordinates of an axis' point, the home
    # position or the target position.
    s = max([abs(a[4]) + abs(a[5]) + abs(a[6]) for a in ax]
            + [sum(abs(home[r][3]) for r in range(3)), sum(abs(float(T[r][3])) for r in range(3))])
    return s if 0.0 < s < math.inf else 1.0


#@ _ik_fk: always
def _ik_fk(ax, home, q):
    # The pose E1(q1) ... En(qn) M (3 x 4) and each joint's current axis (w, p).
    p = np.eye(4)
    cur = []
    for a, qi in zip(ax, q):
        w = np.array(a[1:4])
        cur.append((p[:3, :3] @ w, p[:3, :3] @ np.array(a[4:7]) + p[:3, 3]))
        e = np.eye(4)
        if a[0] != 0.0:
            e[:3, 3] = qi * w
        else:
            s, c = math.sin(qi), math.cos(qi)
            k = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
            e[:3, :3] = c * np.eye(3) + s * k + (1.0 - c) * np.outer(w, w)
            e[:3, 3] = np.array(a[4:7]) - e[:3, :3] @ np.array(a[4:7])
        p = p @ e
    return (p @ np.vstack([home, [0.0, 0.0, 0.0, 1.0]]))[:3], cur


#@ _ik_error: always
def _ik_error(f, T, n):
    # T - F: rotation entries, then positions over the scale (positions only for a
    # position-only solver).
    T = np.asarray(T, dtype=float)
    rows = []
    for r in range(3):
        for c in range(4):
            if c == 3:
                rows.append((T[r, 3] - f[r, 3]) / n)
            elif not IK_POSITION_ONLY:
                rows.append(T[r, c] - f[r, c])
    return np.array(rows)


#@ _ik_max_abs: always
def _ik_max_abs(e):
    return float(np.max(np.abs(e))) if not np.isnan(e).any() else math.nan


#@ _ik_refine: always
def _ik_refine(ax, home, T, n, q):
    # Damped Gauss-Newton on the pose residual from q: at most IK_REFINE_STEPS steps, each
    # kept only when it lowers the residual (else the damping grows a hundredfold); the joint
    # vector and its residual.
    q = list(q)
    f, cur = _ik_fk(ax, home, q)
    e = _ik_error(f, T, n)
    res = _ik_max_abs(e)
    lam = 1e-12
    for _ in range(IK_REFINE_STEPS):
        if res <= IK_CHECK_TOL * 1e-3:
            break
        cols = []
        for a, (w, p) in zip(ax, cur):
            if a[0] != 0.0:
                dr, dt = np.zeros((3, 3)), w
            else:
                dr, dt = np.cross(w, f[:, :3].T).T, np.cross(w, f[:, 3] - p)
            cols.append(_ik_error(np.hstack([-dr, -dt.reshape(3, 1)]), np.zeros((3, 4)), n))
        jac = np.array(cols).T
        a = jac.T @ jac
        g = jac.T @ e
        tr = max(float(np.trace(a)), 2.2250738585072014e-308)
        while True:
            ok = True
            try:
                d = np.linalg.solve(a + lam * tr * np.eye(len(q)), g)
                ok = bool(np.all(np.isfinite(d)))
            except np.linalg.LinAlgError:
                ok = False
            if ok:
                nxt = [x + float(y) for x, y in zip(q, d)]
                f2, cur2 = _ik_fk(ax, home, nxt)
                e2 = _ik_error(f2, T, n)
                r2 = _ik_max_abs(e2)
                if r2 < res:
                    q, f, cur, e, res = nxt, f2, cur2, e2, r2
                    lam = max(lam * 0.01, 1e-15)
                    break
            lam *= 100.0
            if lam > 1.0:
                return q, res
    return q, res


#@ _ik_push: always
def _ik_push(out, q, sg, ck, smp, ax, home, T, n):
    # Writes a solution (q, singular, approximate, residual); one a step asks to check is
    # checked by forward kinematics: refined where its residual exceeds IK_REFINE_TOL, flagged
    # approximate where it stays above IK_POSE_TOL, dropped when it is a sample off the pose or
    # a singular duplicate.
    q = [float(x) for x in q]
    res = 0.0
    if sg or ck:
        f, _ = _ik_fk(ax, home, q)
        res = _ik_max_abs(_ik_error(f, T, n))
        if res > IK_REFINE_TOL:
            r, rr = _ik_refine(ax, home, T, n, q)
            if rr < res:
                q, res = [float(x) for x in r], rr
        if smp and res > IK_POSE_TOL:
            return
        if sg:
            for p, psg, _, _ in out:
                if psg and all(abs(x - y) <= 4 * IK_EPS * max(abs(x), abs(y), 1.0) for x, y in zip(p, q)):
                    return
    out.append((q, sg, not res <= IK_POSE_TOL, res))


#@ _ik_dq_matrix: always
def _ik_dq_matrix(q):
    w, x, y, z, a, b, c, d = (float(v) for v in q)
    return np.array([
        [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
         2 * (-a * x + b * w - c * z + d * y)],
        [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
         2 * (-a * y + b * z + c * w - d * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z,
         2 * (-a * z - b * y + c * x + d * w)],
        [0.0, 0.0, 0.0, 1.0],
    ])