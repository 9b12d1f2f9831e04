"""bench/compare's SymEngine peer: expansion only (SymEngine has no trigonometric simplifier)."""

import sys

import symengine

from common import Lib, run

run(Lib(symengine), sys.argv[1], [])
