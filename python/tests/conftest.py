"""Shared helpers: the repository, the `dqsym` binary (the oracle for "what the command line
prints"), an independent DH / DQ implementation in NumPy, and KaTeX for LaTeX checks."""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest
import sympy

ROOT = pathlib.Path(__file__).resolve().parents[2]
ROBOTS = sorted((ROOT / "examples" / "robots").glob("*.toml"))


def dqsym_bin():
    """The command-line binary: $DQSYM_BIN, or the one `cargo test` builds."""
    path = os.environ.get("DQSYM_BIN") or str(ROOT / "target" / "debug" / "dqsym")
    if not os.path.exists(path):
        pytest.fail(
            f"the dqsym binary is missing ({path}): run `cargo build` first, or use "
            "`bash scripts/test.sh`, which builds it before running pytest"
        )
    return path


def cli(*args):
    """Runs the binary and returns stdout; fails the test on a non-zero status."""
    r = subprocess.run([dqsym_bin(), *args], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    return r.stdout


def parse_sympy_lines(text):
    """`NAME = EXPR` lines of `--format sympy` as a dict of SymPy expressions; every symbol
    bound explicitly, as the emitter's documentation asks."""
    out = {}
    for line in text.splitlines():
        name, expr = line.split(" = ", 1)
        names = set(
            tok
            for tok in __import__("re").findall(r"[A-Za-z_][A-Za-z_0-9]*", expr)
            if tok not in ("sqrt", "sin", "cos", "pi", "Matrix", "atan2")
        )
        local = {n: sympy.Symbol(n) for n in names}
        out[name] = sympy.sympify(expr, locals=local)
    return out


def same(a, b):
    """Equal under SymPy: structurally, or with a difference that expands to zero."""
    if a == b:
        return True
    return sympy.simplify(sympy.expand(a - b, trig=True)) == 0


# An independent implementation for the numeric checks: 4x4 matrices of the DH conventions
# and a dual-quaternion-to-matrix conversion written from the formulas, not from dqsym.


def rot_z(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def rot_x(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1.0, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def trans(x, y, z):
    m = np.eye(4)
    m[:3, 3] = [x, y, z]
    return m


def dh(theta, d, a, alpha):
    return rot_z(theta) @ trans(0, 0, d) @ trans(a, 0, 0) @ rot_x(alpha)


def mdh(alpha, a, theta, d):
    return rot_x(alpha) @ trans(a, 0, 0) @ rot_z(theta) @ trans(0, 0, d)


def quat_mul(p, q):
    w1, x1, y1, z1 = p
    w2, x2, y2, z2 = q
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )


def dq_to_matrix(c):
    """The homogeneous matrix of a unit DQ r + eps q_e: R from r, t = 2 q_e r*."""
    r, e = np.asarray(c[:4], float), np.asarray(c[4:], float)
    w, x, y, z = r
    rot = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )
    t = 2 * quat_mul(e, r * np.array([1, -1, -1, -1]))
    m = np.eye(4)
    m[:3, :3] = rot
    m[:3, 3] = t[1:]
    return m


def katex_check(tex):
    """Renders `tex` with KaTeX in Node (throwOnError) and fails with KaTeX's message."""
    node = shutil.which("node")
    katex = ROOT / "node_modules" / "katex"
    if node is None or not katex.exists():
        pytest.fail("Node and KaTeX (node_modules/katex) are needed: run `bash scripts/test.sh`")
    script = (
        "const k=require(process.argv[1]);let s='';process.stdin.on('data',d=>s+=d);"
        "process.stdin.on('end',()=>{k.renderToString(s,{throwOnError:true,displayMode:true});"
        "console.log('ok')});"
    )
    r = subprocess.run(
        [node, "-e", script, str(katex)], input=tex, capture_output=True, text=True
    )
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr
