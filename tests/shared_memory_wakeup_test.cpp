// Waking on the shared-memory interconnect (queues/interconnects/shared_memory_interconnect.h): a processor
// asleep for rays is woken once per step of the neighbour that sent them (ringNeighbours), not by every push;
// no wake-up may be lost, or two processors waiting for each other's rays would sleep for ever.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <span>
#include <thread>

#include "core/spd/balls.h"
#include "core/view.h"
#include "queues/interconnects/shared_memory_interconnect.h"

namespace raycube::queues {
namespace {

class SharedMemoryWakeup : public ::testing::Test {
 protected:
  SharedMemoryWakeup()
      : view_(core::makeBalls(1).camera, 16, 16, core::Sampling::Centers),
        regions_(node::RegionMap::grid({0, 8, 16}, {0, 8, 16}, node::ScreenLines(view_))),
        machine_(regions_, 4) {}
  node::Transport& at(int p) { return machine_.endpoint(p); }

  // Sends one ray from `from` to its neighbour `to` and ends the step, as the driver does.
  void sendAndEndStep(int from, int to, int round) {
    node::RayMessage m;
    m.tEnter = round;
    m.destination = std::uint16_t(to);
    ASSERT_EQ(at(from).trySend(to, std::span<const node::RayMessage>(&m, 1)), 1u);
    machine_.ringNeighbours(from);
  }
  // Sleeps until a ray arrives (or the machine is stopped), then takes it; returns its round, -1 if stopped.
  int awaitRay(int at_) {
    machine_.waitFor(at_, [&] { return at(at_).anyIncoming() || machine_.terminated(); });
    node::RayMessage m;
    return at(at_).receive(std::span<node::RayMessage>(&m, 1)) == 1 ? int(m.tEnter) : -1;
  }

  core::View view_;
  node::RegionMap regions_;
  SharedMemoryInterconnect<double> machine_;
};

TEST_F(SharedMemoryWakeup, ASleeperWakesWhenItsNeighbourEndsTheStepThatSentItARay) {
  ASSERT_EQ(regions_.faceToward(0, 1), node::Face::Right);  // neighbours
  std::future<int> received = std::async(std::launch::async, [&] { return awaitRay(1); });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // asleep by now, most likely
  sendAndEndStep(0, 1, 7);
  const bool woken = received.wait_for(std::chrono::seconds(10)) == std::future_status::ready;
  EXPECT_TRUE(woken) << "the end of the sender's step woke no one";
  if (!woken) at(0).announceTermination();  // rings every bell: the sleeper returns, the test ends
  EXPECT_EQ(received.get(), woken ? 7 : -1);
}

// Two neighbours answer each other's ray, each sleeping in between: thousands of hand-overs, any of which
// would hang if its ring were lost.
TEST_F(SharedMemoryWakeup, NeighboursWaitingForEachOtherNeverLoseAWakeUp) {
  constexpr int kRounds = 3000;
  std::future<int> ponger = std::async(std::launch::async, [&] {
    int answered = 0;
    for (int round = 0; round < kRounds; ++round) {
      if (awaitRay(1) != round) return answered;
      sendAndEndStep(1, 0, round);
      ++answered;
    }
    return answered;
  });
  std::future<int> pinger = std::async(std::launch::async, [&] {
    int answered = 0;
    for (int round = 0; round < kRounds; ++round) {
      sendAndEndStep(0, 1, round);
      if (awaitRay(0) != round) return answered;
      ++answered;
    }
    return answered;
  });
  const bool done = pinger.wait_for(std::chrono::seconds(60)) == std::future_status::ready &&
                    ponger.wait_for(std::chrono::seconds(10)) == std::future_status::ready;
  EXPECT_TRUE(done) << "a wake-up was lost";
  if (!done) at(0).announceTermination();
  EXPECT_EQ(pinger.get(), kRounds);
  EXPECT_EQ(ponger.get(), kRounds);
}

}  // namespace
}  // namespace raycube::queues
