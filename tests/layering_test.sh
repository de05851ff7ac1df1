#!/usr/bin/env bash
# The folders' includes point one way, and every source file is in its library's list.
#   the parts of the machine:  core <- node <- queues <- host
#   inside core:               core/ <- core/spd/ (the SPD's generators build on the scene, never the reverse)
#   inside queues:             queues/ (FIFOs, doorbells) <- queues/interconnects/
#   inside host, its rooms:    util <- chart <- machine <- prepare <- engines <- render <- report <- studies <- cli
#   inside host/engines:       threads/, simgrid/ and mpi/ never include each other, and the engines' common
#                              headers none of them (only the factories, make_engine.cpp and the module's entry,
#                              name the engines)
# A header of a lower layer that reaches up would compile (every library shares the repository's include
# root), so this test is the layering's guard. It reads every file under a folder, subfolders included.
set -euo pipefail
cd "${1:?usage: layering_test.sh SOURCE_DIR}"
status=0
sourcesUnder() { find "$@" \( -name '*.h' -o -name '*.cpp' \) -print | sort; }
fail() { echo "FAIL: $*"; status=1; }

# forbid FILES... -- PREFIXES...: no file may include a path starting with one of the prefixes.
forbid() {
  local files=() prefixes=() seen=0
  for arg in "$@"; do
    if [ "$arg" = -- ]; then seen=1; elif [ $seen -eq 0 ]; then files+=("$arg"); else prefixes+=("$arg"); fi
  done
  [ ${#files[@]} -gt 0 ] || return 0
  for prefix in "${prefixes[@]}"; do
    if grep -n "#include \"$prefix" "${files[@]}"; then
      fail "the files above include from $prefix, above them (README \"Where things are\")"
    fi
  done
}

# The parts of the machine.
forbid $(sourcesUnder core) -- node/ queues/ host/
forbid $(sourcesUnder node) -- queues/ host/
forbid $(sourcesUnder queues) -- host/
# Inside core and queues.
forbid $(find core -maxdepth 1 \( -name '*.h' -o -name '*.cpp' \)) -- core/spd/
forbid $(find queues -maxdepth 1 \( -name '*.h' -o -name '*.cpp' \)) -- queues/interconnects/

# The host's rooms, lowest first: a room includes only from itself and the rooms before it.
rooms=(util chart machine prepare engines render report studies cli)
for ((i = 0; i < ${#rooms[@]}; ++i)); do
  room=host/${rooms[$i]}
  [ -d "$room" ] || { fail "$room/ is missing: the rooms of host/ are ${rooms[*]}"; continue; }
  above=()
  for ((j = i + 1; j < ${#rooms[@]}; ++j)); do above+=("host/${rooms[$j]}/"); done
  [ ${#above[@]} -eq 0 ] || forbid $(sourcesUnder "$room") -- "${above[@]}"
done
# Every file of host/ is in a room.
for file in $(find host -maxdepth 1 \( -name '*.h' -o -name '*.cpp' \)); do
  fail "$file is in no room of host/ (${rooms[*]})"
done
# The engines apart.
engines=(threads simgrid mpi)
for engine in "${engines[@]}"; do
  others=()
  for other in "${engines[@]}"; do [ "$other" = "$engine" ] || others+=("host/engines/$other/"); done
  forbid $(sourcesUnder "host/engines/$engine") -- "${others[@]}"
done
forbid $(find host/engines -maxdepth 1 -name '*.h') -- host/engines/threads/ host/engines/simgrid/ host/engines/mpi/

# Every source of a library is in its folder's explicit source list (a forgotten one fails only at link).
for folder in core node queues host; do
  for source in $(find "$folder" -name '*.cpp' | sort); do
    relative=${source#"$folder"/}
    [ "$relative" = cli/main.cpp ] && continue
    if ! grep -qE "(^|[[:space:](])$relative([[:space:])]|$)" "$folder/CMakeLists.txt"; then
      fail "$source is not in $folder/CMakeLists.txt"
    fi
  done
done
[ "$status" -eq 0 ] && echo "layering: core <- node <- queues <- host and host's rooms (${rooms[*]}) hold; every source is listed"
exit "$status"
