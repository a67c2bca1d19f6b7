#!/usr/bin/env bash
# Calibration of the kernel check on real photos: what share of
# the verified matches, and how many image pairs, does a correct model
# contradict (CheckMatchConsistency, `tmr_eval --database_path`), and what
# does a wrong one? Reads the workspaces of tools/bench/bench_reconstruct.sh
# (run it first) and, per photo set:
# - correct: tmr_reconstruct's model and automatic_reconstructor's, each
#   against its own database;
# - focal: `colmap mapper` on a copy of tmr's database with every focal
#   length scaled by 0.7 or 1.4 and held there (the mapper's failure the
#   check exists for: focal length traded against depth);
# - moved: tmr's model with the later half of its photos (by name) turned
#   by 2 degrees about their centre and shifted by 5% of the scene's extent,
#   tracks removed (every verified match is tested).
# Each is scored against the ground truth where the set has one, and checked
# twice: with the check's defaults (matches seen under less than COLMAP's
# triangulation angle, or that no third photo confirms, not tested) and with
# every match tested.
# Usage: tools/bench/kernel_check_calibration.sh [SET ...]
# Output: a markdown table; out/kernel_check_calibration/results.csv.
set -euo pipefail
cd "$(dirname "$0")/../.."
COLMAP="${TMR_DEPS_PREFIX:-/opt/tmr-deps}/colmap-4.1.1/bin/colmap"
BIN=build/tools
IN=out/bench_reconstruct
OUT=out/kernel_check_calibration
DATA="${DATA:-../shared/data}"
source tools/bench/ground_truth.sh
mkdir -p "$OUT"
CSV="$OUT/results.csv"
echo "set,model,images,matches,low_angle_share,inconsistent_share_all,inconsistent_pairs_all,inconsistent_share,pairs,inconsistent_pairs,consistent,median_rot_deg" >"$CSV"

# check SET NAME MODEL DATABASE GT: one row, with the check's default
# triangulation angle and third-view confirmation, and with every match tested
# (angle 0, third view not required).
check() {
  local json="$OUT/$1/$2.json"
  # Without ground truth the model is its own reference (counts only).
  if ! "$BIN/tmr_eval" --gt "${5:-$3}" --model "$3" --database_path "$4" --output_json "$json" >/dev/null 2>&1 ||
    ! "$BIN/tmr_eval" --model "$3" --database_path "$4" --match_min_tri_angle 0 --match_third_view 0 \
      --output_json "$json.all" >/dev/null 2>&1; then
    echo "| $1 | $2 | no model |"; return
  fi
  python3 - "$json" "$1" "$2" "$CSV" "$5" <<'PY'
import json, sys
path, name, kind, csv, gt = sys.argv[1:6]
def largest(p): return max(json.load(open(p))["models"], key=lambda m: m["registered_images"])
m, every = largest(path), largest(path + ".all")["match_consistency"]
c = m["match_consistency"]
share = c["inconsistent"] / max(c["matches"], 1)
share_all = every["inconsistent"] / max(every["matches"], 1)
low = c["low_angle"] / max(c["low_angle"] + c["tested"], 1)
rot = f'{m["rotation_error_deg"]["median"]:.2f}' if gt else ""
open(csv, "a").write(f"{name},{kind},{m['registered_images']},{c['matches']},{low:.4f},{share_all:.5f},"
                     f"{every['inconsistent_pairs']},{share:.5f},{c['pairs']},{c['inconsistent_pairs']},"
                     f"{str(c['consistent']).lower()},{rot}\n")
print(f"| {name} | {kind} | {m['registered_images']} | {c['matches']:,} | {100 * low:.0f}% | "
      f"{100 * share_all:.2f}%, {every['inconsistent_pairs']} | {100 * share:.2f}%, {c['inconsistent_pairs']} of {c['pairs']} | "
      f"{'yes' if c['consistent'] else '**no**'} | {rot + '°' if rot else '—'} |")
PY
}

sets=("$@")
if [[ ${#sets[@]} -eq 0 ]]; then
  for dir in "$IN"/*/; do [[ -d "$dir/tmr/sparse/0" ]] && sets+=("$(basename "$dir")"); done
fi
echo "| set | model | registered | verified matches | below the angle | inconsistent, pairs (every match) | inconsistent, pairs (as the check tests) | passes | median rotation error |"
echo "|---|---|---|---|---|---|---|---|---|"
for set in "${sets[@]}"; do
  ws="$IN/$set/tmr"
  [[ -d "$ws/sparse/0" ]] || { echo "no tmr_reconstruct workspace for $set: run bench_reconstruct.sh" >&2; continue; }
  gt=$(ground_truth "$DATA" "$set" "$OUT")
  dir="$OUT/$set"; rm -rf "$dir"; mkdir -p "$dir"
  check "$set" correct "$ws/sparse/0" "$ws/database.db" "$gt"
  [[ -d "$IN/$set/stock/sparse/0" ]] &&
    check "$set" "correct (stock)" "$IN/$set/stock/sparse/0" "$IN/$set/stock/database.db" "$gt"
  for scale in 0.7 1.4; do
    db="$dir/focal$scale.db"
    cp "$ws/database.db" "$db"
    python3 - "$db" "$scale" <<'PY'
import sqlite3, struct, sys
db = sqlite3.connect(sys.argv[1]); scale = float(sys.argv[2])
# COLMAP model ids with one focal (SIMPLE_*: 0, 2, 8) or fx, fy first.
for cid, model, params in db.execute("SELECT camera_id, model, params FROM cameras").fetchall():
    p = list(struct.unpack(f"{len(params) // 8}d", params))
    for i in ([0] if model in (0, 2, 8) else [0, 1]):
        p[i] *= scale
    db.execute("UPDATE cameras SET params = ?, prior_focal_length = 1 WHERE camera_id = ?",
               (struct.pack(f"{len(p)}d", *p), cid))
db.commit()
PY
    mkdir -p "$dir/focal$scale"
    "$COLMAP" mapper --database_path "$db" --image_path "$DATA/$set/images" --output_path "$dir/focal$scale" \
      --Mapper.num_threads 2 --Mapper.ba_refine_focal_length 0 >"$dir/focal$scale.log" 2>&1 || true
    if [[ -d "$dir/focal$scale/0" ]]; then
      check "$set" "focal × $scale" "$dir/focal$scale/0" "$db" "$gt"
    else
      echo "| $set | focal × $scale | no model |"
    fi
  done
  moved="$dir/moved"; mkdir -p "$moved"
  "$COLMAP" model_converter --input_path "$ws/sparse/0" --output_path "$moved" --output_type TXT >/dev/null 2>&1
  python3 - "$moved" <<'PY'
import math, os, sys
d = sys.argv[1]
os.remove(f"{d}/rigs.txt"); os.remove(f"{d}/frames.txt")  # poses from images.txt
def mul(A, B): return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def apply(A, v): return [sum(A[i][k] * v[k] for k in range(3)) for i in range(3)]
def T(A): return [list(r) for r in zip(*A)]
def rot(q):
    w, x, y, z = q
    return [[1-2*(y*y+z*z), 2*(x*y-w*z), 2*(x*z+w*y)],
            [2*(x*y+w*z), 1-2*(x*x+z*z), 2*(y*z-w*x)],
            [2*(x*z-w*y), 2*(y*z+w*x), 1-2*(x*x+y*y)]]
def quat(R):  # Shepperd's method: divide by the largest component
    tr = R[0][0] + R[1][1] + R[2][2]
    if tr > max(R[0][0], R[1][1], R[2][2]):
        w = math.sqrt(1 + tr) / 2
        return [w, (R[2][1]-R[1][2])/(4*w), (R[0][2]-R[2][0])/(4*w), (R[1][0]-R[0][1])/(4*w)]
    i = max(range(3), key=lambda k: R[k][k]); j, k = (i + 1) % 3, (i + 2) % 3
    v = [0.0, 0.0, 0.0]
    v[i] = math.sqrt(max(0.0, 1 + R[i][i] - R[j][j] - R[k][k])) / 2
    v[j] = (R[j][i] + R[i][j]) / (4 * v[i]); v[k] = (R[k][i] + R[i][k]) / (4 * v[i])
    return [(R[k][j] - R[j][k]) / (4 * v[i])] + v
lines = [l for l in open(f"{d}/images.txt") if not l.startswith("#")]
images = []
for head, points in zip(lines[0::2], lines[1::2]):
    f = head.split()
    p = points.split()
    for i in range(2, len(p), 3): p[i] = "-1"  # no tracks: every match is tested
    images.append({"id": f[0], "q": list(map(float, f[1:5])), "t": list(map(float, f[5:8])),
                   "camera": f[8], "name": f[9], "points": " ".join(p)})
for im in images:
    R = rot(im["q"]); im["C"] = [-x for x in apply(T(R), im["t"])]
moved = sorted(images, key=lambda im: im["name"])[len(images) // 2:]
c = [sum(im["C"][k] for im in moved) / len(moved) for k in range(3)]
extent = math.dist([min(im["C"][k] for im in images) for k in range(3)],
                   [max(im["C"][k] for im in images) for k in range(3)])
a = math.radians(2.0)
Rm = [[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]]
for im in moved:  # a moved camera's world point X is at Rm (X - c) + c + shift
    R2 = mul(rot(im["q"]), T(Rm))
    C2 = [v + c[k] + (0.05 * extent if k == 0 else 0) for k, v in
          enumerate(apply(Rm, [im["C"][k] - c[k] for k in range(3)]))]
    im["q"] = quat(R2); im["t"] = [-x for x in apply(R2, C2)]
with open(f"{d}/images.txt", "w") as out:
    for im in images:
        out.write(f"{im['id']} {' '.join(map(repr, im['q']))} {' '.join(map(repr, im['t']))} "
                  f"{im['camera']} {im['name']}\n{im['points']}\n")
open(f"{d}/points3D.txt", "w").close()
PY
  check "$set" "half moved 2°, 5%" "$moved" "$ws/database.db" "$gt"
done
