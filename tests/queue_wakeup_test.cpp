#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "queues/doorbell.h"
#include "queues/spsc_queue.h"
#include "queues/wait.h"
#include "tests/queue_test_support.h"

namespace raycube::queues {
namespace {

using namespace std::chrono_literals;
using testing::runWatched;
using testing::scaled;

// Straight to the doorbell: every wait in these tests is a real sleep, not a lucky spin.
constexpr WaitPolicy kSleepAtOnce{.spins = 0, .yields = 0};

// A random pause before each step: none, a short spin, a yield, or (rarely) a real sleep, so that the
// other thread is caught at every point of its check-then-sleep sequence.
class RandomDelay {
 public:
  explicit RandomDelay(std::uint64_t seed) : random_(seed) {}
  void operator()() {
    const std::uint32_t r = random_();
    switch (r % 8) {
      case 0:
      case 1:
        break;
      case 2:
      case 3:
      case 4:
        for (std::uint32_t i = 0, n = (r >> 8) % 2000; i < n; ++i) cpuRelax();
        break;
      case 5:
      case 6:
        std::this_thread::yield();
        break;
      default:
        if ((r >> 8) % 16 == 0) std::this_thread::sleep_for(std::chrono::microseconds((r >> 12) % 50));
    }
  }

 private:
  std::minstd_rand random_;
};

// The shared watchdog: 120 s, 600 s under sanitizers (a loaded TSan run took longer than 120 s).
const auto kTimeLimit = raycube::testing_support::watchdogLimit();

// Every test runs with the ringer paying for the fence (kSymmetric) and with the sleeper paying
// (kAsymmetric).
class Wakeup : public ::testing::TestWithParam<FenceMode> {};

TEST_P(Wakeup, ConsumerAsleepOnEmptyWakesForOneMessage) {
  const std::uint64_t rounds = scaled(100'000, 100'000);
  runWatched(kTimeLimit, "a waiter missed its wake-up", [&] {
    Doorbell consumerBell(GetParam());
    SpscQueue<std::uint64_t> queue({.capacity = 128, .consumerBell = &consumerBell, .wait = kSleepAtOnce});
    std::thread producer([&] {
      RandomDelay delay(1);
      for (std::uint64_t i = 0; i < rounds; ++i) {
        delay();  // the consumer is (usually) asleep on the empty queue by now
        queue.push(i);
      }
    });
    std::uint64_t misordered = 0;
    for (std::uint64_t i = 0; i < rounds; ++i) misordered += queue.pop() != i;
    producer.join();
    EXPECT_EQ(misordered, 0u);
  });
}

TEST_P(Wakeup, ProducerAsleepOnFullWakesWhenOneSlotFrees) {
  const std::uint64_t rounds = scaled(100'000, 100'000);
  runWatched(kTimeLimit, "a waiter missed its wake-up", [&] {
    Doorbell producerBell(GetParam());
    SpscQueue<std::uint64_t> queue({.capacity = 1, .producerBell = &producerBell, .wait = kSleepAtOnce});
    std::thread consumer([&] {
      RandomDelay delay(2);
      for (std::uint64_t i = 0; i < rounds; ++i) {
        delay();  // the producer is (usually) asleep on the full queue by now
        std::uint64_t value = 0;
        while (!queue.tryPop(value)) std::this_thread::yield();
        EXPECT_EQ(value, i);
      }
    });
    for (std::uint64_t i = 0; i < rounds; ++i) queue.push(i);
    consumer.join();
  });
}

TEST_P(Wakeup, BothSidesSleepingOnATinyQueue) {
  const std::uint64_t rounds = scaled(100'000, 100'000);
  runWatched(kTimeLimit, "a waiter missed its wake-up", [&] {
    Doorbell consumerBell(GetParam()), producerBell(GetParam());
    SpscQueue<std::uint64_t> queue(
        {.capacity = 2, .consumerBell = &consumerBell, .producerBell = &producerBell, .wait = kSleepAtOnce});
    std::thread producer([&] {
      RandomDelay delay(3);
      for (std::uint64_t i = 0; i < rounds; ++i) {
        delay();
        queue.push(i);
      }
    });
    RandomDelay delay(4);
    std::uint64_t misordered = 0;
    for (std::uint64_t i = 0; i < rounds; ++i) {
      delay();
      misordered += queue.pop() != i;
    }
    producer.join();
    EXPECT_EQ(misordered, 0u);
  });
}

// The node loop: one doorbell, several incoming queues, a predicate over all of them.
TEST_P(Wakeup, OneDoorbellServesSeveralQueues) {
  constexpr int kFaces = 4;
  const std::uint64_t perFace = scaled(25'000, 25'000);
  runWatched(kTimeLimit, "a waiter missed its wake-up", [&] {
    Doorbell nodeBell(GetParam());
    std::array<std::unique_ptr<SpscQueue<std::uint64_t>>, kFaces> faces;
    for (auto& face : faces) {
      face =
          std::make_unique<SpscQueue<std::uint64_t>>(SpscOptions{.capacity = 8, .consumerBell = &nodeBell});
    }
    std::vector<std::thread> neighbours;
    for (int f = 0; f < kFaces; ++f) {
      neighbours.emplace_back([&, f] {
        RandomDelay delay(10 + f);
        for (std::uint64_t i = 0; i < perFace; ++i) {
          delay();
          faces[f]->push(i);
        }
      });
    }
    std::array<std::uint64_t, kFaces> next{};
    std::uint64_t received = 0, misordered = 0;
    auto anyMessage = [&] {
      for (const auto& face : faces) {
        if (face->hasMessage()) return true;
      }
      return false;
    };
    while (received < kFaces * perFace) {
      waitUntil(nodeBell, anyMessage, kSleepAtOnce);
      for (int f = 0; f < kFaces; ++f) {
        std::uint64_t value = 0;
        while (faces[f]->tryPop(value)) {
          misordered += value != next[f]++;
          ++received;
        }
      }
    }
    for (auto& t : neighbours) t.join();
    EXPECT_EQ(misordered, 0u);
  });
}

// A doorbell also wakes a waiter for things that are not queues, e.g. a termination token.
TEST_P(Wakeup, RingingWakesAWaiterOnAnyPredicate) {
  const int rounds = static_cast<int>(scaled(20'000, 2'000));
  runWatched(kTimeLimit, "a waiter missed its wake-up", [&] {
    Doorbell bell(GetParam());
    std::atomic<int> token{0};
    std::thread sender([&] {
      RandomDelay delay(5);
      for (int i = 1; i <= rounds; ++i) {
        delay();
        token.store(i, std::memory_order_release);
        bell.ring();
        while (token.load(std::memory_order_acquire) != -i) std::this_thread::yield();
      }
    });
    for (int i = 1; i <= rounds; ++i) {
      waitUntil(
          bell, [&] { return token.load(std::memory_order_acquire) == i; }, kSleepAtOnce);
      token.store(-i, std::memory_order_release);
    }
    sender.join();
  });
}

INSTANTIATE_TEST_SUITE_P(Fences, Wakeup, ::testing::Values(FenceMode::kAsymmetric, FenceMode::kSymmetric),
                         [](const auto& info) {
                           return info.param == FenceMode::kAsymmetric ? "Asymmetric" : "Symmetric";
                         });

TEST(Doorbell, UsesMembarrierWhereTheKernelHasIt) {
  EXPECT_EQ(Doorbell().fenceMode() == FenceMode::kAsymmetric, asymmetricFencesAvailable());
  EXPECT_EQ(Doorbell(FenceMode::kSymmetric).fenceMode(), FenceMode::kSymmetric);
}

// The futex underneath: a sleeper whose word already moved on does not sleep (a ring between its check and
// its sleep is not lost), and one wake reaches every sleeper.
TEST(Doorbell, SleepWhileReturnsAtOnceOnAWordThatMovedOn) {
  std::atomic<std::uint32_t> word{7};
  runWatched(kTimeLimit, "slept on a word that had moved on",
             [&] { sleepWhile(word, 6); });  // 7 is not 6: returns without a wake
}

TEST(Doorbell, WakeAllReachesEverySleeper) {
  std::atomic<std::uint32_t> word{0};
  std::atomic<int> awake{0};
  runWatched(kTimeLimit, "a sleeper missed the wake", [&] {
    std::vector<std::jthread> sleepers;
    for (int k = 0; k < 4; ++k)
      sleepers.emplace_back([&] {
        while (word.load(std::memory_order_acquire) == 0) sleepWhile(word, 0);
        awake.fetch_add(1);
      });
    std::this_thread::sleep_for(20ms);  // most of them asleep by now; the others see the word
    word.store(1, std::memory_order_release);
    wakeAll(word);
  });
  EXPECT_EQ(awake.load(), 4);
}

}  // namespace
}  // namespace raycube::queues
