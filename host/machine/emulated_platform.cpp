#include "host/machine/emulated_platform.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace raycube::host {
namespace {

// The one fitted constant of the iPSC/1 (README, "Headline results"): the node speed that makes one
// processor render the paper's table-2 case (balls 2, 128x128, depth 5) in 13941 s with the cost table
// above. Fitted once with `raycube scaling --emulate ipsc1 --procs 1 --fit 13941`.
constexpr double kIpsc1NodeSpeed = 2138.80;
// A present-day core: the cost table's flop-equivalents per second one core of this host achieves on
// balls 2, measured by benchmarks/cluster_calibration_benchmark.cpp (node_speed;
// benchmarks/results/emulated_machine.md, "On a present-day cluster") and copied here by hand.
constexpr double kClusterNodeSpeed = 4.0e8;

std::map<std::string, double CostTable::*> costFields() {
  return {{"sphereTest", &CostTable::sphereTest},           {"coneTest", &CostTable::coneTest},
          {"polygonTest", &CostTable::polygonTest},         {"polygonVertex", &CostTable::polygonVertex},
          {"patchTest", &CostTable::patchTest},             {"cellStep", &CostTable::cellStep},
          {"raySegment", &CostTable::raySegment},           {"rayFinished", &CostTable::rayFinished},
          {"raySpawned", &CostTable::raySpawned},           {"contribution", &CostTable::contribution},
          {"messageSent", &CostTable::messageSent},         {"messageReceived", &CostTable::messageReceived},
          {"messageRelayed", &CostTable::messageRelayed},   {"tokenVisit", &CostTable::tokenVisit}};
}

template <class Array>
std::uint64_t sum(const Array& a) {
  std::uint64_t s = 0;
  for (auto x : a) s += x;
  return s;
}

}  // namespace

double CostTable::flopsOf(const node::NodeStats& n) const {
  const core::TraceCounters& p = n.processed;
  return sphereTest * double(p.testsByShape[0]) + coneTest * double(p.testsByShape[1]) +
         polygonTest * double(p.testsByShape[2]) + polygonVertex * double(p.polygonVerticesTested) +
         patchTest * double(p.testsByShape[3]) + cellStep * double(p.cellSteps + p.boxTests) +
         raySegment * double(p.totalRays()) + rayFinished * double(sum(n.finished)) +
         raySpawned * double(sum(n.spawned)) + contribution * double(p.contributions) +
         messageSent * double(sum(n.sent)) + messageReceived * double(sum(n.received)) +
         tokenVisit * double(n.tokenVisits);
}

EmulatedPlatform builtinPlatform(std::string_view name) {
  EmulatedPlatform p;
  p.name = std::string(name);
  if (name == "ipsc1") {
    // Intel iPSC/1 (machines-and-engines.md): 80286/80287 nodes at 8 MHz; 10 Mbit/s Ethernet-chip links;
    // about 1 ms to a neighbour and 1 ms more per further hop, routed store and forward in node software.
    p.nodeSpeed = kIpsc1NodeSpeed;
    p.linkLatency = p.hostLinkLatency = 1e-3;
    p.linkBandwidth = p.hostLinkBandwidth = 10e6 / 8;
    p.routing = Routing::StoreAndForward;
    return p;
  }
  if (name == "cluster") {
    // A present-day cluster: links of about 1 us and 10 GB/s through a switch.
    p.nodeSpeed = kClusterNodeSpeed;
    p.linkLatency = p.hostLinkLatency = 1e-6;
    p.linkBandwidth = p.hostLinkBandwidth = 10e9;
    p.routing = Routing::Direct;
    return p;
  }
  throw std::invalid_argument(fmt::format("--emulate {}: the built-in platforms are ipsc1 and cluster", name));
}

void applyCostFile(const std::filesystem::path& costs, EmulatedPlatform& platform) {
  std::ifstream in(costs);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read the cost table", costs.string()));
  const auto fields = costFields();
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string key, value;
    if (!(words >> key)) continue;
    const std::string where = fmt::format("{}:{}", costs.string(), number);
    if (!(words >> value)) throw std::runtime_error(fmt::format("{}: '{}' needs a value", where, key));
    if (key == "routing") {
      if (value != "store-and-forward" && value != "direct")
        throw std::runtime_error(fmt::format("{}: routing is store-and-forward or direct, not '{}'", where, value));
      platform.routing = value == "direct" ? Routing::Direct : Routing::StoreAndForward;
      continue;
    }
    double number_ = 0;
    try {
      std::size_t used = 0;
      number_ = std::stod(value, &used);
      if (used != value.size() || !(number_ >= 0) || !std::isfinite(number_)) throw std::invalid_argument(value);
    } catch (const std::exception&) {
      throw std::runtime_error(fmt::format("{}: '{}' is not a finite number >= 0", where, value));
    }
    if (key == "nodeSpeed") {
      if (number_ <= 0) throw std::runtime_error(fmt::format("{}: nodeSpeed must be positive", where));
      platform.nodeSpeed = number_;
    } else if (const auto f = fields.find(key); f != fields.end()) {
      platform.costs.*(f->second) = number_;
    } else {
      throw std::runtime_error(fmt::format("{}: unknown cost '{}'", where, key));
    }
  }
}

EmulatedPlatform userPlatform(const std::filesystem::path& platformFile, const std::filesystem::path& costs) {
  if (!std::filesystem::is_regular_file(platformFile))
    throw std::runtime_error(fmt::format("--platform {}: not a readable file", platformFile.string()));
  EmulatedPlatform p = builtinPlatform("ipsc1");  // costs and speed unless the cost table says otherwise
  p.name = platformFile.filename().string();
  p.platformFile = platformFile;
  if (!costs.empty()) applyCostFile(costs, p);
  return p;
}

}  // namespace raycube::host
