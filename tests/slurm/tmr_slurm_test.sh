#!/usr/bin/env bash
# tools/tmr_slurm on a real single-node Slurm (tests/slurm/local_slurm.sh):
# a tmr_synth scene reconstructed through Slurm array jobs must give the
# models of the one-command tmr_mapper run (same models, same images, poses
# equal up to bundle-adjustment noise), and a rerun after a lost task
# submits that task alone and ends with the same models. With a memory
# budget below the merge stage's, the merge runs by parts (an array job of
# group merges, then the join) and gives the same models too.
#
#   tmr_slurm_test.sh TMR_SYNTH TMR_MAPPER TMR_EVAL WORK_DIR
# Exits 77 (skipped) when Slurm's daemons are not installed.
set -euo pipefail
synth=$1 mapper=$2 eval_tool=$3 work=$4
here=$(cd "$(dirname "$0")" && pwd)
slurm="$here/local_slurm.sh"
for daemon in slurmctld slurmd munged sbatch; do
  if ! command -v "$daemon" >/dev/null && [[ ! -x /usr/sbin/$daemon ]]; then
    echo "SKIPPED: $daemon not installed (tests/slurm/local_slurm.sh install)"
    exit 77
  fi
done
fail() { echo "tmr_slurm_test: FAILED: $*" >&2; exit 1; }

rm -rf "$work" && mkdir -p "$work"
"$synth" --database_path "$work/database.db" --model_path "$work/gt" \
  --cameras_per_place 40 --place_distance 100 --seed 1 > /dev/null
"$mapper" --database_path "$work/database.db" --output_path "$work/in_process" \
  --Mapper.num_threads 2 > "$work/in_process.log"

"$slurm" start "$work/slurm"
trap '"$slurm" stop "$work/slurm"' EXIT
# shellcheck disable=SC1091
source "$work/slurm/env"

# Submits through tmr_slurm into $work/${1:-staged} (further arguments go to
# tmr_slurm), waits for its jobs, prints tmr_slurm's output.
run_slurm() {
  local out=$work/${1:-staged}
  "$here/../../tools/tmr_slurm" --tmr_mapper "$mapper" --cpus_per_task 1 \
    --database_path "$work/database.db" --output_path "$out" \
    --Tmr.keep_work 1 "${@:2}" > "$work/submit.log" || fail "tmr_slurm: $(cat "$work/submit.log")"
  cat "$work/submit.log"
  # shellcheck disable=SC2046
  LOCAL_SLURM_WAIT_TIMEOUT=900 "$slurm" wait "$work/slurm" $(cat "$out/slurm/jobs.txt") ||
    fail "a job did not complete; logs in $out/slurm"
}

# The models in $work/${1:-staged} against the in-process ones, model by
# model.
compare() {
  python3 - "$work" "$eval_tool" "${1:-staged}" <<'PY' || fail "the staged models differ"
import json, subprocess, sys
work, eval_tool, staged = sys.argv[1:]
a = json.load(open(f"{work}/in_process/report.json"))["model_sizes"]
b = json.load(open(f"{work}/{staged}/report.json"))["model_sizes"]
print("in process:", a, " staged:", b)
assert a == b, "different models"
for i in range(len(a)):
    out = f"{work}/eval{i}.json"
    subprocess.run([eval_tool, "--gt", f"{work}/in_process/{i}", "--model",
                    f"{work}/{staged}/{i}", "--output_json", out], check=True,
                   stdout=subprocess.DEVNULL)
    m = json.load(open(out))["models"][0]
    rot = m["rotation_error_deg"]["max"]
    pos = m["position_error_relative"]["max"]
    print(f"model {i}: {m['common_images']}/{a[i]} images in common, "
          f"rotation differs by <= {rot:.4f} deg, position by <= {pos:.5f}")
    assert m["common_images"] == a[i] == m["registered_images"]
    assert rot < 0.1 and pos < 1e-3
PY
}

run_slurm
grep -q "^kernel tasks: job" "$work/submit.log" || fail "no kernel job submitted"
compare

# A lost leaf task (its record gone): a rerun submits that task alone.
lost=$(find "$work/staged/.tmr_work" -name 'leaf*.result' | sort | head -n1)
rm "$lost"
rm -rf "$work/staged/0" "$work/staged/report.json"
run_slurm
grep -q "^kernel tasks" "$work/submit.log" && fail "kernel tasks submitted again"
if [[ $(grep -c "^leaf tasks" "$work/submit.log") != 1 ]] ||
   ! grep -q "(1 tasks)" "$work/submit.log"; then
  fail "expected one leaf task again"
fi
compare

# The merge stage by parts: 3 groups of one cluster each in this scene.
run_slurm parts --Tmr.memory_budget 0.2
grep -q "^merge by parts: job .* (3 groups)" "$work/submit.log" ||
  fail "expected an array job of 3 group merges"
compare parts
echo "tmr_slurm_test: passed"
