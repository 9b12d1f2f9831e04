#!/usr/bin/env bash
# Runs every test. Sets up, when missing, what the emitter tests hand their output to: a Python
# venv in .venv with sympy and numpy (exported as DQSYM_PYTHON) and KaTeX in node_modules/.
# Idempotent: a second run only checks that both are there.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! .venv/bin/python -c "import sympy, numpy" 2>/dev/null; then
    python3 -m venv .venv
    .venv/bin/python -m pip install --quiet --disable-pip-version-check sympy numpy
fi
export DQSYM_PYTHON="$PWD/.venv/bin/python"

if [ ! -f node_modules/katex/package.json ]; then
    npm install --no-save --no-audit --no-fund --silent katex
fi

cargo test --locked --all-targets "$@"
