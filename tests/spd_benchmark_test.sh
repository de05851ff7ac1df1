#!/usr/bin/env bash
# benchmarks/spd_benchmark.sh on a small image (benchmarks/results/spd_default_sizes.md): its tables name every
# renderer, both take each ratio round by round (checked here against the rounds' own numbers, line k of one
# renderer's runs against line k of the other's), and a scene that fails is reported as failed while the
# others go on. Checks arithmetic and bookkeeping, never a time.
set -euo pipefail
source_dir=${1:?usage: spd_benchmark_test.sh SOURCE_DIR RAYCUBE_BINARY}
raycube=${2:?usage: spd_benchmark_test.sh SOURCE_DIR RAYCUBE_BINARY}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
fail() { echo "FAIL: $*"; status=1; }

printf 'v\nfrom 0 0\n' >"$work/broken.nff"  # a view cut short: raycube refuses it
RUNS=3 SIZE=48x48 SWEEP=0 REFERENCE_LIMIT=60 OUT="$work/out" \
  SCENES="$source_dir/scenes/tetra6.nff $work/broken.nff" \
  "$source_dir/benchmarks/spd_benchmark.sh" "$raycube" >"$work/tables.md" 2>"$work/progress.txt" ||
  fail "the script exited with $?"

for renderer in "reference" "image-parallel" "machine 4×4" "machine 8×8"; do
  grep -q "^| tetra6 (48x48) | 4096 | $renderer" "$work/tables.md" || fail "no tetra6 row for $renderer"
done
for name in reference image-parallel machine4x4 machine8x8; do
  [[ $(grep -c . "$work/out/tetra6.$name.runs") == 3 ]] || fail "tetra6 $name: not 3 runs"
done

# The targets row: every raycube ratio a number with its quartiles; POV-Ray has no tetra 6.
# (A cell is bold where it misses: a sanitized build's ratios do.)
row=$(grep "^| tetra6 (48x48) | \**[0-9.]* (" "$work/tables.md") || fail "no tetra6 targets row"
cells=$(awk -F'|' '{for (i = 3; i <= 8; ++i) print $i}' <<<"$row")
[[ $(grep -cE '^ \**[0-9.]+%? \([0-9.]+%?-[0-9.]+%?\)\** $' <<<"$cells") == 6 ]] ||
  fail "targets row cells are not 'median (quartiles)': $row"
[[ $(awk -F'|' '{print $9}' <<<"$row") == " - " ]] || fail "POV-Ray cell should be '-': $row"

# 4x4 over image-parallel, round by round: the median of the three rounds' own ratios.
expected=$(paste -d ' ' "$work/out/tetra6.machine4x4.runs" "$work/out/tetra6.image-parallel.runs" |
  awk '{print $1 / $7}' | sort -g | sed -n 2p)
printed=$(awk -F'|' '{print $3}' <<<"$row" | tr -d ' *' | cut -d'(' -f1)
[[ $(awk -v e="$expected" 'BEGIN {printf "%.2f", e}') == "$printed" ]] ||
  fail "4x4 / image-parallel printed $printed, the rounds give $expected"
main=$(grep "^| tetra6 (48x48) | 4096 | machine 4×4 " "$work/tables.md" | awk -F'|' '{print $10}' | tr -d ' ×')
[[ $main == "$printed" ]] || fail "the main table's 4x4 ratio $main is not the rounds' median $printed"
# Preprocessing share of the 8x8 run: its own preprocessing over its own wall time, round by round.
expected=$(awk '{print $3 / $1 * 100}' "$work/out/tetra6.machine8x8.runs" | sort -g | sed -n 2p)
printed=$(awk -F'|' '{print $6}' <<<"$row" | tr -d ' *' | cut -d'%' -f1)
[[ $(awk -v e="$expected" 'BEGIN {printf "%.0f", e}') == "$printed" ]] ||
  fail "8x8 preprocessing share printed $printed%, the rounds give $expected%"

# The broken scene: every renderer failed, said so, and left the targets empty.
[[ $(grep -c "^| broken (48x48) | | .* | failed (see " "$work/tables.md") == 4 ]] ||
  fail "broken.nff: not four failed rows"
grep -q "^| broken (48x48) | - | - | - | - | - | - | - |" "$work/tables.md" || fail "broken.nff: targets not '-'"
grep -q "broken.nff .*failed (exit" "$work/progress.txt" || fail "broken.nff: no failure note on stderr"

if ((status != 0)); then
  echo "--- tables:"; cat "$work/tables.md"; echo "--- progress:"; cat "$work/progress.txt"
fi
exit $status
