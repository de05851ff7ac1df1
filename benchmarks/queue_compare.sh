#!/usr/bin/env bash
# Queue throughput of one or two builds of queue_saturation_benchmark (say before and after a change to
# queues/), run alternately so that drift in the machine's load hits both alike. Each round runs each build
# with --benchmark_repetitions=5, repetitions randomly interleaved; prints per benchmark the median over every
# repetition of millions of messages per second, and the second build's over the first's.
#
# usage: benchmarks/queue_compare.sh BENCHMARK_BINARY [OTHER_BENCHMARK_BINARY]
# environment: FILTER (default 'Throughput/ray'), ROUNDS (default 3). Needs jq.
set -euo pipefail
[[ $# -ge 1 && $# -le 2 ]] || { echo "usage: $0 BENCHMARK_BINARY [OTHER_BENCHMARK_BINARY]" >&2; exit 1; }
binaries=("$@")
filter=${FILTER:-Throughput/ray}
rounds=${ROUNDS:-3}
command -v jq > /dev/null || { echo "$0: needs jq" >&2; exit 1; }
out=$(mktemp -d /tmp/queue_compare.XXXXXX)
trap 'rm -rf "$out"' EXIT

for ((round = 1; round <= rounds; ++round)); do
  for i in "${!binaries[@]}"; do
    "${binaries[$i]}" --benchmark_filter="$filter" --benchmark_repetitions=5 \
      --benchmark_enable_random_interleaving=true --benchmark_format=json > "$out/run.json"
    jq -r '.benchmarks[] | select(.run_type == "iteration") | "\(.run_name) \(.items_per_second / 1e6)"' \
      "$out/run.json" >> "$out/$i.txt"
  done
done

# Median per benchmark name, in the order the first build lists them.
medians() { sort -k1,1 -k2,2g "$1" | awk '
  function flush() { if (n) printf "%s %.2f\n", name, (n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2) }
  $1 != name { flush(); name = $1; n = 0 } { v[++n] = $2 } END { flush() }'; }
medians "$out/0.txt" > "$out/0.med"
echo "$filter, $rounds rounds x 5 repetitions per build; M messages/s (median)"
if [[ ${#binaries[@]} -eq 1 ]]; then
  awk '{printf "%-90s %8s\n", $1, $2}' "$out/0.med"
else
  medians "$out/1.txt" > "$out/1.med"
  echo "columns: benchmark, ${binaries[0]}, ${binaries[1]}, second / first"
  join "$out/0.med" "$out/1.med" | awk '{printf "%-90s %8s %8s %6.2f\n", $1, $2, $3, $3 / $2}'
fi
