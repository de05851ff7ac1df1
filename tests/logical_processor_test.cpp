// One logical processor, and a few of them, against a fake transport stepped by hand in one thread: what
// goes in (primary rays, received rays, the token) and what comes out (rays, contributions, counts),
// with no thread, no clock and no waiting (node/logical_processor.h).
#include "node/logical_processor.h"

#include <gtest/gtest.h>

#include <deque>
#include <map>
#include <optional>
#include <utility>

#include "core/spd/balls.h"
#include "host/render/framebuffer.h"
#include "host/render/sequential_renderers.h"
#include "node/scheduling.h"

namespace raycube::node {
namespace {

using Message = RayMessage;

// Every FIFO of a small machine as plain deques of a fixed capacity, the token as an optional per node.
struct FakeInterconnect {
  FakeInterconnect(const RegionMap& regions, std::size_t capacity) : regions(regions), capacity(capacity) {
    tokens.resize(std::size_t(regions.processors()));
  }
  std::deque<Message>& fifo(int from, int to) { return fifos[{from, to}]; }

  const RegionMap& regions;
  std::size_t capacity;
  std::map<std::pair<int, int>, std::deque<Message>> fifos;
  std::vector<std::optional<Token>> tokens;
  std::vector<core::Contribution> contributions;
  std::size_t raysSent = 0;
  bool terminated = false;
};

class FakeTransport final : public Transport {
 public:
  FakeTransport(FakeInterconnect& net, int id) : net_(net), id_(id) {}
  std::size_t trySend(int neighbour, std::span<const Message> messages) override {
    std::deque<Message>& q = net_.fifo(id_, neighbour);
    std::size_t n = 0;
    for (; n < messages.size() && q.size() < net_.capacity; ++n) q.push_back(messages[n]);
    net_.raysSent += n;
    return n;
  }
  std::size_t receive(std::span<Message> into) override {
    std::size_t n = 0;
    for (int from : net_.regions.neighbours(id_)) {
      std::deque<Message>& q = net_.fifo(from, id_);
      while (!q.empty() && n < into.size()) {
        into[n++] = q.front();
        q.pop_front();
      }
    }
    return n;
  }
  bool anyIncoming() const override {
    for (int from : net_.regions.neighbours(id_))
      if (!net_.fifo(from, id_).empty()) return true;
    return false;
  }
  bool canSend(int neighbour) const override { return net_.fifo(id_, neighbour).size() < net_.capacity; }
  void sendContribution(const core::Contribution& c) override { unsent_.push_back(c); }
  void flushContributions() override {
    net_.contributions.insert(net_.contributions.end(), unsent_.begin(), unsent_.end());
    unsent_.clear();
  }
  bool hasToken() const override { return net_.tokens[id_].has_value(); }
  bool receiveToken(Token& token) override {
    if (!hasToken()) return false;
    token = *net_.tokens[id_];
    net_.tokens[id_].reset();
    return true;
  }
  void passToken(const Token& token) override {
    net_.tokens[std::size_t((id_ + 1) % net_.regions.processors())] = token;
  }
  void announceTermination() override { net_.terminated = true; }
  bool terminated() const override { return net_.terminated; }

 private:
  FakeInterconnect& net_;
  int id_;
  std::vector<core::Contribution> unsent_;
};

class LogicalProcessorTest : public ::testing::Test {
 protected:
  static constexpr int kSide = 24;

  LogicalProcessorTest() : scene_(core::makeBalls(1)) {}

  MachineContext contextFor(int columns, int rows) const {
    const core::View view(scene_.camera, kSide, kSide, core::Sampling::Centers);
    const ScreenLines lines(view);
    auto cuts = [](int samples, int parts) {
      std::vector<int> c;
      for (int k = 0; k <= parts; ++k) c.push_back(samples * k / parts);
      return c;
    };
    return MachineContext{view,
                          core::ShadingOptions{},
                          RegionMap::grid(cuts(kSide, columns), cuts(kSide, rows), lines),
                          {},
                          {}};
  }

  // Every object offered to every node (the node keeps those touching its region), light rays as messages.
  NodeSetup setupFor(const MachineContext& context, int id) const {
    NodeSetup s;
    s.id = id;
    s.lightRays = LightRayMode::Messages;
    std::vector<EyeBox> boxes;
    for (const core::Object& o : scene_.objects)
      boxes.push_back(eyeBoxOf(o, context.view, 2 * scene_.largestCoordinate()));
    for (std::uint32_t o = 0; o < boxes.size(); ++o) {
      s.objects.push_back(o);
      if (reachesBehindEye(boxes[o])) s.rearObjects.push_back(o);
    }
    std::vector<std::uint32_t>* lists[] = {&s.objects, &s.rearObjects};
    s.objectBoxes = eyeBoxesOf(boxes, s.objects);
    s.database = std::make_shared<const RegionDatabase>(gatherRegionDatabase(scene_, lists));
    return s;
  }

  core::Image referenceImage() const {
    host::RenderSettings settings;
    settings.width = settings.height = kSide;
    settings.progress = false;
    return host::renderReference(scene_, settings).image;
  }

  static core::Image imageOf(const MachineContext& context, const std::vector<core::Contribution>& cs) {
    host::Framebuffer frame(context.view.samplesX(), context.view.samplesY());
    for (const core::Contribution& c : cs) frame.add(c);
    return frame.resolve(context.view);
  }

  core::Scene scene_;
};

TEST_F(LogicalProcessorTest, OneProcessorTracesTheWholeImageAndProvesItsOwnTermination) {
  const MachineContext context = contextFor(1, 1);
  FakeInterconnect net(context.regions, 4);
  FakeTransport transport(net, 0);
  LogicalProcessor<double> node(context, setupFor(context, 0), transport);
  int steps = 0;
  Step s;
  while ((s = node.step()) != Step::Terminated) {
    ASSERT_LT(++steps, 10 * kSide * kSide) << "the node never terminated";
    ASSERT_TRUE(s == Step::Worked || node.readyToStep()) << "waiting with nothing that could wake it";
  }
  EXPECT_EQ(net.raysSent, 0u);
  EXPECT_EQ(node.stats().tokenRounds, 1u);
  EXPECT_EQ(core::compareImages(imageOf(context, net.contributions), referenceImage()).maxAbs, 0.0);
  const NodeStats stats = node.stats();
  for (int k = 0; k < core::kRayKinds; ++k) EXPECT_EQ(stats.spawned[k], stats.finished[k]) << k;
}

// A step with nothing received shoots up to the primaries it is given (a thread's steps shoot
// scheduling::kPrimariesPerStep; the emulated machine's, one): a eighth of the steps, the same image.
TEST_F(LogicalProcessorTest, AStepShootsUpToItsPrimariesWhenNothingArrived) {
  const MachineContext context = contextFor(1, 1);
  for (int primaries : {1, 8}) {
    SCOPED_TRACE(std::to_string(primaries) + " primaries a step");
    FakeInterconnect net(context.regions, 4);
    FakeTransport transport(net, 0);
    LogicalProcessor<double> node(context, setupFor(context, 0), transport);
    int worked = 0;
    Step s;
    while ((s = node.step(primaries)) != Step::Terminated) {
      ASSERT_LT(worked, 10 * kSide * kSide) << "the node never terminated";
      worked += s == Step::Worked;
    }
    const int shooting = (kSide * kSide + primaries - 1) / primaries;
    EXPECT_GE(worked, shooting);
    EXPECT_LE(worked, shooting + 8);  // and the token's rounds
    EXPECT_EQ(core::compareImages(imageOf(context, net.contributions), referenceImage()).maxAbs, 0.0);
  }
}

// Back-pressure is asked before every primary a step shoots: a processor whose neighbour never takes a ray
// shoots the same primaries, and leaves the same rays waiting, however many primaries its steps may shoot.
TEST_F(LogicalProcessorTest, BackPressureHoldsEveryPrimaryOfAStep) {
  const MachineContext context = contextFor(2, 1);
  auto heldWith = [&](int primaries) {
    FakeInterconnect net(context.regions, 1);
    FakeTransport left(net, 0), right(net, 1);
    LogicalProcessor<double> node0(context, setupFor(context, 0), left);
    Step s = Step::Worked;
    for (int k = 0; k < 100000 && s == Step::Worked; ++k) s = node0.step(primaries);
    EXPECT_EQ(s, Step::Waiting);
    EXPECT_TRUE(node0.blocked());
    return std::pair{node0.stats().overflowHighWater, node0.stats().spawned[0]};
  };
  const auto one = heldWith(1);
  EXPECT_GE(one.first, scheduling::kBacklogLimit);
  EXPECT_EQ(heldWith(8), one);
  EXPECT_EQ(heldWith(64), one);
}

TEST_F(LogicalProcessorTest, AFullNeighbourBlocksTheSenderUntilItHasRoom) {
  const MachineContext context = contextFor(2, 1);
  FakeInterconnect net(context.regions, 1);
  FakeTransport left(net, 0), right(net, 1);
  LogicalProcessor<double> node0(context, setupFor(context, 0), left);
  LogicalProcessor<double> node1(context, setupFor(context, 1), right);
  // Only node 0 runs: it soon fills the one-ray FIFO to node 1 and must wait, blocked, not lose rays.
  Step s = Step::Worked;
  for (int k = 0; k < 100000 && s == Step::Worked; ++k) s = node0.step();
  ASSERT_EQ(s, Step::Waiting);
  EXPECT_TRUE(node0.blocked());
  EXPECT_FALSE(node0.readyToStep());
  EXPECT_EQ(net.fifo(0, 1).size(), 1u);
  // Node 1 takes the ray: node 0 has room again.
  ASSERT_EQ(node1.step(), Step::Worked);
  EXPECT_TRUE(node0.readyToStep());
}

// 3.5.2's lock (FifoFull::Lock): the synthesis task that found its neighbour's FIFO full does nothing else,
// takes no ray in, until one slot of that FIFO frees; then it sends the held ray and goes on. With an
// overflow list (FifoFull::Overflow) the same sender keeps consuming what arrives.
TEST_F(LogicalProcessorTest, AFullFifoLocksItsSenderExactlyUntilOneSlotFrees) {
  for (const FifoFull flow : {FifoFull::Lock, FifoFull::Overflow}) {
    const bool locks = flow == FifoFull::Lock;
    SCOPED_TRACE(locks ? "lock" : "overflow");
    MachineContext context = contextFor(2, 1);
    context.fifoFull = flow;
    FakeInterconnect net(context.regions, 1);
    FakeTransport left(net, 0), right(net, 1);
    LogicalProcessor<double> node0(context, setupFor(context, 0), left);
    LogicalProcessor<double> node1(context, setupFor(context, 1), right);
    // Node 0 alone, until the first send finds the one-ray FIFO to node 1 full.
    while (node0.stats().refusedPushes == 0) ASSERT_EQ(node0.step(), Step::Worked);
    EXPECT_TRUE(node0.blocked());
    EXPECT_EQ(node0.lockedOn(), locks ? 1 : -1);
    EXPECT_EQ(node0.stats().locks, locks ? 1u : 0u);
    EXPECT_EQ(net.fifo(0, 1).size(), 1u);
    // A ray for node 0 arrives (node 1 stepped with node 0's ray kept out of its way): the locked task
    // leaves it in the FIFO, the other takes it.
    const std::deque<Message> held = std::exchange(net.fifo(0, 1), {});
    for (int k = 0; k < 100000 && net.fifo(1, 0).empty(); ++k) node1.step();
    ASSERT_EQ(net.fifo(1, 0).size(), 1u);
    net.fifo(0, 1) = held;
    const NodeStats before = node0.stats();
    const Step s = node0.step();
    EXPECT_EQ(net.fifo(1, 0).size(), locks ? 1u : 0u);
    if (locks) {
      EXPECT_EQ(s, Step::Waiting);
      EXPECT_FALSE(node0.readyToStep()) << "nothing but room in the full FIFO moves a locked task";
      EXPECT_EQ(node0.stats().processed.totalRays(), before.processed.totalRays());
      EXPECT_EQ(node0.stats().spawned, before.spawned) << "no primary ray shot while locked";
      // Node 1 takes its ray in: exactly one slot frees, and node 0 fills it with the ray it held.
      net.fifo(0, 1).pop_front();
      ASSERT_TRUE(node0.readyToStep());
      EXPECT_EQ(node0.step(), Step::Worked);
      EXPECT_EQ(net.fifo(0, 1).size(), 1u);
      EXPECT_GT(node0.stats().sent[std::size_t(Face::Right)], before.sent[std::size_t(Face::Right)]);
      EXPECT_TRUE(net.fifo(1, 0).empty() || node0.lockedOn() == 1) << "unlocked, it takes in what arrived";
    }
  }
}

// Two processors locked on each other's full FIFOs: neither can ever step again (2.2's deadlock), and
// both say on whom they wait.
TEST_F(LogicalProcessorTest, TwoProcessorsLockedOnEachOthersFullFifosNeverStepAgain) {
  MachineContext context = contextFor(2, 1);
  context.fifoFull = FifoFull::Lock;
  FakeInterconnect net(context.regions, 1);
  FakeTransport left(net, 0), right(net, 1);
  LogicalProcessor<double> node0(context, setupFor(context, 0), left);
  LogicalProcessor<double> node1(context, setupFor(context, 1), right);
  // Node 0 locks on node 1; then node 1, with node 0's ray kept out of its way, until it locks on node 0.
  while (node0.lockedOn() != 1) ASSERT_EQ(node0.step(), Step::Worked);
  const std::deque<Message> held = std::exchange(net.fifo(0, 1), {});
  for (int k = 0; k < 100000 && node1.lockedOn() != 0; ++k) node1.step();
  ASSERT_EQ(node1.lockedOn(), 0);
  net.fifo(0, 1) = held;  // node 0's FIFO full again, node 1's full too
  for (int k = 0; k < 100; ++k) {
    EXPECT_EQ(node0.step(), Step::Waiting);
    EXPECT_EQ(node1.step(), Step::Waiting);
  }
  EXPECT_FALSE(node0.readyToStep());
  EXPECT_FALSE(node1.readyToStep());
  EXPECT_EQ(node0.lockedOn(), 1);
  EXPECT_EQ(node1.lockedOn(), 0);
  EXPECT_FALSE(net.terminated);
}

TEST_F(LogicalProcessorTest, ProcessorsSteppedInAnyOrderAgreeWithTheReferenceAndFinishEveryRayOnce) {
  for (const auto& [columns, rows, capacity, flow] :
       std::vector<std::tuple<int, int, std::size_t, FifoFull>>{{2, 1, 1, FifoFull::Overflow},
                                                                {3, 2, 2, FifoFull::Overflow},
                                                                {4, 4, 128, FifoFull::Overflow},
                                                                {3, 2, 128, FifoFull::Lock},
                                                                {4, 4, 128, FifoFull::Lock}}) {
    MachineContext context = contextFor(columns, rows);
    context.fifoFull = flow;
    FakeInterconnect net(context.regions, capacity);
    const int processors = context.regions.processors();
    std::vector<std::unique_ptr<FakeTransport>> transports;
    std::vector<std::unique_ptr<LogicalProcessor<double>>> nodes;
    for (int id = 0; id < processors; ++id) {
      transports.push_back(std::make_unique<FakeTransport>(net, id));
      nodes.push_back(
          std::make_unique<LogicalProcessor<double>>(context, setupFor(context, id), *transports[id]));
    }
    // Round-robin, backwards, a different number of steps per node each turn: any order must do.
    for (int turn = 0; !net.terminated; ++turn) {
      ASSERT_LT(turn, 1000000) << "no termination";
      for (int id = processors - 1; id >= 0; --id)
        for (int k = 0; k <= (turn + id) % 3; ++k) nodes[id]->step();
    }
    std::array<std::uint64_t, core::kRayKinds> spawned{}, finished{};
    for (const auto& n : nodes) {
      for (int k = 0; k < core::kRayKinds; ++k) {
        spawned[k] += n->stats().spawned[k];
        finished[k] += n->stats().finished[k];
      }
      EXPECT_EQ(n->segmentsEvaluated(), n->stats().processed.totalRays())
          << "what progress reads, at the end";
    }
    EXPECT_EQ(spawned, finished);
    for (const auto& [edge, fifo] : net.fifos) EXPECT_TRUE(fifo.empty()) << "a ray left in a FIFO";
    EXPECT_EQ(core::compareImages(imageOf(context, net.contributions), referenceImage()).maxAbs, 0.0)
        << columns << "x" << rows << " capacity " << capacity;
  }
}

}  // namespace
}  // namespace raycube::node
