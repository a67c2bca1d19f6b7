#!/usr/bin/env bash
# Real-photo benchmark: stock `colmap mapper` and tmr_mapper on the
# same database of each photo set in ../shared/data, and the paper's Sec. 6.2
# experiment on a real sequence.
#
# Usage: tools/bench/bench_real.sh [sets|weak_links|all]   (default: all)
#   sets:       every set: tmr_reconstruct (features, exhaustive matching,
#               tmr_mapper), then both mappers timed on its database; scored
#               against gt/colmap_text where the set has it.
#   weak_links: middlebury_templeRing (47 photos on a ring): two arcs with
#               the photos between them removed (two unlinked parts), then
#               one of the gaps thinned instead (weakly linked). Top views
#               per tool in docs/images/real_*.png.
# Environment: DATA (default ../shared/data), THREADS (default 2).
# Results: out/bench_real/results.csv and a markdown table on stdout.
set -euo pipefail
cd "$(dirname "$0")/../.."
COLMAP="${TMR_DEPS_PREFIX:-/opt/tmr-deps}/colmap-4.1.1/bin/colmap"
BIN=build/tools
OUT=out/bench_real
DATA="${DATA:-../shared/data}"
THREADS="${THREADS:-2}"
WHAT="${1:-all}"
[[ -x "$COLMAP" && -x "$BIN/tmr_reconstruct" ]] || { echo "run tools/build.sh first" >&2; exit 1; }
[[ -d "$DATA" ]] || { echo "no photo sets at $DATA" >&2; exit 1; }
mkdir -p "$OUT" docs/images
CSV="$OUT/results.csv"
[[ -f "$CSV" ]] ||
  echo "case,photos,tool,wall_s,registered,models,largest,reproj_px,median_rot_deg,wrong_merges" >"$CSV"

timed() {  # LOG COMMAND...: prints the wall time in seconds
  local log=$1; shift
  /usr/bin/time -f "%e" -o "$log.time" "$@" >"$log" 2>&1 || true
  tail -1 "$log.time"
}

# score CASE PHOTOS TOOL WALL MODELS_DIR GT_DIR|"" [TOP_VIEW_PNG]
score() {
  local json="$5.eval.json" gt="${6:-}"
  local args=(--model "$5" --output_json "$json")
  if [[ -n "$gt" ]]; then args+=(--gt "$gt"); else args+=(--gt "$5/0"); fi
  [[ -n "${7:-}" && -n "$gt" ]] && args+=(--top_view "$7")
  if ! ls -d "$5"/[0-9]* >/dev/null 2>&1 || ! "$BIN/tmr_eval" "${args[@]}" >/dev/null 2>&1; then
    echo "$1,$2,$3,$4,0,0,0,,,0" >>"$CSV"
    printf "| %s | %s | %s | %s s | no model |\n" "$1" "$2" "$3" "$4"
    return
  fi
  python3 - "$json" "$1" "$2" "$3" "$4" "$CSV" "$gt" <<'PY'
import json, sys
models = json.load(open(sys.argv[1]))["models"]
case, photos, tool, wall, csv, gt = sys.argv[2:8]
registered = sum(m["registered_images"] for m in models)
big = max(models, key=lambda m: m["registered_images"])
wrong = sum(1 for m in models if m["wrong_merge"]) if gt else 0
rot = f'{big["rotation_error_deg"]["median"]:.3f}' if gt else ""
sizes = " + ".join(str(m["registered_images"]) for m in models)
open(csv, "a").write(f"{case},{photos},{tool},{wall},{registered},{len(models)},{big['registered_images']},"
                     f"{big['mean_reprojection_error_px']:.3f},{rot},{wrong}\n")
print(f"| {case} | {photos} | {tool} | {wall} | {registered} ({sizes}) | {len(models)} | "
      f"{big['mean_reprojection_error_px']:.2f} | {rot + '°' if gt else 'no ground truth'} | {wrong if gt else '—'} |")
PY
}

# run_case CASE IMAGES_DIR GT_DIR|"" [PICTURE_PREFIX]: features and matches
# once (tmr_reconstruct), then both mappers timed on the same database.
run_case() {
  local name=$1 images=$2 gt=$3 picture=${4:-} dir="$OUT/$1"
  local photos; photos=$(find -L "$images" -maxdepth 1 -type f | wc -l)
  rm -rf "$dir"; mkdir -p "$dir/stock"
  "$BIN/tmr_reconstruct" "$images" "$dir/ws" --num_threads "$THREADS" \
    --FeatureExtraction.max_image_size 1600 >"$dir/reconstruct.log" 2>&1 || true
  [[ -f "$dir/ws/database.db" ]] || { echo "| $name | $photos | tmr_reconstruct failed: $(tail -1 "$dir/reconstruct.log") |"; return; }
  local wall
  wall=$(timed "$dir/tmr.log" "$BIN/tmr_mapper" --database_path "$dir/ws/database.db" \
    --image_path "$images" --output_path "$dir/tmr" --Mapper.num_threads "$THREADS")
  score "$name" "$photos" tmr_mapper "$wall" "$dir/tmr" "$gt" "${picture:+${picture}_tmr_mapper.png}"
  wall=$(timed "$dir/stock.log" "$COLMAP" mapper --database_path "$dir/ws/database.db" \
    --image_path "$images" --output_path "$dir/stock" --Mapper.num_threads "$THREADS")
  score "$name" "$photos" "colmap mapper" "$wall" "$dir/stock" "$gt" "${picture:+${picture}_colmap_mapper.png}"
}

echo "| case | photos | tool | wall s | registered (per model) | models | reprojection px (largest) | median rotation error (largest) | wrong merges |"
echo "|---|---|---|---|---|---|---|---|---|"
# The temple ring's ground truth has 16 cameras rolled 180 degrees against
# their photos on disk; templering_gt.py corrects it and lists the photos
# in ring order (azimuth, degrees).
ring="$DATA/middlebury_templeRing"
ring_gt="$OUT/templeRing_gt"
if [[ -d "$ring/gt/colmap_text" ]]; then
  python3 tools/bench/templering_gt.py "$ring/gt/colmap_text" "$ring_gt" >"$OUT/templeRing_order.txt"
fi
if [[ "$WHAT" == sets || "$WHAT" == all ]]; then
  for set in "$DATA"/*/; do
    set=$(basename "$set")
    gt="$DATA/$set/gt/colmap_text"; [[ -f "$gt/images.txt" ]] || gt=""
    [[ $set == middlebury_templeRing ]] && gt="$ring_gt"
    run_case "$set" "$DATA/$set/images" "$gt"
  done
fi
if [[ "$WHAT" == weak_links || "$WHAT" == all ]]; then
  # templeRing: 47 photos on a ring around the temple, 7.7 degrees apart on
  # average. By ground-truth azimuth, two opposite quarters are kept, [0, 90)
  # and [180, 270) degrees; the quarters between them are removed
  # ("removed": nothing links the arcs), or [90, 180) is thinned to every
  # third photo in ring order ("thinned": a weak link; the other quarter
  # stays removed).
  if [[ -d "$ring/images" && -f "$OUT/templeRing_order.txt" ]]; then
    for variant in removed thinned; do
      sub="$OUT/templeRing_$variant.images"
      rm -rf "$sub"; mkdir -p "$sub"
      awk -v variant="$variant" '{
          q = int($2 / 90)
          if (q == 0 || q == 2) print $1
          else if (q == 1 && variant == "thinned" && (n1++ % 3) == 0) print $1
        }' "$OUT/templeRing_order.txt" |
        while read -r name; do ln -s "$(realpath "$ring/images")/$name" "$sub/"; done
      run_case "templeRing_$variant" "$sub" "$ring_gt" "docs/images/real_templeRing_$variant"
    done
  fi
fi
