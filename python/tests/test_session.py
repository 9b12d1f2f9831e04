"""Sessions, one-liners, conversions both ways, errors with positions, LaTeX."""

import random

import numpy as np
import pytest
import sympy
from sympy import Matrix, Quaternion, Rational, Symbol, cos, pi, sin, sqrt, symbols

import dqsym
from conftest import ROOT, cli, katex_check, parse_sympy_lines, quat_mul, same

t, l, theta1 = symbols("t l theta1")


def test_evaluate_returns_sympy_and_is_exact():
    v = dqsym.evaluate("cos(t)^2 + sin(t)^2")
    assert v == 1 and isinstance(v, sympy.Integer)
    v = dqsym.evaluate("cos(pi/12)")
    assert v == (sqrt(6) + sqrt(2)) / 4
    assert dqsym.evaluate("(1/3)*x + 2/6*x") == Rational(2, 3) * Symbol("x")


def test_evaluate_equals_the_cli_sympy_output():
    for src in [
        "transform(rot((0, 0, 1), theta1), (l, 0, 0))",
        "dh(theta1, d1, a1, pi/2)*dh(theta2, 0, a2, 0)",
        "matrix(dh(theta1, d1, a1, pi/2)*dh(theta2, 0, a2, 0))",
        "cos(t)^3",
        "(1 + 2*x)^5",
    ]:
        expected = cli("-e", src, "--format", "sympy").strip()
        got = dqsym.evaluate(src)
        if isinstance(got, dqsym.DQ):
            want = sympy.sympify(expected)
            assert all(same(a, b) for a, b in zip(got.components, want))
        elif isinstance(got, sympy.MatrixBase):
            want = sympy.sympify(expected)
            want = Matrix(want) if not isinstance(want, tuple) else Matrix(list(want))
            assert got.shape == want.shape
            assert all(same(a, b) for a, b in zip(got, want))
        else:
            assert same(got, sympy.sympify(expected))


def test_angles_with_negative_summands_are_sympys_own_trees():
    # The sign SymPy takes out of a cosine's or sine's sum is decided by the package where the
    # summands' signs decide it (convert.rs, `plain_angle_is_negative`) and by SymPy on a tie:
    # either way the tree is the one sympify makes of the command line's text, exactly.
    for src in [
        "cos(a - b)",
        "sin(a - b)",
        "sin(b - a)",
        "sin(c - a - b)",
        "cos(1 - a - b)",
        "sin(-1 - a)",
        "sin(2 - a)",
        "sin(-3*a)",
        "cos(-a/2)",
        "sin(a + b - 1/2)",
        "sin(c + d - a/2 - b/3)",
        "sin(d - a - b - c)",
        "x*sin(1/3 - a) + y*cos(2 - b - c)",
        # More negative summands than positive ones: SymPy takes the sign out.
        "cos(a - b - c)",
        "sin(a - b - c)",
        "sin(a - b - 1)",
        "cos(a/2 - b - 1/3)",
        "sin(a - b + c - d)",
    ]:
        want = sympy.sympify(cli("-e", src, "--format", "sympy").strip())
        got = dqsym.evaluate(src)
        assert sympy.srepr(got) == sympy.srepr(want), src


def test_the_papers_rrr_script_matches_the_cli_and_numbers():
    src = (ROOT / "examples" / "appendix3_rrr.dq").read_text()
    s = dqsym.Session()
    outs = s.run(src)
    expected = parse_sympy_lines(
        cli("run", "examples/appendix3_rrr.dq", "--format", "sympy").replace(
            "(dq1*dq2*dq3)*v3*cconj(dq1*dq2*dq3)", "last"
        )
    )
    assert [o.label for o in outs][:3] == ["v2", "v1", "v0"]
    for o in outs[:3]:
        want = expected[o.label]
        assert isinstance(o.value, dqsym.DQ)
        assert all(same(a, b) for a, b in zip(o.value.components, want))
    # Numerically: the end effector of the planar arm, written independently.
    v0 = s["v0"]
    rng = random.Random(1)
    for _ in range(5):
        vals = {Symbol(n): rng.uniform(-2, 2) for n in ["l1", "l2", "l3", "theta1", "theta2", "theta3"]}
        L1, L2, L3 = (vals[Symbol(n)] for n in ["l1", "l2", "l3"])
        a1, a2, a3 = (vals[Symbol(n)] for n in ["theta1", "theta2", "theta3"])
        y = L1 * np.cos(a1) + L2 * np.cos(a1 + a2) + L3 * np.cos(a1 + a2 + a3)
        z = L1 * np.sin(a1) + L2 * np.sin(a1 + a2) + L3 * np.sin(a1 + a2 + a3)
        got = [float(c.subs(vals)) for c in v0.components]
        assert np.allclose(got, [1, 0, 0, 0, 0, 0, y, z])


def test_bindings_take_sympy_values():
    s = dqsym.Session(implicit_symbols=True)
    s["q"] = dqsym.evaluate("rot((0, 0, 1), theta1)")
    s["p"] = (l, 0, 0)
    s["k"] = Rational(1, 3) * t + 2
    s["M"] = Matrix([[1, t], [0, 1]])
    s["Q"] = Quaternion(1, 2, 3, 4)
    assert s.eval("transform(q, p)") == Matrix([l * cos(theta1), l * sin(theta1), 0])
    assert s.eval("k*3") == t + 6
    assert s.eval("M*M") == Matrix([[1, 2 * t], [0, 1]])
    assert s.eval("Q*conj(Q)") == Quaternion(30, 0, 0, 0)
    assert sorted(s.keys()) == ["M", "Q", "ans", "k", "p", "q"]
    # Keyword bindings, and a sympy symbol named like a session variable stays a symbol.
    assert dqsym.evaluate("a + b", a=Symbol("b"), b=sqrt(2)) == Symbol("b") + sqrt(2)


def test_inputs_that_are_not_exact_are_refused():
    s = dqsym.Session(implicit_symbols=True)
    with pytest.raises(TypeError, match="float"):
        s["x"] = 0.5
    with pytest.raises(TypeError, match="float"):
        s["x"] = sympy.Float(0.5) * t
    with pytest.raises(TypeError, match="cannot represent"):
        s["x"] = sympy.exp(t)
    with pytest.raises(dqsym.EvalError, match="cannot be assigned"):
        s["pi"] = 3
    assert "x" not in s


def test_dq_arithmetic_is_the_engines_and_matches_numbers():
    a = dqsym.evaluate("dh(theta1, d1, a1, pi/2)")
    b = dqsym.evaluate("dh(theta2, 0, a2, 0)")
    ab = a * b
    assert isinstance(ab, dqsym.DQ)
    # The product against an independent dual quaternion product in NumPy.
    rng = random.Random(2)
    for _ in range(5):
        vals = {Symbol(n): rng.uniform(-2, 2) for n in ["theta1", "theta2", "d1", "a1", "a2"]}
        na = np.array([float(c.subs(vals)) for c in a])
        nb = np.array([float(c.subs(vals)) for c in b])
        real = quat_mul(na[:4], nb[:4])
        dual = quat_mul(na[:4], nb[4:]) + quat_mul(na[4:], nb[:4])
        got = np.array([float(c.subs(vals)) for c in ab])
        assert np.allclose(got, np.concatenate([real, dual]))
    assert a.conj() * a == dqsym.DQ(1, 0, 0, 0, 0, 0, 0, 0)
    m = ab.matrix()
    assert isinstance(m, sympy.MatrixBase) and m.shape == (4, 4)
    assert a.real == Quaternion(*a.components[:4])


def test_parse_errors_carry_line_and_column():
    s = dqsym.Session(implicit_symbols=True)
    with pytest.raises(dqsym.ParseError) as e:
        s.run("x = 1\ny = (2 + \nz = 3")
    err = e.value
    assert err.line >= 2 and err.column >= 1
    assert "-->" in str(err) and "^" in str(err)
    with pytest.raises(dqsym.ParseError) as e:
        s.run("x = 1\ny = (2 + 3")
    assert (e.value.line, e.value.column) == (2, 5)
    assert "never closed" in e.value.message


def test_eval_errors_carry_line_and_column_and_leave_the_session():
    s = dqsym.Session()
    s.run("syms a b\nx = a + b")
    with pytest.raises(dqsym.EvalError) as e:
        s.run("y = 2*x\nx = q + 1\nz = 3")
    assert (e.value.line, e.value.column) == (2, 5)
    assert "unknown name `q`" in e.value.message
    assert "y" in s and "z" not in s
    assert s["x"] == Symbol("a") + Symbol("b")


def test_limits_are_errors_as_in_the_cli():
    s = dqsym.Session(implicit_symbols=True, term_limit=100)
    with pytest.raises(dqsym.LimitError, match="term limit of 100"):
        s.run("(a + b + c + d)^10")
    s = dqsym.Session(implicit_symbols=True, work_budget=1000)
    with pytest.raises(dqsym.LimitError, match="work budget"):
        s.run("(a + b + c)^12")
    with pytest.raises(dqsym.EvalError, match="10000"):
        dqsym.evaluate("x^20000")
    with pytest.raises(dqsym.ParseError, match="nesting deeper than 8"):
        dqsym.Session(max_depth=8).run("x = " + "(" * 20 + "1" + ")" * 20)


def test_outputs_show_the_projects_latex_which_katex_renders():
    s = dqsym.Session()
    outs = s.run(
        "syms l1 l2 theta1 theta2\nq = rot((1, 0, 0), theta1, (0, l1, 0))\nM = matrix(q)\n"
        "v = transform(q, (0, l1 + l2, 0))\nc = cos(theta1 + theta2)"
    )
    for o in outs:
        tex = o._repr_latex_()
        assert tex.startswith("$\\displaystyle ") and tex.endswith("$")
        assert tex[len("$\\displaystyle ") : -1] .strip()
        katex_check(tex[len("$\\displaystyle ") : -1])
        assert o.latex in tex
        assert o.text.startswith(o.label + " =")
    # The DQ class shows the project's LaTeX too, and so does any value through latex().
    katex_check(dqsym.evaluate("rot((0, 0, 1), t)")._repr_latex_()[len("$\\displaystyle ") : -1])
    katex_check(dqsym.latex(Matrix([[cos(t), -sin(t)], [sin(t), cos(t)]])))
    assert "c_{12}" in dqsym.latex(cos(Symbol("theta1") + Symbol("theta2")))


def test_results_of_every_shape():
    assert isinstance(dqsym.evaluate("(1, x, 0, 0)*(1, 0, y, 0)"), Quaternion)
    v = dqsym.evaluate("(x, y, 0)")
    assert v == Matrix([Symbol("x"), Symbol("y"), 0])
    m = dqsym.evaluate("screwparams(dh(theta1, d1, a1, 0))")
    assert isinstance(m, sympy.MatrixBase)
    assert dqsym.evaluate("x = 1;") is None
