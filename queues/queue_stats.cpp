#include "queues/queue_stats.h"

#include <algorithm>

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

}  // namespace raycube::queues
