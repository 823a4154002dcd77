#!/usr/bin/env bash
# Set up if needed, then run the main demo scene: projectile impact on a glass-like cylinder
# (examples/impact).  Output goes to build/demo/ (log.lammps, dump of damage).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$here/tools/setup.sh"
out="$here/build/demo"
mkdir -p "$out"
deck=${1:-in.impact.nosb}
echo "[demo] $deck in $out"
cd "$out"
cp "$here"/examples/impact/impact.geometry .
"$here/build/lmp" -in "$here/examples/impact/$deck" -log "$out/log.lammps"
echo "[demo] done: $out/log.lammps"
