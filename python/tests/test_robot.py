"""Robots: every result against the command line's `fk --format sympy`, against plain 4x4
matrix products written here, and the generated NumPy functions against both."""

import re
import tomllib

import numpy as np
import pytest
import sympy

import dqsym
from conftest import ROBOTS, ROOT, cli, dh, dq_to_matrix, mdh, parse_sympy_lines, rot_z, same, trans


def field_value(text, values):
    """A robot-file field evaluated numerically (independently of dqsym's evaluator): a TOML
    number, or an expression (`90deg` is degrees)."""
    if isinstance(text, (int, float)):
        return float(text)
    text = re.sub(r"(\d+(?:\.\d+)?)\s*deg\b", r"(\1*pi/180)", text)
    names = set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", text)) - {"pi", "sqrt", "cos", "sin"}
    local = {n: sympy.Symbol(n) for n in names}
    e = sympy.sympify(text.replace("^", "**"), locals=local)
    return float(e.subs({local[n]: values[n] for n in names}))


def rotation(axis, angle):
    """Rodrigues' formula, 4x4."""
    n = np.asarray(axis, float)
    n = n / np.linalg.norm(n)
    k = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    m = np.eye(4)
    m[:3, :3] = np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k
    return m


def rot_y(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0, s, 0], [0, 1.0, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]])


def frame(table, v):
    """A [base] or [tool] frame: translation xyz, then rotation rpy (URDF: Rz Ry Rx)."""
    x, y, z = (v(t) for t in table.get("xyz", [0, 0, 0]))
    r, p, w = (v(t) for t in table.get("rpy", [0, 0, 0]))
    from conftest import rot_x

    return trans(x, y, z) @ rot_z(w) @ rot_y(p) @ rot_x(r)


def oracle(path, values):
    """The robot's 4x4 pose and tool point at `values`, from the file, with plain matrices."""
    f = tomllib.loads(pathlib_read(path))
    v = lambda t: field_value(t, values)  # noqa: E731
    m = frame(f["base"], v) if isinstance(f.get("base"), dict) else np.eye(4)
    for j in f["joint"]:
        if f["convention"] == "dh":
            m = m @ dh(v(j["theta"]), v(j["d"]), v(j["a"]), v(j["alpha"]))
        elif f["convention"] == "mdh":
            m = m @ mdh(v(j["alpha"]), v(j["a"]), v(j["theta"]), v(j["d"]))
        else:
            axis = [v(x) for x in j["axis"]]
            q = v(j["variable"])
            if j["type"] == "revolute":
                p = [v(x) for x in j["point"]]
                m = m @ trans(*p) @ rotation(axis, q) @ trans(*(-np.asarray(p)))
            else:
                n = np.asarray(axis) / np.linalg.norm(axis)
                m = m @ trans(*(n * q))
    tool = None
    if isinstance(f.get("tool"), dict):
        m = m @ frame(f["tool"], v)
    elif "tool" in f:
        tool = (m @ np.append([v(x) for x in f["tool"]], 1.0))[:3]
    return m, tool


def pathlib_read(path):
    return open(path, encoding="utf-8").read()


def assert_identical(a, b):
    """The same SymPy tree (not only an equal value)."""
    assert a == b, f"{a} is not the tree {b}"


def random_values(robot, rng):
    return {n: rng.uniform(-1.5, 1.5) for n in robot.variables + robot.parameters}


@pytest.mark.parametrize("path", ROBOTS, ids=[p.stem for p in ROBOTS])
def test_every_result_equals_the_cli_and_plain_matrices(path):
    robot = dqsym.Robot.from_file(str(path))
    want = parse_sympy_lines(cli("fk", str(path), "--format", "sympy", "--jacobian"))
    # The same SymPy trees as sympify makes of the command line's text, entry for entry.
    dq = robot.fk()
    T = robot.fk_matrix()
    J = robot.jacobian()
    n = len(robot.variables)
    assert isinstance(dq, dqsym.DQ) and T.shape == (4, 4) and J.shape == (8, n)
    for k in range(8):
        assert_identical(dq[k], want[f"dq[{k}]"])
    for i in range(3):
        for j in range(4):
            assert_identical(T[i, j], want[f"T[{i}][{j}]"])
    assert list(T[3, :]) == [0, 0, 0, 1]
    for i in range(8):
        for j in range(n):
            assert_identical(J[i, j], want[f"J[{i}][{j}]"])
    p = robot.point() if "p[0]" in want else None
    if p is not None:
        for i in range(3):
            assert_identical(p[i], want[f"p[{i}]"])
    # The entries dict is the CLI's report, name for name.
    entries = robot.entries(jacobian=True)
    assert set(entries) == set(want)
    # Numbers: the pose against a product of plain 4x4 matrices, the DQ against the pose.
    rng = np.random.default_rng(len(path.stem))
    names = robot.variables + robot.parameters
    syms = [sympy.Symbol(n) for n in names]
    t_f = sympy.lambdify(syms, T, "numpy")
    dq_f = sympy.lambdify(syms, list(dq.components), "numpy")
    p_f = sympy.lambdify(syms, p, "numpy") if p is not None else None
    for _ in range(3):
        vals = random_values(robot, rng)
        args = [vals[n] for n in names]
        m, tool = oracle(path, vals)
        assert np.allclose(np.array(t_f(*args), dtype=float), m, atol=1e-9)
        assert np.allclose(dq_to_matrix(dq_f(*args)), m, atol=1e-9)
        if p is not None:
            assert np.allclose(np.array(p_f(*args), dtype=float).ravel(), tool, atol=1e-9)


@pytest.mark.parametrize("path", ROBOTS, ids=[p.stem for p in ROBOTS])
def test_numpy_function_matches_sympy_and_plain_matrices(path):
    robot = dqsym.Robot.from_file(str(path))
    f = robot.lambdify(jacobian=True)
    assert "import numpy" in f.source and f.args[: len(robot.variables)] == robot.variables
    rng = np.random.default_rng(7)
    shape = (4,)
    args = {a: rng.uniform(-1.5, 1.5, size=shape) for a in f.args}
    out = f(**args)
    assert out["dq"].shape == shape + (8,) and out["t"].shape == shape + (3, 4)
    dq, J = robot.fk(), robot.jacobian()
    syms = [sympy.Symbol(a) for a in f.args]
    dq_f = sympy.lambdify(syms, list(dq.components), "numpy")
    j_f = sympy.lambdify(syms, J, "numpy")
    for i in range(shape[0]):
        vals = {a: float(args[a][i]) for a in f.args}
        m, tool = oracle(path, vals)
        assert np.allclose(out["t"][i], m[:3], atol=1e-9)
        assert np.allclose(out["dq"][i], dq_f(*vals.values()), atol=1e-9)
        assert np.allclose(out["j"][i], np.array(j_f(*vals.values()), dtype=float), atol=1e-9)
        if "p" in out:
            assert np.allclose(out["p"][i], tool, atol=1e-9)


def test_a_chain_past_the_term_limit_is_an_exact_recurrence():
    path = ROOT / "tests" / "data" / "chain20_symbolic.toml"
    robot = dqsym.Robot.from_file(str(path))
    with pytest.raises(dqsym.LimitError, match="term limit of 5000"):
        robot.fk()
    entries = robot.entries()
    lines = cli("fk", str(path), "--format", "sympy").splitlines()
    assert list(entries) == [line.split(" = ")[0] for line in lines]
    # Every kind of entry (joint factors, prefix products, the pose) against the CLI's text.
    picked = [x for x in lines if x.startswith(("L1[", "Q2[", "Q20[", "dq[", "T[0]"))]
    want = parse_sympy_lines("\n".join(picked))
    assert len(want) == 8 * 4 + 4 and all(entries[k] == want[k] for k in want)
    # The generated function computes the recurrence; against plain DH products.
    f = robot.lambdify()
    rng = np.random.default_rng(3)
    vals = {a: float(rng.uniform(-1, 1)) for a in f.args}
    m, _ = oracle(path, vals)
    assert np.allclose(f(**vals)["t"], m[:3], atol=1e-9)


def test_from_toml_and_points():
    text = (ROOT / "examples" / "robots" / "rrr.toml").read_text()
    robot = dqsym.Robot.from_toml(text, name="rrr")
    assert robot.variables == ["theta1", "theta2", "theta3"]
    assert robot.convention == "screw"
    l1, l2, t1, t2 = sympy.symbols("l1 l2 theta1 theta2")
    p = robot.point((0, l1 + l2, 0))
    assert p == robot.point("0, l1 + l2, 0")
    assert same(p[1], l1 * sympy.cos(t1) + l2 * sympy.cos(t1 + t2))
    with pytest.raises(TypeError, match="float"):
        robot.point((0, 0.5, 0))


@pytest.mark.parametrize(
    "path",
    sorted((ROOT / "tests" / "data" / "robots_bad").glob("*.toml")),
    ids=lambda p: p.stem,
)
def test_bad_robot_files_raise_the_clis_message(path):
    import subprocess

    from conftest import dqsym_bin

    r = subprocess.run([dqsym_bin(), "fk", str(path)], capture_output=True, text=True)
    assert r.returncode == 1
    with pytest.raises(dqsym.RobotError) as e:
        dqsym.Robot.from_file(str(path))
    assert str(e.value) == r.stderr.strip()
    assert e.value.file == str(path)
    if "joint " in e.value.message or ", field `" in str(e.value):
        assert isinstance(e.value.joint, int) and e.value.field
    m = re.search(r"line (\d+), column (\d+)", str(e.value))
    if m:
        assert (e.value.line, e.value.column) == (int(m.group(1)), int(m.group(2)))


def test_reports_in_every_format_are_the_clis():
    path = str(ROOT / "examples" / "robots" / "puma560.toml")
    robot = dqsym.Robot.from_file(path)
    for fmt in ["plain", "latex", "sympy", "rust"]:
        assert robot.report(format=fmt, jacobian=True) == cli(
            "fk", path, "--format", fmt, "--jacobian"
        )
    with pytest.raises(ValueError, match="unknown format"):
        robot.report(format="pdf")
