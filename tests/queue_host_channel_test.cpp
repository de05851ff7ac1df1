#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

#include "queues/host_channel.h"
#include "queues/wait.h"
#include "tests/queue_test_support.h"

namespace raycube::queues {
namespace {

using namespace std::chrono_literals;

struct Contribution {
  std::uint32_t node = 0;
  std::uint32_t sequence = 0;
  float rgb[3] = {0, 0, 0};
};

TEST(HostChannel, SixtyFourNodesDeliverEveryContributionExactlyOnce) {
  constexpr std::size_t kNodes = 64;
  const std::uint32_t perNode = static_cast<std::uint32_t>(testing::scaled(20'000, 1'000));
  testing::runWatched(300s, "the host or a node missed its wake-up", [&] {
    std::vector<Doorbell> nodeBells(kNodes);
    std::vector<Doorbell*> bellPointers;
    for (auto& bell : nodeBells) bellPointers.push_back(&bell);
    // Few blocks per node so that nodes do fill their queue and sleep until the host drains it.
    HostChannel<Contribution, 16> channel(kNodes, 2, bellPointers);

    std::vector<std::thread> nodes;
    for (std::uint32_t n = 0; n < kNodes; ++n) {
      nodes.emplace_back([&, n] {
        auto sender = channel.sender(n);
        for (std::uint32_t s = 0; s < perNode; ++s) {
          sender.send({n, s, {1, 2, 3}});
          if (s % 1000 == 999) sender.flush();  // goes idle now and then: ships a partial block
        }
        sender.flush();
      });
    }

    std::vector<std::uint32_t> next(kNodes, 0);
    std::uint64_t received = 0, outOfOrder = 0, strays = 0;
    const std::uint64_t total = std::uint64_t{kNodes} * perNode;
    while (received < total) {
      waitUntil(channel.doorbell(), [&] { return channel.anyPending(); });
      received += channel.drain([&](const Contribution& c) {
        if (c.node >= kNodes || c.rgb[2] != 3) {
          ++strays;
          return;
        }
        outOfOrder += c.sequence != next[c.node];  // per node, blocks arrive in order
        next[c.node] = c.sequence + 1;
      });
    }
    for (auto& t : nodes) t.join();
    EXPECT_EQ(received, total);
    EXPECT_EQ(strays, 0u);
    EXPECT_EQ(outOfOrder, 0u);
    for (std::uint32_t n = 0; n < kNodes; ++n) EXPECT_EQ(next[n], perNode) << "node " << n;
    EXPECT_FALSE(channel.anyPending());
  });
}

TEST(HostChannel, PartialBlockWaitsForFlush) {
  HostChannel<Contribution, 8> channel(2);
  auto sender = channel.sender(1);
  for (std::uint32_t s = 0; s < 3; ++s) sender.send({1, s, {}});
  auto count = [&] { return channel.drain([](const Contribution&) {}); };
  EXPECT_EQ(count(), 0u);
  EXPECT_EQ(sender.unsent(), 3u);
  sender.flush();
  EXPECT_EQ(count(), 3u);
  for (std::uint32_t s = 0; s < 8; ++s) sender.send({1, s, {}});  // a full block ships by itself
  EXPECT_EQ(count(), 8u);
}

// A node fills its block in a slot of its queue; when the queue is full it fills a spare block instead,
// shipped once the host has made room, after the blocks before it.
TEST(HostChannel, ABlockStartedWhileTheQueueIsFullShipsAfterTheOthers) {
  HostChannel<Contribution, 4> channel(1, 1);
  auto sender = channel.sender(0);
  std::vector<std::uint32_t> received;
  auto drain = [&] { return channel.drain([&](const Contribution& c) { received.push_back(c.sequence); }); };
  for (std::uint32_t s = 0; s < 6; ++s) sender.send({0, s, {}});  // one block ships, the next waits
  EXPECT_EQ(sender.unsent(), 2u);
  EXPECT_EQ(drain(), 4u);
  sender.flush();                                                 // the spare, copied into the room made
  for (std::uint32_t s = 6; s < 9; ++s) sender.send({0, s, {}});  // the queue is full again: the spare
  EXPECT_EQ(drain(), 2u);
  sender.flush();
  EXPECT_EQ(drain(), 3u);
  for (std::uint32_t s = 9; s < 12; ++s) sender.send({0, s, {}});  // in place again
  sender.flush();
  EXPECT_EQ(drain(), 3u);
  std::vector<std::uint32_t> expected(12);
  for (std::uint32_t s = 0; s < 12; ++s) expected[s] = s;
  EXPECT_EQ(received, expected);
  EXPECT_FALSE(channel.anyPending());
}

TEST(HostChannel, RejectsMismatchedDoorbells) {
  std::vector<Doorbell*> bells(3, nullptr);
  EXPECT_THROW((HostChannel<Contribution>(4, 2, bells)), std::invalid_argument);
}

}  // namespace
}  // namespace raycube::queues
