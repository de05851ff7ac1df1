#!/usr/bin/env bash
# Whole-process timing of the message-passing machine against the image-parallel baseline, side by side in
# one run (absolute times drift; the ratios are what the issue targets hold):
#   machine 4x4 / image-parallel (2 threads)   target <= 1.5
#   machine 8x8 / machine 4x4                  target <= 1.5
# Usage: benchmarks/machine_compare.sh RAYCUBE_BINARY [extra render args, e.g. --light-rays messages]
set -euo pipefail
raycube=${1:?usage: $0 RAYCUBE_BINARY [render args...]}
shift
runs=${RUNS:-7}
scene_args=(render --balls 2 --size 512x512 --depth 5 -q -o /tmp/raycube_machine_compare.png)
declare -A times
configs=("image-parallel:--mode image-parallel --threads 2" "4x4:--procs 4x4 $*" "8x8:--procs 8x8 $*")
source "$(dirname "$0")/timing.sh"
for ((run = 1; run <= runs; ++run)); do
  for config in "${configs[@]}"; do
    name=${config%%:*}
    read -r -a args <<< "${config#*:}"
    start=$(now)
    "$raycube" "${scene_args[@]}" "${args[@]}" > /dev/null
    times[$name]+="$(awk -v a="$(now)" -v b="$start" 'BEGIN {print a - b}') "
  done
done
ip=$(echo "${times[image-parallel]}" | median)
m4=$(echo "${times[4x4]}" | median)
m8=$(echo "${times[8x8]}" | median)
echo "balls size 2, 512x512, depth 5, $runs runs, machine args: ${*:-(defaults)}"
echo "image-parallel (2 threads) median: $ip s"
echo "machine 4x4 median:                $m4 s   ratio to image-parallel: $(awk -v a="$m4" -v b="$ip" 'BEGIN {printf "%.2f", a / b}')"
echo "machine 8x8 median:                $m8 s   ratio to 4x4:            $(awk -v a="$m8" -v b="$m4" 'BEGIN {printf "%.2f", a / b}')"
