#!/usr/bin/env bash
# The folders' includes point one way (README "Where things are": core <- node <- queues <- host), and
# every source file is in its library's list.
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
# Every source of a library is in its folder's explicit source list (a forgotten one fails only at link).
for folder in core node queues host; do
  for source in "$folder"/*.cpp; do
    name=$(basename "$source")
    [ "$name" = main.cpp ] && continue
    if ! grep -qw "$name" "$folder/CMakeLists.txt"; then
      echo "FAIL: $source is not in $folder/CMakeLists.txt"
      status=1
    fi
  done
done
[ "$status" -eq 0 ] && echo "layering: core <- node <- queues <- host holds; every source is listed"
exit "$status"
