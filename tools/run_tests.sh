#!/usr/bin/env bash
# The test command of README.md: installs what is missing, builds, runs ctest,
# then the suite again under ASan and UBSan (TMR_SANITIZE=0 skips it), then
# fuzzes the database and tree.json readers for TMR_FUZZ_SECONDS each
# (default 60; 0 skips it; docs/testing.md). Each phase prints its time.
set -euo pipefail
cd "$(dirname "$0")/.."
phase() {  # NAME COMMAND...: runs COMMAND, then prints how long it took
  local name=$1 start=$SECONDS; shift
  "$@"
  echo "[test] $name took $((SECONDS - start)) s"
}
phase "install and build" bash tools/build.sh
echo "[test] running ctest"
phase ctest ctest --test-dir build --output-on-failure --parallel 2 "$@"
if [[ "${TMR_SANITIZE:-1}" != 0 ]]; then
  phase "sanitized build and ctest" bash tools/run_sanitized_tests.sh
fi
if [[ "${TMR_FUZZ_SECONDS:-60}" != 0 ]]; then
  phase "fuzzing" bash tools/run_fuzzers.sh "${TMR_FUZZ_SECONDS:-60}"
fi
echo "[test] all phases took $SECONDS s"
