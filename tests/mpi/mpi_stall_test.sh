#!/usr/bin/env bash
# The MPI machine's watchdog: a processor stuck inside one step, and a termination token lost, each end the
# job non-zero within seconds with a message naming what stalled (issue 41), never a spin.
# Usage: mpi_stall_test.sh MPI_STALL_PROGRAM MPIEXEC SCRATCH_DIR
set -uo pipefail
program=$1 mpiexec=$2 dir=$3
mkdir -p "$dir" && cd "$dir" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

passed=0
for case in stuck-step lost-token; do
  before=$failures
  timeout 120 "$mpiexec" -n 3 "$program" "$case" >"$case.log" 2>&1
  status=$?
  [ "$status" -eq 124 ] && fail "$case: still running after 120 s (the watchdog did not fire)"
  [ "$status" -eq 0 ] && fail "$case: exit status 0"
  want="the machine stalled.*no rank has sent anything"
  [ "$case" = stuck-step ] && want="the machine stalled.*processor 3 has been inside one step"
  grep -q -- "$want" "$case.log" || { fail "$case: expected '$want' in:"; cat "$case.log"; }
  [ "$failures" -eq "$before" ] && passed=$((passed + 1))
done
echo "$passed passed, $((2 - passed)) failed"
[ "$failures" -eq 0 ]
