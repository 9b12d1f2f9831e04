#!/usr/bin/env bash
# Runs every test. Needs only the Rust toolchain today; later tests that need KaTeX, Chromium or
# a Python venv will be installed here, when missing, before cargo runs.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --locked --all-targets "$@"
