#!/usr/bin/env bash
# Mapper benchmark: stock `colmap mapper`, `colmap hierarchical_mapper`,
# `colmap global_mapper` (all of the same COLMAP 4.1.1 build) and
# `tmr_mapper` on the same tmr_synth databases, in one run, with the same
# thread count. Each COLMAP tool reads its own copy of the database (COLMAP 4
# opens a database read-write and may rewrite it); tmr_mapper reads the
# original, read-only. Prints wall time, peak memory, registered images, models,
# errors, displaced images and wrong merges side by side (tmr_eval against the ground truth)
# and appends them to out/bench_mapper/results.csv.
#
# Usage: tools/bench/bench_mapper.sh [SCENE ...]
#   SCENE: city1 city2 city3 city4 city6 (well-connected, 192 / 552 / 1,088 /
#          1,800 / 3,752 images), placesN, e.g. places8 places32 (weakly linked
#          places of about 75 images each), or plazasN, e.g. plazas8 plazas16
#          (overlapping plazas of 120 photos whose clusters share few tracks,
#          detection 0.35). A suffix sN picks tmr_synth's seed N (default
#          0), e.g. city1s3 for the city block of seed 3; a suffix v has
#          `colmap geometric_verifier` verify the matches again, as a user's
#          matcher would (plazas8v, the scene of issue 42). Default: city1
#          places4.
# Environment: THREADS (default 2); REUSE=1 scores earlier runs again instead
# of repeating them; TOOLS (default "colmap_mapper colmap_hierarchical
# colmap_global tmr_mapper"; also tmr_mapper_paper, tmr_mapper with the
# paper's kernel search and image clustering) picks the tools and their order; TMR_ARGS adds options to
# tmr_mapper (e.g. "--Tmr.keep_work 1"); STOCK_CAP=SECONDS stops `colmap
# mapper` after that long and reports the images it had registered (a
# lower bound on its time, for scenes where it takes hours); GLOBAL_CAP=SECONDS
# does the same for `colmap global_mapper` (reports the stage it was in),
# HIER_CAP=SECONDS for `colmap hierarchical_mapper` (reports the images its
# clusters had registered).
set -euo pipefail
cd "$(dirname "$0")/../.."
COLMAP="${TMR_DEPS_PREFIX:-/opt/tmr-deps}/colmap-4.1.1/bin/colmap"
BIN=build/tools
OUT=out/bench_mapper
THREADS="${THREADS:-2}"
[[ -x "$COLMAP" && -x "$BIN/tmr_mapper" ]] || { echo "run tools/build.sh first" >&2; exit 1; }
mkdir -p "$OUT"
[[ -f "$OUT/results.csv" ]] ||
  echo "scene,images,tool,wall_s,peak_mib,registered,largest,models,median_rot_deg,p90_rot_deg,wrong_merges,displaced" >"$OUT/results.csv"

# shellcheck source=scenes.sh
source "$(dirname "$0")/scenes.sh"

# Prints "wall_s peak_mib" from /usr/bin/time's output file (its last line;
# a line before it tells a non-zero exit status).
wall_and_peak() {
  tail -1 "$1" | awk '{printf "%s %.0f\n", $1, $2 / 1024}'
}

# Runs a command under /usr/bin/time; prints "wall_s peak_mib".
timed() {
  local log=$1; shift
  /usr/bin/time -f "%e %M" -o "$log.time" "$@" >"$log" 2>&1 || true
  wall_and_peak "$log.time"
}

score() {  # NAME SCENE IMAGES TOOL WALL PEAK MODEL_DIR
  local json="$7/eval.json"
  if ! "$BIN/tmr_eval" --gt "$OUT/$2/gt" --model "$7" --output_json "$json" >/dev/null 2>&1; then
    echo "$2,$3,$4,$5,$6,0,0,0,,,0,0" >>"$OUT/results.csv"
    printf "%-10s %-22s %8s s %7s MiB   no model\n" "$2" "$4" "$5" "$6"
    return
  fi
  python3 - "$json" "$2" "$3" "$4" "$5" "$6" "$OUT/results.csv" <<'PY'
import json, sys
models = json.load(open(sys.argv[1]))["models"]
scene, images, tool, wall, peak, csv = sys.argv[2:8]
registered = sum(m["registered_images"] for m in models)
largest = max((m["registered_images"] for m in models), default=0)
big = max(models, key=lambda m: m["registered_images"])
wrong = sum(1 for m in models if m["wrong_merge"])
# Registered but placed off by more than 5% of the scene scale (tmr_eval).
displaced = sum(m["displaced_images"] for m in models)
rot, p90 = big["rotation_error_deg"]["median"], big["rotation_error_deg"]["p90"]
open(csv, "a").write(f"{scene},{images},{tool},{wall},{peak},{registered},{largest},{len(models)},{rot:.3f},{p90:.3f},{wrong},{displaced}\n")
print(f"{scene:<10} {tool:<22} {wall:>8} s {peak:>7} MiB  {registered:>5} registered ({displaced} displaced), largest {largest:>5}, "
      f"{len(models):>3} models, median rot {rot:.3f}°, wrong merges {wrong}")
PY
}

scenes=("$@")
[[ ${#scenes[@]} -gt 0 ]] || scenes=(city1 places4)
for scene in "${scenes[@]}"; do
  dir="$OUT/$scene"
  ensure_scene "$dir" "$scene"
  images=$(sqlite3 "file:$dir/database.db?immutable=1" "SELECT COUNT(*) FROM images")
  for tool in ${TOOLS:-colmap_mapper colmap_hierarchical colmap_global tmr_mapper}; do
    out="$dir/$tool"
    if [[ -n "${REUSE:-}" && -f "$out.log.time" ]]; then  # REUSE=1: keep earlier runs
      read -r wall peak < <(wall_and_peak "$out.log.time")
      score "$tool" "$scene" "$images" "$tool" "$wall" "$peak" "$out"
      continue
    fi
    rm -rf "$out" "$out.db" "$out.db-wal" "$out.db-shm" && mkdir -p "$out"  # a stale -wal would apply to the new copy
    [[ $tool == tmr_mapper ]] || cp "$dir/database.db" "$out.db"  # COLMAP's own copy
    case $tool in
      colmap_mapper)
        read -r wall peak < <(timed "$out.log" ${STOCK_CAP:+timeout -s INT "$STOCK_CAP"} "$COLMAP" mapper \
          --database_path "$out.db" --image_path "$dir/images" --output_path "$out" \
          --Mapper.num_threads "$THREADS")
        if grep -q 'status 124$' "$out.log.time"; then  # timeout: stopped at the cap
          # COLMAP 4.1 logs "Registering image #ID (num_reg_frames=N)".
          registered=$(grep -o 'num_reg_frames=[0-9]*' "$out.log" | tail -1 | cut -d= -f2 || true)
          echo "$scene,$images,colmap_mapper_capped,$wall,$peak,${registered:-0},,0,,,0," >>"$OUT/results.csv"
          printf "%-10s %-22s %8s s %7s MiB   stopped at the cap: %s of %s images registered\n" \
            "$scene" "colmap_mapper" "$wall" "$peak" "${registered:-0}" "$images"
          continue
        fi ;;
      colmap_hierarchical)
        read -r wall peak < <(timed "$out.log" ${HIER_CAP:+timeout -s INT "$HIER_CAP"} \
          "$COLMAP" hierarchical_mapper \
          --database_path "$out.db" --image_path "$dir/images" --output_path "$out" \
          --Mapper.num_threads "$THREADS")
        if grep -q 'status 124$' "$out.log.time"; then  # timeout: stopped at the cap
          # Clusters are mapped side by side and merged at the end: what a
          # user has when it is stopped is the clusters' registrations.
          registered=$(grep -c 'Registering image #' "$out.log" || true)
          echo "$scene,$images,colmap_hierarchical_capped,$wall,$peak,${registered:-0},,0,,,0," >>"$OUT/results.csv"
          printf "%-10s %-22s %8s s %7s MiB   stopped at the cap: %s registrations in clusters so far, no model\n" \
            "$scene" "colmap_hierarchical" "$wall" "$peak" "${registered:-0}"
          continue
        fi ;;
      colmap_global)
        read -r wall peak < <(timed "$out.log" ${GLOBAL_CAP:+timeout -s INT "$GLOBAL_CAP"} \
          "$COLMAP" global_mapper \
          --database_path "$out.db" --image_path "$dir/images" --output_path "$out" \
          --GlobalMapper.num_threads "$THREADS")
        if grep -q 'status 124$' "$out.log.time"; then  # timeout: stopped at the cap
          stage=$(grep -o '=== [^=]* ===' "$out.log" | tail -1 || true)
          echo "$scene,$images,colmap_global_capped,$wall,$peak,,,0,,,0," >>"$OUT/results.csv"
          printf "%-10s %-22s %8s s %7s MiB   stopped at the cap in %s\n" \
            "$scene" "colmap_global" "$wall" "$peak" "${stage:-?}"
          continue
        fi ;;
      tmr_mapper|tmr_mapper_paper)
        # tmr_mapper_paper: the paper's kernel search and image clustering
        # (layers on the whole graph, single-pair links crossed).
        paper_args=()
        [[ $tool == tmr_mapper ]] || paper_args=(--Tmr.kernels_per_place 0 --Tmr.min_bridge_side 0)
        read -r wall peak < <(timed "$out.log" "$BIN/tmr_mapper" --database_path "$dir/database.db" \
          --output_path "$out" --Mapper.num_threads "$THREADS" "${paper_args[@]}" ${TMR_ARGS:-}) ;;
    esac
    score "$tool" "$scene" "$images" "$tool" "$wall" "$peak" "$out"
    if [[ $tool == tmr_mapper* && -f "$out/report.json" ]]; then  # where the time went (issue 42)
      python3 - "$out/report.json" "$wall" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
if "projected_wall_s" not in r:  # a report of a build before issue 42
    sys.exit(0)
after = r["total_s"] - r["tasks_end_s"]
proj = r["projected_wall_s"]
print("           tasks end at %.0f s; %.0f s after them (%.0f%% of the run); critical path %.0f s; "
      "replayed on 2/4/8/16/64 workers: %s s (measured %s s); 2 -> 16 workers: %.2fx"
      % (r["tasks_end_s"], after, 100 * r["after_tasks_share"], r["critical_path_s"],
         "/".join("%.0f" % proj[w] for w in ("2", "4", "8", "16", "64")), sys.argv[2],
         proj["2"] / proj["16"]))
PY
    fi
    if [[ $tool == tmr_mapper* && -f "$out/tree.json" ]]; then  # the partition, for issue 25
      python3 - "$out/tree.json" "$out.log" <<'PY'
import collections, json, re, sys
tree = json.load(open(sys.argv[1]))
origins = collections.Counter(k["origin"] for k in tree["kernels"])
leaves = sorted(len(l) for k in tree["kernels"] for l in k["leaf_clusters"])
seconds = re.findall(r"partition: .*\(([0-9.]+) s\)", open(sys.argv[2]).read())
print("           partition: %d kernels (%s), kernel sizes %s, %d leaf clusters, largest leaf %d, "
      "%d unclustered, %s s" % (len(tree["kernels"]), ", ".join("%d %s" % (n, o) for o, n in sorted(origins.items())),
      "-".join(str(x) for x in (min(len(k["kernel_images"]) for k in tree["kernels"]), max(len(k["kernel_images"]) for k in tree["kernels"]))) if tree["kernels"] else "-",
      len(leaves), leaves[-1] if leaves else 0, len(tree["unclustered"]), seconds[-1] if seconds else "?"))
PY
    fi
  done
done

# Plot: wall time and time per image against scene size, per tool, from the
# latest row of each (scene, tool) in results.csv (well-connected city scenes).
if ! command -v gnuplot >/dev/null; then
  echo "gnuplot not found (apt-get install gnuplot-nox): no plot" >&2
  exit 0
fi
mkdir -p docs/images
for tool in colmap_mapper colmap_hierarchical colmap_global tmr_mapper; do
  awk -F, -v t="$tool" 'NR > 1 && $3 == t && $1 ~ /^city/ {last[$2] = $4}
    END {for (n in last) print n, last[n], last[n] / n}' "$OUT/results.csv" |
    sort -n >"$OUT/$tool.dat"
done
gnuplot <<GP
set terminal pngcairo size 1000,420 noenhanced
set output 'docs/images/bench_mapper.png'
set multiplot layout 1,2 title 'tmr_synth cities, ${THREADS} threads, same machine, one tool at a time'
set key top left
set grid
set xlabel 'images'
set ylabel 'wall time (s)'
plot '$OUT/colmap_mapper.dat' using 1:2 with linespoints lw 2 title 'colmap mapper', \
     '$OUT/colmap_hierarchical.dat' using 1:2 with linespoints lw 2 title 'colmap hierarchical_mapper', \
     '$OUT/colmap_global.dat' using 1:2 with linespoints lw 2 title 'colmap global_mapper', \
     '$OUT/tmr_mapper.dat' using 1:2 with linespoints lw 2 title 'tmr_mapper'
set ylabel 'seconds per image'
plot '$OUT/colmap_mapper.dat' using 1:3 with linespoints lw 2 title 'colmap mapper', \
     '$OUT/colmap_hierarchical.dat' using 1:3 with linespoints lw 2 title 'colmap hierarchical_mapper', \
     '$OUT/colmap_global.dat' using 1:3 with linespoints lw 2 title 'colmap global_mapper', \
     '$OUT/tmr_mapper.dat' using 1:3 with linespoints lw 2 title 'tmr_mapper'
unset multiplot
GP
echo "plot: docs/images/bench_mapper.png"
