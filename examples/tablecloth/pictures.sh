#!/bin/sh
# The tablecloth's pictures (README.md) in one command: the CI run (300 steps, D = 1e-4 N m) and
# the bending sweep at CI size (D = 0, 1e-5, 1e-4, 1e-3 N m, 1500 steps each), one after the
# other on 1 rank, each writing its positions (dump.NAME.STEP, for drape.py), its last frame
# of triangles (frames/NAME.STEP.vtp) and its log (frames/log.NAME); then each last frame is
# rendered as a shaded surface on the table (tools/render_mesh.py) to NAME.STEP.png, and each
# drape drawn from above with its overhang profiles by drape.py to drape.NAME.svg (and its
# numbers printed). About 5 minutes.
#   ./pictures.sh            ci.300.png, D{no,1e-5,1e-4,1e-3}.1500.png and drape.*.svg
#   ./pictures.sh full       full.D{no,1e-5,1e-4,1e-3}.40000.png from the frames that
#                            run_full.sh writes (frames/full.DX.40000.vtp; run it first)
# Environment: LMP (default ../../build/lmp), PYTHON (default /usr/bin/python3 when it exists:
# needs numpy and matplotlib).
set -e
cd "$(dirname "$0")"
LMP=${LMP:-../../build/lmp}
[ -x /usr/bin/python3 ] && PYTHON=${PYTHON:-/usr/bin/python3}
PYTHON=${PYTHON:-python3}
# the cloth (a warm white, its underside a shade darker) on the table: the block of in.tablecloth
render() {
  "$PYTHON" ../../tools/render_mesh.py --color "#e8dcc4" --back-color "#c9b99a" \
    --box -0.4 0.4 -0.4 0.4 -0.75 0 --box-color "#8b5a2b" --elev 28 --azim -55 --zoom 1.35 \
    --limits -0.65 0.65 -0.65 0.65 -0.78 0.1 "$@"
}
modulus() { [ "$1" = no ] && echo "no bending" || echo "D = $1 N m"; }

if [ "${1:-}" = full ]; then
  for d in no 1e-5 1e-4 1e-3; do
    render frames/full.D$d.40000.vtp -o full.D$d.40000.png \
      --title "$(modulus $d), 39911 vertices, at rest"
  done
  exit 0
fi

mkdir -p frames
"$LMP" -in in.tablecloth -var frames 300 -log frames/log.ci -screen none
render frames/ci.300.vtp -o ci.300.png --title "$(modulus 1e-4), t = {time:.1f} s"
"$PYTHON" drape.py cloth_ci.obj dump.ci.300 --svg drape.ci.svg
for d in no 1e-5 1e-4 1e-3; do
  "$LMP" -in in.tablecloth -var bend $d -var steps 1500 -var every 500 -var frames 1500 \
    -var name D$d -log frames/log.D$d -screen none
  render frames/D$d.1500.vtp -o D$d.1500.png --title "$(modulus $d), t = {time:.1f} s"
  "$PYTHON" drape.py cloth_ci.obj dump.D$d.1500 --svg drape.D$d.svg
done
