#pragma once
// Shared by the test programs.
#include <cstdlib>
#include <string>

namespace raycube::testing_support {

// Sanitized builds (the tsan and asan presets set RAYCUBE_SANITIZED=1) run 5-20x slower: tests shrink.
inline bool sanitized() {
  const char* value = std::getenv("RAYCUBE_SANITIZED");
  return value != nullptr && std::string(value) == "1";
}

}  // namespace raycube::testing_support
