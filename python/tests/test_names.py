"""Names never become code through the package: `Robot.lambdify()` executes the generated NumPy
source, so a robot's name must stay inside its docstring, and symbols that Python or the
generated function reserve (`shape`, `lambda`, `np`, `float`) must reach the right parameter
when passed by their own names."""

import keyword
import os

import numpy as np

import dqsym
from conftest import dh


def test_lambdify_runs_no_code_from_the_robot_name():
    flag = "DQSYM_NAMES_INJECTED"
    os.environ.pop(flag, None)
    for name in [
        f'x """; import os; os.environ["{flag}"] = "1"; """',
        f"x\nimport os; os.environ['{flag}'] = '1'",
        'end with a quote "',
        "back slash \\N{BULLET} \\x00 \\",
    ]:
        toml = (
            'name = "' + name.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"\n'
            'convention = "dh"\n[[joint]]\ntype = "revolute"\ntheta = "theta1"\nd = "0"\n'
            'a = "l1"\nalpha = "0"\n'
        )
        r = dqsym.Robot.from_toml(toml)
        f = r.lambdify()
        t = f(theta1=0.3, l1=2.0)["t"]
        assert np.allclose(t, dh(0.3, 0, 2.0, 0)[:3])
        assert flag not in os.environ, name
        # The name is in the docstring, line by line.
        for line in name.split("\n"):
            assert line.strip() in f.__doc__, (line, f.__doc__)


def test_lambdify_takes_reserved_symbol_names_as_keywords():
    # Every pair of Python keywords and NumPy-function names that the language reads as
    # symbols: the joint variable, a length, an offset and another length.
    names = keyword.kwlist + ["shape", "np", "float", "int", "sum", "math"]
    rng = np.random.default_rng(7)
    for i in range(0, len(names) - 3, 4):
        theta, a, d2, a2 = names[i : i + 4]
        toml = (
            f'name = "r{i}"\nconvention = "dh"\n'
            f'[[joint]]\ntype = "revolute"\ntheta = "{theta}"\nd = "0"\na = "{a}"\nalpha = "0"\n'
            f'[[joint]]\ntype = "prismatic"\ntheta = "pi/2"\nd = "{d2}"\na = "{a2}"\nalpha = "pi/2"\n'
        )
        r = dqsym.Robot.from_toml(toml)
        f = r.lambdify()
        assert set(f.args) == {theta, a, d2, a2}, f.args
        q = rng.uniform(-1.5, 1.5, size=(3,))
        vals = {theta: q, a: rng.uniform(0.5, 2), d2: np.array([0.1, 0.2, 0.3]), a2: rng.uniform(0.5, 2)}
        t = f(**vals)["t"]
        assert t.shape == (3, 3, 4)
        for k in range(3):
            want = dh(q[k], 0, vals[a], 0) @ dh(np.pi / 2, vals[d2][k], vals[a2], np.pi / 2)
            assert np.allclose(t[k], want[:3], atol=1e-12), (theta, a, d2, a2)
