#include "host/report/emulated_report.h"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace raycube::host {
namespace {

const char* stateName(ProcessorState s) {
  switch (s) {
    case ProcessorState::Computing:
      return "computing";
    case ProcessorState::Blocked:
      return "blocked";
    case ProcessorState::Idle:
      return "idle";
    case ProcessorState::Forwarding:
      return "forwarding";
  }
  return "?";
}

const EmulatedRun& simulatedOf(const MachineReport& report) {
  if (!report.emulated) throw std::logic_error("not a run in simulated time");
  return *report.emulated;
}

}  // namespace

double blockedShare(const MachineReport& report) {
  const EmulatedRun& run = simulatedOf(report);
  double blocked = 0;
  for (const ProcessorReport& p : report.processors) blocked += p.blockedSeconds;
  const double total = run.makespan * double(report.processors.size());
  return total > 0 ? blocked / total : 0;
}

std::vector<double> blockedShareByTenth(const MachineReport& report) {
  const EmulatedRun& run = simulatedOf(report);
  constexpr int kParts = 10;
  std::vector<double> blocked(kParts, 0.0);
  const double part = run.makespan / kParts;
  if (part <= 0 || report.processors.empty()) return blocked;
  for (const StateInterval& i : run.timeline) {
    if (i.state != ProcessorState::Blocked) continue;
    for (int k = std::max(0, int(i.start / part)); k < kParts && k * part < i.end; ++k)
      blocked[std::size_t(k)] += std::max(0.0, std::min(i.end, (k + 1) * part) - std::max(i.start, k * part));
  }
  for (double& b : blocked) b /= part * double(report.processors.size());
  return blocked;
}

std::string emulatedTable(const MachineReport& report) {
  const EmulatedRun& run = simulatedOf(report);
  std::uint64_t hostBytes = 0;
  for (const LinkTraffic& l : run.links)
    if (l.to == kHostNode) hostBytes += l.bytes;
  std::string text = fmt::format(
      "  emulated {}: makespan {:.6f} simulated s; {} ray messages on the links (relays included), {} bytes "
      "of contributions to the host; blocked share {:.1f}%; simulated in {:.2f} s of wall time ({:.0f} "
      "messages/s)\n",
      run.platform, run.makespan, run.rayMessages, hostBytes, 100 * blockedShare(report), run.wallSeconds,
      run.wallSeconds > 0 ? double(run.rayMessages) / run.wallSeconds : 0.0);
  const HostPreprocessing& pre = run.preprocessing;
  text += fmt::format(
      "  host's preprocessing {:.6f} simulated s (sub-sampling {:.3f}, partitioning {:.3f}, pruning {:.3f}, "
      "mapping {:.3f}, {} setups of {} bytes sent in {:.3f}); end to end {:.6f} simulated s\n",
      pre.seconds, pre.sampling, pre.partitioning, pre.pruning, pre.mapping, pre.messages, pre.bytes,
      pre.transfer, run.endToEnd());
  text += "  blocked share by tenth of the makespan:";
  for (double share : blockedShareByTenth(report)) text += fmt::format(" {:.0f}%", 100 * share);
  text += "\n  node  computing  forwarding    blocked       idle   (simulated seconds)\n";
  for (const ProcessorReport& p : report.processors)
    text += fmt::format("  {:>4} {:>10.3f} {:>11.3f} {:>10.3f} {:>10.3f}\n", p.node.id, p.computeSeconds,
                        p.forwardSeconds, p.blockedSeconds, p.idleSeconds);
  return text;
}

nlohmann::json emulatedJson(const MachineReport& report) {
  const EmulatedRun& run = simulatedOf(report);
  nlohmann::json processors = nlohmann::json::array();
  for (const ProcessorReport& p : report.processors)
    processors.push_back({{"id", p.node.id},
                          {"computingSeconds", p.computeSeconds},
                          {"forwardingSeconds", p.forwardSeconds},
                          {"blockedSeconds", p.blockedSeconds},
                          {"idleSeconds", p.idleSeconds}});
  nlohmann::json links = nlohmann::json::array();
  for (const LinkTraffic& l : run.links)
    links.push_back({{"from", l.from},
                     {"to", l.to == kHostNode ? nlohmann::json("host") : nlohmann::json(l.to)},
                     {"messages", l.messages},
                     {"bytes", l.bytes}});
  const HostPreprocessing& pre = run.preprocessing;
  const HostWork& work = report.hostWork;
  const nlohmann::json preprocessing{{"samplingSeconds", pre.sampling},
                                     {"partitioningSeconds", pre.partitioning},
                                     {"pruningSeconds", pre.pruning},
                                     {"mappingSeconds", pre.mapping},
                                     {"transferSeconds", pre.transfer},
                                     {"setupMessages", pre.messages},
                                     {"setupBytes", pre.bytes},
                                     {"work",
                                      {{"sampledRays", work.sampling.processed.totalRays()},
                                       {"samplingTests", work.sampling.processed.intersectionTests},
                                       {"samplingBoxTests", work.sampling.processed.boxTests},
                                       {"piecesWeighed", work.piecesWeighed},
                                       {"regionTests", work.regionTests},
                                       {"mappingSteps", work.mappingSteps}}}};
  return {{"platform", run.platform},
          {"makespanSeconds", run.makespan},
          {"preprocessingSeconds", pre.seconds},
          {"endToEndSeconds", run.endToEnd()},
          {"preprocessing", preprocessing},
          {"rayMessages", run.rayMessages},
          {"blockedShare", blockedShare(report)},
          {"blockedShareByTenth", blockedShareByTenth(report)},
          {"wallSeconds", run.wallSeconds},
          {"tokenRounds", report.tokenRounds},
          {"processors", processors},
          {"links", links}};
}

void writeChromeTrace(const MachineReport& report, const std::filesystem::path& path) {
  const EmulatedRun& run = simulatedOf(report);
  std::ofstream out(path);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the trace", path.string()));
  out << "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n";
  bool first = true;
  for (const ProcessorReport& p : report.processors) {
    out << (first ? "" : ",\n")
        << fmt::format(
               R"({{"name":"thread_name","ph":"M","pid":0,"tid":{},"args":{{"name":"processor {}"}}}})",
               p.node.id, p.node.id);
    first = false;
  }
  for (const StateInterval& i : run.timeline)
    out << fmt::format(
        ",\n{{\"name\":\"{}\",\"ph\":\"X\",\"pid\":0,\"tid\":{},\"ts\":{:.3f},\"dur\":{:.3f}}}",
        stateName(i.state), i.processor, i.start * 1e6, (i.end - i.start) * 1e6);
  out << "\n]}\n";
}

TimelineChart timelineChart(const MachineReport& report, const std::string& caption) {
  const EmulatedRun& run = simulatedOf(report);
  TimelineChart chart;
  chart.title = fmt::format("Processor states over simulated time ({})", run.platform);
  chart.caption = caption;
  chart.time.label = "simulated time (s)";
  // In ProcessorState's order; forwarding, on the same CPU as the rest, is drawn over them.
  const bool locks = fifoFullFor(report.settings) == node::FifoFull::Lock;
  chart.states = {stateName(ProcessorState::Computing),
                  locks ? "locked (full FIFO)" : "blocked (rays waiting for room)",
                  stateName(ProcessorState::Idle), stateName(ProcessorState::Forwarding)};
  for (const ProcessorReport& p : report.processors)
    chart.rows.push_back({fmt::format("P{}", p.node.id), {}});
  for (const StateInterval& i : run.timeline)
    chart.rows[i.processor].intervals.push_back({i.start, i.end, std::size_t(i.state)});
  return chart;
}

}  // namespace raycube::host
