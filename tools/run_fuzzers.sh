#!/usr/bin/env bash
# Fuzzes the readers of untrusted files with libFuzzer (Clang, ASan, UBSan):
# the COLMAP database reader and the tree.json reader, SECONDS each
# (default 60), starting from the corpus in tests/fuzz/corpus (read only;
# new inputs go to a temporary folder). A finding stops with a non-zero exit
# and the input under out/fuzz/. libtmr only: COLMAP is not needed.
# Usage: tools/run_fuzzers.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
command -v clang++ >/dev/null || { echo "[fuzz] error: clang++ is missing (apt install clang)" >&2; exit 1; }
echo "[fuzz] building the fuzz targets in build-fuzz/"
cmake --preset fuzz >build-fuzz.configure.log 2>&1 ||
  { cat build-fuzz.configure.log >&2; echo "[fuzz] error: configure failed" >&2; exit 1; }
rm -f build-fuzz.configure.log
cmake --build build-fuzz --parallel "${TMR_JOBS:-2}" --target fuzz_database_reader fuzz_tree_json
mkdir -p out/fuzz
for target in database tree_json; do
  binary=build-fuzz/tests/fuzz/fuzz_${target/database/database_reader}
  work=$(mktemp -d)
  echo "[fuzz] $binary for $seconds s"
  if ! "$binary" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
      -artifact_prefix=out/fuzz/ -print_final_stats=1 \
      "$work" "tests/fuzz/corpus/$target" >"out/fuzz/$target.log" 2>&1; then
    tail -40 "out/fuzz/$target.log" >&2
    echo "[fuzz] error: $binary found a problem (input in out/fuzz/)" >&2
    rm -rf "$work"; exit 1
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "out/fuzz/$target.log" | tr '\n' ' '; echo
  rm -rf "$work"
done
echo "[fuzz] no finding"
