#!/usr/bin/env bash
# Two commands timed in pairs, to tell a change of a few percent from the drift of a shared machine: this
# project's 2-vCPU guest runs the same render 10-50% slower from one minute to the next, which medians of
# separate series do not cancel. Each round runs A and B back to back (ABBA order, so a drift within the
# round hits both alike) and takes the ratio B / A of their CPU times (user + system) and of their wall times;
# the medians and quartiles of those ratios are printed, with each command's median times.
#
# usage: benchmarks/paired_compare.sh ROUNDS "COMMAND A" "COMMAND B"
#   e.g. benchmarks/paired_compare.sh 12 "build/release/raycube render scenes/mount6.nff --procs 8x8 -q" \
#                                         "build/release/raycube render scenes/mount6.nff --procs 8x8 -q --cells bvh"
# The commands' own output is discarded; they run through bash (quote them as one argument each). Timed by
# bash's own `time` (milliseconds: GNU time's 10 ms moved ratios on 0.1-0.2 s runs in steps of 5-10%).
set -euo pipefail

die() { echo "paired_compare.sh: $*" >&2; exit 1; }
[[ $# -eq 3 ]] || die "usage: $0 ROUNDS \"COMMAND A\" \"COMMAND B\""
rounds=$1
[[ $rounds =~ ^[1-9][0-9]*$ ]] || die "ROUNDS must be a positive integer, got '$rounds'"
source "$(dirname "$0")/timing.sh"

# One run of a command: its CPU (user + system, its children's included) and wall seconds into `cpu` and
# `wall`; a failing command stops the comparison.
measure() {
  local timing
  timing=$( { TIMEFORMAT='%3U %3S %3R'; time bash -c "$1" > /dev/null 2>&1; } 2>&1) || die "failed: $1"
  read -r cpu wall < <(awk '{printf "%.3f %.3f\n", $1 + $2, $3}' <<< "$timing")
}

cpu_a="" cpu_b="" wall_a="" wall_b="" cpu_ratio="" wall_ratio=""
for ((round = 1; round <= rounds; ++round)); do
  if ((round % 2)); then
    measure "$2" && ca=$cpu wa=$wall
    measure "$3" && cb=$cpu wb=$wall
  else
    measure "$3" && cb=$cpu wb=$wall
    measure "$2" && ca=$cpu wa=$wall
  fi
  cpu_a+="$ca " cpu_b+="$cb " wall_a+="$wa " wall_b+="$wb "
  cpu_ratio+="$(awk -v a="$ca" -v b="$cb" 'BEGIN {print (a > 0) ? b / a : 0}') "
  wall_ratio+="$(awk -v a="$wa" -v b="$wb" 'BEGIN {print (a > 0) ? b / a : 0}') "
  echo "round $round/$rounds: A cpu $ca s wall $wa s, B cpu $cb s wall $wb s" >&2
done

summary() {  # name, ratios, A's times, B's times
  local ratios=$2
  printf '%-4s A median %.3f s, B median %.3f s; B / A median %.3f (quartiles %.3f-%.3f)\n' "$1" \
    "$(echo "$3" | median)" "$(echo "$4" | median)" "$(echo "$ratios" | median)" \
    "$(echo "$ratios" | quantile 0.25)" "$(echo "$ratios" | quantile 0.75)"
}
echo "A: $2"
echo "B: $3"
echo "$rounds rounds, ABBA order"
summary cpu "$cpu_ratio" "$cpu_a" "$cpu_b"
summary wall "$wall_ratio" "$wall_a" "$wall_b"
