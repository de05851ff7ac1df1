#!/usr/bin/env bash
# Deadlocks of the paper's flow control (--fifo-full lock, Priol & Bouatouch 3.5.2 and 2.2) on the emulated
# iPSC/1: balls 2 at a small size, 16 processors, FIFO capacities 1 to 128, uniform grid or BSP, light rays
# as messages or traced in light pyramids (3.7.2). Per run: deadlocked or not, when (simulated s), and the
# share of processor time spent locked (the blocked share). Prints a Markdown table; nothing is timed on
# this host, so the table is the same on every machine.
#
#   benchmarks/deadlock_study.sh [RAYCUBE] [SIZE] [PROCS] > benchmarks/results/deadlock_study.md
set -euo pipefail
raycube=${1:-build/release/raycube}
size=${2:-64x64}
procs=${3:-4x4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| capacity | balance | light rays | result | deadlock at (simulated s) | cycle | makespan (simulated s) | locked share | locked share by tenth (%) |"
echo "|---:|---|---|---|---:|---|---:|---:|---|"
for capacity in 1 2 8 32 128; do
  for balance in uniform bsp; do
    for lights in messages pyramid; do
      stats="$work/stats.json"
      rm -f "$stats"
      set +e
      "$raycube" render --quiet --size "$size" --procs "$procs" --mode machine --emulate ipsc1 \
        --fifo-full lock --queue-capacity "$capacity" --balance "$balance" --load-metric rays \
        --light-rays "$lights" --stats "$stats" > "$work/out.txt" 2> "$work/err.txt"
      code=$?
      set -e
      if [[ $code -eq 4 ]]; then
        result=deadlock
        when=$(jq -r '.machine.deadlock.simulatedSeconds | . * 1000 | round / 1000' "$stats")
        cycle=$(jq -r '[.machine.deadlock.cycle[].from | tostring] | join(" → ")' "$stats")
      elif [[ $code -eq 0 ]]; then
        result=completed
        when="–"
        cycle="–"
      else
        echo "run failed (exit $code): capacity $capacity $balance $lights" >&2
        cat "$work/err.txt" >&2
        exit 1
      fi
      makespan=$(jq -r '.simulated.makespanSeconds | . * 1000 | round / 1000' "$stats")
      share=$(jq -r '.simulated.blockedShare * 1000 | round / 10 | tostring + "%"' "$stats")
      tenths=$(jq -r '[.simulated.blockedShareByTenth[] | . * 100 | round | tostring] | join(" ")' "$stats")
      echo "| $capacity | $balance | $lights | $result | $when | $cycle | $makespan | $share | $tenths |"
    done
  done
done
