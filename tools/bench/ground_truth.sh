# Sourced by the benchmark scripts: the ground truth of a photo set.
# ground_truth DATA SET OUT: prints the folder of SET's ground truth in
# COLMAP text form, or nothing when the set has none. The temple ring's
# has 16 cameras rolled 180 degrees against their photos; templering_gt.py
# writes it corrected to OUT/templeRing_gt (docs/benchmarks.md).
ground_truth() {
  local gt="$1/$2/gt/colmap_text"
  [[ -f "$gt/images.txt" ]] || return 0
  if [[ $2 == middlebury_templeRing ]]; then
    python3 tools/bench/templering_gt.py "$gt" "$3/templeRing_gt" >/dev/null
    gt="$3/templeRing_gt"
  fi
  echo "$gt"
}
