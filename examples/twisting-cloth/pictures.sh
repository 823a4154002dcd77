#!/bin/sh
# The twisting cloth's pictures (README.md) in one command: runs the deck (200 steps of fix
# sissm, 1 rank) writing the strip's triangles every 5 steps to frames/twist.STEP.vtp, renders
# steps 0, 100, 160 and 200 as shaded surfaces (tools/render_mesh.py: one side of the cloth
# ochre, the other blue, so that the twist shows) to twist.STEP.png, and all 41 frames to the
# animation twist.gif. About a minute.
#   ./pictures.sh
# Environment: LMP (default ../../build/lmp), PYTHON (default /usr/bin/python3 when it exists:
# needs numpy and matplotlib).
set -e
cd "$(dirname "$0")"
LMP=${LMP:-../../build/lmp}
[ -x /usr/bin/python3 ] && PYTHON=${PYTHON:-/usr/bin/python3}
PYTHON=${PYTHON:-python3}
render() {
  "$PYTHON" ../../tools/render_mesh.py --color "#d9a441" --back-color "#4a78b5" --elev 20 \
    --azim -70 --zoom 1.9 --limits -0.105 0.105 -0.03 0.03 -0.03 0.03 --size 8 4 "$@"
}
"$LMP" -in in.twisting-cloth -var frames 5 -log none -screen none
for step in 0 100 160 200; do
  render frames/twist.$step.vtp -o twist.$step.png \
    --title "step {step}: each end turned $((step * 360 / 200)) degrees"
done
render frames/twist.pvd -o twist.gif --title "t = {time:.3f} s" --fps 10
