#include "host/studies/calibration.h"

#include <fmt/format.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <thread>

#include "core/bvh.h"
#include "core/intersect.h"
#include "core/spd/balls.h"
#include "core/spd/generators.h"
#include "core/view.h"
#include "core/whitted.h"
#include "host/machine/machine_report.h"
#include "host/render/framebuffer.h"
#include "host/render/render_machine.h"
#include "host/util/clock.h"
#include "node/ray_message.h"
#include "queues/spsc_queue.h"

namespace raycube::host {
namespace {

using Real = double;  // the machine's default precision (RenderSettings)

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// CPU seconds of this thread, or of the whole process: what an operation costs a core, however many other
// programs share the cores (this machine is often shared), where wall time would count their turns too.
double cpuSeconds(clockid_t clock = CLOCK_THREAD_CPUTIME_ID) {
  timespec t{};
  clock_gettime(clock, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The median over `repetitions` of CPU seconds per operation: body() does `operations` of them.
template <class Body>
double secondsPerOperation(int repetitions, double operations, Body&& body) {
  std::vector<double> each;
  for (int r = 0; r < repetitions; ++r) {
    const double start = cpuSeconds();
    body();
    each.push_back((cpuSeconds() - start) / operations);
  }
  return median(each);
}

// Keeps a result alive without the compiler dropping the loop that made it.
template <class T>
void keep(const T& value) {
  asm volatile("" : : "g"(&value) : "memory");
}

std::vector<core::Object> objectsShaped(const core::Scene& scene, std::size_t shape) {
  std::vector<core::Object> out;
  for (const core::Object& o : scene.objects)
    if (o.shape.index() == shape) out.push_back(o);
  return out;
}

// One ray per object, from a random direction at three times its size, aimed at a random point of its box
// doubled: some hit, some miss, as the tests a traversal makes do.
std::vector<core::Ray> raysAt(const std::vector<core::Object>& objects, std::mt19937& random) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<core::Ray> rays;
  for (const core::Object& o : objects) {
    const core::Box b = core::boundsOf(o, 0);
    const core::Vec3 centre = 0.5 * (b.lo + b.hi), half = 0.5 * (b.hi - b.lo);
    const double size = glm::length(half) + 1e-9;
    core::Vec3 from(u(random), u(random), u(random));
    from = centre + 3 * size * glm::normalize(from + core::Vec3(1e-3, 0, 0));
    const core::Vec3 to = centre + 2.0 * half * core::Vec3(u(random), u(random), u(random));
    rays.push_back(core::Ray{from, glm::normalize(to - from), 0, core::kInfinity});
  }
  return rays;
}

// Seconds per nearestHit over objects of one kind, each tested with its own ray.
double secondsPerTest(const std::vector<core::Object>& objects, int repetitions) {
  std::mt19937 random(47);
  const std::vector<core::Ray> rays = raysAt(objects, random);
  const int passes = std::max(1, int(200000 / objects.size()));
  return secondsPerOperation(repetitions, double(passes) * double(objects.size()), [&] {
    double sum = 0;
    for (int p = 0; p < passes; ++p)
      for (std::size_t i = 0; i < objects.size(); ++i)
        sum += core::nearestHit<Real>(objects[i], rays[i], 1e30);
    keep(sum);
  });
}

// A star of `points` points in the plane z = 0 at a random place: a concave polygon, which the polygon test
// takes through its outline (core/polygon_outline.h).
std::vector<core::Object> stars(int points, int count, std::mt19937& random) {
  std::uniform_real_distribution<double> u(-10, 10);
  std::vector<core::Object> out;
  for (int s = 0; s < count; ++s) {
    const core::Vec3 at(u(random), u(random), u(random));
    std::vector<core::Vec3> corners;
    for (int k = 0; k < 2 * points; ++k) {
      const double angle = M_PI * k / points, r = k % 2 ? 0.5 : 1.0;
      corners.push_back(at + core::Vec3(r * std::cos(angle), r * std::sin(angle), 0));
    }
    out.push_back(core::Object{core::Polygon(std::move(corners))});
  }
  return out;
}

// Patches: the triangles given, with normals from their centre out.
std::vector<core::Object> patchesOf(const std::vector<core::Object>& triangles) {
  std::vector<core::Object> out;
  for (const core::Object& o : triangles) {
    const auto& polygon = std::get<core::Polygon>(o.shape);
    core::Patch patch;
    core::Vec3 centre(0, 0, 0);
    for (const core::Vec3& v : polygon.vertices) centre += v / double(polygon.vertices.size());
    for (const core::Vec3& v : polygon.vertices) {
      patch.vertices.push_back(v);
      patch.normals.push_back(glm::normalize(v - centre + core::Vec3(0, 0, 1e-6)));
    }
    out.push_back(core::Object{std::move(patch)});
  }
  return out;
}

struct PrimitiveCosts {
  double sphere, cone, polygon, vertex, patch;
  int starVertices;
};

// 0 sphere, 1 cone, 2 polygon, 3 patch: core::Shape's order. A polygon's test, a + b per vertex, from
// triangles (tetra) and 16-pointed stars.
PrimitiveCosts primitiveCosts(int repetitions) {
  const core::Scene balls = core::makeBalls(2), rings = core::makeSpdScene("rings", 2),
                    tetra = core::makeSpdScene("tetra", 3);
  std::mt19937 random(47);
  PrimitiveCosts c{};
  c.sphere = secondsPerTest(objectsShaped(balls, 0), repetitions);
  c.cone = secondsPerTest(objectsShaped(rings, 1), repetitions);
  const std::vector<core::Object> triangles = objectsShaped(tetra, 2);
  const double triangle = secondsPerTest(triangles, repetitions);
  c.starVertices = 32;
  const double star = secondsPerTest(stars(c.starVertices / 2, 256, random), repetitions);
  c.vertex = std::max(0.0, (star - triangle) / (c.starVertices - 3));
  c.polygon = std::max(0.0, triangle - 3 * c.vertex);
  c.patch = secondsPerTest(patchesOf(triangles), repetitions);
  return c;
}

// The eye rays of a scene at side x side.
std::vector<core::Ray> eyeRays(const core::Scene& scene, int side) {
  const core::View view(scene.camera, side, side, core::Sampling::Centers);
  std::vector<core::Ray> rays;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) rays.push_back(view.eyeRay(x, y));
  return rays;
}

double testSeconds(const core::TraceCounters& c, const PrimitiveCosts& p) {
  return p.sphere * double(c.testsByShape[0]) + p.cone * double(c.testsByShape[1]) +
         p.polygon * double(c.testsByShape[2]) + p.vertex * double(c.polygonVerticesTested) +
         p.patch * double(c.testsByShape[3]);
}

// A BVH node tested: closest hits of balls 3's eye rays through the real BVH, less the primitive tests they
// made, per node tested.
double boxTestSeconds(const PrimitiveCosts& primitives, int repetitions) {
  const core::Scene scene = core::makeBalls(3);
  const core::Whitted shading(scene, core::ShadingOptions{});
  const core::BasicBvh<Real> bvh(scene, shading);
  const std::vector<core::Ray> rays = eyeRays(scene, 96);
  core::TraceCounters counted;
  for (const core::Ray& r : rays) bvh.closestHit(r, counted);
  const double perPass = secondsPerOperation(repetitions, 1, [&] {
    core::TraceCounters c;
    double sum = 0;
    for (const core::Ray& r : rays) sum += bvh.closestHit(r, c).t;
    keep(sum);
  });
  return std::max(0.0, (perPass - testSeconds(counted, primitives)) /
                           double(std::max<std::uint64_t>(1, counted.boxTests)));
}

// Finishing a ray and spawning one: balls 2's eye-ray hits shaded (core::Whitted::shadeHit, which spawns
// the light, reflected and refracted rays) and the light rays they spawn finished (finishLightRay, what most
// finished rays cost). A hit's shading is one ray finished and its spawned rays: (hit - finished) per ray
// spawned.
std::pair<double, double> shadingSeconds(int repetitions) {
  const core::Scene scene = core::makeBalls(2);
  const core::Whitted shading(scene, core::ShadingOptions{});
  const core::BasicBvh<Real> bvh(scene, shading);
  std::vector<std::pair<core::TracedRay, core::Hit>> hits;
  std::vector<core::TracedRay> lightRays;
  core::RayOutcome outcome;
  core::TraceCounters c;
  for (const core::Ray& r : eyeRays(scene, 128)) {
    const core::Hit hit = bvh.closestHit(r, c);
    if (!hit.found()) continue;
    core::TracedRay traced;
    traced.ray = r;
    hits.push_back({traced, hit});
    outcome.clear();
    shading.shadeHit(traced, hit, outcome);
    for (const core::TracedRay& s : outcome.spawned)
      if (s.kind == core::RayKind::Light) lightRays.push_back(s);
  }
  std::size_t spawned = 0;
  const double perHit = secondsPerOperation(repetitions, double(hits.size()), [&] {
    spawned = 0;
    for (const auto& [ray, hit] : hits) {
      outcome.clear();
      shading.shadeHit(ray, hit, outcome);
      spawned += outcome.spawned.size();
    }
  });
  const double perLightRay = secondsPerOperation(repetitions, double(lightRays.size()), [&] {
    for (const core::TracedRay& ray : lightRays) {
      outcome.clear();
      shading.finishLightRay(ray, 0.5, outcome);
      keep(outcome.contributions.size());
    }
  });
  const double spawnedPerHit = double(spawned) / double(std::max<std::size_t>(1, hits.size()));
  return {perLightRay, spawnedPerHit > 0 ? std::max(0.0, (perHit - perLightRay) / spawnedPerHit) : 0.0};
}

// The host: a contribution added to the frame buffer (3.4), over a 512x512 image in random order.
double accumulateSeconds(int repetitions) {
  constexpr int kSide = 512, kPieces = 1 << 20;
  Framebuffer frame(kSide, kSide);
  std::mt19937 random(47);
  std::vector<core::Contribution> pieces;
  for (int i = 0; i < kPieces; ++i)
    pieces.push_back({std::uint32_t(random() % (kSide * kSide)), core::Color(0.25, 0.5, 0.125)});
  return secondsPerOperation(repetitions, kPieces, [&] {
    for (const core::Contribution& c : pieces) frame.add(c);
  });
}

// A contribution into the block a node ships to the host (queues::kContributionsPerShipment at a time).
double contributionSeconds(int repetitions) {
  std::vector<core::Contribution> block;
  block.reserve(4096);
  constexpr int kPieces = 1 << 20;
  return secondsPerOperation(repetitions, kPieces, [&] {
    for (int i = 0; i < kPieces; ++i) {
      if (block.size() == 4096) {
        keep(block.back());
        block.clear();
      }
      block.push_back(core::Contribution{std::uint32_t(i), core::Color(i, 0.5, 0.25)});
    }
  });
}

using RayQueue = queues::SpscQueue<node::BasicRayMessage<Real>>;

// A ray message pushed into a face FIFO and popped, on one thread (the CPU both sides pay), in batches of
// 64; split evenly between the sender and the receiver (timed apart, each side is too short for the clock).
std::pair<double, double> fifoSeconds(int repetitions) {
  RayQueue queue(128);
  node::BasicRayMessage<Real> message{};
  constexpr int kRounds = 20000, kBatch = 64;
  const double both = secondsPerOperation(repetitions, double(kRounds) * kBatch, [&] {
    for (int round = 0; round < kRounds; ++round) {
      for (int i = 0; i < kBatch; ++i) {
        message.ray.sample = std::uint32_t(i);
        queue.tryPush(message);
      }
      for (int i = 0; i < kBatch; ++i) queue.tryPop(message);
    }
    keep(message);
  });
  return {both / 2, both / 2};
}

// One way between two threads through two FIFOs: half a round trip; and ray messages streamed from one
// thread to another, in bytes per second. Both wait by spinning and yielding, as the FIFOs' blocking calls
// do.
std::pair<double, double> fifoLink(int repetitions) {
  constexpr int kTrips = 4000, kStream = 200000;
  std::vector<double> oneWay, bandwidth;
  for (int r = 0; r < repetitions; ++r) {
    queues::SpscQueue<std::uint64_t> there(8), back(8);
    std::thread echo([&] {
      std::uint64_t v = 0;
      for (int i = 0; i < kTrips; ++i) {
        while (!there.tryPop(v)) std::this_thread::yield();
        while (!back.tryPush(v)) std::this_thread::yield();
      }
    });
    auto start = Clock::now();
    for (int i = 0; i < kTrips; ++i) {
      std::uint64_t v = std::uint64_t(i);
      while (!there.tryPush(v)) std::this_thread::yield();
      while (!back.tryPop(v)) std::this_thread::yield();
    }
    oneWay.push_back(secondsSince(start) / (2.0 * kTrips));
    echo.join();

    RayQueue rays(128);
    std::thread consumer([&] {
      node::BasicRayMessage<Real> m{};
      for (int i = 0; i < kStream; ++i)
        while (!rays.tryPop(m)) std::this_thread::yield();
    });
    start = Clock::now();
    node::BasicRayMessage<Real> m{};
    for (int i = 0; i < kStream; ++i)
      while (!rays.tryPush(m)) std::this_thread::yield();
    consumer.join();
    bandwidth.push_back(double(kStream) * sizeof(m) / secondsSince(start));
  }
  return {median(oneWay), median(bandwidth)};
}

RenderSettings oneThread(int side) {
  RenderSettings s;
  s.width = s.height = side;
  s.threads = 1;
  s.progress = false;
  return s;
}

// A 1x1 machine render on threads: the median CPU seconds of the whole process (the processor's thread,
// the host's accumulation; the preprocessing of a small scene is a few percent of it) and the processor's
// counts.
std::pair<double, node::NodeStats> renderOneProcessor(const core::Scene& scene, int side, int repetitions) {
  MachineSettings machine;
  machine.rows = machine.columns = 1;
  std::vector<double> seconds;
  node::NodeStats stats;
  for (int r = 0; r < repetitions; ++r) {
    MachineReport report;
    const double start = cpuSeconds(CLOCK_PROCESS_CPUTIME_ID);
    renderMachine(scene, oneThread(side), machine, &report);
    seconds.push_back(cpuSeconds(CLOCK_PROCESS_CPUTIME_ID) - start);
    stats = report.processors.at(0).node;
  }
  return {median(seconds), stats};
}

double tableSeconds(const CostTable& table, const node::NodeStats& stats) {
  return table.flopsOf(stats) + table.messageSecondsOf(stats);
}

bool haveMpirun() {
  return std::system("command -v mpirun >/dev/null 2>&1") == 0;
}

// An N-rank run's start-up: a render of 8x8 pixels on one processor under mpirun, wall time (all of it
// start-up, MPI_Init and loading the program but a few milliseconds), median of the repetitions.
double startupSeconds(const std::filesystem::path& program, int ranks, int repetitions) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / fmt::format("raycube-calibrate-{}.png", ::getpid());
  const std::string command = fmt::format(
      "mpirun {}--oversubscribe -np {} '{}' render --balls 1 --size 8x8 --procs 1x1 -q --transport mpi -o "
      "'{}' "
      ">/dev/null 2>&1",
      ::geteuid() == 0 ? "--allow-run-as-root " : "", ranks, program.string(), out.string());
  std::vector<double> each;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = Clock::now();
    const int status = std::system(command.c_str());
    each.push_back(secondsSince(start));
    if (status != 0) throw std::runtime_error(fmt::format("calibrate: '{}' failed ({})", command, status));
  }
  std::filesystem::remove(out);
  return median(each);
}

// This machine's seconds per flop-equivalent of the hand counts (CostTable's defaults): the median over the
// primitive tests and the box test, each measured against its own count.
double secondsPerFlopEquivalent(const PrimitiveCosts& p, double box) {
  const CostTable counts;
  return median({p.sphere / counts.sphereTest, p.cone / counts.coneTest, p.polygon / counts.polygonTest,
                 p.patch / counts.patchTest, box / counts.cellStep});
}

std::string seconds(double s) {
  return fmt::format("{:.4g}", s);
}

}  // namespace

Calibration calibrateThisMachine(const CalibrationOptions& options) {
  const int n = options.repetitions;
  Calibration c;
  c.cores = int(std::max(1u, std::thread::hardware_concurrency()));
  const PrimitiveCosts p = primitiveCosts(n);
  const double box = boxTestSeconds(p, n);
  const auto [finished, spawned] = shadingSeconds(n);
  const double contribution = contributionSeconds(n);
  const auto [send, receive] = fifoSeconds(n);
  const std::string median = fmt::format("median of {}", n);

  CostTable table;
  table.sphereTest = p.sphere;
  table.coneTest = p.cone;
  table.polygonTest = p.polygon;
  table.polygonVertex = p.vertex;
  table.patchTest = p.patch;
  table.cellStep = box;
  table.raySegment = 0;
  table.rayFinished = finished;
  table.raySpawned = spawned;
  table.contribution = contribution;
  table.sendSeconds = send;
  table.receiveSeconds = receive;
  table.relaySeconds = send + receive;
  table.accumulateSeconds = accumulateSeconds(n);
  // The host's own preprocessing prices are not timed here: their hand counts at this machine's seconds
  // per flop-equivalent (secondsPerFlopEquivalent).
  const double secondsPerFlop = secondsPerFlopEquivalent(p, box);
  const CostTable counts;
  table.segmentClip = counts.segmentClip * secondsPerFlop;
  table.regionTest = counts.regionTest * secondsPerFlop;
  table.mappingStep = counts.mappingStep * secondsPerFlop;
  // What the microbenchmarks leave out of a real render (taking a ray up in a region, the scheduler, the
  // FIFOs' bookkeeping, cache misses) per ray segment: balls 2 at 128x128 on one processor.
  const core::Scene balls2 = core::makeBalls(2);
  const auto [traced, stats] = renderOneProcessor(balls2, 128, std::max(3, n / 2 + 1));
  table.raySegment = std::max(0.0, (traced - tableSeconds(table, stats)) /
                                       double(std::max<std::uint64_t>(1, stats.processed.totalRays())));
  // The check on another scene, of other primitives: tetra 4's triangles.
  const auto [checkTraced, checkStats] = renderOneProcessor(core::makeSpdScene("tetra", 4), 128, 3);
  c.checkTraceSeconds = checkTraced;
  c.checkPredictedSeconds = tableSeconds(table, checkStats);

  c.costs = {
      {"sphereTest", table.sphereTest,
       "core::nearestHit on balls 2's spheres, a ray each aimed near it, " + median},
      {"coneTest", table.coneTest, "core::nearestHit on rings 2's cylinders, " + median},
      {"polygonTest", table.polygonTest,
       fmt::format("core::nearestHit on tetra 3's triangles less 3 vertices' cost, {}", median)},
      {"polygonVertex", table.polygonVertex,
       fmt::format("(a {}-vertex star's test - a triangle's) / {}, {}", p.starVertices, p.starVertices - 3,
                   median)},
      {"patchTest", table.patchTest, "core::nearestHit on tetra 3's triangles as patches, " + median},
      {"cellStep", table.cellStep,
       "a BVH node tested: balls 3's eye rays (96x96) through core::Bvh::closestHit less their primitive "
       "tests, "
       "per node; a cell step is priced the same, " +
           median},
      {"raySegment", table.raySegment,
       "balls 2 128x128 on one processor (threads): the render's CPU seconds not explained by the other "
       "costs, "
       "per ray segment (median of 3 renders)"},
      {"rayFinished", table.rayFinished,
       "core::Whitted::finishLightRay on the light rays balls 2's eye-ray hits spawn, " + median},
      {"raySpawned", table.raySpawned,
       "(core::Whitted::shadeHit on balls 2's eye-ray hits - a ray finished) per ray the hits spawn, " +
           median},
      {"contribution", table.contribution, "a contribution into a block of 4096 for the host, " + median},
      {"sendSeconds", table.sendSeconds,
       "half of a 128-byte ray message pushed into a face FIFO (SpscQueue) and popped, batches of 64, " +
           median},
      {
          "receiveSeconds",
          table.receiveSeconds,
          "the other half",
      },
      {"relaySeconds", table.relaySeconds, "a receive and a send (routing direct: no relaying happens)"},
      {"segmentClip", table.segmentClip,
       fmt::format("not timed: the host's hand count ({} flop-equivalents) x {} s per flop-equivalent, "
                   "the median of the primitive and box tests against their hand counts",
                   counts.segmentClip, seconds(secondsPerFlop))},
      {"regionTest", table.regionTest,
       fmt::format("not timed: {} flop-equivalents x the same", counts.regionTest)},
      {"mappingStep", table.mappingStep,
       fmt::format("not timed: {} flop-equivalents x the same", counts.mappingStep)},
      {"accumulateSeconds", table.accumulateSeconds,
       "the host: a contribution added to a 512x512 frame buffer (host::Framebuffer::add), random pixels, " +
           median}};
  const auto [oneWay, bytesPerSecond] = fifoLink(n);
  c.latency = {"latency", oneWay, "half a round trip between two threads through two FIFOs, " + median};
  c.bandwidth = {"bandwidth", bytesPerSecond,
                 "128-byte ray messages streamed between two threads, " + median};

  if (!options.mpi) {
    c.mpiNote = "MPI start-up not measured (--no-mpi)";
  } else if (!haveMpirun()) {
    c.mpiNote = "MPI start-up not measured: no mpirun on the PATH";
  } else {
    for (int ranks : options.startupRanks)
      c.startupSeconds.push_back({ranks, startupSeconds(options.program, ranks, std::max(3, n / 2 + 1))});
  }
  return c;
}

std::string costFileOf(const Calibration& c) {
  std::string out = fmt::format(
      "# This machine's cost table, written by `raycube calibrate` ({} cores). Every cost is in seconds of\n"
      "# one core (unit seconds: no node speed applies; the platform's hosts may have any speed), measured "
      "on\n"
      "# the real code in loops, in CPU time (host/studies/calibration.cpp); how each was measured is beside "
      "it.\n"
      "# Measurements move by some percent from run to run; the file's lines do not.\n"
      "unit seconds\n"
      "routing direct   # processors of one machine: no node relays another's messages\n",
      c.cores);
  for (const MeasuredConstant& m : c.costs)
    out += fmt::format("{} {}   # {}\n", m.key, seconds(m.value), m.how);
  out += fmt::format("# link (platform.xml): latency {} s ({}); bandwidth {} B/s ({})\n",
                     seconds(c.latency.value), c.latency.how, seconds(c.bandwidth.value), c.bandwidth.how);
  if (c.startupSeconds.empty()) {
    out += "# " + c.mpiNote + "\n";
  } else {
    for (const auto& [ranks, s] : c.startupSeconds)
      out += fmt::format("# start-up of a {}-rank MPI run: {} s (mpirun of an 8x8 render, median)\n", ranks,
                         seconds(s));
  }
  out += fmt::format("# check: tetra 4 128x128 on one processor took {} CPU s; this table predicts {} s\n",
                     seconds(c.checkTraceSeconds), seconds(c.checkPredictedSeconds));
  return out;
}

std::string platformXmlOf(const Calibration& c, int nodes) {
  std::string out = fmt::format(
      "<?xml version='1.0'?>\n"
      "<!DOCTYPE platform SYSTEM \"https://simgrid.org/simgrid.dtd\">\n"
      "<!-- Written by `raycube calibrate`: this machine, {} cores. Costs in seconds (the costs file's\n"
      "     `unit seconds`) are charged at each host's own speed, so any speed does; a link is the\n"
      "     shared-memory FIFO between two threads as measured (latency {} s, {} B/s). -->\n"
      "<platform version=\"4.1\">\n"
      "  <zone id=\"machine\" routing=\"DijkstraCache\">\n",
      c.cores, seconds(c.latency.value), seconds(c.bandwidth.value));
  std::vector<std::string> names;
  for (int i = 0; i < nodes; ++i) names.push_back(fmt::format("node-{}", i));
  names.push_back("manager");
  for (const std::string& name : names)
    out += fmt::format("    <host id=\"{}\" speed=\"1Gf\" core=\"{}\"/>\n", name, c.cores);
  for (const std::string& name : names)  // two links from node to node: each half the latency
    out += fmt::format("    <link id=\"{}:nic\" bandwidth=\"{}Bps\" latency=\"{}s\"/>\n", name,
                       seconds(c.bandwidth.value), seconds(c.latency.value / 2));
  out += "    <router id=\"switch\"/>\n";
  for (const std::string& name : names)
    out += fmt::format("    <route src=\"{0}\" dst=\"switch\"><link_ctn id=\"{0}:nic\"/></route>\n", name);
  out += "  </zone>\n</platform>\n";
  return out;
}

std::pair<std::filesystem::path, std::filesystem::path> writeCalibration(const Calibration& c,
                                                                         const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const auto xml = dir / "platform.xml", costs = dir / "costs";
  for (const auto& [path, text] : {std::pair{xml, platformXmlOf(c)}, std::pair{costs, costFileOf(c)}}) {
    std::ofstream out(path);
    out << text;
    if (!out) throw std::runtime_error(fmt::format("calibrate: cannot write {}", path.string()));
  }
  return {xml, costs};
}

}  // namespace raycube::host
