#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace raycube::queues {

inline constexpr std::size_t kOccupancyBuckets = 16;

// Saturation accounting of one queue, or the sum over a processor's queues (Priol & Bouatouch 3.7:
// "75 percent of the processes are locked due to the saturation of the FIFO queues").
struct QueueStats {
  std::uint64_t capacity = 0;           // summed when queues are added together
  std::uint64_t pushed = 0;             // messages
  std::uint64_t popped = 0;             // messages
  std::uint64_t refusedPushes = 0;      // try-push calls, or blocking episodes, that found the queue full
  std::uint64_t emptyPops = 0;          // try-pop calls, or blocking episodes, that found the queue empty
  std::uint64_t nanosBlockedFull = 0;   // time spent waiting in push/pushN
  std::uint64_t nanosBlockedEmpty = 0;  // time spent waiting in pop/popN
  // Occupancy is read where the producer reads the consumer's index anyway, or at a sample: every push
  // call up to capacity 8, then every capacity/8 messages, at most 64 (occupancySamplePeriod in
  // spsc_queue.h), so that accounting keeps the cached-index trick.
  std::uint64_t highWater = 0;         // largest occupancy seen after a push; a refused push sees it full
  std::uint64_t occupancySamples = 0;  // samples taken
  std::uint64_t occupancySum = 0;      // sum of the sampled occupancies
  // Bucket b counts samples with occupancy/capacity in [b/16, (b+1)/16); a full queue lands in the last.
  std::array<std::uint64_t, kOccupancyBuckets> occupancyHistogram{};

  double meanOccupancy() const {
    return occupancySamples == 0 ? 0.0 : static_cast<double>(occupancySum) / occupancySamples;
  }

  QueueStats& operator+=(const QueueStats& other);
};

inline std::size_t occupancyBucket(std::uint64_t occupancy, std::uint64_t capacity) {
  const std::uint64_t bucket = occupancy * kOccupancyBuckets / capacity;
  return bucket < kOccupancyBuckets ? bucket : kOccupancyBuckets - 1;
}

}  // namespace raycube::queues
