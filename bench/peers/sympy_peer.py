"""bench/compare's SymPy peer: expand, then trigsimp, then fu (each stage timed from the start)."""

import sys

import sympy

from common import Lib, run

run(Lib(sympy), sys.argv[1], [("trigsimp", sympy.trigsimp), ("fu", sympy.fu)])
