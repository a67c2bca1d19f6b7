#!/usr/bin/env bash
# The main job of README.md on a built-in example: builds tmr, generates a
# synthetic scene as a COLMAP database in out/example/ (two dense places
# joined by a corridor of photos, and a third place on its own), summarises
# its match graph and builds its TMR-tree (tree.json and partition.png).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
out=out/example
rm -rf "$out"
echo "[example] writing a synthetic scene to $out/database.db"
build/tools/tmr_synth --database_path "$out/database.db" --model_path "$out/gt" --seed 1
echo "[example] match graph of $out/database.db"
build/tools/tmr_graph_info --database_path "$out/database.db"
echo "[example] TMR-tree of $out/database.db"
build/tools/tmr_partition --database_path "$out/database.db" --output_path "$out/partition"
