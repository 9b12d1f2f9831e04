#!/usr/bin/env bash
# Runs every test. Sets up, when missing, what the emitter tests hand their output to: a Python
# venv in .venv with sympy and numpy (exported as DQSYM_PYTHON), KaTeX and playwright-core (which
# drives Chromium for the interactive walkthrough page) in node_modules/, and Debian's chromium;
# and for the Python package (python/): maturin, pytest, nbclient and ipykernel in the same venv.
# After the Rust tests it builds the package's wheel (`pip wheel ./python`), installs it, and
# runs its pytest suite, which runs the notebooks in examples/notebooks/ and installs the same
# wheel in a fresh venv.
# Idempotent: a second run only checks that everything is there.
# Every step says what it does (scripts/talk.sh), and a quiet compile prints a heartbeat.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/talk.sh

say "checking the Python venv (.venv: sympy, numpy, maturin, pytest, nbclient, ipykernel, dqrobotics)"

if ! .venv/bin/python -c "import sympy, numpy" 2>/dev/null; then
    say "  creating .venv and installing sympy, numpy (pip)"
    python3 -m venv .venv
    .venv/bin/python -m pip install --quiet --disable-pip-version-check sympy numpy
fi
if ! .venv/bin/python -c "import maturin, pytest, nbclient, nbformat, ipykernel" 2>/dev/null; then
    say "  installing maturin, pytest, nbclient, nbformat, ipykernel (pip)"
    .venv/bin/python -m pip install --quiet --disable-pip-version-check \
        maturin pytest nbclient nbformat ipykernel
fi
# DQ Robotics itself, the reference the DQ Robotics vocabulary is compared with (tests/it/dqr.rs).
if ! .venv/bin/python -c "import dqrobotics" 2>/dev/null; then
    say "  installing dqrobotics (pip)"
    .venv/bin/python -m pip install --quiet --disable-pip-version-check dqrobotics==26.4.0a7
fi
export DQSYM_PYTHON="$PWD/.venv/bin/python"

say "checking node_modules (katex, playwright-core) and chromium"
if [ ! -f node_modules/katex/package.json ] || [ ! -f node_modules/playwright-core/package.json ]; then
    say "  installing katex and playwright-core (npm)"
    npm install --no-save --no-audit --no-fund --silent katex playwright-core
fi

# The walkthrough page is checked in headless Chromium (Debian's package; the machine is root).
if ! command -v chromium >/dev/null 2>&1; then
    say "  installing chromium (apt-get)"
    export DEBIAN_FRONTEND=noninteractive
    apt-get install -y -qq chromium || { apt-get update -qq && apt-get install -y -qq chromium; }
fi

# insta records every snapshot a test reads; with no filter given, a snapshot file that no test
# read is stale and fails the run (as `cargo insta test --unreferenced=reject` would).
refs="$(mktemp)"
trap 'rm -f "$refs"' EXIT
say "compiling and running the Rust tests: cargo test --all-targets (the first build takes minutes)"
INSTA_SNAPSHOT_REFERENCES_FILE="$refs" INSTA_UPDATE=no talking cargo test --locked --all-targets "$@"
# The examples in the crates' documentation, which --all-targets does not build.
if [ "$#" -eq 0 ]; then
    say "running the documentation examples: cargo test --doc"
    talking cargo test --locked --doc
fi
if [ "$#" -eq 0 ]; then
    say "checking for pending and unreferenced snapshots"
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

# The Python package: `pip wheel ./python` builds its wheel once, with the venv's maturin
# (hence --no-build-isolation) in its own target directory, python/target, with its release
# profile at opt-level 2 (python/Cargo.toml); cargo's progress is shown. The wheel goes into
# .venv, and python/tests/test_install.py installs the same wheel into a fresh venv
# ($DQSYM_WHEEL), so the package is compiled once. Then its tests, with the binary
# `cargo test` built as the oracle of "what the command line prints".
say "building the Python package: pip wheel ./python (release, python/target; minutes the first time)"
start=$SECONDS
log="$(mktemp)"
wheels="python/target/wheels"
trap 'rm -f "$refs" "$log"' EXIT
rm -f "$wheels"/dqsym-*.whl
build_wheel() {
    set +o pipefail
    PATH="$PWD/.venv/bin:$PATH" .venv/bin/python -m pip wheel --disable-pip-version-check \
        --no-build-isolation --no-deps -v -w "$wheels" ./python 2>&1 | tee "$log" |
        { grep --line-buffered -E '^ *(Compiling|Finished|Created wheel|Saved)' >&2 || true; }
    local s=${PIPESTATUS[0]}
    set -o pipefail
    return "$s"
}
status=0
talking build_wheel || status=$?
wheel="$(ls "$wheels"/dqsym-*.whl 2>/dev/null | head -1)"
if [ "$status" -ne 0 ] || [ -z "$wheel" ]; then
    cat "$log" >&2
    echo "error: building the Python package failed" >&2
    exit 1
fi
say "installing the wheel into .venv"
.venv/bin/python -m pip install --disable-pip-version-check --quiet --force-reinstall --no-deps \
    "$wheel"
say "the Python package was built and installed in $((SECONDS - start)) s"
say "running the Python package's tests: pytest python/tests"
DQSYM_BIN="$PWD/target/debug/dqsym" DQSYM_WHEEL="$PWD/$wheel" \
    .venv/bin/python -m pytest python/tests -q
