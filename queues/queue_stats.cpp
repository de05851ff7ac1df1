#include "queues/queue_stats.h"

#include <algorithm>
#include <sstream>

namespace raycube::queues {

QueueStats& QueueStats::operator+=(const QueueStats& other) {
  capacity += other.capacity;
  pushed += other.pushed;
  popped += other.popped;
  refusedPushes += other.refusedPushes;
  emptyPops += other.emptyPops;
  nanosBlockedFull += other.nanosBlockedFull;
  nanosBlockedEmpty += other.nanosBlockedEmpty;
  highWater = std::max(highWater, other.highWater);
  occupancySamples += other.occupancySamples;
  occupancySum += other.occupancySum;
  for (std::size_t b = 0; b < kOccupancyBuckets; ++b) occupancyHistogram[b] += other.occupancyHistogram[b];
  return *this;
}

std::string QueueStats::toString() const {
  std::ostringstream out;
  out << "capacity " << capacity << ", pushed " << pushed << ", popped " << popped << ", refused pushes "
      << refusedPushes << ", empty pops " << emptyPops << ", blocked full " << nanosBlockedFull * 1e-9
      << " s, blocked empty " << nanosBlockedEmpty * 1e-9 << " s, high water " << highWater
      << ", mean occupancy " << meanOccupancy() << ", histogram [";
  for (std::size_t b = 0; b < kOccupancyBuckets; ++b) out << (b ? " " : "") << occupancyHistogram[b];
  out << "]";
  return out.str();
}

}  // namespace raycube::queues
