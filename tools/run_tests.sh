#!/usr/bin/env bash
# The test command of README.md: installs what is missing, builds, runs ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
echo "[test] running ctest"
ctest --test-dir build --output-on-failure --parallel 2 "$@"
