// libFuzzer target (built with the `fuzz` preset, clang and RAYCUBE_FUZZ=ON): every input goes through the
// differential oracle; a failure aborts, so libFuzzer keeps the input as a crash reproducer. Add each one to
// tests/fuzz/regressions/ once fixed: fuzz_regressions_test replays them on every build.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "tests/fuzz/differential_oracle.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string failure =
      raycube::fuzz::checkInput(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.nff");
  if (!failure.empty()) {
    std::fprintf(stderr, "ORACLE: %s\n", failure.c_str());
    std::abort();
  }
  return 0;
}
