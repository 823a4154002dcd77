#!/usr/bin/env bash
# Build (if needed) and run tools/bench_passes.cpp: per-pass times of peri/nosb's bond loops on
# an n^3 lattice in one process, against the core library of build/ (bash tools/setup.sh first).
# Usage: bash tools/bench_passes.sh [n, default 38] [rounds, default 15]
#        PERI_SISSM_PASSES=plain bash tools/bench_passes.sh   # the version without fused
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
lib="$here/build/src/core/libperisissm_core.a"
exe="$here/build/bench_passes"
if [ ! -f "$lib" ]; then
  echo "bench_passes: $lib not found; run bash tools/setup.sh first" >&2
  exit 1
fi
if [ ! -x "$exe" ] || [ "$lib" -nt "$exe" ] || [ "$here/tools/bench_passes.cpp" -nt "$exe" ] ||
   [ "$here/unittest/core/peri/cluster.h" -nt "$exe" ]; then
  g++ -O3 -DNDEBUG -std=c++17 -I"$here/src/core" -I"$here/unittest/core" -I/usr/include/eigen3 \
    "$here/tools/bench_passes.cpp" "$lib" -o "$exe"
fi
exec "$exe" "$@"
