#!/bin/sh
# The impact's damage picture (README.md) in one command: runs in.impact.nosb and in.impact.lps
# (1000 steps each, 1 rank) with their particles dumped at the end (dump.impact.nosb,
# dump.impact.lps: id x y z and damage), and draws the mid-plane slice z = 0 (the plane of the
# cylinder's axis and of the impact) of both, side by side, coloured by damage
# (tools/render_particles.py) to damage.png; fragments that flew beyond 1.5 mm of the cylinder
# are outside the picture. About a minute.
#   ./pictures.sh
# Environment: LMP (default ../../build/lmp), PYTHON (default /usr/bin/python3 when it exists:
# needs numpy and matplotlib).
set -e
cd "$(dirname "$0")"
LMP=${LMP:-../../build/lmp}
[ -x /usr/bin/python3 ] && PYTHON=${PYTHON:-/usr/bin/python3}
PYTHON=${PYTHON:-python3}
"$LMP" -in in.impact.nosb -var dump 1000 -log none -screen none
"$LMP" -in in.impact.lps -var dump 1000 -log none -screen none
"$PYTHON" ../../tools/render_particles.py dump.impact.nosb dump.impact.lps --column v_damage \
  --slice z --at 0 --window -0.0065 0.0065 -0.0075 0.0015 --labels peri/nosb peri/lps \
  --range 0 1 --label "damage (broken bond fraction)" \
  --title "impact at 100 m/s, slice z = 0, t = 0.1 ms" --size 8 3.8 -o damage.png
