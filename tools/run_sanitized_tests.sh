#!/usr/bin/env bash
# Builds the whole test suite with AddressSanitizer and
# UndefinedBehaviorSanitizer in build-asan/ (CMake preset "asan": tmr's code
# instrumented, COLMAP's libraries not) and runs it. Any report fails the
# run. The two long stock-vs-tmr comparisons and the real-photo tests are
# left out unless TMR_SANITIZE_ALL=1: they exercise COLMAP's code more than
# tmr's and take three times as long under the sanitizers.
# Usage: tools/run_sanitized_tests.sh [extra ctest arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
echo "[asan] building the test suite in build-asan/"
cmake --preset asan >build-asan.configure.log 2>&1 ||
  { cat build-asan.configure.log >&2; echo "[asan] error: configure failed" >&2; exit 1; }
rm -f build-asan.configure.log
cmake --build build-asan --parallel "${TMR_JOBS:-2}"
# Leaks are reported at exit. Container-overflow and alloc-dealloc-mismatch
# checks need every library instrumented: COLMAP's are not, and its Eigen
# code frees with free() what instrumented inline code allocated with
# operator new (found in AlignReconstructionsViaReprojections).
export ASAN_OPTIONS=detect_leaks=1:detect_container_overflow=0:alloc_dealloc_mismatch=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# find_package_consumer builds a separate, uninstrumented project against
# the instrumented libraries; it tests packaging, not memory.
exclude=(-E "^find_package_consumer$")
# The Slurm test runs the staged code that tmr_mapper_stages covers here;
# the halo test (TmrMapperStages.*) runs COLMAP's mapper on tasks whose
# tmr code the end-to-end plazas test also runs.
[[ "${TMR_SANITIZE_ALL:-0}" == 1 ]] ||
  exclude=(-LE "real|slurm" -E "^(mapper_comparison_on_city_block|find_package_consumer|TmrMapperStages\..*)$")
echo "[asan] running ctest"
ctest --test-dir build-asan --output-on-failure --parallel 2 "${exclude[@]}" "$@"
