#!/usr/bin/env bash
# The test command of README.md: installs what is missing, builds, runs ctest,
# then the suite again under ASan and UBSan (TMR_SANITIZE=0 skips it), then
# fuzzes the database and tree.json readers for TMR_FUZZ_SECONDS each
# (default 60; 0 skips it; docs/testing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
echo "[test] running ctest"
ctest --test-dir build --output-on-failure --parallel 2 "$@"
if [[ "${TMR_SANITIZE:-1}" != 0 ]]; then
  bash tools/run_sanitized_tests.sh
fi
if [[ "${TMR_FUZZ_SECONDS:-60}" != 0 ]]; then
  bash tools/run_fuzzers.sh "${TMR_FUZZ_SECONDS:-60}"
fi
