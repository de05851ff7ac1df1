#!/usr/bin/env bash
# The emulator's speed (issue 42): simulated messages per wall second and per CPU second, for the cases of the
# issue, one binary or two side by side (before/after, interleaved run by run so that the load other processes
# put on the machine drifts over both alike; the ratios of medians are what to quote).
#   ipsc1:   balls 2 at 512x512, 64 processors, light rays as messages, --fifo-full overflow
#   cluster: balls 2 at 256x256, 256 processors (16x16)
# Simulated messages are the stats' simulated.rayMessages (every ray, token and relay on a link between
# hypercube nodes; the contributions to the host are not counted). The simulated makespan and message count
# are printed too: two binaries that model the same machine must agree on them to the last digit.
# Usage: benchmarks/emulator_speed.sh RAYCUBE [BASELINE_RAYCUBE]   (RUNS=3 by default, CASES="ipsc1 cluster")
set -euo pipefail
after=${1:?usage: $0 RAYCUBE [BASELINE_RAYCUBE]}
before=${2:-}
runs=${RUNS:-3}
cases=${CASES:-ipsc1 cluster}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$(dirname "$0")/timing.sh"

case_args() {
  case $1 in
    ipsc1) echo "--balls 2 --size 512x512 --procs 8x8 --light-rays messages --emulate ipsc1 --fifo-full overflow" ;;
    cluster) echo "--balls 2 --size 256x256 --procs 16x16 --emulate cluster" ;;
    small) echo "--balls 2 --size 128x128 --procs 4x4 --light-rays messages --emulate ipsc1 --fifo-full overflow" ;;
    *) echo "unknown case $1" >&2 && exit 2 ;;
  esac
}

# One run: "wall cpu messages makespan peakKB" on stdout.
run_once() {
  local binary=$1 name=$2 tag=$3
  read -r -a args <<< "$(case_args "$name")"
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$binary" render "${args[@]}" -q \
    -o "$work/$tag.png" --stats "$work/$tag.json" > /dev/null
  read -r wall user sys peak < "$work/time"
  python3 - "$work/$tag.json" "$wall" "$user" "$sys" "$peak" << 'EOF'
import json, sys
s = json.load(open(sys.argv[1]))["simulated"]
wall, user, system, peak = (float(x) for x in sys.argv[2:6])
print(wall, user + system, s["rayMessages"], repr(s["makespanSeconds"]), int(peak))
EOF
}

for name in $cases; do
  declare -A rate=() cpurate=() same=()
  for ((run = 1; run <= runs; ++run)); do
    for side in after before; do
      binary=${!side}
      [[ -z $binary ]] && continue
      read -r wall cpu messages makespan peak <<< "$(run_once "$binary" "$name" "$side")"
      rate[$side]+="$(awk -v m="$messages" -v w="$wall" 'BEGIN {print m / w}') "
      cpurate[$side]+="$(awk -v m="$messages" -v c="$cpu" 'BEGIN {print m / c}') "
      same[$side]="$messages messages, makespan $makespan simulated s"
      printf '%-8s %-6s run %d: %9.2f s wall %9.2f s cpu %6d MB peak  %s\n' "$name" "$side" "$run" "$wall" \
        "$cpu" "$((peak / 1024))" "${same[$side]}"
    done
  done
  for side in after before; do
    [[ -z ${rate[$side]:-} ]] && continue
    printf '%-8s %-6s median: %9.0f messages per wall s, %9.0f per cpu s\n' "$name" "$side" \
      "$(echo "${rate[$side]}" | median)" "$(echo "${cpurate[$side]}" | median)"
  done
  if [[ -n $before ]]; then
    echo "$name after/before: wall rate x$(awk -v a="$(echo "${rate[after]}" | median)" \
      -v b="$(echo "${rate[before]}" | median)" 'BEGIN {printf "%.2f", a / b}'), cpu rate x$(awk \
      -v a="$(echo "${cpurate[after]}" | median)" -v b="$(echo "${cpurate[before]}" | median)" \
      'BEGIN {printf "%.2f", a / b}'); simulated results $([[ ${same[after]} == "${same[before]}" ]] &&
      echo identical || echo DIFFER: "${same[after]}" against "${same[before]}")"
  fi
  unset rate cpurate same
done
