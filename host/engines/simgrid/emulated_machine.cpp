#include "host/engines/simgrid/emulated_machine.h"

#include <fmt/format.h>
#include <simgrid/s4u.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <type_traits>

#include "host/engines/wire_codec.h"
#include "host/util/clock.h"
#include "queues/host_channel.h"
#include "queues/interconnects/simgrid_interconnect.h"

namespace raycube::host {
namespace {

namespace s4u = simgrid::s4u;
static_assert(std::is_trivially_copyable_v<ProcessorReport>);

// ---- The child's results travel to the parent through a pipe, as tagged records.
enum class Record : std::uint8_t { SynthesisStarts, Contributions, Progress, Deadlock, Reports, Failure };

// The child's end of the pipe: it exits when the parent is gone.
class PipeSink {
 public:
  explicit PipeSink(int fd) : fd_(fd) {}
  void write(const char* data, std::size_t n) {
    while (n > 0) {
      const ssize_t w = ::write(fd_, data, n);
      if (w <= 0) _exit(3);  // the parent is gone
      data += w;
      n -= std::size_t(w);
    }
  }

 private:
  int fd_;
};

// The parent's end: the simulation's results, until the child closes it.
class PipeSource {
 public:
  explicit PipeSource(int fd) : fd_(fd) {}
  void read(char* data, std::size_t n) {
    while (n > 0) {
      const ssize_t r = ::read(fd_, data, n);
      if (r <= 0) throw std::runtime_error("the simulation ended before sending all its results");
      data += r;
      n -= std::size_t(r);
    }
  }
  void expect(std::size_t) const {}  // a pipe does not know what is left

 private:
  int fd_;
};

using PipeWriter = WireEncoder<PipeSink>;
using PipeReader = WireDecoder<PipeSource>;

// Contributions go to the parent in blocks, as they arrive at the simulated host, each followed by the
// processors' progress (for the parent's progress line).
class ContributionsToParent final : public core::ContributionSink {
 public:
  ContributionsToParent(PipeWriter& out, std::function<std::vector<std::uint64_t>()> progress)
      : out_(out), progress_(std::move(progress)) {}
  ~ContributionsToParent() { flush(); }
  void add(const core::Contribution& c) override {
    block_.push_back(c);
    if (block_.size() == queues::kContributionsPerShipment) flush();
  }
  void flush() {
    if (block_.empty()) return;
    out_.value(Record::Contributions);
    out_.vector(block_);
    block_.clear();
    out_.value(Record::Progress);
    out_.vector(progress_());
  }

 private:
  PipeWriter& out_;
  std::function<std::vector<std::uint64_t>()> progress_;
  std::vector<core::Contribution> block_;
};

std::uint32_t cubeNodesFor(const std::vector<std::uint32_t>& cubeNode) {
  std::uint32_t n = 1;
  for (std::uint32_t node : cubeNode)
    while (n <= node) n *= 2;
  return n;
}

std::string hostName(std::uint32_t cubeNode) { return "node-" + std::to_string(cubeNode); }

// The built-in machines as SimGrid platforms: one host per hypercube node and one for the cube manager.
// Store and forward: a link per direction between hypercube neighbours (the iPSC's seven ports), so a
// message to a non-neighbour is relayed by the nodes' communication tasks. Direct: each node has one
// network interface into a switch, and a route to every node it talks to. Every node has its own link to
// the manager (the iPSC's eighth port).
void buildPlatform(const EmulatedPlatform& platform, std::uint32_t cubeNodes,
                   const std::vector<std::pair<std::uint32_t, std::uint32_t>>& talking) {
  s4u::NetZone* zone = s4u::create_full_zone("machine");
  std::vector<s4u::Host*> hosts;
  for (std::uint32_t n = 0; n < cubeNodes; ++n) hosts.push_back(zone->create_host(hostName(n), platform.nodeSpeed));
  s4u::Host* manager = zone->create_host(queues::kCubeManagerHost, platform.nodeSpeed);
  auto link = [&](const std::string& name, double bandwidth, double latency) {
    return zone->create_link(name, bandwidth)->set_latency(latency);
  };
  auto route = [&](s4u::Host* a, s4u::Host* b, std::vector<s4u::Link*> links) {
    std::vector<s4u::LinkInRoute> path;
    for (s4u::Link* l : links) path.emplace_back(l);
    zone->add_route(a->get_netpoint(), b->get_netpoint(), nullptr, nullptr, path, false);
  };
  for (std::uint32_t n = 0; n < cubeNodes; ++n)
    route(hosts[n], manager,
          {link(hostName(n) + "->manager", platform.hostLinkBandwidth, platform.hostLinkLatency)});
  if (platform.routing == Routing::StoreAndForward) {
    for (std::uint32_t n = 0; n < cubeNodes; ++n)
      for (std::uint32_t bit = 1; bit < cubeNodes; bit *= 2)
        route(hosts[n], hosts[n ^ bit],
              {link(hostName(n) + "->" + hostName(n ^ bit), platform.linkBandwidth, platform.linkLatency)});
  } else {
    std::vector<s4u::Link*> nic;
    for (std::uint32_t n = 0; n < cubeNodes; ++n)
      nic.push_back(link(hostName(n) + "-nic", platform.linkBandwidth, platform.linkLatency / 2));
    for (const auto& [a, b] : talking) route(hosts[a], hosts[b], {nic[a], nic[b]});
  }
  zone->seal();
}

// Who sends to whom: region neighbours, and each processor to the next on the token ring.
std::vector<std::pair<std::uint32_t, std::uint32_t>> talkingPairs(const node::RegionMap& regions,
                                                                   const std::vector<std::uint32_t>& cubeNode) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  const int processors = regions.processors();
  for (int p = 0; p < processors; ++p) {
    for (int n : regions.neighbours(p)) pairs.emplace_back(cubeNode[p], cubeNode[n]);
    const int next = (p + 1) % processors;
    if (next != p && !std::binary_search(regions.neighbours(p).begin(), regions.neighbours(p).end(), next))
      pairs.emplace_back(cubeNode[p], cubeNode[next]);
  }
  return pairs;
}

s4u::Host* hostNamed(const std::string& name, const EmulatedPlatform& platform) {
  s4u::Host* h = s4u::Engine::get_instance()->host_by_name_or_null(name);
  if (h == nullptr)
    throw std::runtime_error(fmt::format("platform {}: no host named '{}' (a platform needs node-0 ... node-<2^d - 1> "
                                         "and manager)",
                                         platform.name, name));
  return h;
}

// A processor's state over simulated time, merged where it does not change.
class Timeline {
 public:
  void add(std::uint32_t processor, ProcessorState state, double start, double end) {
    if (end <= start) return;
    if (!intervals_.empty()) {
      StateInterval& last = intervals_.back();
      if (last.processor == processor && last.state == state && last.end == start) {
        last.end = end;
        return;
      }
    }
    intervals_.push_back({start, end, processor, state});
  }
  std::vector<StateInterval> take() { return std::move(intervals_); }

 private:
  std::vector<StateInterval> intervals_;
};

// A processor's actor: step the node, charge the work the step counted, then ship what it produced (so
// messages leave when the work that made them is done); wait in simulated time when there is nothing to do.
// Where each processor's actor waits, if it does: since when, and whether locked on a full FIFO (3.6). What
// a deadlock leaves them doing.
struct Waiting {
  double since = -1;  // -1: not waiting
  bool blocked = false;
};

template <class Real>
void driveInSimulatedTime(node::LogicalProcessor<Real>& node, queues::SimGridInterconnect<Real>& net, int id,
                          const CostTable& costs, ProcessorReport& report, std::vector<Timeline>& timelines,
                          Waiting& waiting) {
  Timeline& timeline = timelines[std::size_t(id)];
  double counted = costs.flopsOf(node.stats());
  for (;;) {
    const node::Step step = node.step();
    const double now = costs.flopsOf(node.stats());
    if (now > counted) {
      const double start = s4u::Engine::get_clock();
      s4u::this_actor::execute(now - counted);
      report.computeSeconds += s4u::Engine::get_clock() - start;
      timeline.add(std::uint32_t(id), ProcessorState::Computing, start, s4u::Engine::get_clock());
      counted = now;
    }
    net.commit(id);
    if (step == node::Step::Terminated) return net.finish(id);
    if (step == node::Step::Worked) continue;
    const double start = s4u::Engine::get_clock();
    const bool blocked = node.blocked();
    waiting = {start, blocked};
    net.waitFor(id, [&] { return node.readyToStep(); });
    waiting = {};
    const double waited = s4u::Engine::get_clock() - start;
    (blocked ? report.blockedSeconds : report.idleSeconds) += waited;
    timeline.add(std::uint32_t(id), blocked ? ProcessorState::Blocked : ProcessorState::Idle, start,
                 s4u::Engine::get_clock());
  }
}

struct SimulationInput {
  const node::MachineContext& context;
  std::vector<node::NodeSetup>& setups;
  const EmulatedPlatform& platform;
  std::size_t queueCapacity;
  const std::vector<std::uint32_t>& cubeNode;
};

// The whole simulation, in the child process: results to `out`.
template <class Real>
void simulate(SimulationInput in, PipeWriter& out) {
  const auto wallStart = Clock::now();
  std::vector<std::string> args = {"raycube", "--cfg=network/model:CM02", "--cfg=network/crosstraffic:0",
                                   "--log=root.thres:critical"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int argc = int(args.size());
  s4u::Engine engine(&argc, argv.data());
  const std::uint32_t cubeNodes = cubeNodesFor(in.cubeNode);
  if (in.platform.platformFile.empty())
    buildPlatform(in.platform, cubeNodes, talkingPairs(in.context.regions, in.cubeNode));
  else
    engine.load_platform(in.platform.platformFile.string());

  queues::SimGridWiring wiring;
  wiring.capacity = in.queueCapacity;
  wiring.cubeNode = in.cubeNode;
  for (std::uint32_t n = 0; n < cubeNodes; ++n) wiring.hosts.push_back(hostNamed(hostName(n), in.platform));
  wiring.manager = hostNamed(queues::kCubeManagerHost, in.platform);
  wiring.routing = in.platform.routing;
  wiring.relayFlops = in.platform.costs.messageRelayed;
  queues::SimGridInterconnect<Real> net(in.context.regions, wiring);

  const int processors = int(in.setups.size());
  std::vector<std::unique_ptr<node::LogicalProcessor<Real>>> nodes;
  for (int p = 0; p < processors; ++p)
    nodes.push_back(std::make_unique<node::LogicalProcessor<Real>>(in.context, std::move(in.setups[p]), net.endpoint(p)));
  out.value(Record::SynthesisStarts);  // every node has subdivided its region
  std::vector<ProcessorReport> reports(static_cast<std::size_t>(processors));
  std::vector<Timeline> timelines(static_cast<std::size_t>(processors));
  std::vector<Waiting> waiting(static_cast<std::size_t>(processors));
  int finished = 0;
  for (int p = 0; p < processors; ++p)
    s4u::Actor::create("processor-" + std::to_string(p), wiring.hosts[in.cubeNode[p]], [&, p] {
      driveInSimulatedTime(*nodes[p], net, p, in.platform.costs, reports[p], timelines, waiting[p]);
      ++finished;
    });
  ContributionsToParent toParent(out, [&] {
    std::vector<std::uint64_t> evaluated;
    for (const auto& n : nodes) evaluated.push_back(n->segmentsEvaluated());
    return evaluated;
  });
  bool hostDone = false;
  double makespan = 0;
  s4u::Actor::create("host", wiring.manager, [&] {
    net.serveHost(toParent);
    makespan = s4u::Engine::get_clock();
    hostDone = true;
  });
  net.startCommunicationTasks();
  engine.run();
  // SimGrid ends a run where no actor can move as it ends a finished one (it says so on stderr): a cycle
  // of processors locked on each other's full FIFOs (--fifo-full lock) is the run's result.
  std::vector<int> lockedOn;
  for (const auto& n : nodes) lockedOn.push_back(n->lockedOn());
  const std::vector<int> cycle = net.terminated() ? std::vector<int>{} : lockCycle(lockedOn);
  if (!cycle.empty()) {
    Deadlock deadlock =
        deadlockOf(cycle, in.context.regions, [&](int from, int to) { return net.raysIn(from, to); });
    for (int p : cycle) deadlock.simulatedSeconds = std::max(deadlock.simulatedSeconds, waiting[p].since);
    makespan = s4u::Engine::get_clock();
    for (int p = 0; p < processors; ++p) {  // the waits the deadlock left open, to its end
      if (waiting[p].since < 0) continue;
      const bool blocked = waiting[p].blocked;
      (blocked ? reports[p].blockedSeconds : reports[p].idleSeconds) += makespan - waiting[p].since;
      timelines[p].add(std::uint32_t(p), blocked ? ProcessorState::Blocked : ProcessorState::Idle,
                       waiting[p].since, makespan);
    }
    out.value(Record::Deadlock);
    out.vector(deadlock.cycle);
    out.value(deadlock.simulatedSeconds);
  } else if (!net.terminated() || finished != processors || !hostDone) {
    throw std::runtime_error(
        fmt::format("the simulation deadlocked at {:.6f} simulated s: termination {}, {} of {} processors "
                    "finished, host {}",
                    s4u::Engine::get_clock(), net.terminated() ? "announced" : "not announced", finished,
                    processors, hostDone ? "done" : "still waiting"));
  }
  toParent.flush();

  EmulatedRun run;
  run.platform = in.platform.name;
  run.makespan = makespan;
  for (int p = 0; p < processors; ++p) {
    reports[p].node = nodes[p]->stats();
    reports[p].forwardSeconds = net.relaySeconds(in.cubeNode[p]);
  }
  for (const queues::LinkTrafficCount& t : net.traffic()) {
    run.links.push_back({t.from, t.to, t.messages, t.bytes});
    if (t.to != kHostNode) run.rayMessages += t.messages;
  }
  for (Timeline& t : timelines) {
    auto part = t.take();
    run.timeline.insert(run.timeline.end(), part.begin(), part.end());
  }
  std::vector<int> processorAt(wiring.hosts.size(), -1);
  for (int p = 0; p < processors; ++p) processorAt[in.cubeNode[p]] = p;
  for (const queues::RelayInterval& r : net.relayIntervals())
    if (processorAt[r.cubeNode] >= 0)
      run.timeline.push_back(
          {r.start, r.end, std::uint32_t(processorAt[r.cubeNode]), ProcessorState::Forwarding});
  run.wallSeconds = secondsSince(wallStart);
  out.value(Record::Reports);
  out.vector(reports);
  out.string(run.platform);
  out.value(run.makespan);
  out.value(run.rayMessages);
  out.value(run.wallSeconds);
  out.vector(run.links);
  out.vector(run.timeline);
}

// The parent's side: the start of synthesis, contributions to the host's sink and progress as they come,
// then the reports.
MachineRun receiveResults(PipeReader& in, const EngineHooks& hooks) {
  std::optional<Deadlock> deadlock;
  for (;;) {
    const auto tag = in.value<Record>();
    if (tag == Record::SynthesisStarts) {
      if (hooks.synthesisStarts) hooks.synthesisStarts();
    } else if (tag == Record::Contributions) {
      for (const core::Contribution& c : in.vector<core::Contribution>()) hooks.host->add(c);
    } else if (tag == Record::Progress) {
      const auto evaluated = in.vector<std::uint64_t>();
      if (hooks.progress) hooks.progress(evaluated);
    } else if (tag == Record::Deadlock) {
      deadlock.emplace();
      deadlock->cycle = in.vector<LockedFifo>();
      deadlock->simulatedSeconds = in.value<double>();
    } else if (tag == Record::Failure) {
      throw std::runtime_error(in.string());
    } else {
      MachineRun run;
      run.processors = in.vector<ProcessorReport>();
      EmulatedRun s;
      s.platform = in.string();
      s.makespan = in.value<double>();
      s.rayMessages = in.value<std::uint64_t>();
      s.wallSeconds = in.value<double>();
      s.links = in.vector<LinkTraffic>();
      s.timeline = in.vector<StateInterval>();
      run.emulated = std::move(s);
      run.deadlock = std::move(deadlock);
      return run;
    }
  }
}

}  // namespace

template <class Real>
MachineRun EmulatedMachine<Real>::run(const node::MachineContext& context, std::vector<node::NodeSetup> setups,
                                       const EngineHooks& hooks) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot create a pipe for the simulation");
  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("cannot fork the simulation process");
  if (child == 0) {
    ::close(fds[0]);
    PipeWriter out(fds[1]);
    try {
      simulate<Real>(SimulationInput{context, setups, platform_, queueCapacity_, cubeNode_}, out);
    } catch (const std::exception& e) {
      out.value(Record::Failure);
      out.string(e.what());
    }
    ::close(fds[1]);
    std::fflush(nullptr);
    _exit(0);
  }
  ::close(fds[1]);
  PipeReader in(fds[0]);
  std::optional<MachineRun> run;
  std::string failure;
  try {
    run = receiveResults(in, hooks);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (!run) {
    if (WIFSIGNALED(status))
      failure += fmt::format(" (the simulation process died of signal {}: {})", WTERMSIG(status), strsignal(WTERMSIG(status)));
    throw std::runtime_error("emulated machine: " + failure);
  }
  return std::move(*run);
}

template class EmulatedMachine<float>;
template class EmulatedMachine<double>;

}  // namespace raycube::host
