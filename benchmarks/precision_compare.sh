#!/usr/bin/env bash
# --precision float against double, side by side in one run, whole-process medians: the reference (one
# thread), image-parallel (2 threads), and the machine 4x4 with light pyramids and with light rays as
# messages (where the 80-byte float message against the 128-byte double one matters most).
# Usage: benchmarks/precision_compare.sh RAYCUBE_BINARY     (RUNS=7 by default)
set -euo pipefail
raycube=${1:?usage: $0 RAYCUBE_BINARY}
runs=${RUNS:-7}
source "$(dirname "$0")/timing.sh"
scene_args=(render --balls 2 --size 512x512 --depth 5 -q -o /tmp/raycube_precision_compare.png)
modes=("reference:--mode reference" "image-parallel:--mode image-parallel --threads 2"
       "machine-4x4-pyramid:--procs 4x4" "machine-4x4-messages:--procs 4x4 --light-rays messages")
declare -A times
for ((run = 1; run <= runs; ++run)); do
  for mode in "${modes[@]}"; do
    for precision in float double; do
      read -r -a args <<< "${mode#*:}"
      start=$(now)
      "$raycube" "${scene_args[@]}" "${args[@]}" --precision "$precision" > /dev/null
      times[${mode%%:*}/$precision]+="$(awk -v a="$(now)" -v b="$start" 'BEGIN {print a - b}') "
    done
  done
done
echo "balls size 2, 512x512, depth 5, medians of $runs runs"
printf '%-22s %10s %10s %14s\n' mode "float s" "double s" "float/double"
for mode in "${modes[@]}"; do
  name=${mode%%:*}
  f=$(echo "${times[$name/float]}" | median)
  d=$(echo "${times[$name/double]}" | median)
  printf '%-22s %10.3f %10.3f %14.2f\n' "$name" "$f" "$d" "$(awk -v a="$f" -v b="$d" 'BEGIN {print a / b}')"
done
