"""The package installs in a fresh virtual environment: the wheel `pip wheel ./python` built
(scripts/test.sh builds it once, installs it in .venv and names it in $DQSYM_WHEEL) goes into
a new venv with nothing else in it, pip fetches SymPy and NumPy as its dependencies, and the
module imports and computes there."""

import os
import pathlib
import subprocess
import sys

import pytest

from conftest import ROOT


def wheel():
    """$DQSYM_WHEEL, else the newest wheel in python/target/wheels."""
    path = os.environ.get("DQSYM_WHEEL")
    if path:
        return pathlib.Path(path)
    found = sorted(
        (ROOT / "python" / "target" / "wheels").glob("dqsym-*.whl"),
        key=lambda p: p.stat().st_mtime,
    )
    if not found:
        pytest.fail(
            "no wheel of the package: run `bash scripts/test.sh`, which builds it with "
            "`pip wheel ./python` (or set DQSYM_WHEEL)"
        )
    return found[-1]


def test_the_package_installs_and_computes_in_a_fresh_venv(tmp_path):
    whl = wheel()
    assert whl.is_file(), whl
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    py = venv / "bin" / "python"
    # Nothing of the package, SymPy or NumPy is there before.
    bare = subprocess.run([py, "-c", "import dqsym"], capture_output=True, text=True)
    assert bare.returncode != 0 and "No module named 'dqsym'" in bare.stderr
    pip = subprocess.run(
        [py, "-m", "pip", "install", "--disable-pip-version-check", "--quiet", str(whl)],
        capture_output=True,
        text=True,
    )
    assert pip.returncode == 0, pip.stdout + pip.stderr
    # Run from the temporary directory, so that the repository's python/dqsym is not on the
    # path: the installed package is the one imported.
    check = """
import pathlib, sys
import numpy as np, sympy
import dqsym
assert pathlib.Path(dqsym.__file__).is_relative_to(pathlib.Path(sys.prefix)), dqsym.__file__
x, y = sympy.symbols("x y")
assert sympy.expand(dqsym.evaluate("(x + y)^3") - (x + y) ** 3) == 0
t = sympy.Symbol("theta1")
p = dqsym.evaluate("transform(rot((0, 0, 1), theta1), (l, 0, 0))")
l = sympy.Symbol("l")
assert sympy.Matrix(p) == sympy.Matrix([l * sympy.cos(t), l * sympy.sin(t), 0]), p
print(dqsym.__file__)
"""
    out = subprocess.run(
        [py, "-c", check], capture_output=True, text=True, cwd=tmp_path
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert str(venv) in out.stdout
