#!/usr/bin/env bash
# The emulator against real runs (issue 47): this machine calibrated (`raycube calibrate`), then each
# configuration run over Open MPI (median of RUNS) beside its prediction on the calibrated platform
# (`--platform --costs --ranks N`). Not a test: the table in benchmarks/results/mpi_validation.md.
#   measured: tracing (start of synthesis to the last contribution) and wall (mpirun to exit), medians
#   predicted: synthesis (the simulated makespan) and end-to-end (the calibrated start-up of an N-rank run
#              + the emulated run's own preprocessing on this host + synthesis; the image's writing is not
#              charged)
# Then the same predictions with a cost table from one scene only: the hand-counted flop-equivalents
# (cluster.costs) with a node speed fitted to SCENES' first scene at 1x1 and the first rank count.
# Usage: benchmarks/validate_mpi.sh BUILD_DIR [OUT.md]
#   RUNS=5 SIZE=512 SCENES="balls2 balls4 gears4 tetra6 mount6" PROCS="1x1 2x2 3x3 4x4" RANKS="2 3 5"
# (RANKS must be among calibrate's 2 3 5: their start-up is what it measures.)
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [OUT.md]}
out_md=${2:-/dev/null}
raycube=$build/raycube
runs=${RUNS:-5}
size=${SIZE:-512}
scenes=(${SCENES:-balls2 balls4 gears4 tetra6 mount6})
procs=(${PROCS:-1x1 2x2 3x3 4x4})
ranks_list=(${RANKS:-2 3 5})
here=$(cd "$(dirname "$0")" && pwd)
source "$here/timing.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$raycube" calibrate --out "$work/cal" | tee "$work/calibrate.log"
startup() { sed -n "s/.*start-up, $1 ranks *\([0-9.]*\) s.*/\1/p" "$work/calibrate.log"; }
# Both engines hold a region's objects in a BVH (the emulator's default is the paper's cells).
common=(--size "${size}x$size" --cells bvh -q -o "$work/x.png")
sceneFile() { echo "$here/../scenes/$1.nff"; }
tracing() { sed -n 's/.*tracing \([0-9.]*\) s.*/\1/p' "$1" | head -1; }
preprocessing() { sed -n 's/^ *preprocessing \([0-9.]*\) s.*/\1/p' "$1" | head -1; }
makespan() { sed -n 's/.*makespan \([0-9.e+-]*\) simulated s.*/\1/p' "$1" | head -1; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

# measured SCENE PROCS RANKS: "tracing wall", medians of RUNS.
measured() {
  local walls=() traces=() start
  for ((run = 1; run <= runs; ++run)); do
    start=$(now)
    mpirun -np "$3" "$raycube" render "$(sceneFile "$1")" --procs "$2" "${common[@]}" --transport mpi >"$work/mpi.log"
    walls+=("$(awk -v a="$(now)" -v b="$start" 'BEGIN {print a - b}')")
    traces+=("$(tracing "$work/mpi.log")")
  done
  echo "$(echo "${traces[*]}" | median) $(echo "${walls[*]}" | median)"
}

# predicted COSTS SCENE PROCS RANKS: "synthesis end-to-end" (one run: simulated time is deterministic).
predicted() {
  "$raycube" render "$(sceneFile "$2")" --procs "$3" "${common[@]}" --platform "$work/cal/platform.xml" \
    --costs "$1" --ranks "$4" >"$work/sim.log"
  local m p
  m=$(makespan "$work/sim.log")
  p=$(preprocessing "$work/sim.log")
  echo "$m $(awk -v s="$(startup "$4")" -v p="$p" -v m="$m" 'BEGIN {print s + p + m}')"
}

declare -A measuredOf
header="| scene | procs | ranks | measured tracing s | predicted synthesis s | ratio | measured wall s | predicted end-to-end s | ratio |"
rule="|---|---|---|---|---|---|---|---|---|"
{
  echo "### Per-operation costs (\`raycube calibrate\`)"
  echo
  echo "$header"
  echo "$rule"
} | tee -a "$out_md"
# rows COSTS: a row per configuration, measured once (the first table) and predicted with COSTS.
rows() {
  local scene p r mt mw ps pe
  for scene in "${scenes[@]}"; do
    for p in "${procs[@]}"; do
      for r in "${ranks_list[@]}"; do
        [ -n "${measuredOf[$scene/$p/$r]:-}" ] || measuredOf[$scene/$p/$r]=$(measured "$scene" "$p" "$r")
        read -r mt mw <<<"${measuredOf[$scene/$p/$r]}"
        read -r ps pe <<<"$(predicted "$1" "$scene" "$p" "$r")"
        echo "| $scene | $p | $r | $mt | $ps | $(ratio "$ps" "$mt") | $mw | $pe | $(ratio "$pe" "$mw") |" | tee -a "$out_md"
      done
    done
  done
}
rows "$work/cal/costs"

# One scene only: cluster.costs' flop-equivalents, the calibrated messages and accumulation, and the node
# speed that makes the first configuration's synthesis its measured tracing.
first=${scenes[0]}/${procs[0]}/${ranks_list[0]}
{
  grep -v '^\(unit\|sphereTest\|coneTest\|polygonTest\|polygonVertex\|patchTest\|cellStep\|raySegment\|rayFinished\|raySpawned\|contribution\) ' "$work/cal/costs"
  grep '^\(sphereTest\|coneTest\|polygonTest\|polygonVertex\|patchTest\|cellStep\|raySegment\|rayFinished\|raySpawned\|contribution\) ' "$here/../host/machine/platforms/cluster.costs"
} >"$work/one.costs"
cp "$work/one.costs" "$work/one-fit.costs"
echo "nodeSpeed 1e9" >>"$work/one-fit.costs"
read -r atGiga _ <<<"$(predicted "$work/one-fit.costs" "${scenes[0]}" "${procs[0]}" "${ranks_list[0]}")"
read -r firstTracing _ <<<"${measuredOf[$first]}"
speed=$(awk -v m="$atGiga" -v t="$firstTracing" 'BEGIN {printf "%.6g", 1e9 * m / t}')
cp "$work/one.costs" "$work/one-fit.costs"
echo "nodeSpeed $speed" >>"$work/one-fit.costs"
{
  echo
  echo "### One scene's fit (cluster.costs' flop-equivalents at $speed flop-equivalents/s, fitted on $first)"
  echo
  echo "$header"
  echo "$rule"
} | tee -a "$out_md"
rows "$work/one-fit.costs"
echo
echo "calibration:"
cat "$work/cal/costs"
