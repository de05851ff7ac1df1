#pragma once
// Shared by the queue test programs.
#include <cstdint>

#include "test_support.h"

namespace raycube::queues::testing {

using raycube::testing_support::runWatched;
using raycube::testing_support::scaled;

// SplitMix64: a payload that differs for every sequence number, so torn or stale slots are caught.
inline std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace raycube::queues::testing
