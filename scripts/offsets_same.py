"""Output-unchanged check of the closed-form search on offsets off the multiples of pi/12 (the
held-out corpus, scripts/heldout_corpus.py, has none): seeded random sums of 2 to 5 terms, each
a signed small integer, maybe a length, times one to three cosines or sines of sums of one to
four joint angles plus k pi/n (n one of 5, 7, 9, 10, 18 for the whole expression, the offset
left out one time in five), given to `dqsym -e` with two binaries; prints each expression whose
exit status, stdout or stderr differ, then the count. Exit status 1 when any differs.

  python3 scripts/offsets_same.py BEFORE_BINARY AFTER_BINARY [--n 300] [--seed 2211]
"""
import argparse
import random
import subprocess
import sys

ANGLES = ["q1", "q2", "q3", "q4", "q5", "q6"]
LENGTHS = ["a2", "d3", "d4"]


def angle(rng, n):
    """A sum of one to four distinct joint angles, signed, plus k pi/n four times in five."""
    syms = rng.sample(ANGLES, rng.randint(1, 4))
    s = syms[0]
    for x in syms[1:]:
        s += rng.choice(["+", "-"]) + x
    k = rng.randint(1, 2 * n - 1)
    return f"{s}+{k}*pi/{n}" if rng.random() < 0.8 else s


def expression(rng):
    """One expression of the shapes above."""
    n = rng.choice([5, 7, 9, 10, 18])
    terms = []
    for _ in range(rng.randint(2, 5)):
        factors = [str(rng.randint(1, 4))]
        if rng.random() < 0.5:
            factors.append(rng.choice(LENGTHS))
        for _ in range(rng.randint(1, 3)):
            factors.append(f"{rng.choice(['cos', 'sin'])}({angle(rng, n)})")
        terms.append(("-" if rng.random() < 0.5 else "+") + "*".join(factors))
    return "".join(terms).lstrip("+")


def run(binary, e):
    r = subprocess.run([binary, "-e", e], capture_output=True, text=True, timeout=120)
    return (r.returncode, r.stdout, r.stderr)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("before")
    p.add_argument("after")
    p.add_argument("--n", type=int, default=300)
    p.add_argument("--seed", type=int, default=2211)
    a = p.parse_args()
    rng = random.Random(a.seed)
    differ = 0
    for i in range(a.n):
        e = expression(rng)
        x, y = run(a.before, e), run(a.after, e)
        if x != y:
            differ += 1
            print(i, e, "|", x[1].strip(), "|", y[1].strip())
    print("differ:", differ, "of", a.n)
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
