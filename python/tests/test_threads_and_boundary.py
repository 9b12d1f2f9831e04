"""Hostile round 3, the Python rows: one Robot or Session shared by threads, integers past
Python's 4,300-digit string limit across the boundary both ways, and names refused by
`Session[name] = value` exactly as the language refuses them as assignment targets."""

import fractions
import sys
import threading

import pytest
import sympy

import dqsym

from conftest import ROOT


def run_threads(target, n=8):
    """Runs `target(i)` on n threads at once; the results by index, and every exception."""
    results, errors = [None] * n, []
    start = threading.Barrier(n)

    def work(i):
        try:
            start.wait()
            results[i] = target(i)
        except BaseException as e:  # noqa: BLE001 - every failure is what the test reports
            errors.append(repr(e))

    threads = [threading.Thread(target=work, args=(i,)) for i in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return results, errors


def test_one_robot_serves_eight_threads_with_one_answer():
    path = str(ROOT / "examples" / "robots" / "puma560.toml")
    robot = dqsym.Robot.from_file(path)
    # The answers of a robot used by one thread only.
    alone = dqsym.Robot.from_file(path)
    expected = {0: alone.fk_matrix(), 1: alone.fk()}
    results, errors = run_threads(lambda i: robot.fk() if i % 2 else robot.fk_matrix())
    assert errors == []
    for i, r in enumerate(results):
        assert r == expected[i % 2], i


def test_one_session_serves_eight_threads_statement_by_statement():
    s = dqsym.Session(implicit_symbols=True)

    def work(i):
        s.run(f"v{i} = {i}*x + 1")
        s[f"w{i}"] = i
        return s.eval(f"v{i} + w{i}")

    results, errors = run_threads(work)
    assert errors == []
    x = sympy.Symbol("x")
    for i, r in enumerate(results):
        assert sympy.expand(r - (i * x + 1 + i)) == 0
    assert all(f"v{i}" in s and f"w{i}" in s for i in range(8))


def test_integers_past_the_string_limit_cross_exactly_both_ways():
    limit = sys.get_int_max_str_digits() if hasattr(sys, "get_int_max_str_digits") else 4300
    assert limit == 0 or 7**6000 > 10**limit
    # Out: a result of 5,071 digits.
    v = dqsym.evaluate("7^6000")
    assert int(v) == 7**6000
    # In, as an int and inside a Fraction and a SymPy Rational, and back out.
    s = dqsym.Session(implicit_symbols=True)
    s["a"] = 7**6000
    s["b"] = fractions.Fraction(3**7000, 2**9000)
    s["c"] = sympy.Rational(-(5**6500), 7)
    assert int(s.eval("a + 1")) == 7**6000 + 1
    r = s.eval("b")
    assert (int(r.p), int(r.q)) == (3**7000, 2**9000)
    r = s.eval("c*7")
    assert int(r) == -(5**6500)


@pytest.mark.parametrize(
    "name", ["syms", "halfangle", "pi", "I", "eps", "cos", "transform", "x", "ans"]
)
def test_setitem_refuses_exactly_what_assignment_refuses(name):
    script = dqsym.Session(implicit_symbols=True)
    try:
        script.run(f"{name} = 1")
        language_refuses = False
    except (dqsym.ParseError, dqsym.EvalError):
        language_refuses = True
    s = dqsym.Session(implicit_symbols=True)
    try:
        s[name] = 1
        refused = False
    except (dqsym.ParseError, dqsym.EvalError, ValueError):
        refused = True
    assert refused == language_refuses, name
    assert (name in s) == (not refused)


def test_an_interrupted_statement_binds_nothing_and_the_ones_before_it_stay():
    import _thread

    s = dqsym.Session(implicit_symbols=True, term_limit=10**7, work_budget=10**18)
    huge = " + ".join(f"(a{i} + b + c + d)^18" for i in range(1500))
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            s.run(f"first = 6*7\nsecond = {huge}\n")
    finally:
        timer.cancel()
    assert "second" not in s
    assert s.eval("first") == 42
