"""bench/compare's process-level SymEngine run: start Python, import SymEngine, expand the
products of W2 (the PUMA 560 4x4 pose and DQ) or W4 (the PUMA 560 DQ and its 8x6 Jacobian) and
print every entry, as a user's script would. bench/compare times the whole process, to set
against `dqsym fk` as a whole process."""

import sys

import symengine

import common
from common import Lib

L = Lib(symengine)
w = sys.argv[1]
links = common.puma(L)
if w == "W2":
    m = common.matrix_chain(L, links)
    out = [m[i][j] for i in range(3) for j in range(4)] + common.dq_chain(L, links)
elif w == "W4":
    q = common.dq_chain(L, links)
    out = [L.expand(c.diff(l[0])) for c in q for l in links]
else:
    sys.exit("usage: symengine_process.py W2|W4")
for e in out:
    print(e)
