"""Times `Robot.from_file(...).fk()` into SymPy objects, beside what parsing the SymPy text of
the same result costs (`sympify` of `dqsym fk --format sympy`), and splits it: the derivation
in Rust (`report()`, the same derivation printed as text) and the building of SymPy trees (the
rest). Run after installing the package:
`.venv/bin/python bench/python_fk.py [ROBOT.toml [DQSYM_BINARY]]`. Prints medians of fresh runs
(each run reads the file and derives again; SymPy's caches are cleared between runs), as wall
time and as the process's CPU time (all threads; steadier on a loaded machine), and the first
call of a fresh process, which also pays SymPy's one-time lazy imports (`sympy.tensor`,
`sympy.combinatorics`: about half a second, paid by any first `Add` of an expression)."""

import statistics
import subprocess
import sys
import time

import sympy
from sympy.core.cache import clear_cache

import dqsym

path = sys.argv[1] if len(sys.argv) > 1 else "examples/robots/puma560.toml"

t = (time.perf_counter(), time.process_time())
dqsym.Robot.from_file(path).fk()
first = (1000 * (time.perf_counter() - t[0]), 1000 * (time.process_time() - t[1]))


def median_ms(f, runs=15):
    """Median wall and CPU milliseconds of `runs` calls, SymPy's caches cleared before each."""
    wall, cpu = [], []
    for _ in range(runs):
        clear_cache()
        t = (time.perf_counter(), time.process_time())
        f()
        wall.append(time.perf_counter() - t[0])
        cpu.append(time.process_time() - t[1])
    return f"{1000 * statistics.median(wall):7.1f} ms wall, {1000 * statistics.median(cpu):7.1f} ms CPU"


def fk_dq():
    dqsym.Robot.from_file(path).fk()


def derivation_only():
    dqsym.Robot.from_file(path).report(format="plain")


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
print(f"  first call in this process (SymPy's lazy imports too): {first[0]:7.1f} ms wall, {first[1]:7.1f} ms CPU")
print(f"  Robot.from_file(...).fk() (the DQ as SymPy):           {median_ms(fk_dq)}")
print(f"  of which the derivation (report(), text):              {median_ms(derivation_only)}")
print(f"  from_file, fk() and fk_matrix() (DQ and 4x4):          {median_ms(fk_both)}")
print(f"  from_file, fk() and jacobian() (DQ and 8 x n):         {median_ms(fk_jacobian)}")
print(f"  sympify of the `fk --format sympy` text (DQ and 4x4):  {median_ms(parse_text)}")
