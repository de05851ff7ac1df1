#pragma once
// What travels between the host and a node's address space (Priol & Bouatouch 3.2 steps 1-2: the host
// sends each processor its setup, holding the only objects it needs, its RegionDatabase), as bytes: the
// one place where setups, context and reports are serialised. The MPI engine sends a job to each rank
// (the shared context and the setups of its processors) and gets reports back.
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/precision.h"
#include "host/machine.h"
#include "node/logical_processor.h"

namespace raycube::host {

// Bytes in the machine's own layout: every rank runs the same binary on the same kind of host.
class WireWriter {
 public:
  void bytes(const void* data, std::size_t n) {
    if (n == 0) return;  // data may be null (an empty vector's)
    const char* p = static_cast<const char*>(data);
    out_.insert(out_.end(), p, p + n);
  }
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof v);
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(std::uint64_t(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
  void string(const std::string& s) { vector(std::vector<char>(s.begin(), s.end())); }
  std::vector<char> take() { return std::move(out_); }

 private:
  std::vector<char> out_;
};

class WireReader {
 public:
  explicit WireReader(std::span<const char> in) : in_(in) {}
  void bytes(void* data, std::size_t n) {
    if (n > in_.size() - at_) throw std::runtime_error("a message between ranks was cut short");
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy must not see
    std::memcpy(data, in_.data() + at_, n);
    at_ += n;
  }
  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    std::array<char, sizeof(T)> raw;  // T need not be default-constructible (core::View)
    bytes(raw.data(), raw.size());
    return std::bit_cast<T>(raw);
  }
  template <class T>
  std::vector<T> vector() {
    const auto n = value<std::uint64_t>();
    if (n > (in_.size() - at_) / std::max<std::size_t>(1, sizeof(T)))
      throw std::runtime_error("a message between ranks was cut short");
    std::vector<T> v(n);
    bytes(v.data(), n * sizeof(T));
    return v;
  }
  std::string string() {
    const auto chars = vector<char>();
    return std::string(chars.begin(), chars.end());
  }

 private:
  std::span<const char> in_;
  std::size_t at_ = 0;
};

// How a rank runs its share of a render.
struct JobSettings {
  core::Precision precision = core::Precision::Double;
  std::uint64_t queueCapacity = 128;
  std::uint64_t rayBatch = 16;
  unsigned jitterSeed = 0;
  std::vector<int> rankOf;  // per processor: the rank that runs it
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

}  // namespace raycube::host
