#include "host/machine.h"

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "core/framebuffer.h"
#include "host/jitter_transport.h"
#include "host/progress.h"
#include "host/shared_memory_transport.h"
#include "queues/wait.h"

namespace raycube::host {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kHostBatchingPause = std::chrono::microseconds(500);
double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// 3.1: pixel areas with (nearly) equal sample counts.
std::vector<int> evenCuts(int samples, int parts) {
  std::vector<int> cuts;
  for (int k = 0; k <= parts; ++k) cuts.push_back(int((long long)samples * k / parts));
  return cuts;
}

// 3.2 step 1: each processor receives the objects that touch its region; objects reaching behind the eye
// plane go to every processor (see EyeFrameRay: the rear space belongs to all).
std::vector<node::NodeSetup> pruneDatabase(const node::RegionMap& regions, const node::ScreenLines& lines,
                                           const std::vector<node::EyeBox>& boxes, int cellLevel) {
  std::vector<std::uint32_t> rear;
  for (std::uint32_t o = 0; o < boxes.size(); ++o)
    if (node::reachesBehindEye(boxes[o])) rear.push_back(o);
  std::vector<node::NodeSetup> setups;
  for (int p = 0; p < regions.processors(); ++p) {
    const node::SampleRect a = regions.areaOf(p);
    const node::ColumnSlab region{lines.at(0, a.x0), lines.at(0, a.x1), lines.at(1, a.y0), lines.at(1, a.y1), 0,
                                  core::kInfinity};
    node::NodeSetup setup;
    setup.id = p;
    setup.cellLevel = cellLevel;
    setup.rearObjects = rear;
    for (std::uint32_t o = 0; o < boxes.size(); ++o)
      if (node::mayTouch(boxes[o], region)) setup.objects.push_back(o);
    setups.push_back(std::move(setup));
  }
  return setups;
}

}  // namespace

RenderResult renderMachine(const core::Scene& scene, const RenderSettings& settings, const MachineSettings& machine,
                           MachineReport* report) {
  const auto start = Clock::now();
  const core::View view(scene.camera, settings.width, settings.height, settings.sampling);
  if (machine.columns < 1 || machine.rows < 1 || machine.columns > view.samplesX() ||
      machine.rows > view.samplesY())
    throw std::invalid_argument(fmt::format("--procs {}x{}: every processor needs at least one sample row and "
                                            "column of the {}x{} sample grid",
                                            machine.rows, machine.columns, view.samplesX(), view.samplesY()));
  if (machine.queueCapacity < 1) throw std::invalid_argument("--queue-capacity must be at least 1");
  const core::Whitted shading(scene, settings.shading);
  const node::ScreenLines lines(view);
  const node::RegionMap regions(evenCuts(view.samplesX(), machine.columns), evenCuts(view.samplesY(), machine.rows),
                                lines);
  std::vector<node::EyeBox> boxes;
  for (const core::Object& o : scene.objects) boxes.push_back(node::eyeBoxOf(o, view));
  const node::MachineContext context{scene, view, shading, lines, regions, boxes};
  SharedMemoryMachine interconnect(regions, machine.queueCapacity);
  std::vector<std::unique_ptr<JitterTransport>> jitters;
  std::vector<std::unique_ptr<node::LogicalProcessor>> processors;
  for (node::NodeSetup& setup : pruneDatabase(regions, lines, boxes, machine.cellLevel)) {
    const int id = setup.id;
    node::Transport* transport = &interconnect.endpoint(id);
    if (machine.jitterSeed > 0) {
      jitters.push_back(std::make_unique<JitterTransport>(*transport, machine.jitterSeed * 7919u + unsigned(id)));
      transport = jitters.back().get();
    }
    processors.push_back(std::make_unique<node::LogicalProcessor>(context, std::move(setup), *transport));
  }
  RenderResult result;
  result.mode = "machine";
  result.workers = regions.processors();
  result.preprocessSeconds = secondsSince(start);

  const auto traceStart = Clock::now();
  core::Framebuffer frame(view.samplesX(), view.samplesY());
  std::uint64_t accumulated = 0;
  {
    Progress progress("machine", std::uint64_t(view.samplesX()) * view.samplesY(), settings.progress);
    std::vector<std::thread> threads;
    for (auto& p : processors) threads.emplace_back([&p] { p->run(); });
    // The host thread (3.5.1): accumulate contributions until the ring has proved termination.
    ContributionChannel& channel = interconnect.hostChannel();
    auto accumulate = [&](const core::Contribution& c) {
      frame.add(c);
      ++accumulated;
    };
    long long reported = 0;
    while (!interconnect.terminated()) {
      channel.drain(accumulate);
      long long shot = 0;
      for (const auto& p : processors) shot += p->primariesShot();
      progress.advance(std::uint64_t(shot - reported));
      reported = shot;
      // Let blocks pile up a little: one wake-up per batch of blocks, not per block (the host thread shares
      // the two cores with every processor).
      std::this_thread::sleep_for(kHostBatchingPause);
      queues::waitUntil(channel.doorbell(), [&] { return interconnect.terminated() || channel.anyPending(); });
    }
    for (std::thread& t : threads) t.join();
    channel.drain(accumulate);
  }
  result.image = frame.resolve(view);
  result.traceSeconds = secondsSince(traceStart);

  MachineReport local;
  MachineReport& out = report ? *report : local;
  out.settings = machine;
  out.contributionsAccumulated = accumulated;
  for (int p = 0; p < regions.processors(); ++p) {
    ProcessorReport pr;
    pr.node = processors[p]->stats();
    for (int f = 0; f < node::kFaces; ++f) pr.outgoing[f] = interconnect.outgoingStats(p, node::Face(f));
    result.counters += pr.node.processed;
    out.tokenPasses += pr.node.tokenVisits;
    out.processors.push_back(pr);
  }
  out.probes = processors[0]->stats().probes;
  // Rays by kind: each ray counted once, where it finished (segments are in the per-processor reports).
  for (int k = 0; k < core::kRayKinds; ++k) {
    result.counters.rays[k] = 0;
    for (const auto& pr : out.processors) result.counters.rays[k] += pr.node.finished[k];
  }
  return result;
}

}  // namespace raycube::host
