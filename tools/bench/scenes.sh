# The benchmark scenes of tools/bench/*.sh, sourced by them: names, the
# tmr_synth options of each, and writing one once. Needs BIN (the build's
# tools/ folder), COLMAP (its program) and THREADS.

# Prints tmr_synth's options for SCENE (see bench_mapper.sh's usage).
synth_args() {
  local seed=0 scene=$1
  if [[ $scene =~ ^(.*[0-9])s([0-9]+)$ ]]; then scene=${BASH_REMATCH[1]} seed=${BASH_REMATCH[2]}; fi
  echo "--seed $seed"
  case "$scene" in
    city*) local n=${scene#city}; echo "--family city --city_blocks_x $n --city_blocks_y $n" ;;
    places*) local n=${scene#places}
      echo "--family places --num_places $n --num_unlinked_places 0 --link_spacing 9" ;;
    plazas*) local n=${scene#plazas}
      echo "--family plazas --num_places $n --cameras_per_place 120" \
        "--detection_probability 0.35 --match_probability 0.7 --match_angle_falloff_deg 12" ;;
    *) echo "unknown scene $1" >&2; exit 2 ;;
  esac
}

# Writes SCENE's database and ground truth to DIR (DIR/database.db, DIR/gt)
# unless DIR/database.db exists.
ensure_scene() {
  local dir=$1 scene=$2
  [[ -f "$dir/database.db" ]] && return 0
  rm -rf "$dir" && mkdir -p "$dir/images"
  # shellcheck disable=SC2046
  "$BIN/tmr_synth" --database_path "$dir/database.db" --model_path "$dir/gt" $(synth_args "${scene%v}")
  if [[ $scene == *v ]]; then  # two-view geometries verified again by COLMAP
    sqlite3 "$dir/database.db" "DELETE FROM two_view_geometries"
    "$COLMAP" geometric_verifier --database_path "$dir/database.db" --num_threads "$THREADS" \
      >"$dir/geometric_verifier.log" 2>&1
  fi
}

# Writes SCENE's plan into RUN (emptied first) with `tmr_mapper partition`
# on THREADS threads and TMR_ARGS: the scene is made first if need be
# (ensure_scene, in out/bench_mapper/SCENE); the plan and progress lines go
# to RUN.status, errors to RUN.partition.log.
plan_scene() {
  local scene=$1 run=$2 threads=$3 dir=out/bench_mapper/$1
  ensure_scene "$dir" "$scene"
  rm -rf "$run" && mkdir -p "$run"
  # shellcheck disable=SC2086
  "$BIN/tmr_mapper" partition --database_path "$dir/database.db" --output_path "$run" \
    --Mapper.num_threads "$threads" ${TMR_ARGS:-} >"$run.status" 2>"$run.partition.log"
}

# Makes OUT and its results.csv with the columns HEADER unless it exists.
start_results() {
  mkdir -p "$OUT"
  [[ -f "$OUT/results.csv" ]] || echo "$1" >"$OUT/results.csv"
}
