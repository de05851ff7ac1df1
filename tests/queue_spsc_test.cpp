#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "queues/spsc_queue.h"
#include "tests/queue_test_support.h"

namespace raycube::queues {
namespace {

using testing::mix;
using testing::scaled;

// About the size of a ray message, so that a torn copy of a slot is caught by the payload check.
struct Message {
  std::uint64_t sequence = 0;
  std::uint64_t check = 0;
  std::array<std::uint64_t, 10> payload{};
};

Message makeMessage(std::uint64_t sequence) {
  Message m{sequence, mix(sequence), {}};
  m.payload.front() = ~sequence;
  m.payload.back() = sequence * 3;
  return m;
}

bool intact(const Message& m) {
  return m.check == mix(m.sequence) && m.payload.front() == ~m.sequence && m.payload.back() == m.sequence * 3;
}

// kInPlace: the producer claims a slot, writes it there and publishes it; the consumer reads the front in
// place and releases it (neither copies a message).
enum class Mode { kSingle, kBatch, kSleeping, kInPlace };

std::string modeName(Mode mode) {
  switch (mode) {
    case Mode::kSingle:
      return "Single";
    case Mode::kBatch:
      return "Batch";
    case Mode::kSleeping:
      return "Sleeping";
    case Mode::kInPlace:
      return "InPlace";
  }
  return "?";
}

class SpscFuzz : public ::testing::TestWithParam<std::tuple<std::size_t, Mode>> {};

// Two threads: every message arrives once, in order, intact; the checksums of both sides agree.
TEST_P(SpscFuzz, DeliversEveryMessageOnceInOrder) {
  const auto [capacity, mode] = GetParam();
  const std::uint64_t count = scaled(mode == Mode::kSingle ? 10'000'000 : 1'000'000, 100'000);
  // (kInPlace reads a message where it lies: a torn slot shows in the copy taken before release.)
  Doorbell consumerBell, producerBell;
  SpscOptions options{.capacity = capacity};
  if (mode == Mode::kSleeping) {
    options.consumerBell = &consumerBell;
    options.producerBell = &producerBell;
    options.wait = {.spins = 16, .yields = 0};
  }
  SpscQueue<Message> queue(options);

  std::uint64_t producerSum = 0;
  std::thread producer([&] {
    std::vector<Message> batch;
    for (std::uint64_t sequence = 0; sequence < count;) {
      if (mode == Mode::kBatch) {
        const std::uint64_t n = std::min<std::uint64_t>(1 + sequence % 17, count - sequence);
        batch.clear();
        for (std::uint64_t i = 0; i < n; ++i) {
          batch.push_back(makeMessage(sequence + i));
          producerSum += batch.back().check;
        }
        queue.pushN(batch);
        sequence += n;
      } else if (mode == Mode::kInPlace) {
        // Every other message claims by waiting in the queue (claimWaiting), the others by retrying.
        Message* slot = nullptr;
        if (sequence % 2 == 1)
          slot = &queue.claimWaiting();
        else
          while ((slot = queue.claim()) == nullptr) std::this_thread::yield();
        *slot = makeMessage(sequence++);
        producerSum += slot->check;
        queue.publish();
      } else {
        const Message m = makeMessage(sequence++);
        producerSum += m.check;
        queue.push(m);
      }
    }
  });

  std::uint64_t consumerSum = 0, expected = 0, damaged = 0, misordered = 0;
  std::array<Message, 13> buffer;
  while (expected < count) {
    if (mode == Mode::kInPlace) {
      const Message* m = nullptr;
      while ((m = queue.front()) == nullptr) std::this_thread::yield();
      buffer[0] = *m;
      queue.release();
    }
    const std::size_t n = mode == Mode::kBatch     ? queue.popN(buffer)
                          : mode == Mode::kInPlace ? 1
                                                   : (buffer[0] = queue.pop(), 1);
    for (std::size_t i = 0; i < n; ++i) {
      const Message& m = buffer[i];
      if (!intact(m)) ++damaged;
      if (m.sequence != expected) ++misordered;
      consumerSum += m.check;
      expected = m.sequence + 1;
    }
  }
  producer.join();

  EXPECT_EQ(damaged, 0u);
  EXPECT_EQ(misordered, 0u);
  EXPECT_EQ(expected, count);
  EXPECT_EQ(consumerSum, producerSum);
  EXPECT_TRUE(queue.empty());
}

INSTANTIATE_TEST_SUITE_P(Capacities, SpscFuzz,
                         ::testing::Combine(::testing::Values(1, 2, 3, 128, 4096),
                                            ::testing::Values(Mode::kSingle, Mode::kBatch, Mode::kSleeping,
                                                              Mode::kInPlace)),
                         [](const auto& info) {
                           return "Capacity" + std::to_string(std::get<0>(info.param)) +
                                  modeName(std::get<1>(info.param));
                         });

// Indices count messages forever; start them just short of 2^64 and run through the wrap.
TEST(SpscQueue, IndicesWrapAroundAtAnyCapacity) {
  for (std::size_t capacity : {1, 2, 3, 5, 128, 130}) {
    SCOPED_TRACE("capacity " + std::to_string(capacity));
    const std::uint64_t nearMax = std::numeric_limits<std::uint64_t>::max() - 2 * capacity - 3;
    SpscQueue<std::uint64_t> queue({.capacity = capacity, .firstIndex = nearMax});
    std::uint64_t nextIn = 0, nextOut = 0;
    for (int round = 0; round < 8; ++round) {
      while (queue.tryPush(nextIn)) ++nextIn;  // fill to the brim
      ASSERT_EQ(queue.size(), capacity);
      ASSERT_FALSE(queue.tryPush(nextIn));
      for (std::size_t i = 0; i < (capacity + 1) / 2; ++i) {  // drain half
        std::uint64_t value = 0;
        ASSERT_TRUE(queue.tryPop(value));
        ASSERT_EQ(value, nextOut++);
      }
    }
    std::uint64_t value = 0;
    while (queue.tryPop(value)) ASSERT_EQ(value, nextOut++);
    EXPECT_EQ(nextOut, nextIn);
    EXPECT_GT(nextIn, 4 * capacity);  // went well past the wrap
  }
}

// In place and by copy share the indices: a claimed slot stays unseen until published, claim finds no slot
// in a full queue and front no message in an empty one, across the wrap at 2^64.
TEST(SpscQueue, InPlaceSlotsFollowTheIndicesAcrossTheWrap) {
  for (std::size_t capacity : {1, 2, 3, 128}) {
    SCOPED_TRACE("capacity " + std::to_string(capacity));
    SpscQueue<std::uint64_t> queue(
        {.capacity = capacity, .firstIndex = std::numeric_limits<std::uint64_t>::max() - capacity});
    std::uint64_t nextIn = 0, nextOut = 0;
    for (int round = 0; round < 6; ++round) {
      for (;;) {  // fill, alternately in place and by copy
        if (nextIn % 2 == 0) {
          std::uint64_t* slot = queue.claim();
          if (slot == nullptr) break;
          *slot = nextIn;
          EXPECT_EQ(queue.size(), nextIn - nextOut);  // not yet published
          queue.publish();
        } else if (!queue.tryPush(nextIn)) {
          break;
        }
        ++nextIn;
      }
      ASSERT_EQ(queue.size(), capacity);
      EXPECT_EQ(queue.claim(), nullptr);
      while (const std::uint64_t* front = queue.front()) {  // drain, alternately in place and by copy
        if (nextOut % 2 == 0) {
          ASSERT_EQ(*front, nextOut);
          queue.release();
        } else {
          std::uint64_t value = 0;
          ASSERT_TRUE(queue.tryPop(value));
          ASSERT_EQ(value, nextOut);
        }
        ++nextOut;
      }
      ASSERT_EQ(nextOut, nextIn);
      EXPECT_TRUE(queue.empty());
    }
    EXPECT_GT(nextIn, capacity + 1);  // went past the wrap
  }
}

TEST(SpscQueue, TwoThreadsAcrossTheWrap) {
  const std::uint64_t count = scaled(1'000'000, 100'000);
  SpscQueue<std::uint64_t> queue(
      {.capacity = 3, .firstIndex = std::numeric_limits<std::uint64_t>::max() - 1000});
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < count; ++i) queue.push(i);
  });
  std::uint64_t misordered = 0;
  for (std::uint64_t i = 0; i < count; ++i) misordered += queue.pop() != i;
  producer.join();
  EXPECT_EQ(misordered, 0u);
}

TEST(SpscQueue, BatchPushTakesTheLongestPrefixThatFits) {
  SpscQueue<int> queue(5);
  const std::vector<int> first{1, 2, 3}, second{4, 5, 6, 7};
  EXPECT_EQ(queue.tryPushN(first), 3u);
  EXPECT_EQ(queue.tryPushN(second), 2u);
  EXPECT_EQ(queue.tryPushN(second), 0u);
  std::array<int, 4> out{};
  EXPECT_EQ(queue.tryPopN(out), 4u);
  EXPECT_EQ(out, (std::array<int, 4>{1, 2, 3, 4}));
  EXPECT_EQ(queue.tryPopN(out), 1u);
  EXPECT_EQ(out[0], 5);
  EXPECT_EQ(queue.tryPopN(out), 0u);
}

TEST(SpscQueue, DefaultCapacityIsThePapersFifo) {
  SpscQueue<int> queue;
  EXPECT_EQ(queue.capacity(), 128u);
}

TEST(SpscQueue, RejectsZeroCapacity) {
  EXPECT_THROW(SpscQueue<int>(0), std::invalid_argument);
}

// Queues carved from one SlotStorage (a machine's FIFOs): each takes its power of two of slots, keeps its
// messages apart from its neighbours' across the wrap, and storage too small for one more queue says so.
TEST(SpscQueue, QueuesSharingSlotStorageKeepTheirMessagesApart) {
  SlotStorage<int> storage(2 * spscSlotsFor(3));
  SpscQueue<int> a(SpscOptions{.capacity = 3}, storage);
  SpscQueue<int> b(SpscOptions{.capacity = 3}, storage);
  for (int round = 0; round < 5; ++round) {  // 15 messages each: around the 4 slots several times
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(a.tryPush(100 * round + i));
      ASSERT_TRUE(b.tryPush(-(100 * round + i)));
    }
    EXPECT_FALSE(a.tryPush(7));
    EXPECT_FALSE(b.tryPush(7));
    for (int i = 0; i < 3; ++i) {
      int x = 0, y = 0;
      ASSERT_TRUE(a.tryPop(x));
      ASSERT_TRUE(b.tryPop(y));
      EXPECT_EQ(x, 100 * round + i);
      EXPECT_EQ(y, -(100 * round + i));
    }
  }
  EXPECT_THROW(SpscQueue<int>(SpscOptions{.capacity = 1}, storage), std::length_error);
}

// Filled to the brim (occupancies 1 to 4), refused twice, drained, found empty once; by copy or in place (a
// slot claimed and published is a push, a claim finding the queue full a refused push, a front finding it
// empty an empty pop), the same accounting.
TEST(SpscQueue, AccountingCountsRefusalsHighWaterAndOccupancy) {
  for (bool inPlace : {false, true}) {
    SCOPED_TRACE(inPlace ? "in place" : "by copy");
    SpscQueue<int, Accounting::kOn> queue(4);
    auto push = [&](int value) {
      if (!inPlace) return queue.tryPush(value);
      int* slot = queue.claim();
      if (slot == nullptr) return false;
      *slot = value;
      queue.publish();
      return true;
    };
    auto pop = [&] {
      int value = 0;
      if (!inPlace) return queue.tryPop(value);
      if (queue.front() == nullptr) return false;
      queue.release();
      return true;
    };
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(push(i));
    EXPECT_FALSE(push(9));
    EXPECT_FALSE(push(9));
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(pop());
    EXPECT_FALSE(pop());

    const QueueStats stats = queue.stats();
    EXPECT_EQ(stats.capacity, 4u);
    EXPECT_EQ(stats.pushed, 4u);
    EXPECT_EQ(stats.popped, 4u);
    EXPECT_EQ(stats.refusedPushes, 2u);
    EXPECT_EQ(stats.emptyPops, 1u);
    EXPECT_EQ(stats.highWater, 4u);
    EXPECT_EQ(stats.occupancySamples, 4u);
    EXPECT_DOUBLE_EQ(stats.meanOccupancy(), 2.5);
    // Occupancy 1/4 -> bucket 4, 2/4 -> 8, 3/4 -> 12, full -> the last bucket.
    EXPECT_EQ(stats.occupancyHistogram[4], 1u);
    EXPECT_EQ(stats.occupancyHistogram[8], 1u);
    EXPECT_EQ(stats.occupancyHistogram[12], 1u);
    EXPECT_EQ(stats.occupancyHistogram[kOccupancyBuckets - 1], 1u);
  }
}

// Accounting keeps the cached-index trick: a larger queue samples its occupancy every capacity/8 messages
// rather than at every push, counts messages by its indices (here across the wrap at 2^64), and a refused
// push still records the queue full.
TEST(SpscQueue, AccountingSamplesOccupancyEveryEighthOfTheCapacity) {
  EXPECT_EQ(occupancySamplePeriod(1), 1u);
  EXPECT_EQ(occupancySamplePeriod(8), 1u);
  EXPECT_EQ(occupancySamplePeriod(100), 16u);
  EXPECT_EQ(occupancySamplePeriod(4096), 64u);
  SpscQueue<int, Accounting::kOn> queue(SpscOptions{.capacity = 128, .firstIndex = ~std::uint64_t{0} - 60});
  for (int i = 0; i < 128; ++i) ASSERT_TRUE(queue.tryPush(i));
  EXPECT_FALSE(queue.tryPush(0));
  int value = 0;
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(queue.tryPop(value));

  const QueueStats stats = queue.stats();
  EXPECT_EQ(stats.pushed, 128u);
  EXPECT_EQ(stats.popped, 100u);
  EXPECT_EQ(stats.refusedPushes, 1u);
  EXPECT_EQ(stats.highWater, 128u);
  // Samples after pushes 1, 17, 33, ..., 113.
  EXPECT_EQ(stats.occupancySamples, 8u);
  EXPECT_EQ(stats.occupancySum, 8u + 16u * (0 + 1 + 2 + 3 + 4 + 5 + 6 + 7));
  EXPECT_EQ(stats.occupancyHistogram[0], 1u);   // 1 of 128
  EXPECT_EQ(stats.occupancyHistogram[14], 1u);  // 113 of 128
}

TEST(SpscQueue, AccountingTimesBlockingOnFullAndEmpty) {
  // One side waits until the other is known to be blocked (a blocking episode is counted once its clock has
  // started), then holds it 20 ms: the lower bounds hold however the threads are scheduled.
  SpscQueue<int, Accounting::kOn> queue(1);
  auto waitUntilCounted = [&](auto counter, std::uint64_t above) {
    while (counter(queue.stats()) <= above) std::this_thread::yield();
  };
  queue.push(1);
  std::thread consumer([&] {
    waitUntilCounted([](const QueueStats& s) { return s.refusedPushes; }, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(queue.pop(), 1);  // frees the producer, blocked on the full queue
    EXPECT_EQ(queue.pop(), 2);
  });
  queue.push(2);
  consumer.join();
  const QueueStats full = queue.stats();
  EXPECT_GE(full.nanosBlockedFull, 20'000'000u);
  EXPECT_EQ(full.refusedPushes, 1u);

  std::thread emptyConsumer([&] { EXPECT_EQ(queue.pop(), 3); });  // blocks on the empty queue
  waitUntilCounted([](const QueueStats& s) { return s.emptyPops; }, full.emptyPops);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  queue.push(3);
  emptyConsumer.join();
  EXPECT_GE(queue.stats().nanosBlockedEmpty - full.nanosBlockedEmpty, 20'000'000u);
}

TEST(SpscQueue, ClaimWaitingBlocksOnAFullQueueAsPushDoes) {
  SpscQueue<int, Accounting::kOn> queue(1);
  queue.push(1);
  std::thread consumer([&] {
    while (queue.stats().refusedPushes == 0) std::this_thread::yield();  // the producer is waiting
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(queue.pop(), 1);
    EXPECT_EQ(queue.pop(), 2);
  });
  int& slot = queue.claimWaiting();  // returns once the consumer has freed the only slot
  slot = 2;
  queue.publish();
  consumer.join();
  EXPECT_EQ(queue.stats().refusedPushes, 1u);
  EXPECT_GE(queue.stats().nanosBlockedFull, 20'000'000u);
}

TEST(SpscQueue, WithoutAccountingStatsStayZeroAndCostNoSpace) {
  SpscQueue<int> queue(4);
  queue.push(1);
  EXPECT_EQ(queue.stats().pushed, 0u);
  EXPECT_EQ(queue.stats().capacity, 4u);
  EXPECT_LT(sizeof(SpscQueue<int>), sizeof(SpscQueue<int, Accounting::kOn>));
}

TEST(QueueStats, AddingKeepsTheHighestHighWater) {
  QueueStats a, b;
  a.highWater = 7;
  a.pushed = 2;
  b.highWater = 3;
  b.pushed = 5;
  b.occupancyHistogram[2] = 1;
  a += b;
  EXPECT_EQ(a.highWater, 7u);
  EXPECT_EQ(a.pushed, 7u);
  EXPECT_EQ(a.occupancyHistogram[2], 1u);
}

}  // namespace
}  // namespace raycube::queues
