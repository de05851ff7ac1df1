#!/usr/bin/env bash
# The machine over MPI against the threaded machine on this host (issue 14). Not a test: figures for
# benchmarks/results/mpi.md. On a 2-core host the ranks oversubscribe the cores, and that costs something: it is reported.
#   1. ray messages per second between two ranks, batched and unbatched, beside the shared-memory FIFO
#   2. balls size 2, 512x512, 16 processors (4x4): threads, and MPI on N = 2, 3, 5 ranks (median of RUNS)
#   3. MPI messages and bytes per rank (the per-rank table of the last run at each N)
#   4. memory per rank on balls size 4 against the single-process machine (peak RSS)
# Usage: benchmarks/mpi_compare.sh BUILD_DIR (e.g. build/release); RUNS=5 by default.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR}
raycube=$build/raycube
runs=${RUNS:-5}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
source "$(dirname "$0")/timing.sh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "== 1. ray messages between two processors (mpirun -np 3: rank 0 waits)"
mpirun -np 3 "$build/benchmarks/mpi_ray_exchange" 2000000 "$runs"

echo
echo "== 2. balls2 512x512, depth 5, 16 processors (4x4 uniform), $runs runs: median wall s (tracing s)"
args=(render --balls 2 --size 512x512 --depth 5 --procs 4x4 --balance uniform -o "$out/x.png")
tracing() { sed -n 's/.*tracing \([0-9.]*\) s.*/\1/p' "$1"; }
walls=() traces=()
for ((run = 1; run <= runs; ++run)); do
  start=$(now)
  "$raycube" "${args[@]}" -q >"$out/threads.log"
  walls+=("$(awk -v a="$(now)" -v b="$start" 'BEGIN {print a - b}')")
  traces+=("$(tracing "$out/threads.log")")
done
printf "threads (one process)   %6.2f s (%.2f s)\n" "$(echo "${walls[*]}" | median)" "$(echo "${traces[*]}" | median)"
for ranks in 2 3 5; do
  walls=() traces=()
  for ((run = 1; run <= runs; ++run)); do
    start=$(now)
    mpirun -np $ranks "$raycube" "${args[@]}" -q --transport mpi >"$out/mpi$ranks.log"
    walls+=("$(awk -v a="$(now)" -v b="$start" 'BEGIN {print a - b}')")
    traces+=("$(tracing "$out/mpi$ranks.log")")
  done
  printf "MPI, %d ranks            %6.2f s (%.2f s)\n" $ranks "$(echo "${walls[*]}" | median)" "$(echo "${traces[*]}" | median)"
done

echo
echo "== 3. MPI messages and bytes per rank (last run above)"
for ranks in 2 3 5; do
  echo "-- $ranks ranks"
  sed -n '/^  MPI:/,$p' "$out/mpi$ranks.log"
done

echo
echo "== 4. memory on balls4 (7382 objects), 256x256, 16 processors: peak RSS"
for mode in pyramid messages; do
  m=(render --balls 4 --size 256x256 --procs 4x4 --light-rays $mode -q -o "$out/b4.png")
  /usr/bin/time -f "%M" -o "$out/rss" "$raycube" "${m[@]}" >/dev/null
  echo "-- light rays $mode: threads (one process) peak RSS $(awk '{printf "%.1f", $1 / 1024}' "$out/rss") MB"
  for ranks in 3 5; do
    mpirun -np $ranks "$raycube" "${m[@]}" --transport mpi >"$out/b4.log"
    echo "   MPI, $ranks ranks:"
    sed -n '/^  rank/,$p' "$out/b4.log"
  done
done
echo
echo "== baseline: an idle rank (no processor) on balls2"
mpirun -np 4 "$raycube" render --balls 2 --size 64x64 --procs 1x2 --balance uniform -q --transport mpi -o "$out/i.png" |
  sed -n '/^  rank/,$p'
