"""The dual quaternion class of the package. Its arithmetic is the engine's: products,
conjugates and matrices are computed exactly by dqsym, not re-implemented here."""

import sympy
from sympy.core.sympify import _sympify


class DQ:
    """A dual quaternion ``q = r + eps q_e`` with eight SymPy components
    ``(w, x, y, z, w_e, x_e, y_e, z_e)``: ``r = (w, x, y, z)`` and ``q_e = (w_e, x_e, y_e, z_e)``.

    ``DQ(w, x, y, z, w_e, x_e, y_e, z_e)`` or ``DQ(components)``. ``real`` and ``dual`` are
    SymPy Quaternions. ``*``, ``+``, ``-``, ``conj()``, ``cconj()``, ``dconj()``,
    ``inverse()``, ``matrix()`` and ``transform(point)`` are evaluated by dqsym (exactly, with
    the results in closed form); ``subs`` and ``evalf`` act on each component. In Jupyter a DQ
    shows in the project's LaTeX.
    """

    __slots__ = ("components",)

    def __init__(self, *components):
        if len(components) == 1:
            components = tuple(components[0])
        if len(components) != 8:
            raise ValueError(f"a DQ has 8 components, got {len(components)}")
        self.components = tuple(_sympify(c) for c in components)

    @property
    def real(self):
        """The real part ``(w, x, y, z)`` as a SymPy Quaternion."""
        return sympy.Quaternion(*self.components[:4])

    @property
    def dual(self):
        """The dual part ``(w_e, x_e, y_e, z_e)`` as a SymPy Quaternion."""
        return sympy.Quaternion(*self.components[4:])

    def __iter__(self):
        return iter(self.components)

    def __len__(self):
        return 8

    def __getitem__(self, k):
        return self.components[k]

    def __eq__(self, other):
        return isinstance(other, DQ) and self.components == other.components

    def __hash__(self):
        return hash(("DQ",) + self.components)

    def _engine(self, src, **values):
        from . import _dqsym

        return _dqsym.evaluate(src, **values)

    def __mul__(self, other):
        return self._engine("a*b", a=self, b=other)

    def __rmul__(self, other):
        return self._engine("b*a", a=self, b=other)

    def __add__(self, other):
        return self._engine("a + b", a=self, b=other)

    def __radd__(self, other):
        return self._engine("b + a", a=self, b=other)

    def __sub__(self, other):
        return self._engine("a - b", a=self, b=other)

    def __rsub__(self, other):
        return self._engine("b - a", a=self, b=other)

    def __neg__(self):
        return self._engine("-a", a=self)

    def conj(self):
        """The quaternion conjugate ``r* + eps q_e*``."""
        return self._engine("conj(a)", a=self)

    def dconj(self):
        """The dual conjugate ``r - eps q_e`` (the paper's eq 8)."""
        return self._engine("dconj(a)", a=self)

    def cconj(self):
        """The combined conjugate ``r* - eps q_e*`` (the paper's eq 9)."""
        return self._engine("cconj(a)", a=self)

    def inverse(self):
        """The inverse (an error when there is none)."""
        return self._engine("inverse(a)", a=self)

    def matrix(self):
        """The 4x4 homogeneous matrix of a unit DQ (a SymPy Matrix)."""
        return self._engine("matrix(a)", a=self)

    def transform(self, point):
        """The image of a point (three values) under this unit DQ, a 3x1 Matrix."""
        return self._engine("transform(a, p)", a=self, p=tuple(point))

    def subs(self, *args, **kwargs):
        """``subs`` on every component."""
        return DQ(c.subs(*args, **kwargs) for c in self.components)

    def evalf(self, *args, **kwargs):
        """The components as floats (a tuple of SymPy Floats)."""
        return tuple(c.evalf(*args, **kwargs) for c in self.components)

    def applyfunc(self, f):
        """``f`` applied to every component."""
        return DQ(f(c) for c in self.components)

    def __repr__(self):
        return "DQ(" + ", ".join(str(c) for c in self.components) + ")"

    def _repr_latex_(self):
        from . import _dqsym

        try:
            return "$\\displaystyle " + _dqsym.latex(self) + "$"
        except (TypeError, ValueError, _dqsym.DqsymError):
            # Components dqsym cannot hold exactly (floats after evalf, say): SymPy's LaTeX.
            return "$\\displaystyle " + sympy.latex(sympy.Matrix([list(self.components)])) + "$"
