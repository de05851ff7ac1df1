#include "host/engines/simgrid/emulated_machine.h"

#include <fmt/format.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <functional>
#include <memory>
#include <new>
#include <optional>
#include <simgrid/s4u.hpp>
#include <stdexcept>
#include <type_traits>

#include "host/engines/machine_wire.h"
#include "host/engines/stall_watch.h"
#include "host/engines/wire_codec.h"
#include "host/util/clock.h"
#include "queues/host_channel.h"
#include "queues/interconnects/simgrid_interconnect.h"
#include "queues/interconnects/step_stalling_transport.h"

namespace raycube::host {
namespace {

namespace s4u = simgrid::s4u;

// ---- The child's results travel to the parent through a pipe, as tagged records.
enum class Record : std::uint8_t { SynthesisStarts, Contributions, Progress, Reports, Failure };

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
  // whileQuiet() is called every `look` that nothing arrives (the watchdog); it may throw.
  PipeSource(int fd, std::chrono::milliseconds look, std::function<void()> whileQuiet)
      : fd_(fd), look_(look), whileQuiet_(std::move(whileQuiet)) {}
  void read(char* data, std::size_t n) {
    while (n > 0) {
      pollfd ready{fd_, POLLIN, 0};
      if (::poll(&ready, 1, int(look_.count())) == 0) {
        whileQuiet_();
        continue;
      }
      const ssize_t r = ::read(fd_, data, n);
      if (r <= 0) throw std::runtime_error("the simulation ended before sending all its results");
      data += r;
      n -= std::size_t(r);
    }
  }
  void expect(std::size_t) const {}  // a pipe does not know what is left

 private:
  int fd_;
  std::chrono::milliseconds look_;
  std::function<void()> whileQuiet_;
};

using PipeWriter = WireEncoder<PipeSink>;
using PipeReader = WireDecoder<PipeSource>;

// The emulated machine's watchdog (host/engines/stall_watch.h) runs in the parent, on the wall clock:
// actors share the simulation's one thread, so a step that does not end stops the simulated clock and
// every other actor with it. The child shows each processor's steps and whether it is inside one in memory
// shared across the fork (no thread may start in the child of a threaded process).
struct SharedStep {
  std::atomic<std::uint64_t> stepsWorked{0};
  std::atomic<bool> stepping{false};
};

class SharedSteps {
 public:
  explicit SharedSteps(std::size_t processors) : count_(processors) {
    void* memory = ::mmap(nullptr, bytes(), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED) throw std::runtime_error("cannot map memory shared with the simulation");
    steps_ = static_cast<SharedStep*>(memory);
    for (std::size_t p = 0; p < processors; ++p) new (&steps_[p]) SharedStep;
  }
  ~SharedSteps() { ::munmap(steps_, bytes()); }
  SharedSteps(const SharedSteps&) = delete;
  SharedSteps& operator=(const SharedSteps&) = delete;
  SharedStep& operator[](std::size_t p) const { return steps_[p]; }
  std::size_t size() const { return count_; }

 private:
  std::size_t bytes() const { return std::max<std::size_t>(1, count_) * sizeof(SharedStep); }
  std::size_t count_;
  SharedStep* steps_ = nullptr;
};

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

std::string hostName(std::uint32_t cubeNode) {
  return "node-" + std::to_string(cubeNode);
}

s4u::Host* hostNamed(const std::string& name, const EmulatedPlatform& platform) {
  s4u::Host* h = s4u::Engine::get_instance()->host_by_name_or_null(name);
  if (h == nullptr)
    throw std::runtime_error(
        fmt::format("{}: no host named '{}' (a platform needs node-0 ... node-<2^d - 1> and manager)",
                    platform.platformFile.string(), name));
  return h;
}

// Every machine, built in or not, is a SimGrid platform file (host/machine/platforms/ for the built-in ones).
void loadPlatform(s4u::Engine& engine, const EmulatedPlatform& platform) {
  try {
    engine.load_platform(platform.platformFile.string());
  } catch (const std::exception& e) {
    throw std::runtime_error(
        fmt::format("{}: not a usable SimGrid platform: {}", platform.platformFile.string(), e.what()));
  }
}

// A cost table's nodeSpeed sets node-0's speed, the others keeping their ratio to it: every charge is scaled
// (by exactly 1 without one). Costs in seconds are node-0's seconds: node-0's flops per second.
double speedScale(const EmulatedPlatform& platform, const s4u::Host& node0) {
  if (platform.computeUnit == ComputeUnit::Seconds) return node0.get_speed();
  return platform.nodeSpeed ? node0.get_speed() / *platform.nodeSpeed : 1.0;
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

// What a node's counted work costs its host's CPU, in the host's flops: the computation scaled to the cost
// table's node speed (speedScale), the messages' seconds at the host's own speed.
class ChargedWork {
 public:
  ChargedWork(const CostTable& costs, double speedScale)
      : costs_(costs), speedScale_(speedScale), hostSpeed_(s4u::this_actor::get_host()->get_speed()) {}
  double flopsOf(const node::NodeStats& stats) const {
    return costs_.flopsOf(stats) * speedScale_ + costs_.messageSecondsOf(stats) * hostSpeed_;
  }

 private:
  const CostTable& costs_;
  double speedScale_, hostSpeed_;
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
                          const CostTable& costs, double speedScale, ProcessorReport& report,
                          std::vector<Timeline>& timelines, Waiting& waiting, SharedStep& shared) {
  Timeline& timeline = timelines[std::size_t(id)];
  const ChargedWork charged(costs, speedScale);
  double counted = charged.flopsOf(node.stats());
  for (;;) {
    shared.stepping.store(true, std::memory_order_relaxed);
    const node::Step step = node.step();
    shared.stepping.store(false, std::memory_order_relaxed);
    shared.stepsWorked.store(node.stepsWorked(), std::memory_order_relaxed);
    const double now = charged.flopsOf(node.stats());
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
  bool stallAStep;
  const SharedSteps& steps;
};

// SimGrid's settings: the CM02 network model without cross-traffic, so that a platform's numbers mean what
// they say (machines-and-engines.md), and only critical messages.
std::vector<std::string> simulationArguments() {
  return {"raycube", "--cfg=network/model:CM02", "--cfg=network/crosstraffic:0", "--log=root.thres:critical"};
}

// A simulation (one per process) of the platform, with simulationArguments().
std::unique_ptr<s4u::Engine> engineOn(const EmulatedPlatform& platform) {
  std::vector<std::string> args = simulationArguments();
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int argc = int(args.size());
  auto engine = std::make_unique<s4u::Engine>(&argc, argv.data());
  loadPlatform(*engine, platform);
  return engine;
}

// The loaded platform's hosts for the interconnect: node-<n> for each hypercube node, and the manager.
queues::SimGridWiring wiringFor(const SimulationInput& in) {
  queues::SimGridWiring wiring;
  wiring.capacity = in.queueCapacity;
  wiring.cubeNode = in.cubeNode;
  const std::uint32_t cubeNodes = cubeNodesFor(in.cubeNode);
  if (in.platform.ranks > 0) {  // one MPI job on one computer: everything on node-0, sharing its cores
    s4u::Host* computer = hostNamed(hostName(0), in.platform);
    wiring.hosts.assign(cubeNodes, computer);
    wiring.manager = computer;
  } else {
    for (std::uint32_t n = 0; n < cubeNodes; ++n) wiring.hosts.push_back(hostNamed(hostName(n), in.platform));
    wiring.manager = hostNamed(queues::kCubeManagerHost, in.platform);
  }
  wiring.routing = in.platform.routing;
  wiring.relaySeconds = in.platform.costs.relaySeconds;
  return wiring;
}

// SimGrid returns from run() on a deadlock as on completion: check that every actor finished.
void requireCompleted(bool terminated, int finished, int processors, bool hostDone) {
  if (!terminated || finished != processors || !hostDone)
    throw std::runtime_error(
        fmt::format("the simulation deadlocked at {:.6f} simulated s: termination {}, {} of {} processors "
                    "finished, host {}",
                    s4u::Engine::get_clock(), terminated ? "announced" : "not announced", finished,
                    processors, hostDone ? "done" : "still waiting"));
}

// What the simulation measured: its clock, the traffic on its links and the processors' timelines; the
// reports take the nodes' counts and the time their hosts spent relaying.
template <class Real>
EmulatedRun emulatedRunOf(const SimulationInput& in, const queues::SimGridInterconnect<Real>& net,
                          const std::vector<std::unique_ptr<node::LogicalProcessor<Real>>>& nodes,
                          const s4u::Host& node0, std::vector<ProcessorReport>& reports,
                          std::vector<Timeline>& timelines) {
  EmulatedRun run;
  run.platform = in.platform.name;
  run.nodeSpeed = in.platform.nodeSpeed.value_or(node0.get_speed());
  for (std::size_t p = 0; p < nodes.size(); ++p) {
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
  // The relaying a processor's host did for others (store and forward), drawn apart on its row.
  std::vector<int> processorAt(cubeNodesFor(in.cubeNode), -1);
  for (std::size_t p = 0; p < in.cubeNode.size(); ++p) processorAt[in.cubeNode[p]] = int(p);
  for (const queues::RelayInterval& r : net.relayIntervals())
    if (processorAt[r.cubeNode] >= 0)
      run.timeline.push_back(
          {r.start, r.end, std::uint32_t(processorAt[r.cubeNode]), ProcessorState::Forwarding});
  return run;
}

// The host's accumulation (3.4) charged on its own CPU, a block of contributions at a time (an execute per
// contribution would cost the simulation more than the render).
class ChargedAccumulation final : public core::ContributionSink {
 public:
  ChargedAccumulation(core::ContributionSink& sink, double secondsEach)
      : sink_(sink), secondsEach_(secondsEach) {}
  void add(const core::Contribution& c) override {
    sink_.add(c);
    if (++pending_ == queues::kContributionsPerShipment) charge();
  }
  void charge() {
    if (pending_ > 0 && secondsEach_ > 0)
      s4u::this_actor::execute(double(pending_) * secondsEach_ * s4u::this_actor::get_host()->get_speed());
    pending_ = 0;
  }

 private:
  core::ContributionSink& sink_;
  double secondsEach_;
  std::size_t pending_ = 0;
};

// The whole simulation, in the child process: results to `out`.
template <class Real>
void simulate(SimulationInput in, PipeWriter& out) {
  const auto wallStart = Clock::now();
  const std::unique_ptr<s4u::Engine> engine = engineOn(in.platform);
  const queues::SimGridWiring wiring = wiringFor(in);
  const double scale = speedScale(in.platform, *wiring.hosts[0]);
  queues::SimGridInterconnect<Real> net(in.context.regions, wiring);

  const int processors = int(in.setups.size());
  std::optional<queues::StepStallingTransport<Real>> stalling;
  if (in.stallAStep) stalling.emplace(net.endpoint(processors - 1));
  std::vector<std::unique_ptr<node::LogicalProcessor<Real>>> nodes;
  for (int p = 0; p < processors; ++p) {
    node::BasicTransport<Real>& transport = stalling && p == processors - 1
                                                ? static_cast<node::BasicTransport<Real>&>(*stalling)
                                                : net.endpoint(p);
    nodes.push_back(
        std::make_unique<node::LogicalProcessor<Real>>(in.context, std::move(in.setups[p]), transport));
  }
  out.value(Record::SynthesisStarts);  // every node has subdivided its region
  std::vector<ProcessorReport> reports(static_cast<std::size_t>(processors));
  std::vector<Timeline> timelines(static_cast<std::size_t>(processors));
  std::vector<Waiting> waiting(static_cast<std::size_t>(processors));
  int finished = 0;
  for (int p = 0; p < processors; ++p)
    s4u::Actor::create("processor-" + std::to_string(p), wiring.hosts[in.cubeNode[p]], [&, p] {
      driveInSimulatedTime(*nodes[p], net, p, in.platform.costs, scale, reports[p], timelines, waiting[p],
                           in.steps[std::size_t(p)]);
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
    ChargedAccumulation accumulation(toParent, in.platform.costs.accumulateSeconds);
    net.serveHost(accumulation);
    accumulation.charge();
    makespan = s4u::Engine::get_clock();
    hostDone = true;
  });
  net.startCommunicationTasks();
  engine->run();
  // SimGrid ends a run where no actor can move as it ends a finished one (it says so on stderr): a cycle
  // of processors locked on each other's full FIFOs (--fifo-full lock) is the run's result.
  std::vector<int> lockedOn;
  for (const auto& n : nodes) lockedOn.push_back(n->lockedOn());
  const std::vector<int> cycle = net.terminated() ? std::vector<int>{} : lockCycle(lockedOn);
  std::optional<Deadlock> deadlock;
  if (!cycle.empty()) {
    deadlock = deadlockOf(cycle, in.context.regions, [&](int from, int to) { return net.raysIn(from, to); });
    for (int p : cycle) deadlock->simulatedSeconds = std::max(deadlock->simulatedSeconds, waiting[p].since);
    makespan = s4u::Engine::get_clock();
    for (int p = 0; p < processors; ++p) {  // the waits the deadlock left open, to its end
      if (waiting[p].since < 0) continue;
      const bool blocked = waiting[p].blocked;
      (blocked ? reports[p].blockedSeconds : reports[p].idleSeconds) += makespan - waiting[p].since;
      timelines[p].add(std::uint32_t(p), blocked ? ProcessorState::Blocked : ProcessorState::Idle,
                       waiting[p].since, makespan);
    }
  } else {
    requireCompleted(net.terminated(), finished, processors, hostDone);
  }
  toParent.flush();

  EmulatedRun run = emulatedRunOf(in, net, nodes, *wiring.hosts[0], reports, timelines);
  run.makespan = makespan;
  run.wallSeconds = secondsSince(wallStart);
  out.value(Record::Reports);
  writeEmulatedResults(out, reports, run, deadlock);
}

// ---- The host's preparation (3.2 steps 1-2, 3.7.1), in a simulation of its own: the synthesis starts only
// once every node has its setup (3.2 step 3), so the two never overlap, and the synthesis is simulated from
// its own zero, the same to the last digit whether or not the host pays.

// Each processor's setup as the host sends it: the wire format the MPI engine sends (its region database,
// its cells' object lists and boxes, its light sources, and the shared context), its real size in bytes.
std::vector<std::uint64_t> setupBytesOf(const node::MachineContext& context,
                                        const std::vector<node::NodeSetup>& setups) {
  std::vector<std::uint64_t> bytes;
  for (const node::NodeSetup& setup : setups)
    bytes.push_back(encodeJob(JobSettings{}, context, std::span(&setup, 1)).size());
  return bytes;
}

struct HostInput {
  const EmulatedPlatform& platform;
  const HostWork& work;
  const std::vector<std::uint64_t>& setupBytes;  // per processor
  const std::vector<std::uint32_t>& cubeNode;
};

// The host actor: each phase's counted work on the manager's CPU, then each node's setup, one after the
// other, each send paying the manager's CPU its overhead and the node's its receipt; the preparation ends
// when the last node has taken its setup.
HostPreprocessing simulateHostPreprocessing(const HostInput& in) {
  const std::unique_ptr<s4u::Engine> engine = engineOn(in.platform);
  s4u::Host* manager = hostNamed(queues::kCubeManagerHost, in.platform);
  const double scale = speedScale(in.platform, *hostNamed(hostName(0), in.platform));
  const CostTable& costs = in.platform.costs;
  HostPreprocessing pre;
  static int setupToken = 0;  // SimGrid carries a pointer; the size on the wire is the setup's
  double transferStart = 0;
  for (std::size_t p = 0; p < in.cubeNode.size(); ++p) {
    s4u::Host* node = hostNamed(hostName(in.cubeNode[p]), in.platform);
    s4u::Actor::create("setup-of-" + std::to_string(p), node, [&, p, node] {
      s4u::Mailbox::by_name("setup-" + std::to_string(p))->get<int>();
      if (costs.receiveSeconds > 0) s4u::this_actor::execute(costs.receiveSeconds * node->get_speed());
    });
  }
  s4u::Actor::create("host", manager, [&] {
    auto phase = [&](double flops, double& seconds) {
      const double start = s4u::Engine::get_clock();
      if (flops > 0) s4u::this_actor::execute(flops * scale);
      seconds = s4u::Engine::get_clock() - start;
    };
    phase(costs.samplingFlopsOf(in.work), pre.sampling);
    phase(costs.partitioningFlopsOf(in.work), pre.partitioning);
    phase(costs.pruningFlopsOf(in.work), pre.pruning);
    phase(costs.mappingFlopsOf(in.work), pre.mapping);
    transferStart = s4u::Engine::get_clock();
    for (std::size_t p = 0; p < in.cubeNode.size(); ++p) {
      if (costs.sendSeconds > 0) s4u::this_actor::execute(costs.sendSeconds * manager->get_speed());
      s4u::Mailbox::by_name("setup-" + std::to_string(p))->put(&setupToken, in.setupBytes[p]);
      ++pre.messages;
      pre.bytes += in.setupBytes[p];
    }
  });
  engine->run();
  pre.seconds = s4u::Engine::get_clock();  // the last node has taken its setup
  pre.transfer = pre.seconds - transferStart;
  return pre;
}

// The parent's side: the start of synthesis, contributions to the host's sink and progress as they come,
// then the reports.
MachineRun receiveResults(PipeReader& in, const EngineHooks& hooks) {
  for (;;) {
    const auto tag = in.value<Record>();
    if (tag == Record::SynthesisStarts) {
      if (hooks.synthesisStarts) hooks.synthesisStarts();
    } else if (tag == Record::Contributions) {
      for (const core::Contribution& c : in.vector<core::Contribution>()) hooks.host->add(c);
    } else if (tag == Record::Progress) {
      const auto evaluated = in.vector<std::uint64_t>();
      if (hooks.progress) hooks.progress(evaluated);
    } else if (tag == Record::Failure) {
      throw std::runtime_error(in.string());
    } else {
      return readEmulatedResults(in);
    }
  }
}

// Runs simulate(out) in a child process (SimGrid allows one simulation per process) and read(in) on its
// results in this one. look(child), called every `every` the child is silent, may end it (a watchdog) and
// throw why: that message replaces the signal's. Without look, the parent waits as long as the child runs.
template <class Result>
Result inChildProcess(const std::function<void(PipeWriter&)>& simulate,
                      const std::function<Result(PipeReader&)>& read,
                      std::chrono::milliseconds every = std::chrono::milliseconds(-1),
                      const std::function<void(pid_t)>& look = {}) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot create a pipe for the simulation");
  std::fflush(nullptr);
  const pid_t child = ::fork();
  if (child < 0) throw std::runtime_error("cannot fork the simulation process");
  if (child == 0) {
    ::close(fds[0]);
    PipeWriter out(fds[1]);
    try {
      simulate(out);
    } catch (const std::exception& e) {
      out.value(Record::Failure);
      out.string(e.what());
    }
    ::close(fds[1]);
    std::fflush(nullptr);
    _exit(0);
  }
  ::close(fds[1]);
  bool stalled = false;
  PipeReader in(fds[0], look ? every : std::chrono::milliseconds(-1), [&] {
    try {
      look(child);
    } catch (...) {
      stalled = true;
      throw;
    }
  });
  std::optional<Result> run;
  std::string failure;
  try {
    run = read(in);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (!run) {
    if (WIFSIGNALED(status) && !stalled)
      failure += fmt::format(" (the simulation process died of signal {}: {})", WTERMSIG(status),
                             strsignal(WTERMSIG(status)));
    throw std::runtime_error("emulated machine: " + failure);
  }
  return std::move(*run);
}

}  // namespace

template <class Real>
MachineRun EmulatedMachine<Real>::run(const node::MachineContext& context,
                                      std::vector<node::NodeSetup> setups, const EngineHooks& hooks) {
  HostPreprocessing pre;
  if (hooks.hostWork) {
    const std::vector<std::uint64_t> bytes = setupBytesOf(context, setups);
    const HostInput input{platform_, *hooks.hostWork, bytes, cubeNode_};
    try {
      pre = inChildProcess<HostPreprocessing>(
          [&](PipeWriter& out) {
            const HostPreprocessing simulated = simulateHostPreprocessing(input);
            out.value(Record::Reports);
            out.value(simulated);
          },
          [](PipeReader& in) {
            if (in.value<Record>() == Record::Failure) throw std::runtime_error(in.string());
            return in.value<HostPreprocessing>();
          });
    } catch (const std::runtime_error& e) {  // SimGrid aborts on a missing route
      throw std::runtime_error(fmt::format(
          "{} while the host sent the nodes their setups: {} needs a route from manager to every node "
          "(symmetrical=\"YES\" on the nodes' routes to manager)",
          e.what(), platform_.platformFile.string()));
    }
  }
  // The watchdog: no processor moved for a whole period while one is inside a step. Its message replaces
  // the signal's, which only says the watchdog ended the simulation. From the start of synthesis: setting
  // up the processors in the child (their cells) moves no step.
  const SharedSteps steps(setups.size());
  StallWatch stallWatch(steps.size(), stallPeriod_);
  bool synthesis = false;
  EngineHooks watched = hooks;
  watched.synthesisStarts = [&] {
    synthesis = true;
    stallWatch = StallWatch(steps.size(), stallPeriod_);
    if (hooks.synthesisStarts) hooks.synthesisStarts();
  };
  const auto look = [&](pid_t child) {
    if (!synthesis || !stallWatch.stalled([&](std::size_t p) { return steps[p].stepsWorked.load(); })) return;
    std::string busy;
    for (std::size_t p = 0; p < steps.size(); ++p)
      if (steps[p].stepping.load()) busy += (busy.empty() ? "" : ", ") + std::to_string(p);
    if (busy.empty()) return;  // every actor waits: SimGrid ends such a run by itself (requireCompleted)
    ::kill(child, SIGKILL);
    throw std::runtime_error(stallWatch.headline() + " of wall-clock time; processor " + busy +
                             " has been inside one step all that time (a walk that does not end)");
  };
  MachineRun run = inChildProcess<MachineRun>(
      [&](PipeWriter& out) {
        simulate<Real>(
            SimulationInput{context, setups, platform_, queueCapacity_, cubeNode_, stallAStep_, steps}, out);
      },
      [&](PipeReader& in) { return receiveResults(in, watched); }, stallLookEvery(stallPeriod_), look);
  run.emulated->preprocessing = pre;
  return run;
}

template class EmulatedMachine<float>;
template class EmulatedMachine<double>;

}  // namespace raycube::host
