#!/usr/bin/env bash
# The layering test is not blind: on a copy of the sources, an include planted upward inside a subfolder
# of host/ (prepare reaching into cli), of queues/ (a FIFO reaching into an interconnect) or of core/ (the
# scene reaching into the SPD's generators) makes it fail, and the copy unplanted passes.
set -euo pipefail
source_dir=${1:?usage: layering_plant_test.sh SOURCE_DIR}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
check=$source_dir/tests/layering_test.sh
copy() { rm -rf "$work/tree"; mkdir -p "$work/tree"; cp -r "$source_dir"/{core,node,queues,host} "$work/tree"; }
copy
"$check" "$work/tree" >/dev/null || { echo "FAIL: the unplanted copy does not pass"; exit 1; }
plant() {  # file, include
  copy
  printf '#include "%s"\n' "$2" >>"$work/tree/$1"
  if "$check" "$work/tree" >/dev/null; then echo "FAIL: $1 including $2 was not caught"; exit 1; fi
  echo "caught: $1 including $2"
}
plant host/prepare/box_tree.h host/cli/cli.h
plant host/engines/threads/threaded_machine.h host/engines/mpi/mpi_machine.h
plant host/machine/machine_settings.h host/render/render_machine.h
plant queues/spsc_queue.h queues/interconnects/mpi_link.h
plant core/scene.h core/spd/generators.h
plant node/region_map.h host/util/clock.h
echo "layering test catches every planted upward include"
