#!/usr/bin/env bash
# The main job of README.md on a built-in example: builds tmr, generates a
# synthetic scene as a COLMAP database in out/example/, and summarises its
# match graph (similarity graph S of the paper).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
out=out/example
rm -rf "$out"
echo "[example] writing a synthetic 60-image scene to $out/database.db"
build/tools/tmr_synth --database_path "$out/database.db" --model_path "$out/gt" \
  --num_images 60 --num_points3D 3000 --seed 1
echo "[example] match graph of $out/database.db"
build/tools/tmr_graph_info --database_path "$out/database.db"
