#!/usr/bin/env bash
# The project's test command (README.md; .ci/run calls it). Builds with two
# jobs, as on the CI machine, and runs every test in the workspace.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_BUILD_JOBS="${CARGO_BUILD_JOBS:-2}"
start=$(date +%s)
cargo test --workspace --all-targets -j"$CARGO_BUILD_JOBS"
echo "scripts/test.sh: tests took $(( $(date +%s) - start )) s"
