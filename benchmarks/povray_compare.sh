#!/usr/bin/env bash
# Whole-process wall time of POV-Ray 3.7 and raycube on SPD balls 2 at 512x512, 2 threads, no antialiasing,
# run alternately so drift in machine load hits both alike. Prints the medians and povray/raycube.
#
# usage: benchmarks/povray_compare.sh RAYCUBE_BINARY [EXTRA_RAYCUBE_ARGS...]
#        benchmarks/povray_compare.sh --povray-only
# environment: RUNS (default 7), POV_SCENE (default <shared>/reference/balls2.pov), KEEP_OUTPUT=1 keeps images.
#
# balls2.pov has no global_settings, so POV-Ray uses its default max_trace_level of 5, the same depth as
# raycube; the script checks POV-Ray's "Max Level: n/5" statistic to be sure. POV-Ray 3.7's front end idles
# about 0.6 s per process whatever the image size (a 16x16 render takes as long), so its trace time, which
# excludes that, is printed too.
set -euo pipefail

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
shared_dir=${RAYCUBE_SHARED_DIR:-$(realpath -m "$script_dir/../../shared")}
pov_scene=${POV_SCENE:-$shared_dir/reference/balls2.pov}
runs=${RUNS:-7}

die() { echo "povray_compare.sh: $*" >&2; exit 1; }

[[ $# -ge 1 ]] || die "usage: $0 RAYCUBE_BINARY [EXTRA_RAYCUBE_ARGS...]  (or --povray-only)"
raycube=$1
shift
povray_only=0
if [[ $raycube == --povray-only ]]; then
  povray_only=1
else
  [[ -x $raycube ]] || die "raycube binary '$raycube' does not exist or is not executable"
fi
[[ $runs =~ ^[1-9][0-9]*$ ]] || die "RUNS must be a positive integer, got '$runs'"
[[ -r $pov_scene ]] || die "cannot read POV-Ray scene '$pov_scene' (set POV_SCENE or RAYCUBE_SHARED_DIR)"
command -v povray >/dev/null || die "povray not found on PATH (Debian package 'povray')"

out_dir=$(mktemp -d /tmp/povray_compare.XXXXXX)
if [[ ${KEEP_OUTPUT:-0} != 1 ]]; then
  trap 'rm -rf "$out_dir"' EXIT
fi

povray_cmd=(povray "+I$pov_scene" +W512 +H512 -A +WT2 -D "+O$out_dir/povray.png")
raycube_cmd=("$raycube" render --balls 2 --size 512x512 --mode image-parallel --threads 2
             -o "$out_dir/raycube.png" "$@")

source "$(dirname "$0")/timing.sh"

# Runs a command, stdout and stderr to $2; prints its wall time in seconds. A failure stops the script.
timed() {
  local log=$1
  shift
  local start end
  start=$(now)
  if ! "$@" >"$log" 2>&1; then
    echo "povray_compare.sh: '$*' failed; its output:" >&2
    tail -n 20 "$log" >&2
    exit 1
  fi
  end=$(now)
  awk -v s="$start" -v e="$end" 'BEGIN { printf "%.4f\n", e - s }'
}

# POV-Ray's own "Trace Time: ... (0.178 seconds)" line: render time without start-up and parsing.
povray_trace_time() { sed -n 's/^ *Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' "$1" | tail -n 1; }


# One untimed run of each: warms the page cache and fails fast on a bad command line.
timed "$out_dir/povray.log" "${povray_cmd[@]}" >/dev/null
grep -q 'Max Level: [0-9]*/5$' "$out_dir/povray.log" ||
  echo "povray_compare.sh: warning: POV-Ray did not report max_trace_level 5 ($(grep 'Max Level' "$out_dir/povray.log"))" >&2
if [[ $povray_only == 0 ]]; then
  timed "$out_dir/raycube.log" "${raycube_cmd[@]}" >/dev/null
fi

povray_times=()
povray_traces=()
raycube_times=()
for ((i = 1; i <= runs; ++i)); do
  povray_times+=("$(timed "$out_dir/povray.log" "${povray_cmd[@]}")")
  povray_traces+=("$(povray_trace_time "$out_dir/povray.log")")
  line="run $i/$runs: povray ${povray_times[-1]} s (trace ${povray_traces[-1]} s)"
  if [[ $povray_only == 0 ]]; then
    raycube_times+=("$(timed "$out_dir/raycube.log" "${raycube_cmd[@]}")")
    line+=", raycube ${raycube_times[-1]} s"
  fi
  echo "$line" >&2
done

povray_median=$(printf '%s\n' "${povray_times[@]}" | median)
trace_median=$(printf '%s\n' "${povray_traces[@]}" | median)
echo "scene:                 $pov_scene, 512x512, no antialiasing, 2 threads, $runs runs"
echo "povray median:         $povray_median s whole process (trace time alone: $trace_median s)"
if [[ $povray_only == 0 ]]; then
  raycube_median=$(printf '%s\n' "${raycube_times[@]}" | median)
  echo "raycube median:        $raycube_median s whole process${*:+ (extra args: $*)}"
  awk -v p="$povray_median" -v r="$raycube_median" \
    'BEGIN { printf "povray/raycube:        %.2f (above 1: raycube is faster)\n", p / r }'
fi
if [[ ${KEEP_OUTPUT:-0} == 1 ]]; then
  echo "images kept in $out_dir"
fi
