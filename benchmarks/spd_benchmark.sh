#!/usr/bin/env bash
# The SPD scenes at their default sizes (every scenes/*.nff, plus any NFF files given), each rendered by the
# reference renderer (where it finishes within REFERENCE_LIMIT seconds; skipped with a note otherwise),
# image-parallel, the machine at 4x4 and 8x8, and POV-Ray when installed; then the cost per ray against
# the number of primitives, SPD balls sizes 1 to 5, image-parallel and machine 4x4, as a table and a plot.
# Medians of RUNS runs, run side by side (run 1 of every renderer, then run 2, ..., the order reversed
# every other run) so drift in the speed of the computer hits all alike. Markdown tables on stdout;
# progress on stderr.
#
# Per scene and renderer: primitives, preprocessing and tracing time (raycube's --stats: SPD rule 12), rays
# per second over the tracing time, peak memory (maximum resident set, /usr/bin/time), whole-process wall
# time (to the millisecond), and that time over image-parallel's (the median of the rounds' ratios, as
# every ratio here). Then issue 13's targets, each ratio taken
# run by run (the runs of one round side by side) and given as the median and quartiles of those ratios:
# machine 4x4 over image-parallel (at most 1.5), 8x8 over 4x4 (at most 1.3), the machine's preprocessing
# share of its run (at most 20%), its peak memory over image-parallel's (at most 2), POV-Ray over
# image-parallel (at least 2); bold where a median misses.
#
# usage: benchmarks/spd_benchmark.sh RAYCUBE_BINARY [MORE.nff ...]
# environment:
#   RUNS (3)             runs per renderer and scene (the median is printed)
#   DEPTH (5)            maximum ray tree depth
#   SIZE (the file's)    image size WxH for every scene; default: each NFF file's own resolution
#   THREADS (nproc)      image-parallel and POV-Ray threads
#   REFERENCE_LIMIT (60) seconds the reference renderer may take (its first run decides)
#   RUN_LIMIT (900)      seconds any run may take before it is stopped and noted
#   SCENES               the scene files to run instead of scenes/*.nff ("" with SWEEP=1: only the sweep)
#   SWEEP (1)            0 skips the cost-per-ray sweep; SWEEP_SIZE (256x256), SWEEP_BALLS ("1 2 3 4 5")
#   OUT (out/spd_benchmark) the CSV, the plot (cost_per_ray.png) and every run's stats and log
# needs: jq, GNU time (/usr/bin/time); povray optional (Debian 'povray'; scenes in benchmarks/pov/).
set -euo pipefail

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_dir=$(dirname "$script_dir")
die() { echo "spd_benchmark.sh: $*" >&2; exit 1; }

[[ $# -ge 1 ]] || die "usage: $0 RAYCUBE_BINARY [MORE.nff ...]"
raycube=$(realpath "$1")
shift
[[ -x $raycube ]] || die "raycube binary '$raycube' does not exist or is not executable"
command -v jq >/dev/null || die "needs jq (Debian 'jq')"
[[ -x /usr/bin/time ]] || die "needs GNU time at /usr/bin/time (Debian 'time')"
runs=${RUNS:-3}
depth=${DEPTH:-5}
threads=${THREADS:-$(nproc)}
reference_limit=${REFERENCE_LIMIT:-60}
run_limit=${RUN_LIMIT:-900}
sweep=${SWEEP:-1}
sweep_size=${SWEEP_SIZE:-256x256}
read -r -a sweep_balls <<< "${SWEEP_BALLS:-1 2 3 4 5}"
out=${OUT:-out/spd_benchmark}
mkdir -p "$out"
out=$(realpath "$out")
if [[ -v SCENES ]]; then read -r -a scenes <<< "$SCENES"; else scenes=("$repo_dir"/scenes/*.nff); fi
scenes+=("$@")
for scene in "${scenes[@]}"; do [[ -r $scene ]] || die "cannot read scene '$scene'"; done
source "$script_dir/timing.sh"

have_povray=0
if command -v povray >/dev/null; then have_povray=1; fi

# One raycube run: NAME RENDER_ARGS...; appends its numbers to $out/NAME.runs as
# "wall_s peak_kB preprocessing_s tracing_s rays primitives", "timeout" when stopped after the limit, or
# "failed" (a note on stderr; the other runs go on).
# LIMIT (environment) overrides RUN_LIMIT for this run.
run_raycube() {
  local name=$1
  shift
  local stats="$out/$name.json"
  timed "$name" "raycube render $*" timeout "${LIMIT:-$run_limit}" \
    "$raycube" render "$@" --depth "$depth" -q -o "$out/$name.exr" --stats "$stats" || return 0
  echo "$wall_peak $(jq -r '[.seconds.preprocessing, .seconds.tracing, .totalRays, .scene.objects] | @tsv' "$stats")" \
    >>"$out/$name.runs"
}

# Runs COMMAND... (output to $out/NAME.log) under GNU time for its peak memory, timing its wall clock to the
# microsecond with bash's clock (GNU time's 10 ms steps moved the ratios of 0.1-0.2 s runs by 5-10%): sets
# wall_peak to "wall_s peak_kB" and returns 0, or notes "timeout" (stopped after the limit) or "failed" in
# $out/NAME.runs and returns 1. DESCRIPTION names the command in the failure note.
timed() {
  local name=$1 description=$2
  shift 2
  local status=0 start=${EPOCHREALTIME/,/.}
  /usr/bin/time -f "%M" -o "$out/$name.time" "$@" >"$out/$name.log" 2>&1 || status=$?
  local end=${EPOCHREALTIME/,/.}
  if [[ $status == 124 ]]; then
    echo timeout >>"$out/$name.runs"
    return 1
  fi
  if [[ $status != 0 ]]; then
    echo "spd_benchmark.sh: $description failed (exit $status); see $out/$name.log" >&2
    echo failed >>"$out/$name.runs"
    return 1
  fi
  wall_peak="$(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.6f", b - a}') $(tail -n 1 "$out/$name.time")"
}

# POV-Ray: NAME POV_FILE WxH; its parse time counts as preprocessing, as raycube's reading of the NFF does not.
run_povray() {
  local name=$1 pov=$2 width=${3%x*} height=${3#*x}
  timed "$name" "povray $pov" env -C "$out" timeout "$run_limit" \
    povray "+I$pov" "+W$width" "+H$height" -A "+WT$threads" -D +FN "+O$out/$name.png" || return 0
  local parse trace
  parse=$(sed -n 's/^ *Parse Time:.*(\([0-9.]*\) seconds).*/\1/p' "$out/$name.log" | tail -n 1)
  trace=$(sed -n 's/^ *Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' "$out/$name.log" | tail -n 1)
  echo "$wall_peak ${parse:-0} ${trace:-0} - -" >>"$out/$name.runs"
}

# Median of column COLUMN (1-based) of NAME's runs; "timeout" or "failed" when a run was, "-" where the
# renderer does not report it (POV-Ray's rays).
column_median() {
  local file="$out/$1.runs"
  if grep -q timeout "$file"; then echo timeout; return; fi
  if grep -q failed "$file"; then echo failed; return; fi
  if awk -v c="$2" '$c == "-" {found = 1} END {exit !found}' "$file"; then echo -; return; fi
  awk -v c="$2" '{print $c}' "$file" | median
}

fmt() { awk -v v="$1" -v f="$2" 'BEGIN { if (v !~ /^[0-9.e+-]+$/ || v == "-") print v; else printf f, v }'; }

# The ratios, run by run, of column COLUMN_A (1-based, default 1: wall) of A's runs over column COLUMN_B of
# B's: line k of each .runs file is round k. Prints "median first-quartile third-quartile", or "- - -" when
# either is missing or had a run that failed or timed out.
paired_ratios() {
  local a="$out/$1.runs" b="$out/$2.runs" column_a=${3:-1} column_b=${4:-1}
  if [[ ! -f $a || ! -f $b ]] || grep -q "timeout\|failed" "$a" "$b"; then
    echo "- - -"
    return
  fi
  local ratios
  ratios=$(paste -d ' ' "$a" "$b" | awk -v a="$column_a" -v b="$column_b" 'NF == 12 && $(6 + b) > 0 {print $a / $(6 + b)}')
  echo "$(echo "$ratios" | median) $(echo "$ratios" | quantile 0.25) $(echo "$ratios" | quantile 0.75)"
}

# One markdown row: SCENE_LABEL RENDERER NAME IMAGE_PARALLEL_NAME
table_row() {
  local label=$1 renderer=$2 name=$3 baseline=$4
  local wall peak pre trace rays prims
  wall=$(column_median "$name" 1)
  if [[ $wall == timeout || $wall == failed ]]; then
    local what="over ${LIMIT_NOTE:-$run_limit} s"
    [[ $wall == timeout ]] || what="failed (see $out/$name.log)"
    echo "| $label | | $renderer | | | | | $what | |"
    return
  fi
  peak=$(column_median "$name" 2)
  pre=$(column_median "$name" 3)
  trace=$(column_median "$name" 4)
  rays=$(column_median "$name" 5)
  prims=$(awk '{print $6}' "$out/$name.runs" | head -n 1)
  local ratio=""
  if [[ $name != "$baseline" ]]; then
    ratio=$(paired_ratios "$name" "$baseline" | awk '$1 != "-" {printf "%.2f×", $1}')
  fi
  local mrays="-"
  [[ $rays == - ]] || mrays=$(awk -v r="$rays" -v t="$trace" 'BEGIN { if (t > 0) printf "%.3g", r / t / 1e6; else print "-" }')
  echo "| $label | $prims | $renderer | $(fmt "$pre" %.3f) | $(fmt "$trace" %.3f) | $mrays |" \
    "$(awk -v k="$peak" 'BEGIN {printf "%.0f", k / 1024}') | $(fmt "$wall" %.2f) | $ratio |"
}

# A table cell for paired_ratios' output: "median (quartiles)", as a percentage when FORMAT is %, bold when
# the median is above LIMIT (BOUND max) or below it (BOUND min).
target_cell() {
  local median first third
  read -r median first third <<< "$1"
  if [[ $median == - ]]; then echo "-"; return; fi
  awk -v m="$median" -v lo="$first" -v hi="$third" -v limit="$2" -v bound="$3" -v format="${4:-}" 'BEGIN {
    scale = format == "%" ? 100 : 1
    f = format == "%" ? "%.0f%%" : "%.2f"
    cell = sprintf(f " (" f "-" f ")", m * scale, lo * scale, hi * scale)
    shown = sprintf(f, m * scale) + 0  # the median as printed, against the limit
    miss = bound == "max" ? shown > limit * scale : shown < limit * scale
    print miss ? "**" cell "**" : cell
  }'
}

# One row of the targets table: SCENE_LABEL BASE (the runs' names are BASE.RENDERER).
targets_row() {
  local label=$1 b=$2
  echo "| $label | $(target_cell "$(paired_ratios "$b.machine4x4" "$b.image-parallel")" 1.5 max)" \
    "| $(target_cell "$(paired_ratios "$b.machine8x8" "$b.machine4x4")" 1.3 max)" \
    "| $(target_cell "$(paired_ratios "$b.machine4x4" "$b.machine4x4" 3 1)" 0.2 max %)" \
    "| $(target_cell "$(paired_ratios "$b.machine8x8" "$b.machine8x8" 3 1)" 0.2 max %)" \
    "| $(target_cell "$(paired_ratios "$b.machine4x4" "$b.image-parallel" 2 2)" 2 max)" \
    "| $(target_cell "$(paired_ratios "$b.machine8x8" "$b.image-parallel" 2 2)" 2 max)" \
    "| $(target_cell "$(paired_ratios "$b.povray" "$b.image-parallel")" 2 min) |"
}

# The names of round ROUND's renderers in the order they run: as given in odd rounds, reversed in even ones,
# so that a drift within a round weighs on every renderer alike.
round_order() {
  local round=$1
  shift
  if ((round % 2)); then printf '%s\n' "$@"; else printf '%s\n' "$@" | tac; fi
}

# ---- The scenes at their default sizes ----
if ((${#scenes[@]} > 0)); then
  pov_dir=$(mktemp -d /tmp/spd_benchmark_pov.XXXXXX)
  trap 'rm -rf "$pov_dir"' EXIT
  rows=() target_rows=()
  for scene in "${scenes[@]}"; do
    base=$(basename "$scene" .nff)
    size=${SIZE:-$(awk '$1 == "resolution" {print $2 "x" $3; exit}' "$scene")}
    size=${size:-512x512}
    echo "$base at $size: reference, image-parallel, machine 4x4 and 8x8, $runs runs" >&2
    rm -f "$out/$base".*.runs "$out/$base".*.time
    scene_args=("$scene" --size "$size")
    reference=1
    pov=""
    if [[ $have_povray == 1 && -r $script_dir/pov/$base.pov.gz ]]; then
      pov="$pov_dir/$base.pov"
      gunzip -c "$script_dir/pov/$base.pov.gz" >"$pov"
    fi
    for ((run = 1; run <= runs; ++run)); do
      if [[ $reference == 1 ]]; then
        LIMIT=$reference_limit run_raycube "$base.reference" "${scene_args[@]}" --mode reference
        grep -q "timeout\|failed" "$out/$base.reference.runs" && reference=0
      fi
      renderers=(image-parallel machine4x4 machine8x8)
      [[ -z $pov ]] || renderers+=(povray)
      for renderer in $(round_order "$run" "${renderers[@]}"); do
        case $renderer in
          image-parallel) run_raycube "$base.$renderer" "${scene_args[@]}" --mode image-parallel --threads "$threads" ;;
          machine4x4) run_raycube "$base.$renderer" "${scene_args[@]}" --mode machine --procs 4x4 ;;
          machine8x8) run_raycube "$base.$renderer" "${scene_args[@]}" --mode machine --procs 8x8 ;;
          povray) run_povray "$base.$renderer" "$pov" "$size" ;;
        esac
      done
    done
    for renderer in reference machine4x4 machine8x8; do
      if [[ -f $out/$base.$renderer.runs ]] && ! grep -q "timeout\|failed" "$out/$base.$renderer.runs" && ! "$raycube" compare "$out/$base.image-parallel.exr" \
        "$out/$base.$renderer.exr" >/dev/null; then
        echo "spd_benchmark.sh: warning: $base: $renderer's image differs from image-parallel's" >&2
      fi
    done
    label="$base ($size)"
    rows+=("$(LIMIT_NOTE=$reference_limit table_row "$label" reference "$base.reference" "$base.image-parallel")")
    rows+=("$(table_row "$label" "image-parallel ($threads threads)" "$base.image-parallel" "$base.image-parallel")")
    rows+=("$(table_row "$label" "machine 4×4" "$base.machine4x4" "$base.image-parallel")")
    rows+=("$(table_row "$label" "machine 8×8" "$base.machine8x8" "$base.image-parallel")")
    [[ -z $pov ]] || rows+=("$(table_row "$label" "POV-Ray 3.7 ($threads threads)" "$base.povray" "$base.image-parallel")")
    target_rows+=("$(targets_row "$label" "$base")")
  done >/dev/null
  echo "### The SPD scenes at their default sizes"
  echo
  echo "Depth $depth, median of $runs runs, $(nproc) cores; whole process = wall time of the command;" \
    "rays/s over the tracing time; the last column is the whole process over image-parallel's, the median of" \
    "the rounds' ratios."
  [[ $have_povray == 1 ]] || echo "POV-Ray is not installed (Debian 'povray'): no POV-Ray rows."
  echo
  echo "| scene | primitives | renderer | preprocessing (s) | tracing (s) | Mrays/s | peak memory (MB) | whole process (s) | / image-parallel |"
  echo "|---|---:|---|---:|---:|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "### Issue 13's targets, run by run"
  echo
  echo "Each ratio taken within each of the $runs rounds (the renderers of a round run back to back, in" \
    "alternating order), then its median (quartiles); bold where the median misses the target in the heading."
  echo
  echo "| scene | machine 4×4 / image-parallel (≤ 1.5) | 8×8 / 4×4 (≤ 1.3) | preprocessing 4×4 (≤ 20%) | preprocessing 8×8 (≤ 20%) | peak 4×4 / image-parallel (≤ 2) | peak 8×8 / image-parallel (≤ 2) | POV-Ray / image-parallel (≥ 2) |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
  printf '%s\n' "${target_rows[@]}"
  echo
fi

# ---- Cost per ray against primitives: SPD balls 1 to 5 ----
# Median microseconds per ray of NAME's runs (every ray of the tree): over the tracing time, over the whole
# process.
per_ray() {
  local name=$1
  if grep -q "timeout\|failed" "$out/$name.runs"; then echo "- -"; return; fi
  echo "$(awk '{print $4 / $5 * 1e6}' "$out/$name.runs" | median) $(awk '{print $1 / $5 * 1e6}' "$out/$name.runs" | median)"
}

if [[ $sweep == 1 ]]; then
  csv="$out/cost_per_ray.csv"
  echo "primitives,image-parallel ($threads threads),machine 4x4" >"$csv"
  sweep_rows=()
  for size in "${sweep_balls[@]}"; do
    echo "balls $size at $sweep_size: image-parallel and machine 4x4, $runs runs" >&2
    rm -f "$out/balls$size.sweep."*.runs
    for ((run = 1; run <= runs; ++run)); do
      for renderer in $(round_order "$run" image-parallel machine4x4); do
        if [[ $renderer == image-parallel ]]; then
          run_raycube "balls$size.sweep.$renderer" --balls "$size" --size "$sweep_size" --mode image-parallel \
            --threads "$threads"
        else
          run_raycube "balls$size.sweep.$renderer" --balls "$size" --size "$sweep_size" --mode machine --procs 4x4
        fi
      done
    done
    read -r ip_trace ip_whole <<< "$(per_ray "balls$size.sweep.image-parallel")"
    read -r m_trace m_whole <<< "$(per_ray "balls$size.sweep.machine4x4")"
    prims=$(awk '{print $6}' "$out/balls$size.sweep.image-parallel.runs" | head -n 1)
    rays=$(column_median "balls$size.sweep.image-parallel" 5)
    sweep_rows+=("| $size | $prims | $rays | $(fmt "$ip_trace" %.3f) | $(fmt "$ip_whole" %.3f) | $(fmt "$m_trace" %.3f) | $(fmt "$m_whole" %.3f) |")
    echo "$prims,$(fmt "$ip_trace" %.4f | tr -d -),$(fmt "$m_trace" %.4f | tr -d -)" >>"$csv"
  done
  echo "### Cost per ray against primitives (SPD balls, $sweep_size, depth $depth)"
  echo
  echo "Wall time per ray in microseconds (every ray of the tree: eye, reflected, light), median of $runs runs;" \
    "tracing = the tracing phase only, whole = the whole process."
  echo
  echo "| balls size | primitives | rays | image-parallel tracing (µs/ray) | image-parallel whole (µs/ray) | machine 4×4 tracing (µs/ray) | machine 4×4 whole (µs/ray) |"
  echo "|---:|---:|---:|---:|---:|---:|---:|"
  printf '%s\n' "${sweep_rows[@]}"
  echo
  "$raycube" plot "$csv" -o "$out/cost_per_ray.png" --log-x --y-label "tracing time per ray (µs)" \
    --title "Cost per ray against primitives: SPD balls sizes ${sweep_balls[0]} to ${sweep_balls[-1]}" \
    --caption "$sweep_size, depth $depth, median of $runs runs, $(nproc) cores; image-parallel $threads threads" >&2
  echo "plot: $out/cost_per_ray.png (data: $csv)"
fi
