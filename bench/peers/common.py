"""The workloads of bench/compare for a Python CAS (SymPy or SymEngine), done the way a robotics
user would: DH matrices and DH dual quaternions multiplied symbolically and expanded.

Each finished stage prints one JSON line (flushed), so bench/compare, which kills the process at
its time limit, still sees what finished before.
"""

import json
import sys
import time


class Lib:
    """The few functions the workloads need, from sympy or symengine."""

    def __init__(self, mod):
        self.m = mod
        self.sym = mod.Symbol
        self.cos = mod.cos
        self.sin = mod.sin
        self.pi = mod.pi
        self.rat = mod.Rational
        self.expand = mod.expand
        self.zero = mod.Integer(0)


def planar(L, n):
    return [(L.sym(f"theta{i}"), L.zero, L.sym(f"l{i}"), L.zero) for i in range(1, n + 1)]


def puma(L):
    alpha = [(1, 2), (0, 1), (-1, 2), (1, 2), (-1, 2), (0, 1)]
    d = ["0", "0", "d3", "d4", "0", "0"]
    a = ["0", "a2", "a3", "0", "0", "0"]
    v = lambda s: L.zero if s == "0" else L.sym(s)
    return [
        (L.sym(f"theta{i + 1}"), v(d[i]), v(a[i]), L.pi * L.rat(*alpha[i]))
        for i in range(6)
    ]


def generic(L, n):
    return [
        (L.sym(f"theta{i}"), L.sym(f"d{i}"), L.sym(f"a{i}"), L.sym(f"alpha{i}"))
        for i in range(1, n + 1)
    ]


def dh_matrix(L, th, d, a, al):
    c, s, ca, sa = L.cos(th), L.sin(th), L.cos(al), L.sin(al)
    z, one = L.zero, L.m.Integer(1)
    return [
        [c, -s * ca, s * sa, a * c],
        [s, c * ca, -c * sa, a * s],
        [z, sa, ca, d],
        [z, z, z, one],
    ]


def matmul(L, x, y):
    return [
        [L.expand(sum((x[i][k] * y[k][j] for k in range(4)), L.zero)) for j in range(4)]
        for i in range(4)
    ]


def matrix_chain(L, links):
    """The 4x4 product of the links' DH matrices, expanded after each product."""
    acc = None
    for l in links:
        m = dh_matrix(L, *l)
        acc = m if acc is None else matmul(L, acc, m)
    return acc


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return [
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ]


def dh_dq(L, th, d, a, al):
    """r + eps t r / 2 with r = Rz(theta) Rx(alpha), t = (a cos theta, a sin theta, d)."""
    h = L.rat(1, 2)
    z = L.zero
    r = qmul([L.cos(th * h), z, z, L.sin(th * h)], [L.cos(al * h), L.sin(al * h), z, z])
    t = [z, a * L.cos(th) * h, a * L.sin(th) * h, d * h]
    return [L.expand(x) for x in r + qmul(t, r)]


def dq_chain(L, links):
    acc = None
    for l in links:
        q = dh_dq(L, *l)
        if acc is None:
            acc = q
            continue
        ar, ad, br, bd = acc[:4], acc[4:], q[:4], q[4:]
        r = qmul(ar, br)
        d = [u + v for u, v in zip(qmul(ar, bd), qmul(ad, br))]
        acc = [L.expand(x) for x in r + d]
    return acc


def size(exprs):
    """Counts + - * / and calls the way dqsym's Expr::cost does: a sum of n terms is n - 1 ops
    (negative terms free), a product of n factors n - 1 (a -1 coefficient free inside a sum), a
    non-integer rational one division, x^n n - 1 multiplications, sqrt and each cos/sin one op
    and one call; the angle argument of cos/sin is not counted (dqsym's c12 is one call)."""
    ops = calls = 0

    def go(e, in_sum):
        nonlocal ops, calls
        name = type(e).__name__
        if e.is_Number:
            if e.is_Rational and not e.is_Integer:
                ops += 1
            elif not e.is_Rational:
                pass
            return
        if e.is_Symbol or not e.args:
            return
        if e.is_Add:
            ops += len(e.args) - 1
            for a in e.args:
                go(a, True)
            return
        if e.is_Mul:
            n, neg = 0, False
            for a in e.args:
                if a.is_Number and a == -1:
                    neg = True
                    continue
                if a.is_Number and a.is_Rational and a < 0:
                    neg = True
                n += 1
                go(a, False)
            ops += max(n - 1, 0) + (1 if neg and not in_sum else 0)
            return
        if e.is_Pow:
            b, x = e.args
            if x.is_Integer and x > 0:
                ops += int(x) - 1
            elif x.is_Integer:
                ops += -int(x)
            else:
                ops += 1
                calls += 1
                if not (x.is_Rational and x == L_HALF[0]):
                    go(x, False)
            go(b, False)
            return
        ops += 1
        calls += 1
        if name not in ("sin", "cos"):
            for a in e.args:
                go(a, False)

    for x in exprs:
        go(x, False)
    return ops, calls


L_HALF = [None]


def emit(stage, seconds, exprs):
    ops, calls = size(exprs)
    print(
        json.dumps(
            {
                "stage": stage,
                "seconds": round(seconds, 6),
                "ops": ops,
                "calls": calls,
                "entries": len(exprs),
            }
        ),
        flush=True,
    )


def run(L, workload, simplifiers):
    """Runs one workload; `simplifiers` is a list of (name, function) tried after expansion
    (SymPy: trigsimp, fu; SymEngine has none). A simplifier's time is the expansion's plus its
    own."""
    L_HALF[0] = L.rat(1, 2)

    def stages(prefix, t0, xs):
        base = time.perf_counter() - t0
        emit(prefix + "expand", base, xs)
        for name, f in simplifiers:
            t1 = time.perf_counter()
            ys = [f(x) for x in xs]
            emit(prefix + name, base + time.perf_counter() - t1, ys)

    t0 = time.perf_counter()
    if workload == "W1":
        m = matrix_chain(L, planar(L, 3))
        stages("", t0, [m[0][3], m[1][3]])
    elif workload == "W2":
        m = matrix_chain(L, puma(L))
        stages("matrix:", t0, [m[i][j] for i in range(3) for j in range(4)])
        t0 = time.perf_counter()
        stages("dq:", t0, dq_chain(L, puma(L)))
    elif workload == "W3":
        m = matrix_chain(L, generic(L, 6))
        emit("matrix:expand", time.perf_counter() - t0, [m[i][j] for i in range(3) for j in range(4)])
        t0 = time.perf_counter()
        q = dq_chain(L, generic(L, 6))
        emit("dq:expand", time.perf_counter() - t0, q)
    elif workload == "W4":
        links = puma(L)
        q = dq_chain(L, links)
        jac = [L.expand(c.diff(l[0])) for c in q for l in links]
        stages("", t0, jac)
    elif workload == "W5":
        m = matrix_chain(L, planar(L, 20))
        stages("", t0, [m[0][3], m[1][3]])
    else:
        sys.exit("usage: PEER.py W1|W2|W3|W4|W5")
