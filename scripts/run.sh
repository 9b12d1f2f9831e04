#!/usr/bin/env bash
# The main job: the paper's worked examples, derived and printed in closed form.
# The first run builds the release binary (several minutes); cargo shows its progress.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --locked --release
exec target/release/dqsym paper "$@"
