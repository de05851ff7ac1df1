#!/usr/bin/env bash
# benchmarks/instruction_counts.sh on a small image (benchmarks/results/instruction_counts.md): its rows name each
# renderer, every ratio and per-message figure is the one its own counts give, the layers add up to the
# whole, image-parallel runs no interconnect, and a scene that fails is reported as failed while the others
# go on. Checks arithmetic and bookkeeping, never a count's size.
set -euo pipefail
source_dir=${1:?usage: instruction_counts_test.sh SOURCE_DIR RAYCUBE_BINARY}
raycube=${2:?usage: instruction_counts_test.sh SOURCE_DIR RAYCUBE_BINARY}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0
fail() { echo "FAIL: $*"; status=1; }

printf 'v\nfrom 0 0\n' >"$work/broken.nff"  # a view cut short: raycube refuses it
SIZE=32x32 GRIDS="2x2" OUT="$work/out" SCENES="$source_dir/scenes/balls2.nff $work/broken.nff" \
  "$source_dir/benchmarks/instruction_counts.sh" "$raycube" >"$work/tables.md" 2>"$work/progress.txt" ||
  fail "the script exited with $?"

counts() { cat "$work/out/balls2.$1.counts"; }
read -r ip_total ip_segments ip_messages ip_core ip_node ip_queues ip_host ip_libraries <<<"$(counts image-parallel)"
read -r m_total m_segments m_messages m_core m_node m_queues m_host m_libraries <<<"$(counts machine2x2)"

# The counts row of each renderer, with the ratio and the instructions per message its counts give.
grep -q "^| balls2 (32x32) | image-parallel | [0-9.]* | 1.000 | $ip_segments | 0 | - |" "$work/tables.md" ||
  fail "no image-parallel counts row with $ip_segments segments"
((m_messages > 0)) || fail "balls 2 on 2x2 processors sent no message"
ratio=$(awk -v a="$m_total" -v b="$ip_total" 'BEGIN {printf "%.3f", a / b}')
per_message=$(awk -v a="$m_total" -v b="$ip_total" -v m="$m_messages" 'BEGIN {printf "%.0f", (a - b) / m}')
grep -q "^| balls2 (32x32) | machine 2x2 | [0-9.]* | $ratio | $m_segments | $m_messages | $per_message |" \
  "$work/tables.md" || fail "the machine's row does not give ratio $ratio, $m_messages messages, $per_message per message"
# Image-parallel evaluates each ray once, the machine once per processor it reaches.
[[ $ip_segments == $(jq .totalRays "$work/out/balls2.image-parallel.json") ]] || fail "image-parallel's segments are not its rays"
((m_segments > ip_segments)) || fail "the machine's $m_segments segments do not exceed the $ip_segments rays"

# The layers are the whole, and image-parallel does not run the interconnect.
for renderer in image-parallel machine2x2; do
  read -r -a c <<<"$(counts $renderer)"  # total, segments, messages, then the five layers
  layers=$((c[3] + c[4] + c[5] + c[6] + c[7]))
  ((layers == c[0])) || fail "$renderer: the layers sum to $layers, not ${c[0]}"
done
# (Image-parallel's process only asks once whether the kernel offers membarrier, a queues function.)
((ip_queues * 10000 < ip_total)) || fail "image-parallel counted $ip_queues instructions in the queues"
((m_queues > 0 && m_node > 0)) || fail "the machine counted nothing in its node or queues"
grep -q "^| balls2 (32x32) | machine 2x2 − image-parallel | [-+]" "$work/tables.md" || fail "no difference row"

# The broken scene: both renderers failed, said so; balls 2's rows are there all the same.
[[ $(grep -c "^| broken (32x32) | .* | failed (see " "$work/tables.md") == 2 ]] || fail "broken.nff: not two failed rows"
grep -q "broken.image-parallel: failed" "$work/progress.txt" || fail "broken.nff: no failure note on stderr"

if ((status != 0)); then
  echo "--- tables:"; cat "$work/tables.md"; echo "--- progress:"; cat "$work/progress.txt"
fi
exit $status
