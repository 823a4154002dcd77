#!/bin/sh
# The cloth-on-ball pictures (README.md) in one command: runs the deck at its own size (3000
# steps of 20 us, fix nve, 1 rank) for 1, 3 and 6 layers, writing the triangles of the ball and
# the layers every 50 steps to frames/layersL.STEP.vtp, renders the start and 0.04 s (step
# 2000) as shaded surfaces (tools/render_mesh.py: the ball grey, the layers red, orange, yellow,
# green, blue, purple from the bottom up) to layersL.0.png and layersL.2000.png, and the 61
# frames of the single layer to the animation layers1.gif. About 3 minutes (the 6 layers take
# most of it).
#   ./pictures.sh            1, 3 and 6 layers
#   ./pictures.sh 1          one of them
# Environment: LMP (default ../../build/lmp), PYTHON (default /usr/bin/python3 when it exists:
# needs numpy and matplotlib).
set -e
cd "$(dirname "$0")"
LMP=${LMP:-../../build/lmp}
[ -x /usr/bin/python3 ] && PYTHON=${PYTHON:-/usr/bin/python3}
PYTHON=${PYTHON:-python3}
[ $# -gt 0 ] || set -- 1 3 6
render() {
  "$PYTHON" ../../tools/render_mesh.py --mesh-colors "#9a9a9a" "#c0392b" "#e67e22" "#f1c40f" \
    "#27ae60" "#2e86c1" "#7d3c98" --stack --elev 30 --azim -60 --zoom 1.3 \
    --limits -0.11 0.11 -0.11 0.11 -0.06 0.07 "$@"
}
for layers in "$@"; do
  "$LMP" -in in.cloth-on-ball -var layers "$layers" -var frames 50 -log none -screen none
  word=layers
  [ "$layers" != 1 ] || word=layer
  for step in 0 2000; do
    render frames/layers$layers.$step.vtp -o layers$layers.$step.png \
      --title "$layers $word, t = {time:.2f} s"
  done
  if [ "$layers" = 1 ]; then
    render frames/layers1.pvd -o layers1.gif --title "t = {time:.3f} s" --fps 15
  fi
done
