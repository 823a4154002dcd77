#!/bin/sh
# Wall time per simulated frame of the twisting cloth on 1 and 2 MPI ranks, under fix sissm
# (1 ms steps, the deck's default) and fix nve (20 us steps, kappa 100: at the deck's kappa
# 10 the explicit run goes through the barrier after the buckle, see README.md). A frame is
# 1/30 s here (a video frame; the authors report 1/8 s of GPU time per frame of their cloth
# scene): the run is `steps` steps and the time per frame is the loop time x (1/30) / (steps x
# dt). The sissm lines also give the mean force evaluations per step (the log's "Fix sissm ...
# run" line). Prints one line per run. Usage (from this folder):
#   ./per_frame.sh [steps]        (default 200: one full turn of each end, 0.2 s; the nve runs
#                                  take 50 x steps of 20 us, the same 0.2 s)
steps=${1:-200}
lmp=../../build/lmp
for solver in sissm nve; do
  if [ "$solver" = sissm ]; then
    n=$steps; opts="-var dt 1e-3"; dt=1e-3
  else
    n=$((50 * steps)); opts="-var solver nve -var dt 2e-5 -var kappa 100"; dt=2e-5
  fi
  for np in 1 2; do
    if [ "$np" = 1 ]; then run="$lmp"; else run="mpirun -np $np --allow-run-as-root $lmp"; fi
    log=$($run -in in.twisting-cloth $opts -var steps "$n" -var every "$n" -log none \
          -var name timing 2>&1)
    loop=$(echo "$log" | grep "^Loop time")
    iters=$(echo "$log" | grep "^Fix sissm .* run:" | sed 's/.*steps, \([0-9.]*\) iterations per step.*/, \1 evaluations per step/')
    seconds=$(echo "$loop" | awk '{print $4}')
    echo "$solver ranks $np: $loop$iters; per frame of 1/30 s: $(python3 -c "print(f'{$seconds / ($n * $dt) / 30:.2f} s')")"
  done
done
