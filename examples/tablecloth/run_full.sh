#!/bin/sh
# The tablecloth's bending sweep at the SISSM authors' size (README.md, "Full size"), in one
# command: makes cloth_full.obj (39911 vertices, 6.5 mm triangles) when it is missing, runs the
# deck for D = 0 (bend no), 1e-5, 1e-4 and 1e-3 N m for 1.5 s, two runs at a time (one per
# core), each writing log.full.DX, dump.full.DX.STEP and frames/full.DX.STEP.vtp (the cloth's
# triangles, which ./pictures.sh full renders) every EVERY steps, then lets each drape settle:
# from the positions at 1.5 s, at rest, SETTLE more steps with the drag raised to SETTLEDAMP
# (the overhang's swing is still +-0.1 in drape coefficient at 1.5 s with the deck's 2 /s;
# 25 /s damps it beyond critically), and measures each drape at the end
# with drape.py (drape.full.DX.svg) and prints the table (at 1.5 s and settled).
# By default the runs are explicit (fix nve, dt = 50 us: 30000 steps): at this size that is
# 6.5 to 8 times cheaper than fix sissm at the authors' 1 ms (README.md, "Full size").
# SOLVER=krylov DT=1e-3 STEPS=1500 EVERY=250 runs the sweep with fix sissm instead.
# CONTACT=yes adds the cloth's self-contact (the deck's -var contact yes: fix nosb/contact with
# dmin 1 mm, dhat = a/8 = 0.8 mm, kappa 10, skin 1 cm); its files are named full.contact.DX.
#   ./run_full.sh                 all four
#   ./run_full.sh no 1e-3         only these moduli
# Environment: LMP (default ../../build/lmp), SOLVER (nve, or krylov / jacobi for fix sissm),
#   DT (5e-5 s; fix nve with 1e-4 blew up after the landing with D = 1e-3), STEPS (30000),
#   SETTLE (10000; 0 skips the settling), SETTLEDAMP (25 /s), EVERY (5000), JOBS (2), PRECOND (fix sissm's: block, with this light cloth the multigrid
#   saves iterations, not time), WALL (2e9: the deck's 2e8 let an edge vertex of the cloth without
#   bending through the table's surface at 6.5 mm, between 0.25 and 0.3 s), CONTACT (no).
set -e
cd "$(dirname "$0")"
LMP=${LMP:-../../build/lmp}
SOLVER=${SOLVER:-nve}
DT=${DT:-5e-5}
STEPS=${STEPS:-30000}
SETTLE=${SETTLE:-10000}
SETTLEDAMP=${SETTLEDAMP:-25}
EVERY=${EVERY:-5000}
JOBS=${JOBS:-2}
PRECOND=${PRECOND:-block}
WALL=${WALL:-2.0e9}
CONTACT=${CONTACT:-no}
tag=full
[ "$CONTACT" = no ] || tag=full.contact
[ $# -gt 0 ] || set -- no 1e-5 1e-4 1e-3
[ -f cloth_full.obj ] || ./make_meshes.sh full

run_one() {
  name=$tag.D$1
  common="-var mesh cloth_full.obj -var a 0.0065 -var every $EVERY -var frames $EVERY
    -var bend $1 -var solver $SOLVER -var dt $DT -var precond $PRECOND -var wall $WALL
    -var contact $CONTACT -var name $name"
  # shellcheck disable=SC2086
  "$LMP" -in in.tablecloth $common -var steps "$STEPS" -log "log.$name" > /dev/null 2>&1 ||
    { echo "run $name failed: see log.$name" >&2; return; }
  [ "$SETTLE" -gt 0 ] || return 0
  # shellcheck disable=SC2086
  "$LMP" -in in.tablecloth $common -var startstep "$STEPS" -var steps "$SETTLE" \
    -var damp "$SETTLEDAMP" -log "log.$name.settle" > /dev/null 2>&1 ||
    echo "settling $name failed: see log.$name.settle" >&2
}

# at most JOBS runs at a time
running=0
for d in "$@"; do
  run_one "$d" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then
    wait
    running=0
  fi
done
wait

last=$((STEPS + SETTLE))
printf '%-6s %-24s %-24s\n' D "drape at STEPS (hull)" "settled (hull)"
for d in "$@"; do
  line=$(printf '%-6s' "$d")
  for step in "$STEPS" "$last"; do
    dump=dump.$tag.D$d.$step
    if [ ! -f "$dump" ]; then line="$line $(printf '%-24s' "no $dump")"; continue; fi
    svg=drape.$tag.D$d.svg
    [ "$step" = "$last" ] || svg=/dev/null
    r=$(python3 drape.py cloth_full.obj "$dump" --svg "$svg" --json |
      python3 -c 'import json, sys; r = json.load(sys.stdin)
print("%.3f (%.3f)" % (r["drape_coefficient"], r["drape_coefficient_hull"]))')
    line="$line $(printf '%-24s' "$r")"
  done
  echo "$line"
done
