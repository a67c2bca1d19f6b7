#!/usr/bin/env bash
# Builds the whole test suite with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-asan/ (CMake preset "asan": tmr's code
# instrumented, COLMAP's libraries not) and runs its `quick` tests and the
# bad-input matrix (TMR_SANITIZE_ALL=1: every test). Any report fails the
# run.
# Usage: tools/run_sanitized_tests.sh [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
echo "[asan] building the test suite in build-asan/"
cmake --preset asan >build-asan.configure.log 2>&1 ||
  { cat build-asan.configure.log >&2; echo "[asan] error: configure failed" >&2; exit 1; }
rm -f build-asan.configure.log
cmake --build build-asan --parallel "${TMR_JOBS:-2}"
echo "[asan] configure and build took $SECONDS s"
# Leaks are reported at exit. Container-overflow and alloc-dealloc-mismatch
# checks need every library instrumented: COLMAP's are not, and its Eigen
# code frees with free() what instrumented inline code allocated with
# operator new (found in AlignReconstructionsViaReprojections).
export ASAN_OPTIONS=detect_leaks=1:detect_container_overflow=0:alloc_dealloc_mismatch=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The `quick` tests (docs/testing.md) and the bad-input matrix, whose broken
# inputs are what the sanitizers are for. The other `long` tests run COLMAP's
# code (not instrumented) on real photos, under Slurm, or build tmr again
# (find_package_consumer, libtmr_without_colmap: packaging, not memory);
# their tmr code is what the quick end-to-end runs cover.
if [[ "${TMR_SANITIZE_ALL:-0}" == 1 ]]; then
  echo "[asan] running ctest (all tests)"
  ctest --test-dir build-asan --output-on-failure --parallel 2 \
    -E "^(find_package_consumer|libtmr_without_colmap)$" "$@"
else
  # Three block-adjustment cases and the join's adjustment of two pieces
  # spend their time in Ceres' solver on a city (not instrumented: 775 of
  # the 2,425 s the quick tests took under ASan before the join's case);
  # the code they run is also run by their suites' other cases and by
  # synthetic_task_results, whose join adjusts its groups.
  echo "[asan] running ctest -L quick, then the bad-input matrix"
  ctest --test-dir build-asan --output-on-failure --parallel 2 -L quick \
    -E "^(BlockAdjustmentTest[.](BlocksSideBySideDoAsTheWholeAdjustment|RoundsMergeTracksThatFitOnlyAfterAnAdjustment|BlocksRecoverASeamAsTheWholeAdjustmentDoes)|JoinAdjustmentTest[.]PiecesPlacedOffComeBackTogether)$" \
    "$@"
  ctest --test-dir build-asan --output-on-failure -R "^bad_input_matrix$" "$@"
fi
