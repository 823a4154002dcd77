#!/bin/sh
# Wall time per simulated frame of the cloth on a ball, 1, 3 and 6 layers, on 1 and 2 MPI ranks,
# under fix nve (dt 20 us). A frame is 1/30 s here (the talk's videos; the authors report 1/8 s
# of GPU time per frame of the cloth): the run is `steps` steps and the time per frame is the
# loop time x (1/30) / (steps x dt). Prints one line per run. Usage (from this folder):
#   ./per_frame.sh [steps]        (default 500)
steps=${1:-500}
lmp=../../build/lmp
for layers in 1 3 6; do
  for np in 1 2; do
    if [ "$np" = 1 ]; then run="$lmp"; else run="mpirun -np $np --allow-run-as-root $lmp"; fi
    out=$($run -in in.cloth-on-ball -var layers $layers -var steps "$steps" -var every "$steps" \
          -log none -var name timing 2>&1 | grep "^Loop time")
    seconds=$(echo "$out" | awk '{print $4}')
    echo "layers $layers ranks $np: $out; per frame of 1/30 s: $(python3 -c "print(f'{$seconds / ($steps * 2e-5) / 30:.1f} s')")"
  done
done
