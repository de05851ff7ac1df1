#!/usr/bin/env bash
# The host's own time on the emulated iPSC/1 (issue 40): table 2's case (balls 2, 128x128) on 32 processors,
# light pyramids (3.7.2), the cost metric, for sub-sampling windows 8, 4, 2, the window chosen from the
# resolution (--subsample auto) and a few coarser ones, and the uniform grid that needs no estimate. Per
# run: the host's preprocessing by phase, the synthesis span (table 2's), the end-to-end time and the
# efficiency of each against one processor's synthesis. Prints Markdown; nothing is timed on this host, so
# the tables are the same on every machine.
#
#   benchmarks/host_time.sh [RAYCUBE] [PROCS]    # the table of benchmarks/results/host_time.md
set -euo pipefail
raycube=${1:-build/release/raycube}
procs=${2:-4x8}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
common=(render --quiet --balls 2 --size 128x128 --mode machine --emulate ipsc1 --light-rays pyramid
        --load-metric cost -o "$work/image.png")
n=$(( ${procs%x*} * ${procs#*x} ))

# One processor: the sequential work every efficiency is measured against (it needs no partition).
"$raycube" "${common[@]}" --procs 1x1 --stats "$work/one.json" > /dev/null
t1=$(jq -r '.simulated.makespanSeconds' "$work/one.json")

run() {  # label, then the options that differ
  local label=$1
  shift
  "$raycube" "${common[@]}" --procs "$procs" "$@" --stats "$work/run.json" > /dev/null
  jq -r --arg name "$label" --argjson t1 "$t1" --argjson n "$n" '
    def r(d): . * d | round / d;
    .simulated as $s | $s.preprocessing as $p |
    "| \($name) | \(.machine.subsampleWindow) | \(.machine.balance) | \($p.samplingSeconds | r(10)) | \($p.partitioningSeconds | r(10)) | \($p.pruningSeconds | r(10)) | \($p.mappingSeconds | r(10)) | \($p.transferSeconds | r(100)) | \($s.preprocessingSeconds | r(10)) | \($s.makespanSeconds | r(10)) | \($s.endToEndSeconds | r(10)) | \($t1 / $n / $s.makespanSeconds | r(100)) | \($t1 / $n / $s.endToEndSeconds | r(100)) |"' \
    "$work/run.json"
}

echo "One processor (the reference): $(jq -r '.simulated.makespanSeconds * 10 | round / 10' "$work/one.json") simulated s; ${n} processors (${procs}) below."
echo
echo "| run | window | partition | sub-sampling s | BSP s | pruning s | mapping s | setups sent s | host total s | synthesis s | end to end s | synthesis efficiency | end-to-end efficiency |"
echo "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for w in 8 4 2; do run "--subsample $w" --subsample "$w"; done
run "--subsample auto" --subsample auto
for w in 16 24 32; do run "--subsample $w" --subsample "$w"; done
run "--balance uniform" --balance uniform
