#!/usr/bin/env bash
# Task-memory benchmark: the peak memory of kernel and leaf tasks
# against what the plan expects of them (`tmr_mapper status`'s last column,
# controllers/memory_budget.h). Per scene (as bench_mapper.sh names them,
# kept in out/bench_mapper/SCENE): `tmr_mapper partition`, then the largest
# kernel task, and the smallest, median and largest leaf task by expected
# memory (each after its kernel), one `tmr_mapper run_task` each under
# /usr/bin/time. Prints expected and measured peak side by side and appends
# them to out/bench_task_memory/results.csv. The merge stage's figures are
# bench_merge_stage.sh's.
#
# Usage: tools/bench/bench_task_memory.sh SCENE ...   (e.g. city3 plazas8)
# Environment: THREADS (default 2; each task runs on one); TMR_ARGS adds
# options to the partition.
set -euo pipefail
cd "$(dirname "$0")/../.."
COLMAP="${TMR_DEPS_PREFIX:-/opt/tmr-deps}/colmap-4.1.1/bin/colmap"
BIN=build/tools
OUT=out/bench_task_memory
THREADS="${THREADS:-2}"
[[ -x "$BIN/tmr_mapper" ]] || { echo "run tools/build.sh first" >&2; exit 1; }
# shellcheck source=scenes.sh
source "$(dirname "$0")/scenes.sh"
start_results "scene,task,images,expected_mib,peak_mib,seconds"

for scene in "$@"; do
  run="$OUT/$scene"
  plan_scene "$scene" "$run" 1
  grep '^\[tmr.*memory:' "$run.status" | sed 's/^[^]]*] /  /' || true
  # id images base state expected_mib; leaves sorted by expected memory.
  kernel=$(awk '$1 ~ /^kernel\./' "$run.status" | sort -k5,5n | tail -1 | cut -d' ' -f1)
  mapfile -t leaves < <(awk '$1 ~ /^leaf\./' "$run.status" | sort -k5,5n |
    awk '{a[NR] = $1} END {if (NR) print a[1]; if (NR > 2) print a[int((NR + 1) / 2)]; if (NR > 1) print a[NR]}')
  todo=("$kernel")
  for leaf in "${leaves[@]}"; do
    k=${leaf#leaf.} k=kernel.${k%.*}
    [[ " ${todo[*]} " == *" $k "* ]] || todo+=("$k")
    todo+=("$leaf")
  done
  printf '%-8s %-12s %7s %13s %13s %8s\n' scene task images "expected MiB" "measured MiB" seconds
  for task in "${todo[@]}"; do
    read -r _ images base _ expected < <(grep "^$task " "$run.status")
    /usr/bin/time -f "%e %M" -o "$run.$task.time" "$BIN/tmr_mapper" run_task --plan "$run/plan.txt" \
      --task "$task" --Mapper.num_threads 1 >"$run.$task.log" 2>&1 || { tail -3 "$run.$task.log"; continue; }
    read -r wall peak < <(tail -1 "$run.$task.time" | awk '{printf "%s %.0f\n", $1, $2 / 1024}')
    printf '%-8s %-12s %7d %13d %13d %8.1f\n' "$scene" "$task" $((images + base)) "$expected" "$peak" "$wall"
    echo "$scene,$task,$((images + base)),$expected,$peak,$wall" >>"$OUT/results.csv"
  done
done
