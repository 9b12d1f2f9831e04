"""`(x+y+z)^n` (issue 33's expansion target) side by side in one run: dqsym as a process
(`-e`, raised limits: expansion, closed form and printing; wall and CPU of the child) against
SymEngine's in-process `expand` (the bar: dqsym's process <= 10x it) and SymEngine as a process
(start Python, import SymEngine, expand, print).

    python bench/expand_vs_symengine.py [DQSYM_BINARY] [N ...]

Median of five runs each; DQSYM_THREADS=1 for the dqsym process."""

import os
import resource
import statistics
import subprocess
import sys
import time

import symengine

binary = sys.argv[1] if len(sys.argv) > 1 else "target/release/dqsym"
ns = [int(a) for a in sys.argv[2:]] or [30, 60, 80]
RUNS = 5


def child_run(cmd, env=None):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, env=env)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def in_process(n):
    x, y, z = symengine.symbols("x y z")
    t = time.perf_counter()
    symengine.expand((x + y + z) ** n)
    return time.perf_counter() - t


env = dict(os.environ, DQSYM_THREADS="1")
print(f"{'n':>4} {'dqsym wall':>11} {'dqsym cpu':>10} {'SE in-proc':>11} {'SE process':>11} "
      f"{'ratio (dqsym cpu / SE in-proc)':>31}")
for n in ns:
    dq = [child_run([binary, "--term-limit", "1000000", "--work-budget", "1000000000",
                     "-e", f"(x+y+z)^{n}"], env) for _ in range(RUNS)]
    se = [in_process(n) for _ in range(RUNS)]
    script = ("import symengine; x, y, z = symengine.symbols('x y z'); "
              f"print(symengine.expand((x + y + z)**{n}))")
    sp = [child_run([sys.executable, "-c", script]) for _ in range(RUNS)]
    w = statistics.median(r[0] for r in dq)
    c = statistics.median(r[1] for r in dq)
    s = statistics.median(se)
    p = statistics.median(r[0] for r in sp)
    print(f"{n:>4} {w * 1e3:>9.1f}ms {c * 1e3:>8.1f}ms {s * 1e3:>9.2f}ms {p * 1e3:>9.1f}ms "
          f"{c / s:>30.1f}x")
