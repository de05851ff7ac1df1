#!/usr/bin/env bash
# Light cones against light pyramids against light-ray messages (Priol & Bouatouch 3.7.2) on the emulated
# iPSC/1, in the paper's cells (3.3, the emulated default) and, for comparison, with a BVH per region:
# balls 2 at table 2's 128x128 and load metric, 16, 32 and 64 processors. Per run: the objects each
# processor holds (its database) and those of its light volumes (summed over the lights), mean and max; the
# object tests, the cell steps and box tests, and the simulated makespan. Prints a Markdown table; nothing
# is timed on this host, so the table is the same on every machine.
#
#   benchmarks/light_rays_cells.sh [RAYCUBE] [SIZE] > benchmarks/results/light_rays_cells.md
set -euo pipefail
raycube=${1:-build/release/raycube}
size=${2:-128x128}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| procs | cells | light rays | held objects mean / max | light-volume objects mean / max | object tests | cell steps + box tests | light rays traced where they start | simulated s |"
echo "|---:|---|---|---:|---:|---:|---:|---:|---:|"
for grid in 4x4 4x8 8x8; do
  procs=$((${grid%x*} * ${grid#*x}))
  for cells in paper bvh; do
    for lights in cone pyramid messages; do
      stats="$work/stats.json"
      "$raycube" render --quiet --size "$size" --procs "$grid" --emulate ipsc1 --load-metric rays \
        --cells "$cells" --light-rays "$lights" --stats "$stats" -o "$work/image.png" > /dev/null
      jq -r --arg procs "$procs" --arg cells "$cells" --arg lights "$lights" '
        .machine.processors as $p
        | ($p | length) as $n
        | "| \($procs) | \($cells) | \($lights) | "
          + "\(([$p[].heldObjects] | add) / $n * 10 | round / 10) / \([$p[].heldObjects] | max) | "
          + "\(([$p[].lightObjects] | add) / $n * 10 | round / 10) / \([$p[].lightObjects] | max) | "
          + "\(.intersectionTests) | \(([$p[].cellSteps] | add) + .boxTests) | "
          + "\([$p[].lightRaysTracedLocally] | add) | \(.simulated.makespanSeconds * 10 | round / 10) |"' "$stats"
    done
  done
done
