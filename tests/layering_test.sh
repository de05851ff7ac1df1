#!/usr/bin/env bash
# The folders' includes point one way (README "Where things are"): core <- node <- queues <- host.
# A header of a lower layer that reaches up would compile (every library shares the repository's include
# root), so this test is the layering's guard.
set -euo pipefail
cd "${1:?usage: layering_test.sh SOURCE_DIR}"
status=0
check() {  # folder, the folders it must not include from
  local folder=$1; shift
  for above in "$@"; do
    if grep -n "#include \"$above/" "$folder"/*.h "$folder"/*.cpp; then
      echo "FAIL: $folder/ includes from $above/ (includes point one way: core <- node <- queues <- host)"
      status=1
    fi
  done
}
check core node queues host
check node queues host
check queues host
[ "$status" -eq 0 ] && echo "layering: core <- node <- queues <- host holds"
exit "$status"
