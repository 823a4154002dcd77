#!/bin/sh
# Wall time per simulated frame of the cloth on a ball, 1, 3 and 6 layers, on 1 and 2 MPI ranks,
# under fix nve (dt 20 us) or fix sissm (dt 1 ms, collision-free steps: skin 8 mm, ghost cutoff
# 9 cm). A frame is 1/30 s here (a video frame; the authors report 1/8 s of GPU time per
# frame of the cloth): the run is `steps` steps and the time per frame is the loop time x (1/30)
# / (steps x dt). Under fix sissm it also prints the force evaluations per step (fix sissm's
# run summary).
# Prints one line per run. Usage (from this folder):
#   ./per_frame.sh [steps] [nve|sissm]     (default 500 nve; 33 steps of 1 ms = one frame)
steps=${1:-500}
solver=${2:-nve}
lmp=../../build/lmp
if [ "$solver" = sissm ]; then
  dt=1e-3; opts="-var solver sissm -var dt $dt -var skin 0.008 -var comm 0.09"
else
  dt=2e-5; opts=""
fi
for layers in 1 3 6; do
  for np in 1 2; do
    if [ "$np" = 1 ]; then run="$lmp"; else run="mpirun -np $np --allow-run-as-root $lmp"; fi
    out=$($run -in in.cloth-on-ball -var layers $layers -var steps "$steps" -var every "$steps" \
          $opts -log none -var name timing 2>&1)
    loop=$(echo "$out" | grep "^Loop time")
    seconds=$(echo "$loop" | awk '{print $4}')
    frame=$(python3 -c "print(f'{$seconds / ($steps * $dt) / 30:.1f} s')")
    if [ "$solver" = sissm ]; then
      evals=$(echo "$out" | grep "iterations per step" | sed 's/.* \([0-9.]*\) iterations per step.*/\1/')
      echo "layers $layers ranks $np: $loop; per frame of 1/30 s: $frame; evaluations per step $evals"
    else
      echo "layers $layers ranks $np: $loop; per frame of 1/30 s: $frame"
    fi
  done
done
