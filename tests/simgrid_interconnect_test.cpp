// The SimGrid interconnect (queues/interconnects/simgrid_interconnect.h) on a platform small enough to work
// out by hand: a ray message crossing k hypercube hops store and forward arrives after k link transfers plus
// the k - 1 relays' CPU (the iPSC/1 routed in node software), and a full FIFO blocks its sender for exactly
// the time its receiver takes to take the ray in. SimGrid allows one simulation per process: each runs in a
// child.
#include "queues/interconnects/simgrid_interconnect.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>
#include <string>
#include <vector>

#include "core/spd/balls.h"
#include "core/view.h"

namespace raycube::queues {
namespace {

namespace s4u = simgrid::s4u;
using Message = node::BasicRayMessage<double>;

// The platform's numbers, chosen so that every term of the sums is visible and none is a round multiple of
// another.
constexpr double kLatency = 1e-3;      // s per hop
constexpr double kBandwidth = 1.25e6;  // bytes/s per direction (10 Mbit/s)
constexpr double kNodeSpeed = 1e5;     // flop-equivalents/s
constexpr double kRelay = 0.37e-3;     // s of a node's CPU per message relayed
constexpr double kRayBytes = sizeof(Message);
constexpr double kHop = kLatency + kRayBytes / kBandwidth;

// Runs `simulate` (which returns the times it measured) in a child process and returns them.
std::vector<double> inChildProcess(const std::function<std::vector<double>()>& simulate) {
  int fds[2];
  if (::pipe(fds) != 0) ADD_FAILURE() << "pipe";
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(fds[0]);
    const std::vector<double> times = simulate();
    const std::size_t bytes = times.size() * sizeof(double);
    if (::write(fds[1], times.data(), bytes) != ssize_t(bytes)) _exit(2);
    _exit(0);
  }
  ::close(fds[1]);
  std::vector<double> times;
  double t;
  while (::read(fds[0], &t, sizeof t) == ssize_t(sizeof t)) times.push_back(t);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the simulation process failed";
  return times;
}

// A d-cube of 2^d nodes, one link per direction between hypercube neighbours (as the iPSC/1), and the
// manager, on the network model the machine uses (CM02, no cross-traffic: latencies mean what they say).
struct Cube {
  s4u::Engine engine;
  std::vector<s4u::Host*> hosts;
  s4u::Host* manager = nullptr;

  explicit Cube(int dimension) : engine(&arguments().argc, arguments().argv.data()) {
    s4u::NetZone* zone = s4u::create_full_zone("cube");
    const std::uint32_t nodes = 1u << dimension;
    for (std::uint32_t n = 0; n < nodes; ++n)
      hosts.push_back(zone->create_host("node-" + std::to_string(n), kNodeSpeed));
    manager = zone->create_host(queues::kCubeManagerHost, kNodeSpeed);
    auto route = [&](s4u::Host* a, s4u::Host* b, const std::string& name) {
      s4u::Link* link = zone->create_link(name, kBandwidth)->set_latency(kLatency);
      zone->add_route(a->get_netpoint(), b->get_netpoint(), nullptr, nullptr, {s4u::LinkInRoute(link)},
                      false);
    };
    for (std::uint32_t n = 0; n < nodes; ++n) {
      route(hosts[n], manager, "manager-" + std::to_string(n));
      for (std::uint32_t bit = 1; bit < nodes; bit *= 2)
        route(hosts[n], hosts[n ^ bit], std::to_string(n) + "->" + std::to_string(n ^ bit));
    }
    zone->seal();
  }

 private:
  struct Arguments {
    std::vector<std::string> words{"test", "--cfg=network/model:CM02", "--cfg=network/crosstraffic:0",
                                   "--log=root.thres:critical"};
    std::vector<char*> argv;
    int argc = 0;
    Arguments() {
      for (std::string& w : words) argv.push_back(w.data());
      argv.push_back(nullptr);
      argc = int(words.size());
    }
  };
  static Arguments& arguments() {
    static Arguments a;
    return a;
  }
};

// Two processors side by side on the screen, so each is the other's neighbour (a face FIFO each way).
node::RegionMap twoRegions() {
  static const core::Scene scene = core::makeBalls(1);
  static const core::View view(scene.camera, 2, 1, core::Sampling::Centers, 1);
  static const node::ScreenLines lines(view);
  return node::RegionMap::grid({0, 1, 2}, {0, 1}, lines);
}

SimGridWiring wiringFor(const Cube& cube, std::uint32_t receiverNode, std::size_t capacity) {
  SimGridWiring w;
  w.capacity = capacity;
  w.cubeNode = {0, receiverNode};
  w.hosts = cube.hosts;
  w.manager = cube.manager;
  w.routing = Routing::StoreAndForward;
  w.relaySeconds = kRelay;
  return w;
}

// One ray from processor 0 on node 0 to processor 1 on node 2^k - 1: the e-cube path crosses k links and is
// relayed by k - 1 nodes. Returns the simulated time it arrives.
double arrivalAcross(int hops) {
  const std::vector<double> times = inChildProcess([hops] {
    Cube cube(hops);
    const node::RegionMap regions = twoRegions();
    SimGridInterconnect<double> net(regions, wiringFor(cube, (1u << hops) - 1, 1));
    double arrived = -1;
    s4u::Actor::create("sender", cube.hosts[0], [&] {
      const Message ray{};
      net.endpoint(0).trySend(1, {&ray, 1});
      net.commit(0);
    });
    s4u::Actor::create("receiver", cube.hosts[(1u << hops) - 1], [&] {
      net.waitFor(1, [&] { return net.endpoint(1).anyIncoming(); });
      arrived = s4u::Engine::get_clock();
    });
    net.startCommunicationTasks();
    cube.engine.run();
    return std::vector<double>{arrived};
  });
  return times.empty() ? -1 : times.front();
}

TEST(SimGridInterconnect, ARayAcrossKHopsCostsKLinksAndTheRelaysCpu) {
  for (int k = 1; k <= 3; ++k) {
    const double byHand = k * kHop + (k - 1) * kRelay;  // k x (latency + size/bandwidth) + relays' CPU
    EXPECT_NEAR(arrivalAcross(k), byHand, 1e-12) << k << " hops";
  }
}

// Capacity 1: the sender's second ray waits, blocked, until the receiver takes the first in, which it does
// after computing for `hold` seconds from the first ray's arrival. The sender is blocked from 0 until then,
// and the second ray arrives one hop later.
TEST(SimGridInterconnect, AFullFifoBlocksTheSenderUntilTheReceiverTakesTheRayIn) {
  constexpr double kHoldFlops = 250;  // 2.5 ms on the receiver
  const std::vector<double> times = inChildProcess([] {
    Cube cube(1);
    const node::RegionMap regions = twoRegions();
    SimGridInterconnect<double> net(regions, wiringFor(cube, 1, 1));
    double refusedAt = -1, unblockedAt = -1, firstArrived = -1, secondArrived = -1;
    double refused = -1;
    s4u::Actor::create("sender", cube.hosts[0], [&] {
      const Message rays[2]{};
      node::BasicTransport<double>& out = net.endpoint(0);
      out.trySend(1, {&rays[0], 1});
      net.commit(0);
      refused = double(out.trySend(1, {&rays[1], 1}));  // the FIFO is full
      refusedAt = s4u::Engine::get_clock();
      net.waitFor(0, [&] { return out.canSend(1); });
      unblockedAt = s4u::Engine::get_clock();
      out.trySend(1, {&rays[1], 1});
      net.commit(0);
    });
    s4u::Actor::create("receiver", cube.hosts[1], [&] {
      node::BasicTransport<double>& in = net.endpoint(1);
      Message ray;
      net.waitFor(1, [&] { return in.anyIncoming(); });
      firstArrived = s4u::Engine::get_clock();
      s4u::this_actor::execute(kHoldFlops);
      in.receive({&ray, 1});
      net.waitFor(1, [&] { return in.anyIncoming(); });
      secondArrived = s4u::Engine::get_clock();
      in.receive({&ray, 1});
    });
    net.startCommunicationTasks();
    cube.engine.run();
    return std::vector<double>{refused, refusedAt, unblockedAt, firstArrived, secondArrived};
  });
  ASSERT_EQ(times.size(), 5u);
  const double hold = kHoldFlops / kNodeSpeed;
  EXPECT_EQ(times[0], 0) << "a full FIFO takes nothing";
  EXPECT_EQ(times[1], 0);
  EXPECT_NEAR(times[3], kHop, 1e-12);
  EXPECT_NEAR(times[2], kHop + hold, 1e-12) << "blocked exactly until the receiver freed the slot";
  EXPECT_NEAR(times[4], kHop + hold + kHop, 1e-12);
}

}  // namespace
}  // namespace raycube::queues
