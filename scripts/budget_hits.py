"""How often random trigonometric expressions run out of the default work budget (issue 33:
"10 times in 300, was 4"): the seeded expressions of scripts/heldout_corpus.py (its
`generate`, so the two scripts see the same corpus), each given to `dqsym -e` with the
command line's default limits; prints every failure and the number of budget hits.

  python scripts/budget_hits.py [--n 300] [--seed 33] [--bin target/release/dqsym]

Run with a Python that has SymPy (the repository's .venv), from the repository root.
"""
import argparse
import os
import random
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from heldout_corpus import generate  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=300)
    ap.add_argument("--seed", type=int, default=33)
    ap.add_argument("--bin", default="target/release/dqsym")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    budget = other = 0
    for i in range(a.n):
        text = str(generate(rng)).replace("**", "^")
        r = subprocess.run([a.bin, "-e", text], capture_output=True, text=True, timeout=600)
        if r.returncode != 0:
            err = r.stderr.strip()
            if "budget" in err:
                budget += 1
            else:
                other += 1
            print(f"{i}: {err}  <- {text}", flush=True)
    print(f"random trig expressions (seed {a.seed}): {budget}/{a.n} hit the work budget, "
          f"{other} failed otherwise")
    return 0


if __name__ == "__main__":
    sys.exit(main())
