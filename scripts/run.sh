#!/usr/bin/env bash
# The main job: the paper's worked examples, derived and printed in closed form.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo run --locked --release --quiet -- paper "$@"
