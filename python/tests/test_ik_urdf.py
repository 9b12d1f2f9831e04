"""Inverse kinematics and URDF robots, where the library has them."""

import numpy as np
import pytest
import sympy

import dqsym
from conftest import ROOT, cli, dh, parse_sympy_lines, rot_z, trans

PUMA = ROOT / "examples" / "robots" / "puma560.toml"

URDF = """<robot name="two_r">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="tip"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.5" rpy="0 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.25 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/></joint>
  <joint name="j3" type="fixed"><parent link="l2"/><child link="tip"/>
    <origin xyz="0.125 0 0" rpy="0 0 0"/></joint>
</robot>
"""


def test_ik_is_the_clis_and_its_solver_inverts_fk():
    robot = dqsym.Robot.from_file(str(PUMA))
    want = parse_sympy_lines(
        "\n".join(
            line
            for line in cli("ik", str(PUMA), "--format", "sympy").splitlines()
            if not line.startswith("#")
        )
    )
    got = robot.ik()
    assert list(got) == list(want)
    assert all(got[k] == want[k] for k in want)
    # The generated solver against the generated forward kinematics at random poses.
    ik = robot.ik_function()
    fk = robot.lambdify()
    rng = np.random.default_rng(11)
    params = {"a2": 0.4318, "a3": 0.0203, "d3": 0.15, "d4": 0.4318}
    for _ in range(5):
        q = rng.uniform(-2.5, 2.5, 6)
        t = np.eye(4)
        t[:3] = fk(*q, **params)["t"]
        sols = ik(t, **params)
        assert len(sols) >= 1
        for s in sols:
            t2 = np.eye(4)
            t2[:3] = fk(*s, **params)["t"]
            assert np.allclose(t2, t, atol=1e-8)
        assert any(np.allclose(np.angle(np.exp(1j * (np.asarray(s) - q))), 0, atol=1e-6) for s in sols)


def test_urdf_robots_read_as_the_cli_reads_them(tmp_path):
    path = tmp_path / "two_r.urdf"
    path.write_text(URDF)
    robot = dqsym.Robot.from_file(str(path))
    assert robot.variables == ["j1", "j2"] or len(robot.variables) == 2
    want = parse_sympy_lines(cli("fk", str(path), "--format", "sympy"))
    T = robot.fk_matrix()
    for i in range(3):
        for j in range(4):
            assert T[i, j] == want[f"T[{i}][{j}]"]
    same = dqsym.Robot.from_urdf(URDF, name=str(path))
    assert same.fk_matrix() == T
    # Against plain matrices: Tz(0.5) Rz(q1) Tx(0.25) Rz(q2) Tx(0.125).
    f = sympy.lambdify([sympy.Symbol(v) for v in robot.variables], T, "numpy")
    rng = np.random.default_rng(5)
    for _ in range(3):
        q1, q2 = rng.uniform(-3, 3, 2)
        m = trans(0, 0, 0.5) @ rot_z(q1) @ trans(0.25, 0, 0) @ rot_z(q2) @ trans(0.125, 0, 0)
        assert np.allclose(np.array(f(q1, q2), dtype=float), m)
    assert dh(0, 0, 0, 0).shape == (4, 4)


def test_bad_urdf_is_an_error_with_the_clis_message():
    import subprocess

    from conftest import dqsym_bin

    for path in sorted((ROOT / "tests" / "data" / "urdf_bad").glob("*.urdf")):
        r = subprocess.run([dqsym_bin(), "fk", str(path)], capture_output=True, text=True)
        assert r.returncode == 1
        with pytest.raises(dqsym.DqsymError) as e:
            dqsym.Robot.from_file(str(path))
        assert str(e.value) == r.stderr.strip()
