#!/usr/bin/env bash
# Installs the dependencies (once per machine), then configures and builds tmr
# in ./build (Release, Ninja, 2 jobs). Extra arguments go to cmake's configure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup_dependencies.sh
echo "[build] configuring tmr in build/"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >build.configure.log 2>&1 ||
  { cat build.configure.log >&2; echo "[build] error: configure failed" >&2; exit 1; }
rm -f build.configure.log
echo "[build] building tmr with ${TMR_JOBS:-2} jobs"
cmake --build build --parallel "${TMR_JOBS:-2}"
