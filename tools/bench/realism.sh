#!/usr/bin/env bash
# Realism of tmr_synth scenes: the similarity (Eq. 1) and track-length
# histograms of the real photo sets in ../shared/data, after COLMAP feature
# extraction, exhaustive matching and `colmap mapper`, beside those of the
# default synthetic scenes. Writes out/realism/*.csv and, with gnuplot,
# docs/images/realism_similarity.png and docs/images/realism_tracks.png.
#
# Usage: tools/bench/realism.sh [DATA_DIR]   (default ../shared/data)
set -euo pipefail
cd "$(dirname "$0")/../.."
DATA="${1:-../shared/data}"
COLMAP="${TMR_DEPS_PREFIX:-/opt/tmr-deps}/colmap-4.1.1/bin/colmap"
BIN=build/tools
OUT=out/realism
[[ -x "$COLMAP" && -x "$BIN/tmr_synth" ]] || { echo "run tools/build.sh first" >&2; exit 1; }
[[ -d "$DATA" ]] || { echo "no data folder '$DATA': real sets skipped" >&2; }
mkdir -p "$OUT" docs/images

# Track-length histogram of the largest model of a mapper output folder as
# CSV (length,count,fraction), from tmr_eval's JSON.
tracks_csv() {  # SPARSE_DIR CSV
  local largest
  largest=$(ls -d "$1"/*/ | while read -r m; do
    echo "$(stat -c %s "$m/images.bin") $m"; done | sort -n | tail -1 | cut -d' ' -f2)
  "$BIN/tmr_eval" --gt "$largest" --model "$largest" --output_json "$2.json" >/dev/null
  python3 - "$2.json" "$2" <<'PY'
import json, sys
model = json.load(open(sys.argv[1]))["models"][0]
h = model["track_length_histogram"]
total = sum(h) or 1
with open(sys.argv[2], "w") as f:
    f.write("length,count,fraction\n")
    for k, c in enumerate(h):
        if k >= 2: f.write(f"{k},{c},{c/total}\n")
if model["registered_images"] < 5:  # the mapper failed: no track statistics
    import os; os.remove(sys.argv[2])
print(f"{model['registered_images']} images in the largest model, "
      f"mean track length {model['mean_track_length']:.2f}, "
      f"reprojection error {model['mean_reprojection_error_px']:.2f} px")
PY
}

summarise() {  # NAME DB MODEL_DIR
  local name=$1 db=$2 model=$3
  "$BIN/tmr_graph_info" --database_path "$db" --histogram_csv "$OUT/$name.similarity.csv" |
    grep -E "^(images|verified|similarity|mean n)" | sed "s/^/[$name] /"
  if [[ -f "$model/0/images.bin" ]]; then
    tracks_csv "$model" "$OUT/$name.tracks.csv" | sed "s/^/[$name] /"
  fi
}

if [[ -d "$DATA" ]]; then
  for set in "$DATA"/*/; do
    name=$(basename "$set")
    [[ -d "$set/images" ]] || continue
    dir="$OUT/$name"
    if [[ ! -f "$dir/sparse/0/images.bin" ]]; then
      rm -rf "$dir" && mkdir -p "$dir/sparse"
      echo "[$name] feature extraction, exhaustive matching, mapper"
      "$COLMAP" feature_extractor --database_path "$dir/database.db" \
        --image_path "$set/images" --FeatureExtraction.use_gpu 0 \
        --FeatureExtraction.max_image_size 1600 >"$dir/log.txt" 2>&1
      "$COLMAP" exhaustive_matcher --database_path "$dir/database.db" \
        --FeatureMatching.use_gpu 0 >>"$dir/log.txt" 2>&1
      "$COLMAP" mapper --database_path "$dir/database.db" --image_path "$set/images" \
        --output_path "$dir/sparse" >>"$dir/log.txt" 2>&1
    fi
    summarise "$name" "$dir/database.db" "$dir/sparse"
  done
fi

# Default synthetic scenes of each family (small enough for the mapper).
declare -A SYNTH=(
  [synth_places]="--family places"
  [synth_street]="--family street --street_length 200"
  [synth_city]="--family city --city_blocks_x 1 --city_blocks_y 1"
  [synth_plazas]="--family plazas --num_places 4 --cameras_per_place 60 --detection_probability 0.35 --match_probability 0.7 --match_angle_falloff_deg 12"
)
for name in "${!SYNTH[@]}"; do
  dir="$OUT/$name"
  if [[ ! -f "$dir/sparse/0/images.bin" ]]; then
    rm -rf "$dir" && mkdir -p "$dir/sparse" "$dir/images"
    echo "[$name] tmr_synth ${SYNTH[$name]}, mapper"
    # shellcheck disable=SC2086
    "$BIN/tmr_synth" --database_path "$dir/database.db" --model_path "$dir/gt" ${SYNTH[$name]}
    "$COLMAP" mapper --database_path "$dir/database.db" --image_path "$dir/images" \
      --output_path "$dir/sparse" >"$dir/log.txt" 2>&1
  fi
  summarise "$name" "$dir/database.db" "$dir/sparse"
done

if ! command -v gnuplot >/dev/null; then
  echo "gnuplot not found (apt-get install gnuplot-nox): no plots" >&2
  exit 0
fi
plot() {  # KIND XLABEL XRANGE OUTPUT
  local kind=$1 files=("$OUT"/*."$1".csv) cmd="" sep=""
  for f in "${files[@]}"; do
    local n; n=$(basename "$f" ".$kind.csv")
    local x='($1+$2)/2' style="lines lw 2"
    [[ $kind == tracks ]] && x='1'
    [[ $n == synth_* ]] && style="lines lw 3 dt 2"
    cmd+="$sep'$f' using $x:(\$$( [[ $kind == tracks ]] && echo 3 || echo 4 )) with $style title '$n'"
    sep=", "
  done
  gnuplot <<GP
set terminal pngcairo size 900,500 noenhanced
set output '$4'
set datafile separator ','
set key top right
set xlabel '$2'
set ylabel 'share'
set xrange $3
set grid
plot $cmd
GP
}
plot similarity "Jaccard similarity s_ij (Eq. 1)" "[0:0.6]" docs/images/realism_similarity.png
plot tracks "track length (images per 3D point)" "[2:30]" docs/images/realism_tracks.png
echo "wrote docs/images/realism_similarity.png and docs/images/realism_tracks.png"
