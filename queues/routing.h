#pragma once
// How a machine's network carries a message between two nodes that are not neighbours.
#include <cstdint>

namespace raycube::queues {

enum class Routing : std::uint8_t {
  StoreAndForward,  // iPSC/1: received and re-sent, in node software, by every node on the e-cube path
  Direct,           // a router or a switch: one transfer, whatever the distance
};

// E-cube routing on a hypercube: the next node from `at` towards `to` fixes the lowest differing bit.
inline std::uint32_t ecubeNextHop(std::uint32_t at, std::uint32_t to) {
  const std::uint32_t differ = at ^ to;
  return at ^ (differ & (~differ + 1));
}

}  // namespace raycube::queues
