"""Writes tests/data/trig_identities.txt: textbook, half/multiple-angle, regular-polygon,
Chebyshev, Morrie's-law, exact-constant and robotics identities, one `lhs = rhs` a line, the
rhs the short hand form (0 for the identities that are zeros). Run from the repository root:
python3 scripts/trig_corpus.py. The corpus is checked by tests/it/trig_corpus.rs."""
from fractions import Fraction
from math import comb

out = []


def add(cat, lhs, rhs="0"):
    out.append(f"{cat} | {lhs} = {rhs}")


def pi(k, n):
    f = Fraction(k, n)
    if f == 0:
        return "0"
    s = "-" if f < 0 else ""
    f = abs(f)
    num = "pi" if f.numerator == 1 else f"{f.numerator}*pi"
    return s + (num if f.denominator == 1 else f"{num}/{f.denominator}")


def shift(x, k, n):
    p = pi(k, n)
    if p == "0":
        return x
    return f"{x} - {p[1:]}" if p.startswith("-") else f"{x} + {p}"


# Textbook identities.
for x, y in [("x", "y"), ("a", "b"), ("t1", "t2"), ("u", "v")]:
    add("textbook", f"sin({x})^2 + cos({x})^2", "1")
    add("textbook", f"cos({x})^2 - sin({x})^2", f"cos(2*{x})")
    add("textbook", f"2*sin({x})*cos({x})", f"sin(2*{x})")
    add("textbook", f"1 - 2*sin({x})^2", f"cos(2*{x})")
    add("textbook", f"2*cos({x})^2 - 1", f"cos(2*{x})")
    add("textbook", f"cos({x})*cos({y}) - sin({x})*sin({y})", f"cos({x} + {y})")
    add("textbook", f"cos({x})*cos({y}) + sin({x})*sin({y})", f"cos({x} - {y})")
    add("textbook", f"sin({x})*cos({y}) + cos({x})*sin({y})", f"sin({x} + {y})")
    add("textbook", f"sin({x})*cos({y}) - cos({x})*sin({y})", f"sin({x} - {y})")
    add("textbook", f"(cos({x} - {y}) + cos({x} + {y}))/2", f"cos({x})*cos({y})")
    add("textbook", f"(cos({x} - {y}) - cos({x} + {y}))/2", f"sin({x})*sin({y})")
    add("textbook", f"(sin({x} + {y}) + sin({x} - {y}))/2", f"sin({x})*cos({y})")
    add("textbook", f"sin({x} - {y}) + sin({x} + {y})", f"2*sin({x})*cos({y})")
    add("textbook", f"cos({x} - {y}) + cos({x} + {y})", f"2*cos({x})*cos({y})")
    add("textbook", f"cos({x} - {y}) - cos({x} + {y})", f"2*sin({x})*sin({y})")
    add("textbook", f"sin({x} + {y})*sin({x} - {y})", f"sin({x})^2 - sin({y})^2")
    add("textbook", f"cos({x} + {y})*cos({x} - {y})", f"cos({x})^2 - sin({y})^2")
    add("textbook", f"1 - sin({x})^2", f"cos({x})^2")
    add("textbook", f"1 - cos({x})^2", f"sin({x})^2")
    add("textbook", f"cos({x})^4 - sin({x})^4", f"cos(2*{x})")
    add("textbook", f"sin({x})^4 + cos({x})^4 + 2*sin({x})^2*cos({x})^2", "1")
    add("textbook", f"(sin({x}) + cos({x}))^2", f"1 + sin(2*{x})")
    add("textbook", f"(cos({x}) - sin({x}))*(cos({x}) + sin({x}))", f"cos(2*{x})")
    add("textbook", f"sin(pi/2 - {x})", f"cos({x})")
    add("textbook", f"cos(pi - {x})", f"-cos({x})")
    add("textbook", f"sin({x} + pi)", f"-sin({x})")
    add("textbook", f"cos({x} + 3*pi/2)", f"sin({x})")

# Half and multiple angles.
for x in ["x", "t"]:
    add("half-angle", f"2*cos({x}/2)^2 - 1", f"cos({x})")
    add("half-angle", f"1 - 2*sin({x}/2)^2", f"cos({x})")
    add("half-angle", f"2*sin({x}/2)*cos({x}/2)", f"sin({x})")
    add("half-angle", f"(1 + cos({x}))/2", f"cos({x}/2)^2")
    add("half-angle", f"(1 - cos({x}))/2", f"sin({x}/2)^2")
    add("multiple-angle", f"3*sin({x}) - 4*sin({x})^3", f"sin(3*{x})")
    add("multiple-angle", f"4*cos({x})^3 - 3*cos({x})", f"cos(3*{x})")
    add("multiple-angle", f"8*cos({x})^4 - 8*cos({x})^2 + 1", f"cos(4*{x})")
    add("multiple-angle", f"sin({x})^2*cos({x})^2", f"sin(2*{x})^2/4")
    add("multiple-angle", f"4*sin({x})*cos({x})*cos(2*{x})", f"sin(4*{x})")
    add("multiple-angle", f"16*sin({x})^5 - 20*sin({x})^3 + 5*sin({x})", f"sin(5*{x})")
    add("multiple-angle", f"sin({x})^10", f"sin({x})^10")
    add("multiple-angle", f"(cos({x}) - 1)^2*(cos({x}) + 1)^3", f"(cos({x}) - 1)^2*(cos({x}) + 1)^3")
    add("multiple-angle", f"cos({x})^2*sin({x})^2 + cos({x})^4", f"cos({x})^2")


# Chebyshev: cos(n x) = T_n(cos x), sin((n+1) x) = sin(x) U_n(cos x).
def cheb_t(n):
    t = [[1], [0, 1]]
    for k in range(2, n + 1):
        a = [0] + [2 * c for c in t[k - 1]]
        b = t[k - 2] + [0] * (len(a) - len(t[k - 2]))
        t.append([p - q for p, q in zip(a, b)])
    return t[n]


def cheb_u(n):
    u = [[1], [0, 2]]
    for k in range(2, n + 1):
        a = [0] + [2 * c for c in u[k - 1]]
        b = u[k - 2] + [0] * (len(a) - len(u[k - 2]))
        u.append([p - q for p, q in zip(a, b)])
    return u[n]


def poly(cs, v):
    terms = []
    for i, c in reversed(list(enumerate(cs))):
        if c == 0:
            continue
        mono = "1" if i == 0 else (v if i == 1 else f"{v}^{i}")
        s = f"{abs(c)}*{mono}" if abs(c) != 1 and i > 0 else (mono if i > 0 else str(abs(c)))
        terms.append(("- " if c < 0 else "+ ") + s)
    text = " ".join(terms)
    return text[2:] if text.startswith("+ ") else "-" + text[2:]


for n in range(2, 13):
    add("chebyshev", poly(cheb_t(n), "cos(x)"), f"cos({n}*x)")
for n in range(1, 11):
    add("chebyshev", f"sin(x)*({poly(cheb_u(n), 'cos(x)')})", f"sin({n + 1}*x)")

# Regular polygons: sums of cosines and sines over the vertices.
for n in range(3, 21):
    add("polygon", " + ".join(f"cos({shift('x', 2 * k, n)})" for k in range(n)))
for n in range(3, 13):
    add("polygon", " + ".join(f"sin({shift('x', 2 * k, n)})" for k in range(n)))
for n in range(3, 25):
    add("polygon", " + ".join(f"cos({pi(2 * k, n)})" for k in range(1, n)), "-1")
for n in range(3, 13):
    add("polygon", " + ".join(f"cos({shift('x', k, n)})^2" for k in range(n)), str(Fraction(n, 2)).replace("/", "/"))
for n in range(3, 12):
    add("polygon", " + ".join(f"sin({pi(k, n)})^2" for k in range(1, n)), str(Fraction(n, 2)))

# Morrie's law and products of cosines at constant angles.
for n in range(1, 9):
    prod = "*".join(f"cos({2 ** k}*x)" if k else "cos(x)" for k in range(n))
    add("morrie", f"{2 ** n}*sin(x)*{prod}", f"sin({2 ** n}*x)")
add("morrie", "cos(pi/9)*cos(2*pi/9)*cos(4*pi/9)", "1/8")
add("morrie", "cos(pi/7)*cos(2*pi/7)*cos(4*pi/7)", "-1/8")
add("morrie", "cos(pi/5)*cos(2*pi/5)", "1/4")
add("morrie", "sin(pi/9)*sin(2*pi/9)*sin(4*pi/9)", "sqrt(3)/8")
for n in range(1, 11):
    add("morrie", "*".join(f"cos({pi(k, 2 * n + 1)})" for k in range(1, n + 1)), f"1/{2 ** n}")
for n in range(2, 13):
    add("morrie", "*".join(f"sin({pi(k, n)})" for k in range(1, n)), str(Fraction(n, 2 ** (n - 1))))
# 2^n + 1 up to 33: within the degree bound of exact constants.
for n in range(2, 6):
    add("morrie", "*".join(f"cos({pi(2 ** k, 2 ** n + 1)})" for k in range(n)), f"1/{2 ** n}")

# Exact constants.
add("constants", "cos(pi/5)", "(1 + sqrt(5))/4")
add("constants", "cos(2*pi/5)", "(sqrt(5) - 1)/4")
add("constants", "sin(pi/10)", "(sqrt(5) - 1)/4")
add("constants", "cos(pi/5) - cos(2*pi/5)", "1/2")
add("constants", "cos(pi/8)^2", "(2 + sqrt(2))/4")
add("constants", "sin(pi/8)^2", "(2 - sqrt(2))/4")
add("constants", "cos(3*pi/8) - sin(pi/8)")
add("constants", "cos(3*pi/7) + cos(4*pi/7)")
add("constants", "sin(8*pi/7) + sin(pi/7)")
add("constants", "cos(pi/7) - cos(2*pi/7) + cos(3*pi/7)", "1/2")
add("constants", "cos(pi/9) - cos(2*pi/9) - cos(4*pi/9)", "0")
add("constants", "cos(2*pi/9) + cos(4*pi/9) + cos(8*pi/9)")
add("constants", "4*cos(pi/5)^2 - 2*cos(pi/5) - 1")
add("constants", "16*sin(pi/16)^2*cos(pi/16)^2", "2 - sqrt(2)")
add("constants", "cos(pi/12)", "(sqrt(2) + sqrt(6))/4")
add("constants", "sin(pi/12)", "(sqrt(6) - sqrt(2))/4")
for n in [5, 7, 8, 9, 10, 11, 12, 13, 16, 18, 20, 24]:
    for k in range(1, n):
        if Fraction(k, n).denominator != n or 2 * k > n:
            continue
        add("constants", f"sin({pi(k, n)}) - cos({pi(n - 2 * k, 2 * n)})")
        if len(out) > 10_000:
            break
for n in [5, 7, 9, 16, 24]:
    for k in range(1, n):
        if Fraction(k, n).denominator == n:
            add("constants", f"cos({pi(k, n)})^2 + sin({pi(k, n)})^2", "1")

# Symbolic angles offset by rational multiples of pi.
for n in [5, 7, 8, 9, 10, 16, 24]:
    add("offsets", f"cos({shift('x', n + 1, n)}) + cos({shift('x', 1, n)})")
    add("offsets", f"sin({shift('x', 1, n)}) - cos({shift('x', 2 - n, 2 * n)})")
    add("offsets", f"cos({shift('x', 1, n)})*cos({shift('x', -1, n)}) + sin({shift('x', 1, n)})*sin({shift('x', -1, n)})", f"cos({pi(2, n)})")
add("offsets", "sin(x)/2 + sqrt(3)*cos(x)/2", "cos(x - pi/6)")
add("offsets", "sqrt(2)*(cos(t) - sin(t))/2", "cos(t + pi/4)")
add("offsets", "cos(x) + sin(x)", "sqrt(2)*cos(x - pi/4)")
add("offsets", "sqrt(3)*cos(x) - sin(x)", "2*cos(x + pi/6)")
add("offsets", "cos(t + pi/4)", "cos(t + pi/4)")
add("offsets", "cos(x + pi/3) + cos(x - pi/3)", "cos(x)")

# Robotics groupings.
for a, b, c in [("q1", "q2", "q3"), ("theta1", "theta2", "theta3")]:
    add("robotics", f"cos({a})*cos({b}) - sin({a})*sin({b})", f"cos({a} + {b})")
    add("robotics", f"(l1*cos({a}) + l2*cos({a} + {b}))^2 + (l1*sin({a}) + l2*sin({a} + {b}))^2", f"l1^2 + l2^2 + 2*l1*l2*cos({b})")
    add("robotics", f"cos({a})*(l1*cos({a}) + l2*cos({a} + {b})) + sin({a})*(l1*sin({a}) + l2*sin({a} + {b}))", f"l1 + l2*cos({b})")
    add("robotics", f"cos({a} + {b})*cos({c}) - sin({a} + {b})*sin({c})", f"cos({a} + {b} + {c})")
    add("robotics", f"sin({a} + {b})*cos({c}) + cos({a} + {b})*sin({c})", f"sin({a} + {b} + {c})")
    add("robotics", f"cos({a})*cos({b})*cos({c}) - cos({a})*sin({b})*sin({c})", f"cos({a})*cos({b} + {c})")
    add("robotics", f"sin({a})*cos({b})*cos({c}) - sin({a})*sin({b})*sin({c}) + cos({a})*sin({b} + {c})", f"sin({a} + {b} + {c})")
    add("robotics", f"(cos({a})*cos({b}) - sin({a})*sin({b}))^2 + (sin({a})*cos({b}) + cos({a})*sin({b}))^2", "1")
    add("robotics", f"l1*cos({a}) + l2*cos({a})*cos({b}) - l2*sin({a})*sin({b})", f"l1*cos({a}) + l2*cos({a} + {b})")
    add("robotics", f"d*sin({a})*cos({b}) + d*cos({a})*sin({b})", f"d*sin({a} + {b})")
    add("robotics", f"cos({a}/2)^2 - sin({a}/2)^2", f"cos({a})")
    add("robotics", f"cos({a}/2)*cos({b}/2) - sin({a}/2)*sin({b}/2)", f"cos(({a} + {b})/2)")
    add("robotics", f"2*cos({a}/2)*sin({a}/2)*l1", f"l1*sin({a})")
    add("robotics", f"cos({a})*cos({b} + {c}) - sin({a})*sin({b} + {c})", f"cos({a} + {b} + {c})")
    add("robotics", f"a2*cos({a})*cos({b}) - a2*sin({a})*sin({b}) + a3*cos({a} + {b} + {c})", f"a2*cos({a} + {b}) + a3*cos({a} + {b} + {c})")
# Kinova-style offsets.
add("robotics", "cos(q + 5*pi/9) + cos(q - 4*pi/9)")
add("robotics", "sin(q + 5*pi/9) + sin(q - 4*pi/9)")
add("robotics", "cos(pi/3)*cos(q) - sin(pi/3)*sin(q)", "cos(q + pi/3)")
add("robotics", "cos(q + 5*pi/9)*cos(pi/3) - sin(q + 5*pi/9)*sin(pi/3)", "cos(q + 8*pi/9)")
# Factorizations and sums of polynomials in one cosine or sine each.
for x in ["x", "t", "q1"]:
    add("textbook", f"(cos({x}) - 1)^2*(cos({x}) + 1)^3", f"sin({x})^4*(cos({x}) + 1)")
    add("textbook", f"(1 - cos({x})^2)*(1 + cos({x}))", f"sin({x})^2*(cos({x}) + 1)")
    add("textbook", f"(sin({x}) - 1)^2*(sin({x}) + 1)^2", f"cos({x})^4")
    add("textbook", f"(cos({x})^2 - 1)*(sin({x}) + 1)", f"-sin({x})^2*(sin({x}) + 1)")
for a, b in [("a", "b"), ("x", "y"), ("q1", "q2")]:
    add("textbook", f"2 - cos({a})^2 - cos({b})^2", f"sin({a})^2 + sin({b})^2")
    add("textbook", f"cos({a})^4 + 1 - cos({b})^2", f"cos({a})^4 + sin({b})^2")
    add("textbook", f"1 - cos(2*{a})/2 - cos(2*{b})/2", f"sin({a})^2 + sin({b})^2")
    add("textbook", f"cos({a} + {b})*cos({a} - {b}) + sin({b})^2", f"cos({a})^2")

# Factorizations over the integers in several angles (sines and cosines of distinct angles
# as independent variables modulo sin^2 + cos^2 = 1), sum to product in several angles, and
# robotics groupings with lengths; the left sides written expanded.
for a, b, c in [("a", "b", "c"), ("x", "y", "z"), ("q1", "q2", "q3")]:
    add("factorization", f"1 + cos({a}) - cos({b}) - (cos({a} - {b}) + cos({a} + {b}))/2", f"(1 + cos({a}))*(1 - cos({b}))")
    add("factorization", f"2 + cos({c}) + 2*cos({a}) + cos({a})*cos({c}) - 2*cos({b}) - cos({b})*cos({c}) - 2*cos({a})*cos({b}) - cos({a})*cos({b})*cos({c})", f"(1 + cos({a}))*(1 - cos({b}))*(2 + cos({c}))")
    add("factorization", f"sin({a})^2*cos({b})^2 - cos({a})^2*sin({b})^2", f"sin({a} + {b})*sin({a} - {b})")
    add("factorization", f"cos({a})^2*cos({b})^2 - sin({a})^2*sin({b})^2", f"cos({a} + {b})*cos({a} - {b})")
    add("factorization", f"cos({a})^3 - cos({a})*cos({b})^2", f"cos({a})*(cos({a}) - cos({b}))*(cos({a}) + cos({b}))")
    add("factorization", f"cos({a})*cos({b}) + cos({a})*sin({c}) + sin({b})*cos({b}) + sin({b})*sin({c})", f"(cos({a}) + sin({b}))*(cos({b}) + sin({c}))")
    add("factorization", f"cos({a})^2 + 2*cos({a})*cos({b}) + cos({b})^2 - sin({c})*(cos({a})^2 + 2*cos({a})*cos({b}) + cos({b})^2)", f"(cos({a}) + cos({b}))^2*(1 - sin({c}))")
    add("factorization", f"1 - cos({a})^2 - cos({b})^2 + cos({a})^2*cos({b})^2", f"sin({a})^2*sin({b})^2")
    add("factorization", f"(cos({a}) - cos({b}))*(cos({a}) + cos({b}))*(sin({c}) + cos({a}))", f"(cos({a}) - cos({b}))*(cos({a}) + cos({b}))*(sin({c}) + cos({a}))")
    add("factorization", f"(cos(2*{a}) - cos(2*{b}))*(1 + cos({c}))", f"2*(cos({a}) - cos({b}))*(cos({a}) + cos({b}))*(1 + cos({c}))")
    add("sum-to-product", f"cos({a} + {b}) + cos({a} - {b}) + cos({c} + {b}) + cos({c} - {b})", f"2*cos({b})*(cos({a}) + cos({c}))")
    add("sum-to-product", f"sin({a} + {b} + {c}) + sin({a} + {b} - {c})", f"2*sin({a} + {b})*cos({c})")
    add("sum-to-product", f"cos({a} + {b} + {c}) - cos({a} - {b} + {c})", f"-2*sin({a} + {c})*sin({b})")
    add("robotics", f"l1^2 - l2^2*cos({b})^2", f"(l1 - l2*cos({b}))*(l1 + l2*cos({b}))")
    add("robotics", f"a2^2*cos({a})^2 - a3^2*cos({a} + {b})^2", f"(a2*cos({a}) - a3*cos({a} + {b}))*(a2*cos({a}) + a3*cos({a} + {b}))")

# Session 7: squares of angle sums read as variables of their own, constant products with
# radical cofactors or beside a constant, and angles with a rational constant.
for (p, q, a, b) in [("a2", "a3", "q1", "q2"), ("l1", "l2", "theta1", "theta2"), ("d", "r", "u", "v")]:
    add("robotics", f"({p}*cos({a}) - {q}*cos({a} + {b}))*({p}*cos({a}) + {q}*cos({a} + {b}))", f"{p}^2*cos({a})^2 - {q}^2*cos({a} + {b})^2")
    add("robotics", f"{p}^2*sin({a})^2 - {q}^2*sin({a} + {b})^2", f"({p}*sin({a}) - {q}*sin({a} + {b}))*({p}*sin({a}) + {q}*sin({a} + {b}))")
    add("factorization", f"cos({a} + {b})^2 - {p}*cos({a} - {b})^2", f"(cos({a} + {b}))^2 - {p}*(cos({a} - {b}))^2")
for (k1, n1, k2, n2) in [(1, 7, 1, 9), (1, 5, 2, 7), (1, 8, 1, 9), (1, 11, 1, 12), (3, 16, 1, 7)]:
    add("constants", f"1 - cos({k1}*pi/{n1})*cos({k2}*pi/{n2})", f"1 - cos({k1}*pi/{n1})*cos({k2}*pi/{n2})")
for (r, k, n) in [(2, 1, 7), (3, 1, 9), (5, 2, 7), (2, 1, 11)]:
    add("constants", f"sqrt({r})*sin({k}*pi/{n})^2 - 1/2", f"sqrt({r})*(1 - cos(2*{k}*pi/{n}))/2 - 1/2")
for (k, n) in [(1, 11), (1, 7), (2, 9)]:
    add("constants", f"sin({k}*pi/{n})^2*cos(pi/5)", f"(1 + sqrt(5))/4*sin({k}*pi/{n})^2")
for (c, t) in [("1/3", "t"), ("2", "x"), ("1/2", "q1")]:
    add("offsets", f"sin({c} - {t}/2)", f"-sin({t}/2 - {c})")
    add("offsets", f"cos({c} - {t})*cos({c} + {t}) + sin({c} - {t})*sin({c} + {t})", f"cos(2*{t})")

# Session 8: products of one angle's cosines and sines with different offsets, found from the
# roots of the sum as a polynomial in e^{i x} (crates/dqsym-engine/src/closed/roots.rs).
add("offsets", "cos(x + 5*pi/8)^2", "sin(x + pi/8)^2")
add("offsets", "l*(sin(2*x + 3*pi/7) + sin(3*pi/7))/2", "l*cos(x)*sin(x + 3*pi/7)")
add("offsets", "(cos(2*x - 5*pi/63) + cos(23*pi/63))/2", "cos(x + pi/7)*cos(x - 2*pi/9)")
add("offsets", "sin(x + pi/5)^2*cos(x - pi/3)", "sin(x + pi/5)^2*cos(x - pi/3)")
add("offsets", "cos(x) - cos(pi/7) + sin(2*x)/2 - (sin(x + pi/7) + sin(x - pi/7))/2", "(cos(x) - cos(pi/7))*(sin(x) + 1)")
add("offsets", "(cos(3*x + 13*pi/40) + cos(x - 3*pi/40))/2", "cos(2*x + pi/8)*cos(x + pi/5)")
add("offsets", "3*sin(q1 + q2 + pi/7)*cos(q1 + q2 - pi/9)", "3*sin(q1 + q2 + pi/7)*cos(q1 + q2 - pi/9)")

with open("tests/data/trig_identities.txt", "w") as f:
    f.write("# category | lhs = rhs   (generated by scripts/trig_corpus.py)\n")
    f.write("\n".join(out) + "\n")
print(len(out))
