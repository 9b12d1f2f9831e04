"""A held-out corpus for the closed-form search (issue 33): seeded random trigonometric
expressions that no heuristic was tuned on, each expanded (so the short form must be found),
given to `dqsym -e` and to SymPy's trigsimp, fu and simplify; prints the share of expressions
whose closed form is no longer than SymPy's best (by SymPy's count_ops of both, the input
itself counting as a SymPy answer). With --cache, SymPy's best count for each expression is
kept in FILE (JSON, keyed by the expression's text) and read from it on the next run, so that
a run that changes only the binary does not wait for SymPy again.

  python scripts/heldout_corpus.py [--n 200] [--seed 33] [--bin target/release/dqsym]
      [--timeout 10] [--show] [--cache FILE]

Run with a Python that has SymPy (the repository's .venv). The shapes: products of two or
three cosines and sines of integer (or half) combinations of one or two symbols, optionally
with a length symbol and an offset at a multiple of pi/6 or pi/4, sums of two such products,
and squares of sums; symbol names (p, r, w, u1, u2, k1) unused by tests/data/trig_identities.txt.
"""
import argparse
import json
import os
import random
import signal
import subprocess
import sys

import sympy as sp
from sympy.simplify.fu import fu

SYMS = sp.symbols("p r w u1 u2")
LENGTHS = sp.symbols("k1 k2")


def angle(rng):
    """A linear combination of one or two symbols, maybe with an offset."""
    xs = rng.sample(SYMS, rng.choice([1, 1, 2]))
    a = sum(rng.choice([1, 1, 2, -1, sp.Rational(1, 2)]) * x for x in xs)
    if rng.random() < 0.3:
        a += sp.pi * rng.choice([sp.Rational(1, 6), sp.Rational(1, 4), sp.Rational(1, 3), sp.Rational(-1, 6)])
    return a


def product(rng):
    f = sp.Integer(1)
    for _ in range(rng.choice([2, 2, 3])):
        f *= rng.choice([sp.sin, sp.cos])(angle(rng))
    if rng.random() < 0.4:
        f *= rng.choice(LENGTHS)
    return f * rng.choice([1, 1, 2, -1, sp.Rational(1, 2)])


def generate(rng):
    shape = rng.random()
    if shape < 0.5:
        e = product(rng)
    elif shape < 0.85:
        e = product(rng) + product(rng)
    else:
        t = rng.choice(LENGTHS) * sp.cos(angle(rng)) + sp.sin(angle(rng))
        e = t**2
    return sp.expand(sp.expand_trig(e))


class Timeout(Exception):
    pass


def _alarm(*_):
    raise Timeout


def limited(f, e, seconds):
    signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(seconds)
    try:
        return f(e)
    except Timeout:
        return None
    except Exception:  # SymPy's own failures count as no answer
        return None
    finally:
        signal.alarm(0)


def ops(e):
    return int(sp.count_ops(e, visual=False))


def ours(binary, e):
    text = str(e).replace("**", "^")
    r = subprocess.run(
        [binary, "--format", "sympy", "-e", text],
        capture_output=True,
        text=True,
        timeout=120,
    )
    if r.returncode != 0:
        return None, r.stderr.strip()
    out = r.stdout.strip()
    return sp.sympify(out, locals={s.name: s for s in SYMS + LENGTHS}), out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--seed", type=int, default=33)
    ap.add_argument("--bin", default="target/release/dqsym")
    ap.add_argument("--timeout", type=int, default=10)
    ap.add_argument("--show", action="store_true")
    ap.add_argument("--cache", default=None)
    a = ap.parse_args()
    cache = {}
    if a.cache and os.path.exists(a.cache):
        with open(a.cache) as f:
            cache = json.load(f)
    rng = random.Random(a.seed)
    ok = longer = failed = 0
    for i in range(a.n):
        e = generate(rng)
        mine, text = ours(a.bin, e)
        if mine is None:
            failed += 1
            print(f"{i}: dqsym failed: {text}  <- {e}")
            continue
        # The closed form must equal the input (checked at a random point, in floats).
        pt = {s: rng.uniform(0.3, 1.7) for s in SYMS + LENGTHS}
        assert abs(complex((mine - e).evalf(subs=pt))) < 1e-9, (i, e, text)
        key = str(e)
        if key in cache:
            best, how = cache[key]
        else:
            best = ops(e)
            how = "input"
            for name, f in [("trigsimp", sp.trigsimp), ("fu", fu), ("simplify", sp.simplify)]:
                r = limited(f, e, a.timeout)
                if r is not None and ops(r) < best:
                    best, how = ops(r), name
            cache[key] = [best, how]
        m = ops(mine)
        if m <= best:
            ok += 1
        else:
            longer += 1
            if a.show:
                print(f"{i}: ours {m} > {how} {best}: {text}  <- {e}", flush=True)
        if a.show and (i + 1) % 10 == 0:
            print(f"after {i + 1}: {ok} no longer, {longer} longer, {failed} failed", flush=True)
    if a.cache:
        with open(a.cache, "w") as f:
            json.dump(cache, f, indent=0, sort_keys=True)
    n = ok + longer
    print(f"held-out corpus (seed {a.seed}): {ok}/{n} = {100.0 * ok / max(n, 1):.1f}% no longer than "
          f"SymPy's best; {failed} failed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
