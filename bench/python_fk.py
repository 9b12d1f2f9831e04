"""Times `Robot.from_file(...).fk()` into SymPy objects, beside what parsing the SymPy text of
the same result costs (`sympify` of `dqsym fk --format sympy`). Run after installing the
package: `.venv/bin/python bench/python_fk.py [ROBOT.toml [DQSYM_BINARY]]`. Prints medians of fresh runs
(each run reads the file and derives again; SymPy's caches are cleared between runs)."""

import statistics
import subprocess
import sys
import time

import sympy
from sympy.core.cache import clear_cache

import dqsym

path = sys.argv[1] if len(sys.argv) > 1 else "examples/robots/puma560.toml"


def median_ms(f, runs=15):
    times = []
    for _ in range(runs):
        clear_cache()
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return 1000 * statistics.median(times)


def fk_dq():
    dqsym.Robot.from_file(path).fk()


def fk_both():
    r = dqsym.Robot.from_file(path)
    r.fk()
    r.fk_matrix()


def fk_jacobian():
    r = dqsym.Robot.from_file(path)
    r.fk()
    r.jacobian()


text = subprocess.run(
    ["target/release/dqsym" if len(sys.argv) < 3 else sys.argv[2], "fk", path, "--format", "sympy"],
    capture_output=True,
    text=True,
    check=True,
).stdout
lines = [line.split(" = ", 1) for line in text.splitlines()]
names = {n: sympy.Symbol(n) for n in ["a2", "a3", "d3", "d4"] + [f"theta{i}" for i in range(1, 7)]}


def parse_text():
    for _, e in lines:
        sympy.sympify(e, locals=names)


print(f"{path}:")
print(f"  Robot.from_file(...).fk() (the DQ as SymPy):          {median_ms(fk_dq):7.1f} ms")
print(f"  from_file, fk() and fk_matrix() (DQ and 4x4):         {median_ms(fk_both):7.1f} ms")
print(f"  from_file, fk() and jacobian() (DQ and 8 x n):        {median_ms(fk_jacobian):7.1f} ms")
print(f"  sympify of the `fk --format sympy` text (DQ and 4x4): {median_ms(parse_text):7.1f} ms")
