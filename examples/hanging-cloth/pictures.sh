#!/bin/sh
# The hanging cloth's picture (README.md) in one command: runs the deck (the shipped 3038-vertex
# cloth, fix sissm at 2 ms) for 300 steps (0.6 s) on 1 rank, writing the cloth's triangles every
# 50 steps to frames/hanging.STEP.vtp, and renders the last frame as a shaded surface
# (tools/render_mesh.py) to hanging.png. About 3 minutes.
#   ./pictures.sh
# Environment: LMP (default ../../build/lmp), PYTHON (default /usr/bin/python3 when it exists:
# needs numpy and matplotlib).
set -e
cd "$(dirname "$0")"
LMP=${LMP:-../../build/lmp}
[ -x /usr/bin/python3 ] && PYTHON=${PYTHON:-/usr/bin/python3}
PYTHON=${PYTHON:-python3}
"$LMP" -in in.hanging -var steps 300 -var every 50 -var frames 50 -log none -screen none
"$PYTHON" ../../tools/render_mesh.py frames/hanging.300.vtp -o hanging.png --elev 20 \
  --azim -120 --zoom 1.25 --title "hanging cloth, t = {time:.1f} s"
