// libFuzzer target (built with the `fuzz` preset, clang and RAYCUBE_FUZZ=ON): every input goes through the
// differential oracle; a failure aborts, so libFuzzer keeps the input as a crash reproducer. Add each one to
// tests/fuzz/regressions/ once fixed: fuzz_regressions_test replays them on every build.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <string_view>

#include "tests/fuzz/differential_oracle.h"
#include "tests/fuzz/nff_mutator.h"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t maxSize);

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string failure =
      raycube::fuzz::checkInput(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.nff");
  if (!failure.empty()) {
    std::fprintf(stderr, "ORACLE: %s\n", failure.c_str());
    std::abort();
  }
  return 0;
}

// Structure-aware (tests/fuzz/nff_mutator.h) three times in four, libFuzzer's own byte mutations otherwise
// (and whenever the NFF mutation would not fit).
extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t maxSize,
                                               unsigned int seed) {
  std::mt19937_64 random(seed);
  if (random() % 4 == 0) return LLVMFuzzerMutate(data, size, maxSize);
  const std::string mutated =
      raycube::fuzz::mutateNff(std::string_view(reinterpret_cast<const char*>(data), size), random);
  if (mutated.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
  std::memcpy(data, mutated.data(), mutated.size());
  return mutated.size();
}
