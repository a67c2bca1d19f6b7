#!/usr/bin/env bash
# Matching thousands of unordered photos: tmr_reconstruct with
# retrieval matching (a vocabulary built from the photos' own features,
# each photo with its 30 most similar) on sets of 200 to 2,000 photos, and
# with exhaustive matching of the same features where that is affordable.
# The photos are views cut from the 107 photos of ../shared/data: each a
# window of 45-75% of a photo's width at a random place (of the photo
# scaled to 2 x SIZE px), scaled to at most SIZE px, under a name that
# hides where it came from (the first N views of one list of 2,000, so
# every set holds views of every photo). Prints,
# per set size: extraction, vocabulary and matching time and the matching
# time per photo, pairs matched and verified, the share of exhaustive
# matching's verified pairs that retrieval also verified (recall), and the
# registered views, largest model and models; appends to
# out/bench_retrieval/results.csv.
#
# Usage: tools/bench/bench_retrieval.sh [N ...]   (default: 200 500 1000 2000)
# Environment: DATA (default ../shared/data), THREADS (default 2), SIZE
# (default 640), FEATURES (default 2048 per view: CPU matching of 8,192
# would take hours at 2,000 views), EXHAUSTIVE_MAX (default 500: sets up to
# this size are also matched exhaustively), MAP_MAX (default 1000: larger
# sets are stopped after matching, their times read from the log; mapping
# 1,000 views of one camera each took 27 min), TMR_ARGS (more options).
set -euo pipefail
cd "$(dirname "$0")/../.."
BIN=build/tools
OUT=out/bench_retrieval
DATA="${DATA:-../shared/data}"
THREADS="${THREADS:-2}"
SIZE="${SIZE:-640}"
FEATURES="${FEATURES:-2048}"
EXHAUSTIVE_MAX="${EXHAUSTIVE_MAX:-500}"
MAP_MAX="${MAP_MAX:-1000}"
[[ -x "$BIN/tmr_reconstruct" ]] || { echo "run tools/build.sh first" >&2; exit 1; }
command -v oiiotool >/dev/null || { echo "oiiotool not found (apt-get install openimageio-tools)" >&2; exit 1; }
[[ -d "$DATA" ]] || { echo "no photo sets at $DATA" >&2; exit 1; }
mkdir -p "$OUT/views"
CSV="$OUT/results.csv"
[[ -f "$CSV" ]] || echo "views,matcher,extraction_s,vocabulary_s,matching_s,matching_s_per_view,matched_pairs,verified_pairs,recall,registered,largest,models,total_s,peak_mib" >"$CSV"

# The 2,000 views, cut once (deterministic: seed 0).
if [[ ! -f "$OUT/views/done" ]]; then
  echo "cutting 2,000 views from the photos of $DATA"
  python3 - "$DATA" "$OUT/views" "$SIZE" <<'PY'
import glob, hashlib, os, random, subprocess, sys
data, out, size = sys.argv[1], sys.argv[2], int(sys.argv[3])
photos = sorted(p for p in glob.glob(f"{data}/*/images/*") if p.lower().endswith((".jpg", ".jpeg", ".png")))
rng = random.Random(0)
order = []
while len(order) < 2000:
    batch = photos[:]; rng.shuffle(batch); order += batch
lines = order[:2000]
open(f"{out}/list.txt", "w").write("\n".join(lines) + "\n")
# Each photo is decoded once, scaled to at most 2 x SIZE px (a view covers
# at least 45% of it, so it is still downscaled to SIZE).
os.makedirs(f"{out}/scaled", exist_ok=True)
# (--resize to computed sizes: oiiotool's --fit pads to a square.)
def fitted(w, h, limit):
    scale = min(1.0, limit / max(w, h))
    return max(1, round(w * scale)), max(1, round(h * scale))
scaled, sizes = {}, {}
for k, photo in enumerate(sorted(set(lines))):
    scaled[photo] = f"{out}/scaled/{k:03d}.png"
    info = subprocess.run(["oiiotool", "--info", photo], capture_output=True, text=True).stdout
    w, h = info.split(":", 1)[1].split(",")[0].strip().split(" x ")
    sizes[photo] = fitted(int(w), int(h), 2 * size)
    subprocess.run(["oiiotool", photo, "--resize", "{}x{}".format(*sizes[photo]), "--eraseattrib", ".*",
                    "-o", scaled[photo]], check=True)
for i, photo in enumerate(lines):
    w, h = sizes[photo]
    share = rng.uniform(0.45, 0.75)
    cw, ch = int(w * share), int(h * share)
    x, y = rng.randint(0, w - cw), rng.randint(0, h - ch)
    name = hashlib.sha1(f"{i}:{photo}".encode()).hexdigest()[:16] + ".jpg"
    # No EXIF: a crop's focal length is not its photo's.
    subprocess.run(["oiiotool", scaled[photo], "--cut", f"{cw}x{ch}+{x}+{y}",
                    "--resize", "{}x{}".format(*fitted(cw, ch, size)),
                    "--eraseattrib", ".*", "-o", f"{out}/{i:04d}_{name}"], check=True)
    if (i + 1) % 200 == 0: print(f"  {i + 1} views", flush=True)
PY
  touch "$OUT/views/done"
fi

# run N MATCHER: one tmr_reconstruct into $OUT/N/MATCHER (features copied
# from the retrieval run for the exhaustive one, so only matching differs).
run() {
  local n=$1 matcher=$2 ws="$OUT/$1/$2"
  rm -rf "$ws" && mkdir -p "$ws"
  if [[ $matcher == exhaustive ]]; then
    cp "$OUT/$n/retrieval/database.db" "$ws/database.db"
    sqlite3 "$ws/database.db" "DELETE FROM matches; DELETE FROM two_view_geometries;"
  fi
  # shellcheck disable=SC2086
  /usr/bin/time -f "%e %M" -o "$ws/log.time" "$BIN/tmr_reconstruct" "$OUT/$n/photos" "$ws" \
    --num_threads "$THREADS" --matcher "$matcher" --FeatureExtraction.max_image_size "$SIZE" \
    --SiftExtraction.max_num_features "$FEATURES" ${TMR_ARGS:-} >"$ws/log" 2>&1 &
  local pid=$!
  # Above MAP_MAX views the run is stopped once matching is done (the line
  # that chooses the mapper settings follows it).
  while [[ $n -gt $MAP_MAX ]] && kill -0 "$pid" 2>/dev/null; do
    if grep -q "move along the viewing direction: mapping" "$ws/log"; then
      pkill -TERM -P "$pid" tmr_reconstruct || true
      break
    fi
    sleep 2
  done
  wait "$pid" || true
}

sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(200 500 1000 2000)
printf "%6s %-10s %9s %9s %9s %8s %8s %8s %7s %11s %7s %7s\n" views matcher "extract s" "vocab s" \
  "match s" "s/view" pairs verified recall registered largest models
for n in "${sizes[@]}"; do
  rm -rf "$OUT/$n/photos" && mkdir -p "$OUT/$n/photos"
  mapfile -t views < <(find "$OUT/views" -name '*.jpg' | sort)
  for view in "${views[@]:0:n}"; do
    ln -s "$(realpath "$view")" "$OUT/$n/photos/${view##*_}"
  done
  matchers=(retrieval)
  [[ $n -le $EXHAUSTIVE_MAX ]] && matchers+=(exhaustive)
  for matcher in "${matchers[@]}"; do run "$n" "$matcher"; done
  for matcher in "${matchers[@]}"; do
    python3 - "$OUT/$n" "$matcher" "$n" "$CSV" <<'PY'
import re, sqlite3, sys
sys.path.insert(0, "tools/bench")
from tmr_summary import first_number, stage_seconds
base, matcher, n, csv = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
ws = f"{base}/{matcher}"
log = open(f"{ws}/log").read()
summary = open(f"{ws}/summary.txt").read() if re.search("registered:", log) else ""
wall, peak = open(f"{ws}/log.time").read().split()[-2:]
extraction, matching = stage_seconds(summary)
vocabulary = first_number(r"vocabulary tree built in ([0-9.]+) s", log)
if not summary:  # stopped after matching (MAP_MAX): times from the log's stamps
    stamp = lambda p: first_number(r"\[tmr +([0-9.]+) s\] " + p, log)
    extraction = stamp("(?:building a vocabulary|matching \\d+ images)")
    matching = stamp(r".*move along the viewing direction: mapping") - extraction
def pairs(db, verified):  # by image names: extraction numbers images in the order they finish
    c = sqlite3.connect(f"file:{db}?mode=ro", uri=True)  # reads a stopped run's WAL too
    names = dict(c.execute("SELECT image_id, name FROM images"))
    q = "SELECT pair_id FROM two_view_geometries WHERE rows >= 15" if verified else "SELECT pair_id FROM matches"
    return {frozenset((names[p // 2147483647], names[p % 2147483647])) for (p,) in c.execute(q)}
matched = len(pairs(f"{ws}/database.db", False))
verified = pairs(f"{ws}/database.db", True)
recall = ""
if matcher == "retrieval":
    try:
        exhaustive = pairs(f"{base}/exhaustive/database.db", True)
        recall = f"{len(verified & exhaustive) / max(len(exhaustive), 1):.3f}"
    except Exception:
        pass
sizes = [int(m) for m in re.findall(r"sparse/\d+: (\d+) images", summary)]
registered, largest, models = sum(sizes), max(sizes, default=0), len(sizes)
if not summary:  # not mapped
    registered, largest, models = "", "", ""
open(csv, "a").write(f"{n},{matcher},{extraction:.1f},{vocabulary:.1f},{matching:.1f},{matching / n:.3f},{matched},{len(verified)},"
                     f"{recall},{registered},{largest},{models},{wall},{int(peak) // 1024}\n")
print(f"{n:>6} {matcher:<10} {extraction:>9.1f} {vocabulary:>9.1f} {matching:>9.1f} {matching / n:>8.3f} {matched:>8} "
      f"{len(verified):>8} {recall:>7} {registered:>11} {largest:>7} {models:>7}")
PY
  done
done
