#!/usr/bin/env bash
# What the machine costs beyond the sequential work, counted rather than timed: each scene's whole run
# under Valgrind's callgrind, which counts every instruction the program executes (the same count from run
# to run within 0.01%, however fast or loaded the computer is), image-parallel's against the machine's at
# each grid. This computer's speed drifts by a third within minutes, which hides a change of a few percent
# in any timing; a count does not drift. It leaves out what is not an instruction of the program: the
# kernel's work (system calls, context switches) and the time lost waiting on memory, so it bounds the
# machine's overhead from below.
#
# Markdown on stdout, progress on stderr. Per scene and renderer: instructions executed; their ratio to
# image-parallel's; the ray segments the processors evaluated and the messages they sent (the run's
# --stats); the instructions beyond image-parallel's per message. Then where the instructions go, by
# layer: raycube's core (the tracing itself: BVHs, intersections, shading), node (the processors'
# regions, walks and bookkeeping), queues (the interconnect), host, and the libraries (C library, zlib,
# OpenEXR, oneTBB, ...), each renderer's own instructions, and the machine's minus image-parallel's.
#
# usage: benchmarks/instruction_counts.sh RAYCUBE_BINARY [MORE.nff ...]
# environment:
#   SCENES (scenes/mount6.nff scenes/balls4.nff)  the scene files
#   SIZE (128x128)     image size for every scene (callgrind runs the program 50-100 times slower)
#   DEPTH (5)          maximum ray tree depth
#   GRIDS ("4x4 8x8")  the machine's processor grids
#   OUT (out/instruction_counts) every run's callgrind profile, stats and log
# needs: valgrind (Debian 'valgrind': callgrind and callgrind_annotate), jq.
set -euo pipefail

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_dir=$(dirname "$script_dir")
die() { echo "instruction_counts.sh: $*" >&2; exit 1; }

[[ $# -ge 1 ]] || die "usage: $0 RAYCUBE_BINARY [MORE.nff ...]"
raycube=$(realpath "$1")
shift
[[ -x $raycube ]] || die "raycube binary '$raycube' does not exist or is not executable"
command -v valgrind >/dev/null && command -v callgrind_annotate >/dev/null ||
  die "needs valgrind and callgrind_annotate (Debian 'valgrind')"
command -v jq >/dev/null || die "needs jq (Debian 'jq')"
size=${SIZE:-128x128}
depth=${DEPTH:-5}
read -r -a grids <<< "${GRIDS:-4x4 8x8}"
read -r -a scenes <<< "${SCENES:-$repo_dir/scenes/mount6.nff $repo_dir/scenes/balls4.nff}"
scenes+=("$@")
for scene in "${scenes[@]}"; do [[ -r $scene ]] || die "cannot read scene '$scene'"; done
for grid in "${grids[@]}"; do [[ $grid =~ ^[1-9][0-9]*x[1-9][0-9]*$ ]] || die "a grid is CxR, got '$grid'"; done
out=${OUT:-out/instruction_counts}
mkdir -p "$out"
out=$(realpath "$out")

# One run under callgrind: NAME RENDER_ARGS...; writes $out/NAME.counts, one line: the instructions, the
# segments evaluated, the messages sent, then the instructions of each layer (core, node, queues, host,
# libraries).
# Returns 1 (with a note on stderr and in $out/NAME.counts) when raycube fails.
count() {
  local name=$1
  shift
  echo "$name: raycube render $* under callgrind" >&2
  if ! valgrind --tool=callgrind --callgrind-out-file="$out/$name.callgrind" \
    "$raycube" render "$@" --size "$size" --depth "$depth" -q -o "$out/$name.exr" --stats "$out/$name.json" \
    >"$out/$name.log" 2>&1; then
    echo "$name: failed (see $out/$name.log)" >&2
    echo failed >"$out/$name.counts"
    return 1
  fi
  local rays_messages by_layer
  # Image-parallel traces each ray in one piece: one segment per ray, no message.
  rays_messages=$(jq -r 'if .machine then [([.machine.processors[].raysProcessed[]] | add),
                           ([.machine.processors[].messagesByKind[]] | add)]
                         else [.totalRays, 0] end | @tsv' "$out/$name.json")
  # Every function's own instructions (callgrind_annotate's lines "N (p%)  file:function [object]"), summed
  # by the namespace of the function itself: its qualified name is the last word before its parameter list
  # outside template arguments (after any return type), so std::map<..., raycube::node::...> is the
  # libraries' and BasicBvh<...>::traverse<raycube::node::...> is core's. What is not raycube's is the
  # libraries'.
  by_layer=$(callgrind_annotate --threshold=100 --inclusive=no "$out/$name.callgrind" | awk '
    function layer_of(f,    i, c, depth, start, name) {
      depth = 0; start = 1
      for (i = 1; i <= length(f); ++i) {
        c = substr(f, i, 1)
        if (c == "<") ++depth
        else if (c == ">") --depth
        else if (depth == 0 && c == " ") start = i + 1
        else if (depth == 0 && c == "(") break
      }
      name = substr(f, start, i - start)
      return match(name, /^raycube::(core|node|queues|host)::/) ? substr(name, 10, RLENGTH - 11) : "libraries"
    }
    /^ *[0-9,]+ +\([ 0-9.]+%\) +[^ ]/ && !/PROGRAM TOTALS/ {
      n = $1; gsub(",", "", n)
      f = $0; sub(/^ *[0-9,]+ +\([ 0-9.]+%\) +[^:]*:/, "", f)
      layer = layer_of(f); sum[layer] += n; total += n
    }
    END { printf "%.0f", total; split("core node queues host libraries", l, " ")
          for (i = 1; i <= 5; ++i) printf " %.0f", sum[l[i]]; print "" }')
  read -r total rest <<< "$by_layer"
  echo "$total $rays_messages $rest" | tr '\t' ' ' >"$out/$name.counts"
}

millions() { awk -v n="$1" 'BEGIN {printf "%.1f", n / 1e6}'; }

counts_rows=() layer_rows=()
for scene in "${scenes[@]}"; do
  base=$(basename "$scene" .nff)
  label="$base ($size)"
  names=("$base.image-parallel")
  count "$base.image-parallel" "$scene" --mode image-parallel --threads 1 || true
  for grid in "${grids[@]}"; do
    names+=("$base.machine$grid")
    count "$base.machine$grid" "$scene" --mode machine --procs "$grid" || true
  done
  # Each run's counts (see count): c[0] instructions, c[1] segments, c[2] messages, c[3..7] the layers.
  read -r -a ip < "$out/$base.image-parallel.counts"
  for name in "${names[@]}"; do
    renderer=${name#"$base".}
    [[ $renderer == machine* ]] && renderer="machine ${renderer#machine}"
    read -r -a c < "$out/$name.counts"
    if [[ ${c[0]} == failed ]]; then
      counts_rows+=("| $label | $renderer | failed (see $out/$name.log) | | | | |")
      continue
    fi
    ratio=- per_message=-
    if [[ ${ip[0]} != failed ]]; then
      ratio=$(awk -v a="${c[0]}" -v b="${ip[0]}" 'BEGIN {printf "%.3f", a / b}')
      ((c[2] > 0)) && per_message=$(awk -v a="${c[0]}" -v b="${ip[0]}" -v m="${c[2]}" 'BEGIN {printf "%.0f", (a - b) / m}')
    fi
    counts_rows+=("| $label | $renderer | $(millions "${c[0]}") | $ratio | ${c[1]} | ${c[2]} | $per_message |")
    cells=""
    for k in 3 4 5 6 7; do cells+=" $(millions "${c[k]}") |"; done
    layer_rows+=("| $label | $renderer |$cells")
    if [[ $name != "$base.image-parallel" && ${ip[0]} != failed ]]; then
      cells=""
      for k in 3 4 5 6 7; do cells+=" $(awk -v a="${c[k]}" -v b="${ip[k]}" 'BEGIN {printf "%+.1f", (a - b) / 1e6}') |"; done
      layer_rows+=("| $label | $renderer − image-parallel |$cells")
    fi
  done
done

echo "Instructions executed, whole process, under Valgrind's callgrind (image-parallel on one thread); depth $depth."
echo "Segments: rays evaluated, counted once per processor that evaluated a part of one (image-parallel: rays)."
echo
echo "| scene | renderer | instructions (M) | / image-parallel | segments | messages | beyond image-parallel, per message |"
echo "|---|---|---:|---:|---:|---:|---:|"
printf '%s\n' "${counts_rows[@]}"
echo
echo "By layer, each function's own instructions (millions), by the raycube namespace it is named in."
echo
echo "| scene | renderer | core | node | queues | host | libraries |"
echo "|---|---|---:|---:|---:|---:|---:|"
printf '%s\n' "${layer_rows[@]}"
