#pragma once
// What travels between the host and a node's address space (Priol & Bouatouch 3.2 steps 1-2: the host
// sends each processor its setup, holding the only objects it needs, its RegionDatabase), as bytes: the
// one place where setups, context and reports are serialised. The MPI engine sends a job to each rank
// (the shared context and the setups of its processors) and gets reports back; the simulation's child
// process sends its reports and emulated run back through a pipe.
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/precision.h"
#include "host/engines/wire_codec.h"
#include "host/machine/machine_engine.h"
#include "host/machine/machine_report.h"
#include "node/logical_processor.h"

namespace raycube::host {

// A message being written, in memory.
struct ByteBuffer {
  std::vector<char> bytes;
  void write(const char* data, std::size_t n) { bytes.insert(bytes.end(), data, data + n); }
};

class WireWriter : public WireEncoder<ByteBuffer> {
 public:
  std::vector<char> take() { return std::move(sink().bytes); }
};

// A message received, read in order.
class ByteSpan {
 public:
  explicit ByteSpan(std::span<const char> in) : in_(in) {}
  void read(char* data, std::size_t n) {
    expect(n);
    std::memcpy(data, in_.data() + at_, n);
    at_ += n;
  }
  void expect(std::size_t n) const {
    if (n > in_.size() - at_) throw std::runtime_error("a message between ranks was cut short");
  }

 private:
  std::span<const char> in_;
  std::size_t at_ = 0;
};

using WireReader = WireDecoder<ByteSpan>;

// How a rank runs its share of a render.
struct JobSettings {
  core::Precision precision = core::Precision::Double;
  std::uint64_t queueCapacity = 128;
  std::uint64_t rayBatch = 16;
  unsigned jitterSeed = 0;
  std::int64_t stallPeriodMs = 120000;  // MachineSettings::stallPeriod, for each rank's watchdog
  bool stallAStep = false;              // MachineSettings::stallAStepForTests
  bool loseTheToken = false;            // MachineSettings::loseTheTokenForTests
  std::vector<int> rankOf;              // per processor: the rank that runs it
};

// One rank's share of a render: the settings, the shared context, and the setups of its processors only.
struct MachineJob {
  JobSettings settings;
  node::MachineContext context;
  std::vector<node::NodeSetup> setups;  // of this rank's processors, in increasing id
};

std::vector<char> encodeJob(const JobSettings& settings, const node::MachineContext& context,
                            std::span<const node::NodeSetup> setups);
MachineJob decodeJob(std::span<const char> bytes);

// What a rank sends back when the machine has terminated.
struct RankResults {
  RankReport rank;
  std::vector<ProcessorReport> processors;
};
std::vector<char> encodeResults(const RankResults& results);
RankResults decodeResults(std::span<const char> bytes);

// What the simulation sends back when its machine has terminated or deadlocked
// (host/engines/simgrid/emulated_machine.cpp), over its pipe: the processors' reports, the emulated run and
// the deadlock, if any.
template <class Sink>
void writeEmulatedResults(WireEncoder<Sink>& out, const std::vector<ProcessorReport>& processors,
                          const EmulatedRun& run, const std::optional<Deadlock>& deadlock) {
  static_assert(std::is_trivially_copyable_v<ProcessorReport>);
  out.vector(processors);
  out.string(run.platform);
  out.value(run.makespan);
  out.value(run.nodeSpeed);
  out.value(run.rayMessages);
  out.value(run.wallSeconds);
  out.vector(run.links);
  out.vector(run.timeline);
  out.value(deadlock.has_value());
  if (deadlock) {
    out.vector(deadlock->cycle);
    out.value(deadlock->simulatedSeconds);
  }
}

template <class Source>
MachineRun readEmulatedResults(WireDecoder<Source>& in) {
  MachineRun machine;
  machine.processors = in.template vector<ProcessorReport>();
  EmulatedRun run;
  run.platform = in.string();
  run.makespan = in.template value<double>();
  run.nodeSpeed = in.template value<double>();
  run.rayMessages = in.template value<std::uint64_t>();
  run.wallSeconds = in.template value<double>();
  run.links = in.template vector<LinkTraffic>();
  run.timeline = in.template vector<StateInterval>();
  machine.emulated = std::move(run);
  if (in.template value<bool>()) {
    machine.deadlock.emplace();
    machine.deadlock->cycle = in.template vector<LockedFifo>();
    machine.deadlock->simulatedSeconds = in.template value<double>();
  }
  return machine;
}

}  // namespace raycube::host
