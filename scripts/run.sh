#!/usr/bin/env bash
# The main job: the paper's worked examples, derived and printed in closed form.
# The first run builds the release binary (minutes); every step says what it does, and cargo's
# lines (with a heartbeat while one crate compiles quietly) are shown whether or not the
# output is a terminal.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/talk.sh
say "building the release binary: cargo build --release (the first time takes minutes)"
talking cargo build --locked --release
say "running: target/release/dqsym paper $*"
exec target/release/dqsym paper "$@"
