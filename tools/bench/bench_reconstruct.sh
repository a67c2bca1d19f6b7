#!/usr/bin/env bash
# Photos to models: tmr_reconstruct against the stock pipeline,
# `colmap automatic_reconstructor` of the same COLMAP build (sparse only,
# CPU, its default quality "high", exhaustive matching below 200 photos),
# on every photo set of ../shared/data, one after the other, with the same
# threads. Prints extraction, matching and mapping time side by side, with
# total time, peak memory, registered photos, models and the largest
# model's median rotation error against the set's ground truth; appends to
# out/bench_reconstruct/results.csv.
#
# Usage: tools/bench/bench_reconstruct.sh [SET ...]   (default: every set)
# Environment: DATA (default ../shared/data), THREADS (default 2),
# TMR_ARGS (more tmr_reconstruct options), TOOLS (default "stock tmr":
# automatic_reconstructor and tmr_reconstruct; "tmr" runs tmr's alone).
set -euo pipefail
cd "$(dirname "$0")/../.."
COLMAP="${TMR_DEPS_PREFIX:-/opt/tmr-deps}/colmap-4.1.1/bin/colmap"
BIN=build/tools
OUT=out/bench_reconstruct
DATA="${DATA:-../shared/data}"
THREADS="${THREADS:-2}"
TOOLS="${TOOLS:-stock tmr}"
[[ -x "$COLMAP" && -x "$BIN/tmr_reconstruct" ]] || { echo "run tools/build.sh first" >&2; exit 1; }
[[ -d "$DATA" ]] || { echo "no photo sets at $DATA" >&2; exit 1; }
mkdir -p "$OUT"
CSV="$OUT/results.csv"
[[ -f "$CSV" ]] || echo "set,photos,tool,extraction_s,matching_s,mapping_s,total_s,peak_mib,registered,largest,models,median_rot_deg" >"$CSV"

source tools/bench/ground_truth.sh

# report SET PHOTOS TOOL LOG MODELS_DIR GT: one table row and one CSV line.
report() {
  local json="$OUT/$1/$3.eval.json" gt_args=()
  if [[ -n "$6" ]]; then gt_args=(--gt "$6"); elif [[ -d "$5/0" ]]; then gt_args=(--gt "$5/0"); fi
  if [[ ! -d "$5/0" ]] || ! "$BIN/tmr_eval" "${gt_args[@]}" --model "$5" --output_json "$json" >/dev/null 2>&1; then
    echo '{"models": []}' >"$json"
  fi
  python3 - "$@" "$json" "$CSV" <<'PY'
import datetime, json, re, sys
sys.path.insert(0, "tools/bench")
from tmr_summary import stage_seconds
name, photos, tool, log, models_dir, gt, json_path, csv = sys.argv[1:9]
wall, peak = open(log + ".time").read().split()[-2:]
total, peak = float(wall), int(peak) // 1024
text = open(log, errors="replace").read()
if tool == "tmr_reconstruct":
    try:
        summary = open(models_dir + "/../summary.txt").read()
    except OSError:
        summary = ""
    extraction, matching = stage_seconds(summary)
    mapping = total - extraction - matching
else:  # glog time stamps of automatic_reconstructor's stage headings
    stamps = {}
    for m in re.finditer(r"^[IWE]\d{8} (\d\d):(\d\d):(\d\d\.\d+) .*=== (Feature extraction|Feature matching|Sparse reconstruction) ===", text, re.M):
        stamps.setdefault(m.group(4), 3600 * int(m.group(1)) + 60 * int(m.group(2)) + float(m.group(3)))
    t = [stamps.get(k) for k in ("Feature extraction", "Feature matching", "Sparse reconstruction")]
    extraction = t[1] - t[0] if None not in t[:2] else float("nan")
    matching = t[2] - t[1] if None not in t[1:] else float("nan")
    mapping = total - extraction - matching
models = json.load(open(json_path))["models"]
registered = sum(m["registered_images"] for m in models)
largest = max((m["registered_images"] for m in models), default=0)
rot = ""
if gt and models:
    big = max(models, key=lambda m: m["registered_images"])
    rot = f'{big["rotation_error_deg"]["median"]:.3f}'
open(csv, "a").write(f"{name},{photos},{tool},{extraction:.1f},{matching:.1f},{mapping:.1f},{total:.1f},{peak},{registered},{largest},{len(models)},{rot}\n")
print(f"| {name} | {photos} | {tool} | {extraction:.1f} | {matching:.1f} | {mapping:.1f} | {total:.1f} | {peak:,} | "
      f"{registered} ({largest}) | {len(models)} | {rot + '°' if rot else '—'} |")
PY
}

sets=("$@")
if [[ ${#sets[@]} -eq 0 ]]; then
  for dir in "$DATA"/*/; do [[ -d "$dir/images" ]] && sets+=("$(basename "$dir")"); done
fi
echo "| set | photos | tool | extraction s | matching s | mapping s | total s | peak MiB | registered (largest) | models | median rotation error |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for set in "${sets[@]}"; do
  images="$DATA/$set/images"
  [[ -d "$images" ]] || { echo "no photos at $images" >&2; continue; }
  photos=$(find -L "$images" -type f | wc -l)
  gt=$(ground_truth "$DATA" "$set" "$OUT")
  dir="$OUT/$set"
  rm -rf "$dir" && mkdir -p "$dir/stock"
  if [[ " $TOOLS " == *" stock "* ]]; then
    /usr/bin/time -f "%e %M" -o "$dir/stock.log.time" "$COLMAP" automatic_reconstructor \
      --workspace_path "$dir/stock" --image_path "$images" --num_threads "$THREADS" \
      --use_gpu 0 --dense 0 >"$dir/stock.log" 2>&1 || true
    report "$set" "$photos" "colmap automatic_reconstructor" "$dir/stock.log" "$dir/stock/sparse" "$gt"
  fi
  [[ " $TOOLS " == *" tmr "* ]] || continue
  # shellcheck disable=SC2086
  /usr/bin/time -f "%e %M" -o "$dir/tmr.log.time" "$BIN/tmr_reconstruct" "$images" "$dir/tmr" \
    --num_threads "$THREADS" ${TMR_ARGS:-} >"$dir/tmr.log" 2>&1 || true
  report "$set" "$photos" "tmr_reconstruct" "$dir/tmr.log" "$dir/tmr/sparse" "$gt"
done
