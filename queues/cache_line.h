#pragma once

#include <cstddef>

namespace raycube::queues {

// 128, not 64: x86 adjacent-line prefetchers fetch lines in pairs, so 64-byte padding still false-shares.
inline constexpr std::size_t kCacheLine = 128;

}  // namespace raycube::queues
