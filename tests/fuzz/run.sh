#!/bin/sh
# Runs the libFuzzer target for a given time: tests/fuzz/run.sh [seconds] [libFuzzer options...]
# (default 900 s).
# Builds it first with the `fuzz` preset (clang-14, ASan, UBSan). New inputs go to build/fuzz/corpus; crash
# reproducers to build/fuzz/artifacts: once fixed, copy each to tests/fuzz/regressions/ (replayed by ctest).
set -eu
cd "$(dirname "$0")/../.."
seconds=${1:-900}
[ $# -gt 0 ] && shift
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target fuzz_nff
mkdir -p build/fuzz/corpus build/fuzz/artifacts
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
exec nice ./build/fuzz/fuzz_nff build/fuzz/corpus tests/fuzz/seeds tests/fuzz/regressions tests/data/nff \
  -dict=tests/fuzz/nff.dict -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 -max_len=4096 \
  -artifact_prefix=build/fuzz/artifacts/ -print_final_stats=1 "$@"
