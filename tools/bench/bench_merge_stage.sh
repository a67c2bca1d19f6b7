#!/usr/bin/env bash
# Merge-stage benchmark: tmr_mapper's merge stage alone, on task
# results generated from a scene's ground truth (tmr_synth_tasks: every
# kernel and leaf model with noisy poses and points, each in a frame of its
# own), so that its time and memory can be measured at sizes where running
# the tasks would take days. Per scene: the scene (as bench_mapper.sh names
# them, kept in out/bench_mapper/SCENE), `tmr_mapper partition`,
# tmr_synth_tasks, then `tmr_mapper merge` under /usr/bin/time; prints the
# merge's wall time and peak memory, its time per photo, and the models
# scored by tmr_eval; appends them to out/bench_merge_stage/results.csv.
#
# Usage: tools/bench/bench_merge_stage.sh SCENE ...   (e.g. city3 city6 city10)
# Environment: THREADS (default 2); NOISE_ARGS adds options to
# tmr_synth_tasks (e.g. "--rotation_noise_deg 0.05"); TMR_ARGS adds options
# to the partition (and so to the merge); TAG names such a variant (its
# runs go to out/bench_merge_stage/SCENE-TAG, e.g. TAG=parts with
# TMR_ARGS="--Tmr.memory_budget 1" for a merge stage by parts). The
# expected peak is the largest step's: the whole merge, or by parts the
# largest group's or the join's. JOBS=1 (a merge stage by parts) merges each
# group in a process of its own (`tmr_mapper merge --group merge.G`), then
# joins (`tmr_mapper merge`), as Slurm jobs would run, and prints each job's
# wall time and peak; the totals are then their sum and the largest peak.
# REUSE=1 keeps the run's plan, tasks and merged groups (out/...SCENE.jobs
# lists the groups done), so that a stage too long for one session goes on
# where the last call stopped. With JOBS=1 the join keeps the work folder
# (--Tmr.keep_work 1), so that REUSE=1 runs the join again alone.
set -euo pipefail
cd "$(dirname "$0")/../.."
COLMAP="${TMR_DEPS_PREFIX:-/opt/tmr-deps}/colmap-4.1.1/bin/colmap"
BIN=build/tools
OUT=out/bench_merge_stage
THREADS="${THREADS:-2}"
[[ -x "$BIN/tmr_synth_tasks" ]] || { echo "run tools/build.sh first" >&2; exit 1; }
# shellcheck source=scenes.sh
source "$(dirname "$0")/scenes.sh"
start_results "scene,images,tasks,synth_s,merge_s,peak_mib,s_per_photo,models,largest,median_rot_deg,wrong_merges,expected_peak_mib"

for scene in "$@"; do
  dir=out/bench_mapper/$scene
  run="$OUT/$scene${TAG:+-$TAG}"
  synth=0
  if [[ -z "${REUSE:-}" || ! -f "$run/plan.txt" ]]; then
    plan_scene "$scene" "$run" "$THREADS"
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$BIN/tmr_synth_tasks" --plan "$run/plan.txt" --model_path "$dir/gt" ${NOISE_ARGS:-} >"$run.synth.log" 2>&1
    synth=$(echo "$(date +%s.%N) - $start" | bc)
  fi
  tasks=$(grep -c -E "^(kernel|leaf)\." "$run/plan.txt")
  if [[ -n "${JOBS:-}" ]]; then  # each group a job of its own, then the join
    [[ -f "$run.jobs" && -n "${REUSE:-}" ]] || : >"$run.jobs"
    for group in $(awk '/^merge\.[0-9]+ / { print $1 }' "$run/plan.txt"); do
      grep -q "^$group " "$run.jobs" && continue  # merged by an earlier call
      /usr/bin/time -f "%e %M" -o "$run.$group.time" "$BIN/tmr_mapper" merge --plan "$run/plan.txt" \
        --group "$group" --Mapper.num_threads "$THREADS" >"$run.$group.log" 2>&1 ||
        { tail -3 "$run.$group.log"; continue 2; }
      job=$(tail -1 "$run.$group.time" | awk '{printf "%s %.0f", $1, $2 / 1024}')
      echo "$group $job $(awk -v g="$group" '$1 == g { print $2, $4 }' "$run/plan.txt")" >>"$run.jobs"
      echo "$scene $group: $job (wall s, peak MiB)"
    done
  fi
  /usr/bin/time -f "%e %M" -o "$run.merge.time" "$BIN/tmr_mapper" merge --plan "$run/plan.txt" \
    --Mapper.num_threads "$THREADS" ${JOBS:+--Tmr.keep_work 1} >"$run.merge.log" 2>&1 || { tail -3 "$run.merge.log"; continue; }
  read -r wall peak < <(tail -1 "$run.merge.time" | awk '{printf "%s %.0f\n", $1, $2 / 1024}')
  if [[ -n "${JOBS:-}" ]]; then  # one job after another: the sum, the largest peak
    echo "$scene join: $wall $peak (wall s, peak MiB)"
    echo "           jobs (group, wall s, peak MiB, photos, expected MiB):"
    sed 's/^/             /' "$run.jobs"
    read -r wall peak < <(awk -v w="$wall" -v p="$peak" '{ w += $2; if ($3 > p) p = $3 }
      END { printf "%s %d\n", w, p }' "$run.jobs")
  fi
  expected=$(awk '/^merge/ && $4 > max { max = $4 } END { print max }' "$run/plan.txt")
  "$BIN/tmr_eval" --gt "$dir/gt" --model "$run" --output_json "$run/eval.json" >/dev/null 2>&1
  python3 - "$run/eval.json" "$scene${TAG:+-$TAG}" "$tasks" "$synth" "$wall" "$peak" "$OUT/results.csv" "$expected" <<'PY'
import json, sys
models = json.load(open(sys.argv[1]))["models"]
scene, tasks, synth, wall, peak, csv, expected = sys.argv[2:9]
big = max(models, key=lambda m: m["registered_images"])
images = big["reference_images"]
wrong = sum(1 for m in models if m["wrong_merge"])
rot = big["rotation_error_deg"]["median"]
per_photo = float(wall) / images
open(csv, "a").write(f"{scene},{images},{tasks},{float(synth):.1f},{wall},{peak},{per_photo:.4f},{len(models)},"
                     f"{big['registered_images']},{rot:.4f},{wrong},{expected}\n")
print(f"{scene:<8} {images:>6} photos, {tasks} tasks generated in {float(synth):.0f} s; merge stage {wall} s "
      f"({1000 * per_photo:.0f} ms per photo), peak {peak} MiB (expected {expected}); {len(models)} models, largest {big['registered_images']}, "
      f"median rot {rot:.4f}°, wrong merges {wrong}")
PY
  python3 - "$run/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
for t in r["tasks"]:  # the steps of a second or more, with the memory then
    if t["seconds"] >= 1 and "rss_mib" in t:
        print(f"           {t['task'][:48]:<48} {t['seconds']:7.1f} s  rss {t['rss_mib']:>6} MiB, peak {t['peak_mib']:>6} MiB")
PY
done
