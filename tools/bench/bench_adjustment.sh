#!/usr/bin/env bash
# Peak memory of the largest step of a mapper, side by side on one model:
# COLMAP's own global bundle adjustment (`colmap bundle_adjuster`, the
# problem stock `colmap mapper` builds at the end of a scene of that size,
# without the correspondences the mapper holds beside it) and tmr's
# refinement of a merged model (tools/bench/bench_adjustment), whole and by
# blocks (--Tmr.ba_max_block_images).
#
#   tools/bench/bench_adjustment.sh DATABASE MODEL [ITERATIONS]
#
# ITERATIONS (default 3) bounds COLMAP's adjustment: its memory peaks as
# soon as the problem is built. The database and model are only read.
set -euo pipefail
if [[ $# -lt 2 ]]; then
  echo "usage: $0 DATABASE MODEL [ITERATIONS]" >&2
  exit 2
fi
database=$1
model=$2
iterations=${3:-3}
root=$(cd "$(dirname "$0")/../.." && pwd)
colmap=${COLMAP:-/opt/tmr-deps/colmap-4.1.1/bin/colmap}
bench=${BENCH_ADJUSTMENT:-$root/build/tools/bench_adjustment}
for f in "$database" "$model/images.bin" "$colmap" "$bench"; do
  [[ -e $f ]] || { echo "$0: error: '$f' not found" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

measure() {  # label, command...: prints "label seconds peak_MiB"
  local label=$1
  shift
  /usr/bin/time -f "%e %M" -o "$work/time" "$@" > "$work/$label.log" 2>&1 ||
    { echo "$0: error: $label failed, see below" >&2; tail -5 "$work/$label.log" >&2; exit 1; }
  read -r seconds kib < "$work/time"
  printf "| %s | %s | %d |\n" "$label" "$seconds" $((kib / 1024))
}

echo "| step | seconds | peak MiB |"
echo "|---|---|---|"
mkdir -p "$work/colmap_out"
measure "colmap bundle_adjuster ($iterations iterations)" \
  "$colmap" bundle_adjuster --input_path "$model" \
  --output_path "$work/colmap_out" \
  --BundleAdjustment.max_num_iterations "$iterations"
measure "tmr refinement, whole" "$bench" "$database" "$model" 0
measure "tmr refinement, blocks of 1000" "$bench" "$database" "$model" 1000
