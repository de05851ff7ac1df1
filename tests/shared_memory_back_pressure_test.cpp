// Machine-wide back-pressure on the shared-memory interconnect
// (queues/interconnects/shared_memory_interconnect.h): the processors' reports of waiting rays add up;
// primaries are held from the limit until fewer than the release wait, on every processor at once; and
// letting go wakes a processor asleep for it.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <thread>

#include "core/spd/balls.h"
#include "core/view.h"
#include "node/scheduling.h"
#include "queues/interconnects/shared_memory_interconnect.h"

namespace raycube::queues {
namespace {

class BackPressure : public ::testing::Test {
 protected:
  static constexpr std::size_t kLimit = 10;  // release below 5
  BackPressure()
      : view_(core::makeBalls(1).camera, 16, 16, core::Sampling::Centers),
        regions_(node::RegionMap::grid({0, 8, 16}, {0, 8, 16}, node::ScreenLines(view_))),
        machine_(regions_, 4, kLimit) {}
  node::Transport& at(int p) { return machine_.endpoint(p); }
  bool anyHeld() {
    bool any = false;
    for (int p = 0; p < 4; ++p) any |= at(p).primariesHeld();
    return any;
  }
  bool allHeld() {
    bool all = true;
    for (int p = 0; p < 4; ++p) all &= at(p).primariesHeld();
    return all;
  }

  core::View view_;
  node::RegionMap regions_;
  SharedMemoryInterconnect<double> machine_;
};

TEST_F(BackPressure, HeldFromTheLimitUntilFewerThanHalfWait) {
  ASSERT_EQ(node::scheduling::machineBacklogRelease(kLimit), 5u);
  at(0).countWaiting(6);
  at(1).countWaiting(3);
  EXPECT_EQ(machine_.waitingRays(), 9);
  EXPECT_FALSE(anyHeld());
  at(2).countWaiting(1);
  EXPECT_TRUE(allHeld());
  at(0).countWaiting(-4);  // 6 wait: still held
  EXPECT_TRUE(allHeld());
  at(1).countWaiting(-1);  // 5
  EXPECT_TRUE(allHeld());
  at(2).countWaiting(-1);  // 4: let go
  EXPECT_FALSE(anyHeld());
  at(3).countWaiting(5);  // 9: below the limit again, not held until it is reached
  EXPECT_FALSE(anyHeld());
  at(3).countWaiting(1);
  EXPECT_TRUE(allHeld());
}

TEST_F(BackPressure, TheReleaseWakesAProcessorAsleepForIt) {
  at(0).countWaiting(std::ptrdiff_t(kLimit));
  std::promise<void> woke;
  std::thread sleeper([&] {
    machine_.waitFor(3, [&] { return !at(3).primariesHeld() || machine_.terminated(); });
    woke.set_value();
  });
  std::future<void> done = woke.get_future();
  EXPECT_EQ(done.wait_for(std::chrono::milliseconds(100)), std::future_status::timeout) << "woke while held";
  at(0).countWaiting(-std::ptrdiff_t(kLimit));
  const bool woken = done.wait_for(std::chrono::seconds(10)) == std::future_status::ready;
  EXPECT_TRUE(woken) << "the release woke no one";
  if (!woken) at(0).announceTermination();  // rings every bell: the sleeper returns, the test ends
  sleeper.join();
}

TEST_F(BackPressure, ALimitOfNoRayIsRefused) {
  EXPECT_THROW(SharedMemoryInterconnect<double>(regions_, 4, 0), std::invalid_argument);
}

// Where memory is not shared (the iPSC, SimGrid, MPI) a transport has no machine-wide view: never held.
TEST(BackPressureElsewhere, ATransportWithoutAViewNeverHolds) {
  struct Distributed final : node::Transport {
    std::size_t trySend(int, std::span<const Message>) override { return 0; }
    std::size_t receive(std::span<Message>) override { return 0; }
    bool anyIncoming() const override { return false; }
    bool canSend(int) const override { return false; }
    void sendContribution(const core::Contribution&) override {}
    void flushContributions() override {}
    bool hasToken() const override { return false; }
    bool receiveToken(node::Token&) override { return false; }
    void passToken(const node::Token&) override {}
    void announceTermination() override {}
    bool terminated() const override { return false; }
  } transport;
  transport.countWaiting(1'000'000);
  EXPECT_FALSE(transport.primariesHeld());
}

}  // namespace
}  // namespace raycube::queues
