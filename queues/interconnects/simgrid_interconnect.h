#pragma once
// The machine's interconnect in simulated time, on SimGrid's S4U (Priol & Bouatouch 3.5 on the iPSC):
// every ray, token and block of contributions is a SimGrid message between the hosts the processors run
// on, so links charge their latency and bandwidth. A face FIFO is a count of credits per directed
// adjacency (SimGrid's mailboxes are unbounded): a ray takes one when sent and gives it back when its
// receiver takes it in. Each hypercube node runs a communication task (a daemon actor) that receives,
// relays in software what is for another node (store and forward, charged on its CPU) and delivers the
// rest to its processor. Waiting is a condition variable in simulated time, never a poll.
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <simgrid/s4u.hpp>
#include <vector>

#include "core/contribution_sink.h"
#include "node/region_map.h"
#include "node/transport.h"
#include "queues/routing.h"

namespace raycube::queues {

// The SimGrid host of the host process: the iPSC's cube manager, as user platforms name it too.
inline constexpr const char* kCubeManagerHost = "manager";

struct LinkTrafficCount {
  std::uint32_t from = 0, to = 0;  // hypercube nodes (the host is node -1 when it is one end)
  std::uint64_t messages = 0, bytes = 0;
};

// A stretch of simulated time a hypercube node's communication task spent relaying (store and forward).
struct RelayInterval {
  std::uint32_t cubeNode = 0;
  double start = 0, end = 0;
};

struct SimGridWiring {
  std::size_t capacity = 128;              // rays per face FIFO
  std::vector<std::uint32_t> cubeNode;     // per processor: its node on the hypercube
  std::vector<simgrid::s4u::Host*> hosts;  // per hypercube node (2^d of them)
  simgrid::s4u::Host* manager = nullptr;   // the host (cube manager)
  Routing routing = Routing::StoreAndForward;
  double relaySeconds = 0;  // CPU a node spends relaying one message
};

template <class Real>
class SimGridInterconnect {
 public:
  using Message = node::BasicRayMessage<Real>;
  SimGridInterconnect(const node::RegionMap& regions, SimGridWiring wiring);
  ~SimGridInterconnect();
  SimGridInterconnect(const SimGridInterconnect&) = delete;
  SimGridInterconnect& operator=(const SimGridInterconnect&) = delete;

  node::BasicTransport<Real>& endpoint(int processor);
  // One daemon actor per hypercube node; call before the simulation runs.
  void startCommunicationTasks();

  // ---- A processor's driver (its actor).
  // Ships what the processor's last step produced: called after the step's compute time was charged.
  void commit(int processor);
  // Blocks in simulated time until ready() holds; anything delivered to the processor re-checks it.
  template <class Ready>
  void waitFor(int processor, Ready&& ready) {
    std::unique_lock lock(*mutex_);
    while (!ready()) wakeUp_[processor]->wait(lock);
  }
  // The processor has seen termination: tell the host how many contributions to expect from it.
  void finish(int processor);

  // ---- The host's actor: accumulates every block until every processor has finished and all arrived.
  void serveHost(core::ContributionSink& sink);
  bool terminated() const { return terminated_; }
  // Rays processor `from` has sent its neighbour `to` that `to` has not taken in: its FIFO's occupancy.
  std::size_t raysIn(int from, int to) const;

  double relaySeconds(std::uint32_t cubeNode) const { return relaySeconds_[cubeNode]; }
  std::uint64_t relayed(std::uint32_t cubeNode) const { return relayed_[cubeNode]; }
  // Every relay, back-to-back ones of a node merged, in the order they ended.
  const std::vector<RelayInterval>& relayIntervals() const { return relayIntervals_; }
  std::vector<LinkTrafficCount> traffic() const;

 private:
  class Endpoint;
  struct Packet;
  void route(std::uint32_t at, std::unique_ptr<Packet> packet);
  void communicationTask(std::uint32_t cubeNode);
  void deliver(std::unique_ptr<Packet> packet);
  void wake(int processor) { wakeUp_[processor]->notify_all(); }

  const node::RegionMap& regions_;
  SimGridWiring wiring_;
  std::vector<int> processorAt_;  // per hypercube node, -1 when none runs there
  std::vector<std::unique_ptr<Endpoint>> endpoints_;
  simgrid::s4u::MutexPtr mutex_;
  std::vector<simgrid::s4u::ConditionVariablePtr> wakeUp_;
  bool terminated_ = false;
  std::vector<double> relaySeconds_;
  std::vector<std::uint64_t> relayed_;
  std::vector<RelayInterval> relayIntervals_;
  std::vector<std::size_t> lastRelay_;  // per node: its latest interval in relayIntervals_, or SIZE_MAX
  std::map<std::pair<std::int64_t, std::int64_t>, LinkTrafficCount> traffic_;
};

}  // namespace raycube::queues
