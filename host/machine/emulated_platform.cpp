#include "host/machine/emulated_platform.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace raycube::host {
namespace {

constexpr std::string_view kBuiltinPlatforms[] = {"ipsc1", "cluster"};

std::map<std::string, double CostTable::*> costFields() {
  return {{"sphereTest", &CostTable::sphereTest},     {"coneTest", &CostTable::coneTest},
          {"polygonTest", &CostTable::polygonTest},   {"polygonVertex", &CostTable::polygonVertex},
          {"patchTest", &CostTable::patchTest},       {"cellStep", &CostTable::cellStep},
          {"raySegment", &CostTable::raySegment},     {"rayFinished", &CostTable::rayFinished},
          {"raySpawned", &CostTable::raySpawned},     {"contribution", &CostTable::contribution},
          {"sendSeconds", &CostTable::sendSeconds},   {"receiveSeconds", &CostTable::receiveSeconds},
          {"relaySeconds", &CostTable::relaySeconds}, {"accumulateSeconds", &CostTable::accumulateSeconds},
          {"segmentClip", &CostTable::segmentClip},   {"regionTest", &CostTable::regionTest},
          {"mappingStep", &CostTable::mappingStep}};
}

// The message costs a cost table gave in flop-equivalents before they were seconds: what replaces each.
const std::map<std::string, std::string_view> kFormerMessageCosts{
    {"messageSent", "sendSeconds"},
    {"messageReceived", "receiveSeconds"},
    {"messageRelayed", "relaySeconds"},
    {"tokenVisit", "sendSeconds and receiveSeconds"}};

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
         raySpawned * double(sum(n.spawned)) + contribution * double(p.contributions);
}

double CostTable::messageSecondsOf(const node::NodeStats& n) const {
  return sendSeconds * double(sum(n.sent) + n.tokenVisits) +
         receiveSeconds * double(sum(n.received) + n.tokenVisits);
}

std::vector<std::filesystem::path> platformDirectories() {
  if (const char* path = std::getenv("RAYCUBE_PLATFORMS"); path != nullptr && *path != '\0') return {path};
  std::vector<std::filesystem::path> directories;
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    directories.push_back(self.parent_path() / "platforms");
    directories.push_back(self.parent_path().parent_path() / "share" / "raycube" / "platforms");
  }
  directories.emplace_back(RAYCUBE_BUILD_PLATFORMS);
  return directories;
}

EmulatedPlatform builtinPlatform(std::string_view name) {
  if (std::find(std::begin(kBuiltinPlatforms), std::end(kBuiltinPlatforms), name) ==
      std::end(kBuiltinPlatforms))
    throw std::invalid_argument(fmt::format("--emulate {}: the built-in platforms are {}", name,
                                            fmt::join(kBuiltinPlatforms, " and ")));
  const std::string xml = fmt::format("{}.xml", name), costs = fmt::format("{}.costs", name);
  const std::vector<std::filesystem::path> directories = platformDirectories();
  for (const std::filesystem::path& directory : directories) {
    if (!std::filesystem::exists(directory / xml)) continue;
    EmulatedPlatform p = userPlatform(directory / xml, directory / costs);
    p.name = std::string(name);
    return p;
  }
  std::vector<std::string> places;
  for (const std::filesystem::path& directory : directories) places.push_back(directory.string());
  throw std::runtime_error(
      fmt::format("--emulate {}: {} is in none of {} (set RAYCUBE_PLATFORMS to its folder)", name, xml,
                  fmt::join(places, ", ")));
}

namespace {

// A word of a cost file that names one of a few choices.
template <class Choice>
Choice choiceOf(const std::string& where, const std::string& key, const std::string& value,
                std::initializer_list<std::pair<const char*, Choice>> choices) {
  std::string names;
  for (const auto& [name, choice] : choices) {
    if (value == name) return choice;
    names += fmt::format("{}{}", names.empty() ? "" : " or ", name);
  }
  throw std::runtime_error(fmt::format("{}: {} is {}, not '{}'", where, key, names, value));
}

}  // namespace

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
      platform.routing = choiceOf<Routing>(
          where, key, value, {{"store-and-forward", Routing::StoreAndForward}, {"direct", Routing::Direct}});
      continue;
    }
    if (key == "fifoFull") {
      platform.fifoFull = choiceOf<node::FifoFull>(
          where, key, value, {{"lock", node::FifoFull::Lock}, {"overflow", node::FifoFull::Overflow}});
      continue;
    }
    if (key == "unit") {
      if (value != "flop-equivalents" && value != "seconds")
        throw std::runtime_error(
            fmt::format("{}: unit is flop-equivalents or seconds, not '{}'", where, value));
      platform.computeUnit = value == "seconds" ? ComputeUnit::Seconds : ComputeUnit::FlopEquivalents;
      continue;
    }
    double number_ = 0;
    try {
      std::size_t used = 0;
      number_ = std::stod(value, &used);
      if (used != value.size() || !(number_ >= 0) || !std::isfinite(number_))
        throw std::invalid_argument(value);
    } catch (const std::exception&) {
      throw std::runtime_error(fmt::format("{}: '{}' is not a finite number >= 0", where, value));
    }
    if (key == "nodeSpeed") {
      if (platform.computeUnit == ComputeUnit::Seconds)
        throw std::runtime_error(fmt::format("{}: nodeSpeed has no meaning for costs in seconds", where));
      if (number_ <= 0) throw std::runtime_error(fmt::format("{}: nodeSpeed must be positive", where));
      platform.nodeSpeed = number_;
    } else if (const auto f = fields.find(key); f != fields.end()) {
      platform.costs.*(f->second) = number_;
    } else if (const auto former = kFormerMessageCosts.find(key); former != kFormerMessageCosts.end()) {
      throw std::runtime_error(
          fmt::format("{}: '{}' (flop-equivalents) is now {}, in seconds of the CPU that pays it", where, key,
                      former->second));
    } else {
      throw std::runtime_error(fmt::format("{}: unknown cost '{}'", where, key));
    }
  }
}

EmulatedPlatform userPlatform(const std::filesystem::path& platformFile, const std::filesystem::path& costs) {
  if (!std::filesystem::is_regular_file(platformFile))
    throw std::runtime_error(fmt::format("--platform {}: not a readable file", platformFile.string()));
  EmulatedPlatform p;  // CostTable's costs and store and forward unless the cost table says otherwise
  p.name = platformFile.filename().string();
  p.platformFile = platformFile;
  if (!costs.empty()) applyCostFile(costs, p);
  if (p.computeUnit == ComputeUnit::Seconds && p.nodeSpeed)
    throw std::runtime_error(fmt::format("{}: nodeSpeed has no meaning for costs in seconds (unit seconds)",
                                         costs.string()));
  return p;
}

}  // namespace raycube::host
