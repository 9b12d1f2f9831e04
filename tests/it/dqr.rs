//! DQ Robotics' vocabulary (`dqr`, `dqexp`, the `--jacobian=KIND` task Jacobians): every
//! operation's exact result, evaluated at random points, against an independent NumPy
//! implementation written here and against the `dqrobotics` package itself (pinned in
//! scripts/test.sh); exact identities; snapshots of the closed forms on a symbolic screw.

use super::tools::run_python;
use dqsym::{algebra::dqr, kin::dqexp, DualQuat, Quat, Scalar};
use std::process::Command;

fn s(x: &str) -> Scalar {
    Scalar::sym(x)
}

fn r(n: i64, d: i64) -> Scalar {
    Scalar::int(n).try_div(&Scalar::int(d)).unwrap()
}

/// An exact unit axis.
fn axis() -> [Scalar; 3] {
    [r(2, 3), r(1, 3), r(-2, 3)]
}

/// Two symbolic unit DQs: a general screw and a rotation after a translation.
fn poses() -> (DualQuat<Scalar>, DualQuat<Scalar>) {
    let q1 = DualQuat::screw(&axis(), &[s("a"), s("b"), s("c")], &s("theta"), &s("d"));
    let q2 = DualQuat::rotation(&[r(0, 1), r(0, 1), r(1, 1)], &s("phi"))
        * DualQuat::translation(&[s("e"), s("f"), r(1, 2)]);
    (q1, q2)
}

type Env = Vec<(&'static str, f64)>;

fn env(k: usize) -> Env {
    // Deterministic pseudo-random values; angles in (0.2, 2.9) so that acos's branch agrees.
    let mut x = 0x9e37_79b9_7f4a_7c15_u64.wrapping_mul(k as u64 + 1);
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut v = |lo: f64, hi: f64| lo + (hi - lo) * next();
    vec![
        ("theta", v(0.2, 2.9)),
        ("phi", v(0.2, 2.9)),
        ("d", v(-1.0, 1.0)),
        ("a", v(-1.0, 1.0)),
        ("b", v(-1.0, 1.0)),
        ("c", v(-1.0, 1.0)),
        ("e", v(-1.0, 1.0)),
        ("f", v(-1.0, 1.0)),
        ("t", v(0.0, 1.0)),
    ]
}

fn ev(x: &Scalar, e: &Env) -> f64 {
    x.eval_at(e)
        .unwrap_or_else(|err| panic!("eval {x:?}: {err}"))
}

fn evs(xs: &[Scalar], e: &Env) -> Vec<f64> {
    xs.iter().map(|x| ev(x, e)).collect()
}

fn fmt(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.17e}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn dq8(q: &DualQuat<Scalar>, e: &Env) -> Vec<f64> {
    evs(&q.components(), e)
}

fn q4(q: &Quat<Scalar>, e: &Env) -> Vec<f64> {
    evs(&q.components(), e)
}

fn flat(m: &[Vec<Scalar>], e: &Env) -> Vec<f64> {
    m.iter().flat_map(|row| evs(row, e)).collect()
}

fn flat4(m: &[[Scalar; 4]; 4], e: &Env) -> Vec<f64> {
    m.iter().flat_map(|row| evs(row, e)).collect()
}

/// The NumPy oracle: an independent dual-quaternion implementation (8-vectors), DQ Robotics'
/// definitions written from its documentation, and the `dqrobotics` package. Each input line is
/// `op;arg1;arg2;number;expected` (comma-separated floats; empty fields allowed).
const ORACLE: &str = r#"
import sys, numpy as np
from dqrobotics import DQ, vec8, vec4, vec3, vec6, hamiplus4, haminus4, hamiplus8, haminus8
import dqrobotics as dqr
from dqrobotics.utils import DQ_Geometry as G

def qm(a, b):
    w1, x1, y1, z1 = a; w2, x2, y2, z2 = b
    return np.array([w1*w2-x1*x2-y1*y2-z1*z2, w1*x2+x1*w2+y1*z2-z1*y2,
                     w1*y2-x1*z2+y1*w2+z1*x2, w1*z2+x1*y2-y1*x2+z1*w2])
def m(a, b): return np.concatenate([qm(a[:4], b[:4]), qm(a[:4], b[4:]) + qm(a[4:], b[:4])])
def qc(a): return np.array([a[0], -a[1], -a[2], -a[3]])
def conj(a): return np.concatenate([qc(a[:4]), qc(a[4:])])
def sharp(a): return np.concatenate([a[:4], -a[4:]])
def pure(v): return np.array([0.0, *v])
def transl(a): return 2 * qm(a[4:], qc(a[:4]))
def qexp(r):
    th = np.linalg.norm(r[1:])
    return np.array([1.0, 0, 0, 0]) if th == 0 else np.concatenate([[np.cos(th)], np.sin(th) * r[1:] / th])
def dexp(h):
    p = qexp(h[:4]); return np.concatenate([p, qm(h[4:], p)])
def angle(a): return 2 * np.arccos(np.clip(a[0], -1, 1))
def axis(a):
    ph = angle(a) / 2
    return np.array([0, 0, 0, 1.0]) if ph == 0 else np.concatenate([[0], a[1:4] / np.sin(ph)])
def dlog(a): return np.concatenate([0.5 * angle(a) * axis(a), 0.5 * transl(a)])
def screw(q):
    th = angle(q); n = q[1:4] / np.sin(th / 2)
    d = -2 * q[4] / np.sin(th / 2)
    mo = (2 * q[5:8] - np.cos(th / 2) * d * n) / (2 * np.sin(th / 2))
    return th, d, n, mo
def spow(q, t):
    th, d, n, mo = screw(q)
    c, s = np.cos(t * th / 2), np.sin(t * th / 2)
    return np.concatenate([[c], s * n, [-t * d / 2 * s], t * d / 2 * c * n + s * mo])
def ham(a, plus):
    w, x, y, z = a
    if plus: return np.array([[w,-x,-y,-z],[x,w,-z,y],[y,z,w,-x],[z,-y,x,w]])
    return np.array([[w,-x,-y,-z],[x,w,z,-y],[y,-z,w,x],[z,y,-x,w]])
def ham8(a, plus):
    P, D = ham(a[:4], plus), ham(a[4:], plus)
    return np.block([[P, np.zeros((4, 4))], [D, P]])
def line(l, p): return np.concatenate([pure(l), pure(np.cross(p, l))])
def plane(n, p): return np.concatenate([pure(n), [np.dot(p, n), 0, 0, 0]])

def ours(op, a, b, k):
    if op == "P": return a[:4]
    if op == "D": return a[4:]
    if op == "Re": return np.array([a[0], 0, 0, 0, a[4], 0, 0, 0])
    if op == "Im": return np.array([0, *a[1:4], 0, *a[5:8]])
    if op == "conj": return conj(a)
    if op == "sharp": return sharp(a)
    if op == "norm":
        n = np.sqrt(a[:4] @ a[:4]); return np.array([n, 0, 0, 0, (a[:4] @ a[4:]) / n, 0, 0, 0])
    if op == "inv":
        P = qc(a[:4]) / (a[:4] @ a[:4]); return np.concatenate([P, -qm(qm(P, a[4:]), P)])
    if op == "translation": return transl(a)
    if op == "rotation": return a[:4]
    if op == "rotation_angle": return np.array([angle(a)])
    if op == "rotation_axis": return axis(a)
    if op == "log": return dlog(a)
    if op == "exp": return dexp(a)
    if op == "pow": return dexp(k[0] * dlog(a))
    if op == "screwpow": return spow(a, k[0])
    if op == "sclerp": return m(a, spow(m(conj(a), b), k[0]))
    if op == "sclerpdot":
        h = 1e-6
        return (m(a, spow(m(conj(a), b), k[0] + h)) - m(a, spow(m(conj(a), b), k[0] - h))) / (2 * h)
    if op == "screwlog":
        th, d, n, mo = screw(a)
        return np.concatenate([[0], th / 2 * n, [0], d / 2 * n + th / 2 * mo])
    if op == "tplus": return m(a, np.concatenate([qc(a[:4]), np.zeros(4)]))
    if op == "Ad": return m(m(a, b), conj(a))
    if op == "Adsharp": return m(m(sharp(a), b), conj(a))
    if op == "hamiplus4": return ham(a[:4], True).ravel()
    if op == "haminus4": return ham(a[:4], False).ravel()
    if op == "hamiplus8": return ham8(a, True).ravel()
    if op == "haminus8": return ham8(a, False).ravel()
    if op == "cross": return (m(a, b) - m(b, a)) / 2
    if op == "dot": return -(m(a, b) + m(b, a)) / 2
    if op == "line": return line(a[1:4], b[1:4])
    if op == "plane": return plane(a[1:4], b[1:4])
    if op == "p2p": return np.array([np.sum((a[1:4] - b[1:4])**2)])
    if op == "p2l": return np.array([np.sum((np.cross(a[1:4], b[1:4]) - b[5:8])**2)])
    if op == "p2pi": return np.array([a[1:4] @ b[1:4] - b[4]])
    if op == "normalize":
        nP = np.sqrt(a[:4] @ a[:4])
        return m(a, np.array([1 / nP, 0, 0, 0, -(a[:4] @ a[4:]) / nP**3, 0, 0, 0]))
    if op == "crossmatrix4":
        x, y, z = a[1:4]
        return np.array([[0, 0, 0, 0], [0, 0, -z, y], [0, z, 0, -x], [0, -y, x, 0]]).ravel()
    if op == "proj":
        l, mm = b[1:4], b[5:8]
        return pure(np.cross(l, mm) + (a[1:4] @ l) * l)
    if op == "closest":
        # Minimize |c1 + s l1 - c2 - u l2| over s, u (c the points nearest the origin).
        l1, l2 = a[1:4], b[1:4]
        c1, c2 = np.cross(l1, a[5:8]), np.cross(l2, b[5:8])
        A = np.array([[l1 @ l1, -(l1 @ l2)], [l1 @ l2, -(l2 @ l2)]])
        s_, u = np.linalg.solve(A, [(c2 - c1) @ l1, (c2 - c1) @ l2])
        return np.concatenate([c1 + s_ * l1, c2 + u * l2])
    if op == "vec3": return a[1:4]
    if op == "vec4": return a[:4]
    if op == "vec6": return np.concatenate([a[1:4], a[5:8]])
    if op == "vec8": return a
    if op == "twist": return 2 * m(b, conj(a))
    if op == "bodytwist": return 2 * m(conj(a), b)
    if op == "qdot": return 0.5 * m(b, a)
    if op == "l2la": return np.array([np.arccos(np.clip(a[1:4] @ b[1:4], -1, 1))])
    if op == "plane_move":
        w, x, y, z = a[:4]
        R = np.array([[1-2*(y*y+z*z), 2*(x*y-w*z), 2*(x*z+w*y)],
                      [2*(x*y+w*z), 1-2*(x*x+z*z), 2*(y*z-w*x)],
                      [2*(x*z-w*y), 2*(y*z+w*x), 1-2*(x*x+y*y)]])
        n = R @ b[1:4]
        return np.array([0, *n, b[4] + transl(a)[1:] @ n, 0, 0, 0])
    if op == "l2l":
        c = np.cross(a[1:4], b[1:4]); dd = a[1:4] @ b[5:8] + a[5:8] @ b[1:4]
        return np.array([dd**2 / (c @ c)])
    raise SystemExit("unknown op " + op)

def theirs(op, a, b, k):
    A, B = DQ(a), DQ(b) if len(b) else None
    v = lambda x: vec8(x)
    f = {"P": lambda: vec4(dqr.P(A)), "D": lambda: vec4(dqr.D(A)), "Re": lambda: v(dqr.Re(A)),
         "Im": lambda: v(dqr.Im(A)), "conj": lambda: v(dqr.conj(A)), "sharp": lambda: v(dqr.sharp(A)),
         "norm": lambda: v(dqr.norm(A)), "inv": lambda: v(dqr.inv(A)),
         "translation": lambda: vec4(dqr.translation(A)), "rotation": lambda: vec4(dqr.rotation(A)),
         "rotation_angle": lambda: np.array([dqr.rotation_angle(A)]),
         "rotation_axis": lambda: vec4(dqr.rotation_axis(A)), "log": lambda: v(dqr.log(A)),
         "exp": lambda: v(dqr.exp(A)), "pow": lambda: v(dqr.pow(A, k[0])),
         "tplus": lambda: v(dqr.tplus(A)), "Ad": lambda: v(dqr.Ad(A, B)),
         "Adsharp": lambda: v(dqr.Adsharp(A, B)), "plane_move": lambda: v(dqr.Adsharp(A, B)),
         "vec3": lambda: vec3(A), "vec4": lambda: vec4(A), "vec6": lambda: vec6(A), "vec8": lambda: vec8(A),
         "l2la": lambda: np.array([G.line_to_line_angle(A, B)]),
         "normalize": lambda: v(dqr.normalize(A)), "crossmatrix4": lambda: dqr.crossmatrix4(A).ravel(),
         "proj": lambda: vec4(G.point_projected_in_line(A, B)),
         "closest": lambda: np.concatenate([vec3(p) for p in G.closest_points_between_lines(A, B)]), "hamiplus4": lambda: hamiplus4(A).ravel(),
         "haminus4": lambda: haminus4(A).ravel(), "hamiplus8": lambda: hamiplus8(A).ravel(),
         "haminus8": lambda: haminus8(A).ravel(), "cross": lambda: v(dqr.cross(A, B)),
         "dot": lambda: v(dqr.dot(A, B)),
         "p2p": lambda: np.array([G.point_to_point_squared_distance(A, B)]),
         "p2l": lambda: np.array([G.point_to_line_squared_distance(A, B)]),
         "p2pi": lambda: np.array([G.point_to_plane_distance(A, B)]),
         "l2l": lambda: np.array([G.line_to_line_squared_distance(A, B)])}
    return f[op]() if op in f else None

checked = {"numpy": 0, "dqrobotics": 0}
for line_ in sys.stdin:
    op, a, b, k, want = line_.rstrip("\n").split(";")
    arr = lambda s: np.array([float(x) for x in s.split(",")]) if s else np.array([])
    a, b, k, want = arr(a), arr(b), arr(k), arr(want)
    tol = 1e-5 if op == "sclerpdot" else 1e-9
    for name, fn in (("numpy", ours), ("dqrobotics", theirs)):
        got = fn(op, a, b, k)
        if got is None: continue
        got = np.asarray(got, dtype=float).ravel()
        if got.shape != want.shape or not np.allclose(got, want, atol=tol, rtol=tol):
            raise SystemExit(f"{op} differs from {name}: ours {want}, {name} {got}, inputs {a} {b} {k}")
        checked[name] += 1
print(checked["numpy"], checked["dqrobotics"])
"#;

fn pt(v: &[Scalar; 3], e: &Env) -> Vec<f64> {
    let mut out = vec![0.0];
    out.extend(evs(v, e));
    out
}

/// The cases handed to the oracle, one `op;a;b;k;want` line each: the operation, its
/// arguments `a`, `b` and scalars `k` evaluated at a point, and what dqsym computes there.
#[derive(Default)]
struct Cases(Vec<String>);

impl Cases {
    fn add(&mut self, op: &str, a: Vec<f64>, b: Vec<f64>, k: Vec<f64>, want: Vec<f64>) {
        self.0.push(format!(
            "{op};{};{};{};{}",
            fmt(&a),
            fmt(&b),
            fmt(&k),
            fmt(&want)
        ));
    }
}

/// Parts, conjugates, norm, inverse, translation and rotation.
fn algebra_cases(c: &mut Cases, q1: &DualQuat<Scalar>, q2: &DualQuat<Scalar>, e: &Env) {
    let a = dq8(q1, e);
    c.add("P", a.clone(), vec![], vec![], q4(&dqr::primary(q1), e));
    c.add("D", a.clone(), vec![], vec![], q4(&dqr::dual_part(q1), e));
    c.add("Re", a.clone(), vec![], vec![], dq8(&dqr::re(q1), e));
    c.add("Im", a.clone(), vec![], vec![], dq8(&dqr::im(q1), e));
    c.add("conj", a.clone(), vec![], vec![], dq8(&q1.conjugate(), e));
    c.add("sharp", a.clone(), vec![], vec![], dq8(&dqr::sharp(q1), e));
    let scaled = q2.scale(&Scalar::int(3));
    let n = dqexp::norm(&scaled).unwrap();
    c.add("norm", dq8(&scaled, e), vec![], vec![], dq8(&n, e));
    c.add(
        "inv",
        dq8(&scaled, e),
        vec![],
        vec![],
        dq8(&scaled.try_inverse().unwrap(), e),
    );
    c.add(
        "translation",
        a.clone(),
        vec![],
        vec![],
        q4(&dqr::translation(q1), e),
    );
    c.add("rotation", a.clone(), vec![], vec![], q4(&q1.real, e));
    let ang = dqexp::rotation_angle(q1).unwrap();
    c.add(
        "rotation_angle",
        a.clone(),
        vec![],
        vec![],
        vec![ev(&ang, e)],
    );
    let ax = dqexp::rotation_axis(q1).unwrap();
    c.add("rotation_axis", a.clone(), vec![], vec![], q4(&ax, e));
}

/// log, exp, powers, the screw operations and ScLERP.
fn exponential_cases(c: &mut Cases, q1: &DualQuat<Scalar>, q2: &DualQuat<Scalar>, e: &Env) {
    let (a, b) = (dq8(q1, e), dq8(q2, e));
    let t = ev(&s("t"), e);
    let third = r(1, 3);
    for q in [q1, q2] {
        let l = dqexp::log(q).unwrap();
        c.add("log", dq8(q, e), vec![], vec![], dq8(&l, e));
        c.add(
            "exp",
            dq8(&l, e),
            vec![],
            vec![],
            dq8(&dqexp::exp(&l).unwrap(), e),
        );
        let p = dqexp::pow(q, &third, None).unwrap();
        c.add("pow", dq8(q, e), vec![], vec![1.0 / 3.0], dq8(&p, e));
        // A symbolic exponent with its named angle psi = t * rotation_angle(q).
        let p = dqexp::pow(q, &s("t"), Some(&s("psi"))).unwrap();
        let mut e2 = e.clone();
        let psi = t * ev(&dqexp::rotation_angle(q).unwrap(), e);
        e2.push(("psi", psi));
        c.add("pow", dq8(q, e), vec![], vec![t], dq8(&p, &e2));
    }
    // The screw operations need the axis and moment as polynomials: q1 is a screw about a
    // constant axis through a symbolic point (q2's planar centre is a quotient).
    let mut e2 = e.clone();
    e2.push(("psi", t * ev(&dqexp::rotation_angle(q1).unwrap(), e)));
    let sp = dqexp::screw_pow(q1, &s("t"), Some(&s("psi"))).unwrap();
    c.add("screwpow", a.clone(), vec![], vec![t], dq8(&sp, &e2));
    let sl = dqexp::screw_log(q1).unwrap();
    c.add("screwlog", a.clone(), vec![], vec![], dq8(&sl, e));
    // ScLERP from q2 to q2 q1 (relative motion q1) and its derivative.
    let end = q2 * q1;
    let sc = dqexp::sclerp(q2, &end, &s("t"), Some(&s("psi"))).unwrap();
    c.add("sclerp", b.clone(), dq8(&end, e), vec![t], dq8(&sc, &e2));
    let scd = dqexp::sclerp_derivative(q2, &end, &s("t"), Some(&s("psi"))).unwrap();
    c.add(
        "sclerpdot",
        b.clone(),
        dq8(&end, e),
        vec![t],
        dq8(&scd, &e2),
    );
}

/// The line `x` through `(e, 2, f)` along `axis()` and its image `y` by `q2`.
fn lines_of(q2: &DualQuat<Scalar>) -> (DualQuat<Scalar>, DualQuat<Scalar>) {
    let x = dqr::line(&axis(), &[s("e"), Scalar::int(2), s("f")]);
    let y = dqr::transform_line(q2, &x);
    (x, y)
}

/// Adjoints, Hamilton matrices, lines, planes and distances.
fn geometry_cases(c: &mut Cases, q1: &DualQuat<Scalar>, q2: &DualQuat<Scalar>, e: &Env) {
    let a = dq8(q1, e);
    let two = Scalar::int(2);
    c.add("tplus", a.clone(), vec![], vec![], dq8(&dqr::tplus(q1), e));
    let x = dqr::line(&axis(), &[s("e"), two.clone(), s("f")]);
    let p = DualQuat::from_real_and_dual(Quat::identity(), Quat::vector(s("a"), s("b"), s("c")));
    c.add(
        "Ad",
        a.clone(),
        dq8(&x, e),
        vec![],
        dq8(&dqr::ad(q1, &x), e),
    );
    c.add(
        "Adsharp",
        a.clone(),
        dq8(&p, e),
        vec![],
        dq8(&dqr::adsharp(q1, &p), e),
    );
    c.add(
        "hamiplus4",
        a.clone(),
        vec![],
        vec![],
        flat4(&dqr::hamiplus4(&q1.real), e),
    );
    c.add(
        "haminus4",
        a.clone(),
        vec![],
        vec![],
        flat4(&dqr::haminus4(&q1.real), e),
    );
    c.add(
        "hamiplus8",
        a.clone(),
        vec![],
        vec![],
        flat(&dqr::hamiplus8(q1), e),
    );
    c.add(
        "haminus8",
        a.clone(),
        vec![],
        vec![],
        flat(&dqr::haminus8(q1), e),
    );
    let y = dqr::transform_line(q2, &x);
    c.add(
        "cross",
        dq8(&x, e),
        dq8(&y, e),
        vec![],
        dq8(&dqr::cross(&x, &y), e),
    );
    c.add(
        "dot",
        dq8(&x, e),
        dq8(&y, e),
        vec![],
        dq8(&dqr::dot(&x, &y), e),
    );
    let (dir, at) = (axis(), [s("a"), s("b"), s("c")]);
    c.add(
        "line",
        pt(&dir, e),
        pt(&at, e),
        vec![],
        dq8(&dqr::line(&dir, &at), e),
    );
    c.add(
        "plane",
        pt(&dir, e),
        pt(&at, e),
        vec![],
        dq8(&dqr::plane(&dir, &at), e),
    );
    let (u, w) = ([s("a"), s("b"), s("c")], [s("e"), s("f"), s("d")]);
    let pu = |v: &[Scalar; 3]| DualQuat::from_real(Quat::from_vector(v));
    c.add(
        "p2p",
        dq8(&pu(&u), e),
        dq8(&pu(&w), e),
        vec![],
        vec![ev(&dqr::point_to_point_squared_distance(&u, &w), e)],
    );
    c.add(
        "p2l",
        dq8(&pu(&u), e),
        dq8(&y, e),
        vec![],
        vec![ev(&dqr::point_to_line_squared_distance(&u, &y), e)],
    );
    let pl = dqr::plane(&axis(), &w);
    c.add(
        "p2pi",
        dq8(&pu(&u), e),
        dq8(&pl, e),
        vec![],
        vec![ev(&dqr::point_to_plane_distance(&u, &pl), e)],
    );
}

/// Vectorizations, twists and back, angles, normalization, projections and closest points.
fn vector_cases(c: &mut Cases, q1: &DualQuat<Scalar>, q2: &DualQuat<Scalar>, e: &Env) {
    let a = dq8(q1, e);
    let two = Scalar::int(2);
    let scaled = q2.scale(&Scalar::int(3));
    let (x, y) = lines_of(q2);
    let pl = dqr::plane(&axis(), &[s("e"), s("f"), s("d")]);
    // Vectorizations, twists and back, the angle between two lines.
    c.add(
        "vec3",
        a.clone(),
        vec![],
        vec![],
        evs(&q1.real.vector_part(), e),
    );
    c.add("vec4", a.clone(), vec![], vec![], q4(&q1.real, e));
    c.add("vec6", a.clone(), vec![], vec![], evs(&dqr::vec6(q1), e));
    c.add("vec8", a.clone(), vec![], vec![], dq8(q1, e));
    let qd = DualQuat::from_components(q1.components().map(|c| c.diff("theta") + c.diff("d")));
    let xi = dqexp::twist(q1, &qd, false);
    c.add("twist", a.clone(), dq8(&qd, e), vec![], dq8(&xi, e));
    let xib = dqexp::twist(q1, &qd, true);
    c.add("bodytwist", a.clone(), dq8(&qd, e), vec![], dq8(&xib, e));
    c.add(
        "qdot",
        a.clone(),
        dq8(&xi, e),
        vec![],
        dq8(&dqexp::from_twist(q1, &xi, false), e),
    );
    let x0 = dqr::line(&[r(1, 1), r(0, 1), r(0, 1)], &[s("e"), two.clone(), s("f")]);
    let spun0 = dqr::ad(
        &DualQuat::rotation(&[r(0, 1), r(0, 1), r(1, 1)], &s("phi")),
        &x0,
    );
    let angle = dqr::line_to_line_cos(&x0, &spun0)
        .as_cos_of_angle()
        .expect("cos(phi)");
    c.add(
        "l2la",
        dq8(&x0, e),
        dq8(&spun0, e),
        vec![],
        vec![ev(&angle, e)],
    );
    // normalize, crossmatrix4, the projection on a line and the closest points of two lines.
    let h = scaled.clone()
        + DualQuat::from_real_and_dual(Quat::zero(), Quat::new(s("a"), s("b"), r(0, 1), s("c")));
    c.add(
        "normalize",
        dq8(&h, e),
        vec![],
        vec![],
        dq8(&dqexp::normalize(&h).unwrap(), e),
    );
    let pq = Quat::vector(s("a"), s("b"), s("c"));
    c.add(
        "crossmatrix4",
        dq8(&DualQuat::from_real(pq.clone()), e),
        vec![],
        vec![],
        flat4(&dqr::crossmatrix4(&pq), e),
    );
    let proj = dqr::point_projected_in_line(&pq.vector_part(), &y);
    c.add(
        "proj",
        dq8(&DualQuat::from_real(pq.clone()), e),
        dq8(&y, e),
        vec![],
        pt(&proj, e),
    );
    let (c1, c2, den) = dqr::closest_points_between_lines(&x, &y).unwrap();
    let dv = ev(&den, e);
    c.add(
        "closest",
        dq8(&x, e),
        dq8(&y, e),
        vec![],
        evs(&c1, e)
            .into_iter()
            .chain(evs(&c2, e))
            .map(|z| z / dv)
            .collect(),
    );
    // The plane through (e, f, d) with normal `axis()`, moved by q1.
    c.add(
        "plane_move",
        a.clone(),
        dq8(&pl, e),
        vec![],
        dq8(&dqr::transform_plane(q1, &pl), e),
    );
    let (num, den) = dqr::line_to_line_squared_distance(&x, &y);
    c.add(
        "l2l",
        dq8(&x, e),
        dq8(&y, e),
        vec![],
        vec![ev(&num, e) / ev(&den, e)],
    );
}

#[test]
fn every_operation_matches_numpy_and_dqrobotics_at_random_points() {
    let (q1, q2) = poses();
    let mut cases = Cases::default();
    for i in 0..6 {
        let e = env(i);
        algebra_cases(&mut cases, &q1, &q2, &e);
        exponential_cases(&mut cases, &q1, &q2, &e);
        geometry_cases(&mut cases, &q1, &q2, &e);
        vector_cases(&mut cases, &q1, &q2, &e);
    }
    let lines = cases.0;
    let out = run_python(ORACLE, &(lines.join("\n") + "\n"), "dqrobotics");
    let counts: Vec<usize> = out.split_whitespace().map(|x| x.parse().unwrap()).collect();
    assert_eq!(counts[0], lines.len(), "every case checked against NumPy");
    assert!(
        counts[1] >= lines.len() * 3 / 4,
        "most cases checked against dqrobotics: {out}"
    );
}

mod exact {
    //! Exact identities (proptest over axes, points, angles and slides).
    use super::*;
    use proptest::prelude::*;

    /// Exact unit axes with rational components.
    const AXES: [[(i64, i64); 3]; 5] = [
        [(1, 1), (0, 1), (0, 1)],
        [(0, 1), (0, 1), (1, 1)],
        [(2, 3), (1, 3), (-2, 3)],
        [(3, 5), (0, 1), (4, 5)],
        [(-2, 7), (3, 7), (6, 7)],
    ];

    fn ax(k: usize) -> [Scalar; 3] {
        AXES[k].map(|(n, d)| r(n, d))
    }

    /// A screw with an angle `k pi/6 + j theta` (j in 0..=1; half angles with exact cosines), a
    /// small integer point and a slide `k + d`.
    fn screw_strategy() -> impl Strategy<Value = DualQuat<Scalar>> {
        (
            0usize..5,
            -3i64..4,
            -3i64..4,
            -3i64..4,
            1i64..6,
            0i64..2,
            -3i64..4,
        )
            .prop_map(|(k, x, y, z, a, j, d)| {
                let angle = Scalar::pi() * r(a, 6) + s("theta") * Scalar::int(j);
                let p = [Scalar::int(x), Scalar::int(y), Scalar::int(z)];
                DualQuat::screw(&ax(k), &p, &angle, &(Scalar::int(d) + s("d")))
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        #[test]
        fn exp_of_log_is_the_pose_up_to_sign(q in screw_strategy()) {
            let back = dqexp::exp(&dqexp::log(&q).unwrap()).unwrap();
            prop_assert!(back == q || back == -q.clone(), "{back:?} vs {q:?}");
        }

        #[test]
        fn screw_log_of_coaxial_screws_adds(k in 0usize..5, x in -3i64..4, z in -3i64..4,
                                           a in 1i64..6, b in 1i64..6) {
            // Two screws about one axis (angles theta + a pi/6 and b pi/6, slides d and 2):
            // the screw log of the product is the sum of the logs.
            let p = [Scalar::int(x), Scalar::int(0), Scalar::int(z)];
            let t1 = s("theta") + Scalar::pi() * r(a, 6);
            let t2 = Scalar::pi() * r(b, 6);
            let q1 = DualQuat::screw(&ax(k), &p, &t1, &s("d"));
            let q2 = DualQuat::screw(&ax(k), &p, &t2, &Scalar::int(2));
            let sum = dqexp::screw_log(&q1).unwrap() + dqexp::screw_log(&q2).unwrap();
            prop_assert_eq!(dqexp::screw_log(&(&q1 * &q2)).unwrap(), sum);
        }

        #[test]
        fn sclerp_has_its_endpoints_and_a_constant_body_twist(q in screw_strategy(),
                                                               k in 0usize..5, w in -2i64..3) {
            let q0 = DualQuat::rotation(&ax(k), &s("phi")) * DualQuat::translation(&[Scalar::int(w), s("e"), Scalar::int(1)]);
            let q1 = &q0 * &q;
            prop_assert_eq!(dqexp::sclerp(&q0, &q1, &Scalar::int(0), None).unwrap(), q0.clone());
            prop_assert_eq!(dqexp::sclerp(&q0, &q1, &Scalar::int(1), None).unwrap(), q1.clone());
            // q(t) = sclerp, q'(t) = sclerp xi: the body twist 2 q* q' is 2 xi, free of t and psi.
            let x = dqexp::sclerp(&q0, &q1, &s("t"), Some(&s("psi"))).unwrap();
            let xd = dqexp::sclerp_derivative(&q0, &q1, &s("t"), Some(&s("psi"))).unwrap();
            let body = dqexp::twist(&x, &xd, true);
            let xi = dqexp::screw_log(&q).unwrap().scale(&Scalar::int(2));
            prop_assert_eq!(body, xi);
        }

        #[test]
        fn ad_moves_lines_like_points_and_keeps_pluecker_constraints(q in screw_strategy(),
                                                                   k in 0usize..5,
                                                                   x in -3i64..4) {
            let p = [Scalar::int(x), s("b"), Scalar::int(1)];
            let l = dqr::line(&ax(k), &p);
            let moved = dqr::transform_line(&q, &l);
            let (a, b) = dqr::line_constraints(&moved);
            prop_assert!(a.is_zero_value() && b.is_zero_value());
            let dir = (&q.real * &Quat::from_vector(&ax(k)) * q.real.conjugate()).vector_part();
            prop_assert_eq!(&moved, &dqr::line(&dir, &q.transform_point(&p)));
            // Ad(q) x = q x q* (conj conjugates both parts).
            prop_assert_eq!(moved, &q * &l * q.conjugate());
        }

        #[test]
        fn adsharp_moves_planes_like_points(q in screw_strategy(), k in 0usize..5,
                                            x in -3i64..4) {
            // A plane through (x, b, 1) with unit normal n: Adsharp(q, plane) is the plane
            // through the moved point with the rotated normal, a plane again (pure unit normal,
            // scalar dual part); signed distances of moved points to it are unchanged; and
            // q plane q* (Ad) is not a plane (its dual part has the vector t x n').
            let p = [Scalar::int(x), s("b"), Scalar::int(1)];
            let pl = dqr::plane(&ax(k), &p);
            let moved = dqr::transform_plane(&q, &pl);
            let n = (&q.real * &Quat::from_vector(&ax(k)) * q.real.conjugate()).vector_part();
            prop_assert_eq!(&moved, &dqr::plane(&n, &q.transform_point(&p)));
            prop_assert!(moved.real.w.is_zero_value());
            prop_assert!(moved.dual.vector_part().iter().all(Scalar::is_zero_value));
            let nn = dqr::dot3(&moved.real.vector_part(), &moved.real.vector_part());
            prop_assert!((nn - Scalar::int(1)).is_zero_value());
            let u = [s("u"), s("v"), Scalar::int(x)];
            prop_assert_eq!(
                dqr::point_to_plane_distance(&q.transform_point(&u), &moved),
                dqr::point_to_plane_distance(&u, &pl)
            );
            let t = dqr::translation(&q).vector_part();
            let ad = dqr::ad(&q, &pl);
            let txn = [
                &t[1] * &n[2] - &t[2] * &n[1],
                &t[2] * &n[0] - &t[0] * &n[2],
                &t[0] * &n[1] - &t[1] * &n[0],
            ];
            prop_assert_eq!(ad.dual.vector_part(), txn);
        }

        #[test]
        fn hamilton_matrices_compute_the_product_exactly(a in screw_strategy(), b in screw_strategy()) {
            let ab = (&a * &b).components();
            let (hp, hm) = (dqr::hamiplus8(&a), dqr::haminus8(&b));
            let (va, vb) = (a.components(), b.components());
            for i in 0..8 {
                let p = (0..8).fold(Scalar::int(0), |acc, j| acc + &hp[i][j] * &vb[j]);
                let m = (0..8).fold(Scalar::int(0), |acc, j| acc + &hm[i][j] * &va[j]);
                prop_assert_eq!(&p, &ab[i]);
                prop_assert_eq!(&m, &ab[i]);
            }
        }
    }

    #[test]
    fn closest_points_and_projections_are_on_their_lines() {
        // Two skew lines through symbolic points: each closest point lies on its line, their
        // difference is perpendicular to both, and its squared length is the line-to-line
        // squared distance (all multiplied through by the denominator |l1 x l2|^2). The
        // projection of a point lies on the line, the offset perpendicular to it.
        let l1 = dqr::line(&ax(2), &[s("a"), s("b"), s("c")]);
        let l2 = dqr::line(&ax(3), &[s("e"), s("f"), Scalar::int(1)]);
        let (p1, p2, den) = dqr::closest_points_between_lines(&l1, &l2).unwrap();
        let on = |p: &[Scalar; 3], l: &DualQuat<Scalar>, k: &Scalar| {
            let c = dqsym::algebra::dqr::cross(&DualQuat::from_real(Quat::from_vector(p)), l).real;
            // p x l = k m (cross of pure quaternions is the vector cross product).
            assert_eq!(c.vector_part(), l.dual.vector_part().map(|x| x * k));
        };
        on(&p1, &l1, &den);
        on(&p2, &l2, &den);
        let diff: [Scalar; 3] = std::array::from_fn(|i| &p1[i] - &p2[i]);
        assert!(dqr::dot3(&diff, &l1.real.vector_part()).is_zero_value());
        assert!(dqr::dot3(&diff, &l2.real.vector_part()).is_zero_value());
        let (num, dn) = dqr::line_to_line_squared_distance(&l1, &l2);
        assert_eq!(dn, den);
        assert_eq!(dqr::dot3(&diff, &diff), num * &den);
        let p = [s("u"), s("v"), Scalar::int(2)];
        let proj = dqr::point_projected_in_line(&p, &l1);
        on(&proj, &l1, &Scalar::int(1));
        let off: [Scalar; 3] = std::array::from_fn(|i| &p[i] - &proj[i]);
        assert!(dqr::dot3(&off, &l1.real.vector_part()).is_zero_value());
        // Parallel lines have no unique closest points.
        let l3 = dqr::line(&ax(2), &[s("e"), Scalar::int(0), Scalar::int(1)]);
        assert!(dqr::closest_points_between_lines(&l1, &l3).is_none());
    }

    #[test]
    fn special_cases_are_exact() {
        // Zero rotation: log is eps t/2, the axis is k (DQ Robotics' convention), exp inverts it.
        let t = DualQuat::translation(&[s("a"), Scalar::int(2), s("c")]);
        let l = dqexp::log(&t).unwrap();
        assert_eq!(
            l,
            DualQuat::from_real_and_dual(
                Quat::zero(),
                Quat::vector(s("a") * r(1, 2), Scalar::int(1), s("c") * r(1, 2))
            )
        );
        assert_eq!(dqexp::exp(&l).unwrap(), t);
        assert_eq!(
            dqexp::rotation_axis(&t).unwrap(),
            Quat::vector(Scalar::int(0), Scalar::int(0), Scalar::int(1))
        );
        assert_eq!(
            dqexp::screw_pow(&t, &s("u"), None).unwrap(),
            DualQuat::translation(&[s("a") * s("u"), s("u") * Scalar::int(2), s("c") * s("u")])
        );
        // A full turn has no axis; its negation is the identity.
        let full = DualQuat::rotation(&ax(2), &(Scalar::pi() * Scalar::int(2)));
        assert!(matches!(dqexp::log(&full), Err(dqexp::DqError::FullTurn)));
        // A symbolic power whose angle is not linear asks for a name.
        let q = DualQuat::rotation(&ax(2), &s("theta"));
        assert!(matches!(
            dqexp::pow(&q, &s("t"), None),
            Err(dqexp::DqError::NeedsAngle { .. })
        ));
        // -cos(x): the branch pi - x keeps sin's sign.
        let q = DualQuat::rotation(&ax(0), &(s("theta") + Scalar::pi() * Scalar::int(2)));
        let back = dqexp::exp(&dqexp::log(&q).unwrap()).unwrap();
        assert!(back == q || back == -q.clone());
    }
}

#[test]
fn closed_forms_on_a_symbolic_screw() {
    // A screw of angle theta and slide d about the axis n = (2/3, 1/3, -2/3) through the
    // symbolic point (a, b, c) (moment m = (a, b, c) x n), and its operations in closed form.
    let src = "syms theta d a b c t psi phi e
q = screw((2/3, 1/3, -2/3), (a, b, c), theta, d)
rotation_angle(q)
rotation_axis(q)
translation(q)
log(q)
exp(log(q))
screwlog(q)
pow(q, t, psi)
screwpow(q, t, psi)
screwpow(q, 1/2)
q0 = rot((0, 0, 1), phi) * trans((e, 0, 0))
sclerp(q0, q0 * q, t, psi)
sclerpdot(q0, q0 * q, t, psi)
bodytwist(q, diff(q, theta))
Ad(q, line((0, 0, 1), (e, 0, 0)))
line_to_line_squared_distance(line((1, 0, 0), (0, 0, 0)), line((0, 1, 0), (0, 0, d)))
point_to_line_squared_distance((a, b, c), line((0, 0, 1), (e, 0, 0)))
";
    // The same operations on a screw whose axis is symbolic too: the unit axis
    // n = (sin(beta) cos(alpha), sin(beta) sin(alpha), cos(beta)), exactly unit, through the
    // point (a, b, c), so the moment m = (a, b, c) x n is symbolic.
    let src = format!(
        "{src}syms alpha beta
n = (sin(beta)*cos(alpha), sin(beta)*sin(alpha), cos(beta))
g = screw(n, (a, b, c), theta, d)
rotation_axis(g)
log(g)
exp(log(g)) - g
screwlog(g)
screwpow(g, t, psi)
bodytwist(g, diff(g, theta))
"
    );
    // Every other operation on the screw q (and some on g): parts and conjugates, the norm and
    // inverse, Hamilton matrices, vectorizations, products of lines, planes, twists, and the
    // task Jacobians by theta and d.
    let src = format!(
        "{src}P(q)
D(q)
Re(q)
Im(q)
conj(q)
sharp(q)
norm(2*q)
inv(q)
rotation(q)
tplus(q)
rotation_angle(g)
translation(g)
hamiplus4(q)
haminus4(q)
hamiplus8(q)
haminus8(q)
vec3(translation(q))
vec4(q)
vec6(screwlog(q))
vec8(q)
l = line((0, 0, 1), (e, 0, 0))
m = Ad(q, line((1, 0, 0), (0, e, 0)))
cross(l, m)
dot(l, m)
line_to_line_angle(line((1, 0, 0), (0, 0, 0)), Ad(rot((0, 0, 1), phi), line((1, 0, 0), (0, 0, e))))
plane((2/3, 1/3, -2/3), (a, b, c))
Adsharp(q, plane((0, 0, 1), (e, 0, 0)))
point_to_plane_distance((e, 0, 0), Adsharp(q, plane((0, 0, 1), (0, 0, 0))))
point_to_point_squared_distance(vec3(translation(q)), (e, 0, 0))
twist(q, diff(q, theta))
qdot(q, twist(q, diff(q, d)))
pose_jacobian(q, [theta, d])
rotation_jacobian(q, [theta, d])
translation_jacobian(q, [theta, d])
line_jacobian(q, [theta, d], (0, 0, 1))
plane_jacobian(q, [theta, d], (0, 0, 1))
distance_jacobian(q, [theta, d])
point_to_point_distance_jacobian(q, [theta, d], (e, 0, 0))
point_to_line_distance_jacobian(q, [theta, d], line((0, 0, 1), (e, 0, 0)))
point_to_plane_distance_jacobian(q, [theta, d], plane((0, 0, 1), (0, 0, e)))
line_to_point_distance_jacobian(q, [theta, d], (0, 0, 1), (e, 0, 0))
plane_to_point_distance_jacobian(q, [theta, d], (0, 0, 1), (e, 0, 0))
line_to_line_distance_jacobian(q, [theta, d], (1, 0, 0), line((0, 0, 1), (e, 0, 0)))
line_to_line_angle_jacobian(q, [theta, d], (0, 0, 1), line((1, 0, 0), (0, 0, 0)))
pose_jacobian_derivative(q, [theta, d])
rotation_jacobian_derivative(q, [theta, d])
translation_jacobian_derivative(q, [theta, d])
line_jacobian_derivative(q, [theta, d], (0, 0, 1))
plane_jacobian_derivative(q, [theta, d], (0, 0, 1))
distance_jacobian_derivative(q, [theta, d])
"
    );
    let src = src.as_str();
    let program = dqsym::parse(src).unwrap();
    let out = dqsym::Session::new().run(&program).unwrap();
    let opts = dqsym::ShowOptions::default();
    let text: String = out.iter().map(|d| dqsym::show(d, &opts).unwrap()).collect();
    crate::common::snapshot_settings().bind(|| insta::assert_snapshot!("dqr_symbolic_screw", text));
}

/// The task quantity of an f64 pose, written here with the f64 algebra (a quotient as its
/// value).
fn task_f64(p: &[f64], t: &dqsym::app::TaskJacobian) -> Vec<f64> {
    use dqsym::app::TaskJacobian as T;
    let q = DualQuat::from_components([p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]]);
    let tr = dqr::translation(&q);
    let tv = tr.vector_part();
    let f = |v: &[Scalar; 3]| -> [f64; 3] { std::array::from_fn(|k| v[k].eval_at(&[]).unwrap()) };
    let moved =
        |v: &[Scalar; 3]| (&q.real * &Quat::from_vector(&f(v)) * q.real.conjugate()).vector_part();
    let robot_line = |l0: &[Scalar; 3]| dqr::line(&moved(l0), &tv);
    match t {
        T::Pose | T::Derivative(_) => q.components().to_vec(),
        T::Rotation => q.real.components().to_vec(),
        T::Translation => tr.components().to_vec(),
        T::Line(l0) => robot_line(l0).components().to_vec(),
        T::Plane(n0) => dqr::plane(&moved(n0), &tv).components().to_vec(),
        T::Distance => vec![tr.norm_squared()],
        T::PointToPoint(x) => vec![dqr::point_to_point_squared_distance(&tv, &f(x))],
        T::PointToLine(l, x) => vec![dqr::point_to_line_squared_distance(
            &tv,
            &dqr::line(&f(l), &f(x)),
        )],
        T::PointToPlane(n, x) => vec![dqr::point_to_plane_distance(&tv, &dqr::plane(&f(n), &f(x)))],
        T::LineToPoint(l0, x) => vec![dqr::point_to_line_squared_distance(&f(x), &robot_line(l0))],
        T::PlaneToPoint(n0, x) => vec![dqr::point_to_plane_distance(
            &f(x),
            &dqr::plane(&moved(n0), &tv),
        )],
        T::LineToLine(l0, d, x) => {
            let (n, den) =
                dqr::line_to_line_squared_distance(&robot_line(l0), &dqr::line(&f(d), &f(x)));
            vec![n / den]
        }
        T::LineToLineAngle(l0, d, _) => {
            let (l, d) = (moved(l0), f(d));
            vec![(0..3).map(|k| (l[k] - d[k]).powi(2)).sum()]
        }
        // Velocities, not the gradient of a quantity: tests/it/geometric.rs checks them.
        T::Geometric | T::GeometricBody => Vec::new(),
    }
}

#[test]
fn task_jacobians_match_finite_differences() {
    // The exact task Jacobians of two robots (quotients divided out), evaluated at random
    // configurations, against central differences of the task quantities computed in f64 from
    // the evaluated pose; and every time derivative against d/ds J(q + s qdot) at s = 0.
    use dqsym::app::{task_jacobian, TaskJacobian};
    let v = |a: (i64, i64), b: (i64, i64), c: (i64, i64)| [r(a.0, a.1), r(b.0, b.1), r(c.0, c.1)];
    let k = [Scalar::int(0), Scalar::int(1), Scalar::int(0)];
    let (wd, wp) = (v((2, 3), (-2, 3), (1, 3)), v((1, 2), (1, 3), (-1, 1)));
    let point = v((1, 5), (-1, 2), (3, 4));
    // The spatial RRPR arm and the SCARA with every kind; the 6R Puma-like arm (slower to
    // evaluate in a debug build) with the pose and line Jacobians.
    for file in ["rrpr", "scara", "puma_like"] {
        let robot = if file == "rrpr" {
            dqsym::parse_robot(RRPR, "rrpr.toml", &dqsym::eval_scalar_text).expect("robot")
        } else {
            let path = format!("{}/examples/robots/{file}.toml", env!("CARGO_MANIFEST_DIR"));
            crate::robots::load(&path)
        };
        let x = robot.forward();
        let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
        let params = robot.parameters();
        let tasks = if file == "puma_like" {
            vec![TaskJacobian::Pose, TaskJacobian::Line(k.clone())]
        } else {
            vec![
                TaskJacobian::Pose,
                TaskJacobian::Rotation,
                TaskJacobian::Translation,
                TaskJacobian::Line(k.clone()),
                TaskJacobian::Plane(k.clone()),
                TaskJacobian::Distance,
                TaskJacobian::PointToPoint(point.clone()),
                TaskJacobian::PointToLine(wd.clone(), wp.clone()),
                TaskJacobian::PointToPlane(wd.clone(), wp.clone()),
                TaskJacobian::LineToPoint(k.clone(), point.clone()),
                TaskJacobian::PlaneToPoint(k.clone(), point.clone()),
                TaskJacobian::LineToLine(k.clone(), wd.clone(), wp.clone()),
                TaskJacobian::LineToLineAngle(k.clone(), wd.clone(), wp.clone()),
            ]
        };
        let mut rng = crate::common::Rng::new(7);
        let mut env: Vec<(String, f64)> = vars
            .iter()
            .map(|v| (v.to_string(), rng.range(-2.0, 2.0)))
            .collect();
        env.extend(params.iter().map(|p| (p.clone(), rng.range(0.3, 1.5))));
        let rates: Vec<f64> = vars.iter().map(|_| rng.range(-1.0, 1.0)).collect();
        let refs = |e: &[(String, f64)]| -> Vec<(String, f64)> { e.to_vec() };
        let eval = |s: &Scalar, e: &[(String, f64)]| {
            let e: Vec<(&str, f64)> = e.iter().map(|(a, b)| (a.as_str(), *b)).collect();
            s.eval_at(&e).unwrap()
        };
        let pose_at = |e: &[(String, f64)]| -> Vec<f64> {
            x.components().iter().map(|c| eval(c, e)).collect()
        };
        let shift = |e: &[(String, f64)], dir: &[(usize, f64)]| -> Vec<(String, f64)> {
            let mut e2 = refs(e);
            for (j, d) in dir {
                e2[*j].1 += d;
            }
            e2
        };
        let h = 1e-6;
        let close = |exact: f64, fd: f64| (fd - exact).abs() < 1e-6 * (1.0 + fd.abs());
        let mut with_rates = env.clone();
        with_rates.extend(
            vars.iter()
                .zip(&rates)
                .map(|(v, r)| (dqsym::app::rate_name(v), *r)),
        );
        // The pose at q +- h e_j, once per robot.
        let shifted: Vec<(Vec<f64>, Vec<f64>)> = (0..vars.len())
            .map(|j| {
                (
                    pose_at(&shift(&env, &[(j, h)])),
                    pose_at(&shift(&env, &[(j, -h)])),
                )
            })
            .collect();
        for t in &tasks {
            let jac = task_jacobian(&x, &vars, t);
            assert_eq!(
                jac.as_polynomial().is_none(),
                matches!(t, TaskJacobian::LineToLine(..))
            );
            let entry = |i: usize, j: usize, e: &[(String, f64)]| {
                eval(&jac.num[i][j], e) / eval(&jac.den, e)
            };
            for (j, (plus, minus)) in shifted.iter().enumerate() {
                let (hi, lo) = (task_f64(plus, t), task_f64(minus, t));
                for i in 0..jac.num.len() {
                    let fd = (hi[i] - lo[i]) / (2.0 * h);
                    let exact = entry(i, j, &env);
                    assert!(close(exact, fd), "{file} {t:?} [{i}][{j}]: {exact} vs {fd}");
                }
            }
            // The time derivative: d/ds J(q + s qdot) at s = 0 (DQ Robotics has none for the
            // line-to-line distance, whose expanded quotient's derivative is large).
            if matches!(t, TaskJacobian::LineToLine(..)) {
                continue;
            }
            let jd = task_jacobian(&x, &vars, &TaskJacobian::Derivative(Box::new(t.clone())));
            let along = |s: f64| -> Vec<(String, f64)> {
                let dir: Vec<(usize, f64)> =
                    rates.iter().enumerate().map(|(j, r)| (j, s * r)).collect();
                shift(&env, &dir)
            };

            let (ep, em) = (along(h), along(-h));
            for i in 0..jac.num.len() {
                for j in 0..vars.len() {
                    let fd = (entry(i, j, &ep) - entry(i, j, &em)) / (2.0 * h);
                    let exact = eval(&jd.num[i][j], &with_rates) / eval(&jd.den, &with_rates);
                    assert!(
                        close(exact, fd),
                        "{file} d/dt {t:?} [{i}][{j}]: {exact} vs {fd}"
                    );
                }
            }
        }
    }
}

/// A spatial RRPR arm in classic DH, the same in DQ Robotics' `DQ_SerialManipulatorDH` (rows
/// theta, d, a, alpha, type; type 1 prismatic, its d added to the row's d).
const RRPR: &str = r#"name = "RRPR"
convention = "dh"
[[joint]]
type = "revolute"
theta = "theta1"
d = "1/2"
a = "0"
alpha = "pi/2"
[[joint]]
type = "revolute"
theta = "theta2"
d = "0"
a = "3/4"
alpha = "0"
[[joint]]
type = "prismatic"
theta = "pi/2"
d = "d3"
a = "0"
alpha = "-pi/2"
[[joint]]
type = "revolute"
theta = "theta4"
d = "1/5"
a = "1/10"
alpha = "pi/3"
"#;

/// The task Jacobians of [`generated_task_jacobians_match_dqrobotics`]: the key the oracle
/// knows it by, the kind, and the field the generated code returns it in (the key when none).
fn task_kinds() -> Vec<(&'static str, dqsym::app::TaskJacobian, Option<&'static str>)> {
    use dqsym::app::TaskJacobian;
    let k = [Scalar::int(0), Scalar::int(0), Scalar::int(1)];
    let kinds = [
        ("j", TaskJacobian::Pose),
        ("jr", TaskJacobian::Rotation),
        ("jt", TaskJacobian::Translation),
        ("jl", TaskJacobian::Line(k.clone())),
        ("jpi", TaskJacobian::Plane(k.clone())),
        ("jd", TaskJacobian::Distance),
        (
            "jdot",
            TaskJacobian::Derivative(Box::new(TaskJacobian::Pose)),
        ),
    ];
    let v = |a: (i64, i64), b: (i64, i64), c: (i64, i64)| [r(a.0, a.1), r(b.0, b.1), r(c.0, c.1)];
    let distances = [
        (
            "p2p",
            TaskJacobian::PointToPoint(v((3, 10), (-1, 5), (1, 2))),
        ),
        (
            "p2l",
            TaskJacobian::PointToLine(v((0, 1), (0, 1), (1, 1)), v((1, 2), (1, 3), (0, 1))),
        ),
        (
            "p2pi",
            TaskJacobian::PointToPlane(v((0, 1), (1, 1), (0, 1)), v((0, 1), (1, 4), (0, 1))),
        ),
    ];
    // The distances from the robot's line and plane (the robot line along the end effector's
    // x axis for line_to_line, its z axis otherwise), and the time derivatives of the task
    // Jacobians; `jd_num / jd_den` for the line-to-line distance (a quotient).
    let i = [r(1, 1), r(0, 1), r(0, 1)];
    let workspace = (v((2, 7), (3, 7), (6, 7)), v((1, 2), (-1, 4), (1, 1)));
    let robot_distances = [
        (
            "l2p",
            TaskJacobian::LineToPoint(k.clone(), v((1, 3), (1, 2), (-1, 5))),
            "jd",
        ),
        (
            "pi2p",
            TaskJacobian::PlaneToPoint(k.clone(), v((1, 3), (1, 2), (-1, 5))),
            "jd",
        ),
        (
            "l2l",
            TaskJacobian::LineToLine(i.clone(), workspace.0.clone(), workspace.1.clone()),
            "jd_num",
        ),
        (
            "l2la",
            TaskJacobian::LineToLineAngle(k.clone(), workspace.0.clone(), workspace.1.clone()),
            "jd",
        ),
        (
            "jrdot",
            TaskJacobian::Derivative(Box::new(TaskJacobian::Rotation)),
            "jrdot",
        ),
        (
            "jtdot",
            TaskJacobian::Derivative(Box::new(TaskJacobian::Translation)),
            "jtdot",
        ),
        (
            "jldot",
            TaskJacobian::Derivative(Box::new(TaskJacobian::Line(k.clone()))),
            "jldot",
        ),
        (
            "jpidot",
            TaskJacobian::Derivative(Box::new(TaskJacobian::Plane(k.clone()))),
            "jpidot",
        ),
        (
            "jddot",
            TaskJacobian::Derivative(Box::new(TaskJacobian::Distance)),
            "jddot",
        ),
    ];
    let mut all: Vec<_> = kinds
        .into_iter()
        .map(|(key, kind)| (key, kind, None))
        .collect();
    all.extend(
        distances
            .into_iter()
            .map(|(key, kind)| (key, kind, Some("jd"))),
    );
    all.extend(
        robot_distances
            .into_iter()
            .map(|(key, kind, field)| (key, kind, Some(field))),
    );
    all
}

/// The oracle of [`generated_task_jacobians_match_dqrobotics`] (after the generated functions
/// `fk_KEY`, before the `check` calls): DQ Robotics' pose Jacobian and its derivative, and the
/// task Jacobians built from them, at random configurations and rates; the generated pose
/// Jacobian and time derivatives also against central differences of the generated code.
const TASK_ORACLE: &str = r#"
dh = np.array([[0, 0, np.pi/2, 0], [0.5, 0, 0, 0.2], [0, 0.75, 0, 0.1],
               [np.pi/2, 0, -np.pi/2, np.pi/3], [0, 0, 1, 0]])
robot = DQ_SerialManipulatorDH(dh)
rng = np.random.default_rng(5)
count = 0
for _ in range(5):
    q = rng.uniform(-2, 2, 4)
    qd = rng.uniform(-1, 1, 4)
    vals = {"theta1": q[0], "theta2": q[1], "d3": q[2], "theta4": q[3],
            "theta1_dot": qd[0], "theta2_dot": qd[1], "d3_dot": qd[2], "theta4_dot": qd[3]}
    x = robot.fkm(q)
    J = robot.pose_jacobian(q)
    want = {"j": J, "jr": K.rotation_jacobian(J), "jt": K.translation_jacobian(J, x),
            "jl": K.line_jacobian(J, x, k_), "jpi": K.plane_jacobian(J, x, k_),
            "jd": K.distance_jacobian(J, x), "jdot": robot.pose_jacobian_derivative(q, qd)}
    Jt, t = K.translation_jacobian(J, x), translation(x)
    want["p2p"] = K.point_to_point_distance_jacobian(Jt, t, 0.3*i_ - 0.2*j_ + 0.5*k_)
    want["p2l"] = K.point_to_line_distance_jacobian(Jt, t, k_ + E_*cross(0.5*i_ + (1/3)*j_, k_))
    want["p2pi"] = K.point_to_plane_distance_jacobian(Jt, t, j_ + E_*0.25)
    # The robot's line (along z, or x for the line-to-line distance) and plane through t.
    Jl, Jlx, Jpi = K.line_jacobian(J, x, k_), K.line_jacobian(J, x, i_), K.plane_jacobian(J, x, k_)
    lz, lx = Ad(rotation(x), k_), Ad(rotation(x), i_)
    robot_line, robot_line_x = lz + E_*cross(t, lz), lx + E_*cross(t, lx)
    point = (1/3)*i_ + 0.5*j_ - 0.2*k_
    wd = (2/7)*i_ + (3/7)*j_ + (6/7)*k_
    workspace_line = wd + E_*cross(0.5*i_ - 0.25*j_ + k_, wd)
    want["l2p"] = K.line_to_point_distance_jacobian(Jl, robot_line, point)
    want["pi2p"] = K.plane_to_point_distance_jacobian(Jpi, point)
    want["l2l"] = K.line_to_line_distance_jacobian(Jlx, robot_line_x, workspace_line)
    want["l2la"] = K.line_to_line_angle_jacobian(Jl, robot_line, workspace_line)
    # The line-to-line distance Jacobian is also the central difference of the squared distance.
    def l2l_distance(qq):
        xx = robot.fkm(qq)
        lq = Ad(rotation(xx), i_)
        return G.line_to_line_squared_distance(lq + E_*cross(translation(xx), lq), workspace_line)
    fd = np.array([[(l2l_distance(q + 1e-6*e) - l2l_distance(q - 1e-6*e)) / 2e-6 for e in np.eye(4)]])
    assert np.allclose(fd, want["l2l"], atol=1e-6), ("l2l finite differences", fd, want["l2l"])
    Jdot = want["jdot"]
    want["jrdot"] = K.rotation_jacobian_derivative(Jdot)
    want["jtdot"] = K.translation_jacobian_derivative(J, Jdot, x, qd)
    want["jldot"] = K.line_jacobian_derivative(J, Jdot, x, k_, qd)
    want["jpidot"] = K.plane_jacobian_derivative(J, Jdot, x, k_, qd)
    want["jddot"] = K.distance_jacobian_derivative(J, Jdot, x, qd)
    def call(f, at):
        return f(*[np.array([at[p]]) for p in inspect.signature(f).parameters])
    def shifted(h):
        at = dict(vals)
        for k, name in enumerate(["theta1", "theta2", "d3", "theta4"]):
            at[name] += h * qd[k]
        return at
    # The generated code against central differences of itself: the pose Jacobian against
    # d dq / dq_j, and each time derivative against d/ds J(q + s qdot) of the generated J.
    h = 1e-6
    for j, name in enumerate(["theta1", "theta2", "d3", "theta4"]):
        up, down = dict(vals), dict(vals)
        up[name] += h
        down[name] -= h
        fd = (call(fk_j, up)["dq"][0] - call(fk_j, down)["dq"][0]) / (2 * h)
        assert np.allclose(fd, np.asarray(call(fk_j, vals)["j"][0])[:, j], atol=1e-7), ("j fd", j)
    for dkey, key in [("jdot", "j"), ("jrdot", "jr"), ("jtdot", "jt"), ("jldot", "jl"),
                      ("jpidot", "jpi"), ("jddot", "jd")]:
        f = globals()["fk_" + key]
        fd = (np.asarray(call(f, shifted(h))[key][0]) - np.asarray(call(f, shifted(-h))[key][0])) / (2 * h)
        got = np.asarray(call(globals()["fk_" + dkey], vals)[dkey][0])
        assert np.allclose(fd, got, atol=1e-7), (dkey, fd, got)
    def check(key, f, field=None):
        global count
        r = call(f, vals)
        assert np.allclose(r["dq"][0], vec8(x), atol=1e-12), ("dq", r["dq"][0], vec8(x))
        got = np.asarray(r[field or key][0])
        if field == "jd_num":
            got = got / np.asarray(r["jd_den"][0])
        got = got.reshape(want[key].shape)
        assert np.allclose(got, want[key], atol=1e-10), (key, got, want[key])
        count += 1
"#;

#[test]
fn generated_task_jacobians_match_dqrobotics() {
    // Every `--jacobian=KIND` as a generated NumPy function, run at random configurations and
    // rates, against DQ Robotics' numeric pose, pose Jacobian and its derivative, and the
    // rotation, translation, line, plane and distance Jacobians built from them.
    use dqsym::{
        app::{task_report, TaskJacobian},
        FkOptions, Format,
    };
    let robot = dqsym::parse_robot(RRPR, "rrpr.toml", &dqsym::eval_scalar_text).expect("robot");
    let o = FkOptions {
        format: Format::Python,
        ..FkOptions::default()
    };
    let kinds = task_kinds();
    let mut script = String::from(
        "import inspect, numpy as np\nfrom dqrobotics import *\nfrom dqrobotics.robot_modeling import DQ_SerialManipulatorDH, DQ_Kinematics as K\nfrom dqrobotics.utils import DQ_Geometry as G\n",
    );
    let mut checks = String::new();
    for (key, kind, field) in &kinds {
        let code = if *kind == TaskJacobian::Pose {
            dqsym::fk_report(
                &robot,
                &FkOptions {
                    jacobian: true,
                    ..o.clone()
                },
            )
        } else {
            task_report(&robot, &o, kind)
        }
        .expect("generated code");
        script.push_str(&code.replace("def rrpr_fk(", &format!("def fk_{key}(")));
        checks.push_str(&match field {
            None => format!("    check('{key}', fk_{key})\n"),
            Some(field) => format!("    check('{key}', fk_{key}, '{field}')\n"),
        });
    }
    script.push_str(TASK_ORACLE);
    script.push_str(&checks);
    script.push_str("print(count)\n");
    let out = run_python(&script, "", "dqrobotics");
    assert_eq!(out.trim(), (5 * kinds.len()).to_string());
}

#[test]
fn twists_give_the_geometric_jacobian() {
    // For every joint of the Stanford arm: xi = 2 (dq/dqj) q* = omega + eps (t-dot + t x omega),
    // and the geometric Jacobian's column is (t-dot; omega); qdot(q, xi) gives the derivative
    // back, and the body twist is conj(q) xi q. Exact.
    let path = format!(
        "{}/examples/robots/stanford.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let robot = crate::robots::load(&path);
    let q = robot.forward();
    let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
    let gj = dqsym::kin::geometric_jacobian(&q, &vars);
    let t = dqr::translation(&q).vector_part();
    for (j, v) in vars.iter().enumerate() {
        let qd = DualQuat::from_components(q.components().map(|c| c.diff(v)));
        let xi = dqexp::twist(&q, &qd, false);
        assert!(xi.real.w.is_zero_value() && xi.dual.w.is_zero_value());
        let omega = xi.real.vector_part();
        let cross = [
            &t[1] * &omega[2] - &t[2] * &omega[1],
            &t[2] * &omega[0] - &t[0] * &omega[2],
            &t[0] * &omega[1] - &t[1] * &omega[0],
        ];
        for k in 0..3 {
            assert_eq!(gj[k + 3][j], omega[k], "omega {v} {k}");
            assert_eq!(
                gj[k][j],
                &xi.dual.vector_part()[k] - &cross[k],
                "t-dot {v} {k}"
            );
        }
        assert_eq!(dqexp::from_twist(&q, &xi, false), qd);
        let body = dqexp::twist(&q, &qd, true);
        assert_eq!(body, q.conjugate() * &xi * &q);
        assert_eq!(dqexp::from_twist(&q, &body, true), qd);
    }
}

#[test]
fn language_task_jacobians_are_the_library_ones() {
    // Each Jacobian built-in of the language (DQ Robotics' names) on a spatial two-joint arm is
    // the library's task Jacobian of that kind, exactly; the line-to-line one is a quotient.
    use dqsym::{
        app::{task_jacobian, TaskJacobian as T},
        Frac, Value,
    };
    let mut session = dqsym::Session::new();
    let src = "syms theta1 theta2 a d
x = dh(theta1, 1/2, a, pi/3) * dh(theta2, d, 0, pi/2)
wl = line((2/3, -2/3, 1/3), (1/2, 1/3, -1))
wp = plane((2/3, -2/3, 1/3), (1/2, 1/3, -1))
";
    session.run(&dqsym::parse(src).unwrap()).unwrap();
    let x = match session.get("x") {
        Some(Value::DualQuat(x)) => x.clone(),
        other => panic!("x is {other:?}"),
    };
    let v = |a: (i64, i64), b: (i64, i64), c: (i64, i64)| [r(a.0, a.1), r(b.0, b.1), r(c.0, c.1)];
    let (wd, wpt) = (v((2, 3), (-2, 3), (1, 3)), v((1, 2), (1, 3), (-1, 1)));
    let (dir, pt) = (v((0, 1), (1, 1), (0, 1)), v((1, 5), (-1, 2), (3, 4)));
    let deriv = |t: T| T::Derivative(Box::new(t));
    let cases = [
        ("pose_jacobian(x, [theta1, theta2])", T::Pose),
        ("rotation_jacobian(x, [theta1, theta2])", T::Rotation),
        ("translation_jacobian(x, [theta1, theta2])", T::Translation),
        (
            "line_jacobian(x, [theta1, theta2], (0, 1, 0))",
            T::Line(dir.clone()),
        ),
        (
            "plane_jacobian(x, [theta1, theta2], (0, 1, 0))",
            T::Plane(dir.clone()),
        ),
        ("distance_jacobian(x, [theta1, theta2])", T::Distance),
        (
            "point_to_point_distance_jacobian(x, [theta1, theta2], (1/5, -1/2, 3/4))",
            T::PointToPoint(pt.clone()),
        ),
        // The workspace line and plane as DQs: their point is recovered on them (the line's
        // point nearest the origin), the same primitive.
        (
            "point_to_line_distance_jacobian(x, [theta1, theta2], wl)",
            T::PointToLine(wd.clone(), wpt.clone()),
        ),
        (
            "point_to_plane_distance_jacobian(x, [theta1, theta2], wp)",
            T::PointToPlane(wd.clone(), wpt.clone()),
        ),
        (
            "line_to_point_distance_jacobian(x, [theta1, theta2], (0, 1, 0), (1/5, -1/2, 3/4))",
            T::LineToPoint(dir.clone(), pt.clone()),
        ),
        (
            "plane_to_point_distance_jacobian(x, [theta1, theta2], (0, 1, 0), (1/5, -1/2, 3/4))",
            T::PlaneToPoint(dir.clone(), pt.clone()),
        ),
        (
            "line_to_line_distance_jacobian(x, [theta1, theta2], (0, 1, 0), wl)",
            T::LineToLine(dir.clone(), wd.clone(), wpt.clone()),
        ),
        (
            "line_to_line_angle_jacobian(x, [theta1, theta2], (0, 1, 0), wl)",
            T::LineToLineAngle(dir.clone(), wd.clone(), wpt.clone()),
        ),
        (
            "pose_jacobian_derivative(x, [theta1, theta2])",
            deriv(T::Pose),
        ),
        (
            "rotation_jacobian_derivative(x, [theta1, theta2])",
            deriv(T::Rotation),
        ),
        (
            "translation_jacobian_derivative(x, [theta1, theta2])",
            deriv(T::Translation),
        ),
        (
            "line_jacobian_derivative(x, [theta1, theta2], (0, 1, 0))",
            deriv(T::Line(dir.clone())),
        ),
        (
            "plane_jacobian_derivative(x, [theta1, theta2], (0, 1, 0))",
            deriv(T::Plane(dir.clone())),
        ),
        (
            "distance_jacobian_derivative(x, [theta1, theta2])",
            deriv(T::Distance),
        ),
    ];
    for (expr, kind) in cases {
        session
            .run(&dqsym::parse(&format!("y = {expr}")).unwrap())
            .unwrap();
        let want = task_jacobian(&x, &["theta1", "theta2"], &kind);
        assert_eq!(
            want.as_polynomial().is_none(),
            matches!(kind, T::LineToLine(..))
        );
        match (session.get("y").unwrap(), want.as_polynomial()) {
            (Value::Matrix(rows), Some(w)) => assert_eq!(rows, w, "{expr}"),
            (Value::QuotientMatrix(rows), None) => {
                assert_eq!(rows.len(), want.num.len(), "{expr}");
                for (row, wrow) in rows.iter().zip(&want.num) {
                    for (e, n) in row.iter().zip(wrow) {
                        assert_eq!(
                            *e,
                            Frac::new(n.clone(), want.den.clone()).unwrap(),
                            "{expr}"
                        );
                    }
                }
            }
            (other, _) => panic!("{expr}: {other:?}"),
        }
    }
}

/// The interpolation script of [`generated_interpolation_matches_an_independent_sclerp`]: ScLERP
/// from `q0` to `q1 = q0 rel` (`rel` a screw of angle theta and slide d about the axis
/// (2/3, 1/3, -2/3) through the point (a, b, c)), its derivative in t, DQ Robotics' decoupled
/// `pow` and the screw power of `rel`, with t symbolic and psi = t theta.
const INTERPOLATION: &str = "syms a b c d e phi t psi theta
q0 = rot((0, 0, 1), phi) * trans((e, 0, 0));
rel = screw((2/3, 1/3, -2/3), (a, b, c), theta, d);
q1 = q0 * rel;
s = sclerp(q0, q1, t, psi)
sd = sclerpdot(q0, q1, t, psi)
p = pow(rel, t, psi)
sp = screwpow(rel, t, psi)
";

/// The symbols every generated interpolation function may take, in the order of the input lines.
const INTERPOLATION_SYMBOLS: [&str; 9] = ["a", "b", "c", "d", "e", "phi", "psi", "t", "theta"];

/// The argument names of the generated function `name` (`pub fn s(a: f64, ...)`,
/// `void s(double a, ..., double s[8])`, `def s(a, ...)`).
fn generated_args(code: &str, name: &str) -> Vec<String> {
    let line = code
        .lines()
        .find(|l| {
            [
                format!("pub fn {name}("),
                format!("void {name}("),
                format!("def {name}("),
            ]
            .iter()
            .any(|p| l.starts_with(p.as_str()))
        })
        .unwrap_or_else(|| panic!("no function {name} in\n{code}"));
    let inner = &line[line.find('(').unwrap() + 1..line.find(')').unwrap()];
    inner
        .split(',')
        .map(|a| {
            a.trim()
                .trim_start_matches("double ")
                .split(':')
                .next()
                .unwrap()
                .trim()
        })
        .filter(|a| !a.contains('['))
        .map(str::to_owned)
        .collect()
}

#[test]
fn generated_interpolation_matches_an_independent_sclerp() {
    // The script's interpolation functions emitted by `dqsym --format rust|c|python`, compiled
    // (rustc and gcc with warnings as errors) or run (NumPy), called with t and psi = t theta at
    // random parameters, and checked by an independent NumPy oracle: the matrix of sclerp(t) is
    // T0 expm(t X) (X the 4x4 twist of the screw, built from its axis, point, angle and slide),
    // that of screwpow(rel, t) is expm(t X), sclerp(0) = q0 exactly, sclerpdot is the central
    // difference of the generated sclerp and the body twist 2 s* s' is constant in t, and pow
    // is dqrobotics' DQ.pow of rel (its decoupled power).
    let names = ["s", "sd", "p", "sp"];
    let dir = crate::tools::temp_dir("interpolation");
    let script = dir.join("interp.dq");
    std::fs::write(&script, INTERPOLATION).unwrap();
    let script = script.to_str().unwrap();
    let code = |format: &str| crate::tools::dqsym_ok(&["--format", format, "run", script]);
    // Input lines: the nine symbols, at t, t + h, t - h, 0 and 1 for each random point.
    let h = 1e-6;
    let mut rng = crate::common::Rng::new(11);
    let mut input = String::new();
    for _ in 0..5 {
        let base: Vec<f64> = vec![
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(0.3, 2.8),
        ];
        let (t, theta) = (rng.range(0.05, 0.95), rng.range(0.3, 2.8));
        for tt in [t, t + h, t - h, 0.0, 1.0] {
            let mut v = base.clone();
            v.extend([tt * theta, tt, theta]);
            let line: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
            input.push_str(&(line.join(" ") + "\n"));
        }
    }
    let index = |a: &str| INTERPOLATION_SYMBOLS.iter().position(|s| *s == a).unwrap();
    let mut results = Vec::new();

    // Rust.
    let rust = code("rust");
    let mut main = String::from(
        "\nfn main() {\n    let mut text = String::new();\n    std::io::Read::read_to_string(&mut std::io::stdin(), &mut text).unwrap();\n    for line in text.lines() {\n        let v: Vec<f64> = line.split_whitespace().map(|x| x.parse().unwrap()).collect();\n        let mut out: Vec<f64> = Vec::new();\n",
    );
    for n in names {
        let call: Vec<String> = generated_args(&rust, n)
            .iter()
            .map(|a| format!("v[{}]", index(a)))
            .collect();
        main.push_str(&format!(
            "        out.extend({n}({}).{n});\n",
            call.join(", ")
        ));
    }
    main.push_str("        let words: Vec<String> = out.iter().map(|x| format!(\"{x:?}\")).collect();\n        println!(\"{}\", words.join(\" \"));\n    }\n}\n");
    let src = dir.join("interp.rs");
    std::fs::write(&src, rust + &main).unwrap();
    let exe = dir.join("interp_rs");
    crate::tools::compile_rust_clean(&src, &exe, false, "the generated interpolation (Rust)");
    results.push((
        "rust",
        crate::tools::run(Command::new(&exe), &input, "generated Rust"),
    ));

    // C.
    let c = code("c");
    let mut main = String::from(
        "\n#include <stdio.h>\nint main(void)\n{\n    double v[9];\n    for (;;) {\n        for (int i = 0; i < 9; i++)\n            if (scanf(\"%lf\", &v[i]) != 1) return 0;\n        double out[32];\n",
    );
    for (k, n) in names.iter().enumerate() {
        let call: Vec<String> = generated_args(&c, n)
            .iter()
            .map(|a| format!("v[{}]", index(a)))
            .collect();
        main.push_str(&format!(
            "        {n}({}, out + {});\n",
            call.join(", "),
            8 * k
        ));
    }
    main.push_str("        for (int k = 0; k < 32; k++) printf(\"%.17g \", out[k]);\n        printf(\"\\n\");\n    }\n}\n");
    let src = dir.join("interp.c");
    std::fs::write(&src, c + &main).unwrap();
    let exe = dir.join("interp_c");
    let mut gcc = Command::new("gcc");
    gcc.args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-o"])
        .arg(&exe)
        .arg(&src)
        .arg("-lm");
    crate::tools::run(
        gcc,
        "",
        "gcc -std=c99 -Werror on the generated interpolation",
    );
    results.push((
        "c",
        crate::tools::run(Command::new(&exe), &input, "generated C"),
    ));

    // Python (NumPy, one vectorized call per function).
    let py = code("python");
    let mut driver =
        String::from("\nimport sys\ndata = np.loadtxt(sys.stdin, ndmin=2)\ncols = []\n");
    for n in names {
        let call: Vec<String> = generated_args(&py, n)
            .iter()
            .map(|a| format!("data[:, {}]", index(a)))
            .collect();
        driver.push_str(&format!("cols.append({n}({})[{n:?}])\n", call.join(", ")));
    }
    driver.push_str("for row in np.concatenate(cols, axis=1):\n    print(' '.join(repr(float(x)) for x in row))\n");
    results.push(("python", run_python(&(py + &driver), &input, "numpy")));

    // The oracle reads `language;inputs;outputs` lines.
    let mut lines = String::new();
    for (lang, out) in &results {
        let outs: Vec<&str> = out.lines().collect();
        let ins: Vec<&str> = input.lines().collect();
        assert_eq!(
            outs.len(),
            ins.len(),
            "{lang}: one output line per input line"
        );
        for (i, o) in ins.iter().zip(outs) {
            lines.push_str(&format!("{lang};{i};{o}\n"));
        }
    }
    let checked = run_python(SCLERP_ORACLE, &lines, "dqrobotics");
    assert_eq!(
        checked.trim(),
        "5 5 5",
        "random points checked per language"
    );
}

/// The independent ScLERP of [`generated_interpolation_matches_an_independent_sclerp`]: 4x4
/// matrices and a matrix exponential (Taylor series with scaling and squaring), quaternions
/// from rotation matrices, and dqrobotics' `DQ.pow`.
const SCLERP_ORACLE: &str = r#"
import sys, numpy as np
from dqrobotics import DQ, vec8
import dqrobotics as dqr

def expm(A):
    s = max(0, int(np.ceil(np.log2(max(np.abs(A).sum(), 1e-300)))) + 1)
    B = A / 2**s
    E, term = np.eye(4), np.eye(4)
    for k in range(1, 25):
        term = term @ B / k
        E = E + term
    for _ in range(s):
        E = E @ E
    return E

def hat(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])

def qm(a, b):
    w1, x1, y1, z1 = a; w2, x2, y2, z2 = b
    return np.array([w1*w2-x1*x2-y1*y2-z1*z2, w1*x2+x1*w2+y1*z2-z1*y2,
                     w1*y2-x1*z2+y1*w2+z1*x2, w1*z2+x1*y2-y1*x2+z1*w2])
def qc(a): return np.array([a[0], -a[1], -a[2], -a[3]])
def dm(a, b): return np.concatenate([qm(a[:4], b[:4]), qm(a[:4], b[4:]) + qm(a[4:], b[:4])])

def matrix(q):
    w, x, y, z = q[:4]
    R = np.array([[1-2*(y*y+z*z), 2*(x*y-w*z), 2*(x*z+w*y)],
                  [2*(x*y+w*z), 1-2*(x*x+z*z), 2*(y*z-w*x)],
                  [2*(x*z-w*y), 2*(y*z+w*x), 1-2*(x*x+y*y)]])
    T = np.eye(4); T[:3, :3] = R; T[:3, 3] = (2 * qm(q[4:], qc(q[:4])))[1:]
    return T

def dq_of(T):
    # A rotation of angle below pi: w = sqrt(1 + trace)/2 > 0.
    R = T[:3, :3]
    w = np.sqrt(1 + np.trace(R)) / 2
    r = np.array([w, (R[2, 1] - R[1, 2]) / (4*w), (R[0, 2] - R[2, 0]) / (4*w), (R[1, 0] - R[0, 1]) / (4*w)])
    return np.concatenate([r, 0.5 * qm(np.array([0, *T[:3, 3]]), r)])

n = np.array([2, 1, -2]) / 3
counts = {}
rows = [l.rstrip("\n").split(";") for l in sys.stdin if l.strip()]
for i in range(0, len(rows), 5):
    group = rows[i:i+5]
    lang = group[0][0]
    ins = [np.array([float(x) for x in g[1].split()]) for g in group]
    outs = [np.array([float(x) for x in g[2].split()]) for g in group]
    a, b, c, d, e, phi, psi, t, theta = ins[0]
    point = np.array([a, b, c])
    X = np.zeros((4, 4)); X[:3, :3] = hat(theta * n); X[:3, 3] = -np.cross(theta * n, point) + d * n
    T0 = np.eye(4); T0[:3, :3] = [[np.cos(phi), -np.sin(phi), 0], [np.sin(phi), np.cos(phi), 0], [0, 0, 1]]
    T0[:3, 3] = T0[:3, :3] @ np.array([e, 0, 0])
    rel = dq_of(expm(X))
    for inp, out in zip(ins, outs):
        tt = inp[7]
        s, sd, p, sp = out[:8], out[8:16], out[16:24], out[24:32]
        for what, got, want in (("sclerp", matrix(s), T0 @ expm(tt * X)),
                                ("screwpow", matrix(sp), expm(tt * X)),
                                ("pow", p, vec8(dqr.pow(DQ(rel), tt)))):
            if not np.allclose(got, want, atol=1e-9):
                raise SystemExit(f"{lang} {what} at t={tt}: {got} vs {want}")
        # The body twist 2 s* s' is the constant 2 screwlog(rel), the same at every t.
        xi = 2 * dm(np.concatenate([qc(s[:4]), qc(s[4:])]), sd)
        xi0 = 2 * dm(np.concatenate([qc(outs[0][:4]), qc(outs[0][4:])]), outs[0][8:16])
        if not np.allclose(xi, xi0, atol=1e-9):
            raise SystemExit(f"{lang} body twist at t={tt}: {xi} vs {xi0}")
    if not np.allclose(outs[3][:8], dq_of(T0), atol=1e-12):
        raise SystemExit(f"{lang} sclerp(0) = {outs[3][:8]}, q0 = {dq_of(T0)}")
    fd = (outs[1][:8] - outs[2][:8]) / 2e-6
    if not np.allclose(outs[0][8:16], fd, atol=1e-6):
        raise SystemExit(f"{lang} sclerpdot {outs[0][8:16]} vs central difference {fd}")
    counts[lang] = counts.get(lang, 0) + 1
print(counts.get("rust", 0), counts.get("c", 0), counts.get("python", 0))
"#;

#[test]
fn task_jacobians_are_dq_robotics_chain_rule_exactly() {
    // DQ Robotics builds the translation, line and plane Jacobians from the pose Jacobian
    // J = [J_P; J_D] by the chain rule (DQ_Kinematics.cpp): Jt = 2 haminus4(r*) J_D +
    // 2 hamiplus4(D(x)) C4 J_P; for a direction l0 (normal n0), Jrx = haminus4(l0 r*) J_P +
    // hamiplus4(r l0) C4 J_P; the line's moment rows crossmatrix4(lx)^T Jt + crossmatrix4(t) Jrx;
    // the plane's distance row vec4(nz)^T Jt + vec4(t)^T Jrz. Written here with the exact
    // Hamilton matrices on the spatial RRPR arm, they equal the task Jacobians entry for entry.
    use dqsym::app::{task_jacobian, TaskJacobian};
    let robot = dqsym::parse_robot(RRPR, "rrpr.toml", &dqsym::eval_scalar_text).expect("robot");
    let x = robot.forward();
    let vars: Vec<&str> = robot.variables.iter().map(String::as_str).collect();
    let n = vars.len();
    let j = task_jacobian(&x, &vars, &TaskJacobian::Pose).num;
    let (jp, jd) = (j[..4].to_vec(), j[4..].to_vec());
    type M = Vec<Vec<Scalar>>;
    let zero = || Scalar::int(0);
    let times = |m: &[[Scalar; 4]; 4], b: &M| -> M {
        (0..4)
            .map(|i| {
                (0..n)
                    .map(|c| (0..4).fold(zero(), |acc, k| acc + &m[i][k] * &b[k][c]))
                    .collect()
            })
            .collect()
    };
    let square = |a: &[[Scalar; 4]; 4], b: &[[Scalar; 4]; 4]| -> [[Scalar; 4]; 4] {
        std::array::from_fn(|i| {
            std::array::from_fn(|c| (0..4).fold(zero(), |acc, k| acc + &a[i][k] * &b[k][c]))
        })
    };
    let plus = |a: &M, b: &M| -> M {
        a.iter()
            .zip(b)
            .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p + q).collect())
            .collect()
    };
    let scaled = |a: &M, k: i64| -> M {
        a.iter()
            .map(|row| row.iter().map(|e| e * Scalar::int(k)).collect())
            .collect()
    };
    let crossmatrix4 = |a: &Quat<Scalar>| -> [[Scalar; 4]; 4] {
        let [_, x, y, z] = a.components();
        [
            [zero(), zero(), zero(), zero()],
            [zero(), zero(), -z.clone(), y.clone()],
            [zero(), z, zero(), -x.clone()],
            [zero(), -y, x, zero()],
        ]
    };
    let transpose = |m: [[Scalar; 4]; 4]| -> [[Scalar; 4]; 4] {
        std::array::from_fn(|i| std::array::from_fn(|c| m[c][i].clone()))
    };
    let rot = x.real.clone();
    let t = dqr::translation(&x);
    let c4 = dqr::c4::<Scalar>();
    let jt = plus(
        &scaled(&times(&dqr::haminus4(&rot.conjugate()), &jd), 2),
        &scaled(&times(&square(&dqr::hamiplus4(&x.dual), &c4), &jp), 2),
    );
    assert_eq!(jt, task_jacobian(&x, &vars, &TaskJacobian::Translation).num);
    let row = |v: &Quat<Scalar>, m: &M| -> Vec<Scalar> {
        let v = v.components();
        (0..n)
            .map(|c| (0..4).fold(zero(), |acc, k| acc + &v[k] * &m[k][c]))
            .collect()
    };
    for d0 in [[r(0, 1), r(0, 1), r(1, 1)], [r(2, 3), r(1, 3), r(-2, 3)]] {
        let l0 = Quat::from_vector(&d0);
        let jrx = plus(
            &times(&dqr::haminus4(&(&l0 * &rot.conjugate())), &jp),
            &times(&square(&dqr::hamiplus4(&(&rot * &l0)), &c4), &jp),
        );
        let lx = &rot * &l0 * rot.conjugate();
        // Line: [Jrx; crossmatrix4(lx)^T Jt + crossmatrix4(t) Jrx].
        let jmx = plus(
            &times(&transpose(crossmatrix4(&lx)), &jt),
            &times(&crossmatrix4(&t), &jrx),
        );
        let line: M = jrx.iter().chain(&jmx).cloned().collect();
        assert_eq!(
            line,
            task_jacobian(&x, &vars, &TaskJacobian::Line(d0.clone())).num
        );
        // Plane: [Jrz; vec4(nz)^T Jt + vec4(t)^T Jrz; 0; 0; 0].
        let mut plane = jrx.clone();
        plane.push(plus(&vec![row(&lx, &jt)], &vec![row(&t, &jrx)]).remove(0));
        plane.extend((0..3).map(|_| vec![zero(); n]));
        assert_eq!(
            plane,
            task_jacobian(&x, &vars, &TaskJacobian::Plane(d0)).num
        );
    }
}

#[test]
fn walkthrough_explains_twists_with_the_geometric_jacobian() {
    // `dqsym walk examples/twists.dq`: each twist step gives omega = P(xi) and
    // t-dot = D(xi) - t x omega, exactly the joint's column (t-dot; omega) of the geometric
    // Jacobian; the body twist step gives P and D of 2 q* qdot; the ScLERP derivative step gives
    // the constant body twist 2 screwlog(home* goal). Snapshot of the text.
    use dqsym::walk::{Step, Word};
    let path = format!("{}/examples/twists.dq", env!("CARGO_MANIFEST_DIR"));
    let src = std::fs::read_to_string(&path).expect("example");
    let w = dqsym::walk_script(&src, "examples/twists.dq").expect("walkthrough");
    let mut session = dqsym::Session::new();
    session.run(&dqsym::parse(&src).unwrap()).unwrap();
    let dq = |n: &str| match session.get(n) {
        Some(dqsym::Value::DualQuat(d)) => d.clone(),
        other => panic!("{n}: {other:?}"),
    };
    let q = dq("q");
    let gj = dqsym::kin::geometric_jacobian(&q, &["theta1", "theta2"]);
    let tuples = |name: &str| -> Vec<Vec<Scalar>> {
        let meaning = w
            .steps
            .iter()
            .find_map(|s| match s {
                Step::Define {
                    name: n, meaning, ..
                } if n == name => Some(meaning.clone()),
                _ => None,
            })
            .unwrap_or_else(|| panic!("no step defines {name}"));
        meaning
            .0
            .iter()
            .filter_map(|w| match w {
                Word::Tuple(v) => Some(v.clone()),
                _ => None,
            })
            .collect()
    };
    for (j, name) in ["xi1", "xi2"].iter().enumerate() {
        let t = tuples(name);
        assert_eq!(t.len(), 2, "{name}: omega and t-dot");
        let column: Vec<Scalar> = (0..6).map(|k| gj[k][j].clone()).collect();
        assert_eq!(t[1], column[..3].to_vec(), "{name}: t-dot");
        assert_eq!(t[0], column[3..].to_vec(), "{name}: omega");
    }
    let xb = dq("xib2");
    assert_eq!(
        tuples("xib2"),
        vec![
            xb.real.vector_part().to_vec(),
            xb.dual.vector_part().to_vec()
        ]
    );
    let body = dqexp::screw_log(&(dq("home").conjugate() * dq("goal")))
        .unwrap()
        .scale(&Scalar::int(2));
    assert_eq!(tuples("sd"), vec![body.components().to_vec()]);
    let text = dqsym::walk_text(&w).expect("text");
    crate::common::snapshot_settings().bind(|| insta::assert_snapshot!("walk_twists_text", text));
}
