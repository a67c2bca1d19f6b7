#!/usr/bin/env bash
# The main job of README.md on a built-in example: builds tmr, generates a
# synthetic scene as a COLMAP database in out/example/ (two dense places
# joined by a corridor of photos, and a third place on its own), summarises
# its match graph, reconstructs it with tmr_mapper (TMR-tree, kernel and leaf
# tasks with COLMAP's mapper, merges), scores the models against the ground
# truth with tmr_eval and writes the run's report page with the scores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
out=out/example
rm -rf "$out"
echo "[example] writing a synthetic scene to $out/database.db"
build/tools/tmr_synth --database_path "$out/database.db" --model_path "$out/gt" --seed 1
echo "[example] match graph of $out/database.db"
build/tools/tmr_graph_info --database_path "$out/database.db"
echo "[example] tmr_mapper: reconstruction on the TMR-tree into $out/sparse"
build/tools/tmr_mapper --database_path "$out/database.db" --output_path "$out/sparse"
echo "[example] models scored against the ground truth"
build/tools/tmr_eval --gt "$out/gt" --model "$out/sparse" --output_json "$out/sparse/eval.json"
echo "[example] the report page again, with the scores"
build/tools/tmr_mapper report --plan "$out/sparse/plan.txt"
echo "[example] report page: $out/sparse/report.html (open it in a browser);" \
  "partition picture: $out/sparse/partition.png, tree: $out/sparse/tree.json"
