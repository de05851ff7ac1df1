#!/bin/sh
# Runs the libFuzzer target for a given time: tests/fuzz/run.sh [seconds] [libFuzzer options...]
# (default 900 s).
# Builds it first with the `fuzz` preset (clang-14, ASan, UBSan). New inputs go to build/fuzz/corpus; crash
# reproducers to build/fuzz/artifacts: once fixed, copy each to tests/fuzz/regressions/ (replayed by ctest).
# Its custom mutator is NFF-aware (nff_mutator.h); the SPD scenes at size 1 join the seeds.
#
# tests/fuzz/run.sh campaign [seconds] [random seed]: the same oracle and mutator without libFuzzer, with
# the release preset's compiler (fuzz_campaign): failing inputs go to build/fuzz/campaign.
set -eu
cd "$(dirname "$0")/../.."
spdSeeds() {
  mkdir -p "$1"
  for scene in balls jacks lattice mount rings tetra; do
    "$2" spd "$scene:1" >"$1/${scene}1.nff"
  done
}
if [ "${1:-}" = campaign ]; then
  seconds=${2:-900}
  cmake --preset release >/dev/null
  cmake --build --preset release --target raycube fuzz_campaign
  mkdir -p build/fuzz/campaign
  spdSeeds build/fuzz/spd-seeds build/release/raycube
  exec nice ./build/release/fuzz_campaign build/fuzz/campaign "$seconds" "${3:-1}" tests/fuzz/seeds/*.nff \
    build/fuzz/spd-seeds/*.nff tests/fuzz/regressions/*.nff
fi
seconds=${1:-900}
[ $# -gt 0 ] && shift
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target fuzz_nff raycube
mkdir -p build/fuzz/corpus build/fuzz/artifacts
spdSeeds build/fuzz/spd-seeds build/fuzz/raycube
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
exec nice ./build/fuzz/fuzz_nff build/fuzz/corpus tests/fuzz/seeds build/fuzz/spd-seeds tests/fuzz/regressions \
  tests/data/nff -dict=tests/fuzz/nff.dict -max_total_time="$seconds" -timeout=60 -rss_limit_mb=2048 -max_len=4096 \
  -artifact_prefix=build/fuzz/artifacts/ -print_final_stats=1 "$@"
