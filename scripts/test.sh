#!/usr/bin/env bash
# Runs every test. Sets up, when missing, what the emitter tests hand their output to: a Python
# venv in .venv with sympy and numpy (exported as DQSYM_PYTHON), KaTeX and playwright-core (which
# drives Chromium for the interactive walkthrough page) in node_modules/, and
# Debian's chromium for the walkthrough page.
# Idempotent: a second run only checks that both are there.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! .venv/bin/python -c "import sympy, numpy" 2>/dev/null; then
    python3 -m venv .venv
    .venv/bin/python -m pip install --quiet --disable-pip-version-check sympy numpy
fi
# DQ Robotics itself, the reference the DQ Robotics vocabulary is compared with (tests/it/dqr.rs).
if ! .venv/bin/python -c "import dqrobotics" 2>/dev/null; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check dqrobotics==26.4.0a7
fi
export DQSYM_PYTHON="$PWD/.venv/bin/python"

if [ ! -f node_modules/katex/package.json ] || [ ! -f node_modules/playwright-core/package.json ]; then
    npm install --no-save --no-audit --no-fund --silent katex playwright-core
fi

# The walkthrough page is checked in headless Chromium (Debian's package; the machine is root).
if ! command -v chromium >/dev/null 2>&1; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y -qq chromium || { apt-get update -qq && apt-get install -y -qq chromium; }
fi

# insta records every snapshot a test reads; with no filter given, a snapshot file that no test
# read is stale and fails the run (as `cargo insta test --unreferenced=reject` would).
refs="$(mktemp)"
trap 'rm -f "$refs"' EXIT
INSTA_SNAPSHOT_REFERENCES_FILE="$refs" INSTA_UPDATE=no cargo test --locked --all-targets "$@"
if [ "$#" -eq 0 ]; then
    pending="$(find snapshots -name '*.snap.new' -o -name '*.pending-snap')"
    if [ -n "$pending" ]; then
        echo "error: pending snapshots (review them, then accept or delete):" >&2
        echo "$pending" >&2
        exit 1
    fi
    unreferenced="$(comm -23 <(find "$PWD/snapshots" -name '*.snap' | sort) <(sort -u "$refs"))"
    if [ -n "$unreferenced" ]; then
        echo "error: snapshots no test reads (delete them or restore their test):" >&2
        echo "$unreferenced" >&2
        exit 1
    fi
fi
