#pragma once
// A rank's connection to the others over MPI (MPI_COMM_WORLD): packets of bytes, each with its kind and the
// number of the render it belongs to in the MPI tag. Sends never wait (MPI_Isend, the buffer kept until
// MPI_Test says it left); receives take whatever has arrived (MPI_Improbe, MPI_Mrecv). Only one thread
// of a rank calls it at a time: MPI runs in MPI_THREAD_SERIALIZED.
#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace raycube::queues {

enum class Packet : std::uint8_t {
  Job,        // host -> rank: settings, context and setups of its processors (host/engines/machine_wire.h)
  Ready,      // rank -> host: its processors have subdivided their regions
  Start,      // host -> rank: the synthesis phase begins
  Rays,       // rank -> rank: a batch of rays, each for one directed edge between processors
  Credits,    // rank -> rank: room freed in FIFOs, per directed edge
  Token,      // rank -> rank: Safra's token for a processor
  Terminate,  // rank -> rank: processor 0 has proved termination
  Contributions,  // rank -> host: a block of contributions
  Progress,       // rank -> host: ray segments evaluated so far by each of its processors
  Results,        // rank -> host: its reports, once its processors have stopped
  Quit,           // host -> rank: no more renders; the host's exit status
};
inline constexpr int kPacketKinds = 11;

struct MpiTraffic {
  std::uint64_t messagesSent = 0, bytesSent = 0, messagesReceived = 0, bytesReceived = 0;
};

class MpiLink {
 public:
  // MPI must be initialised (MPI_THREAD_SERIALIZED or better).
  MpiLink();
  ~MpiLink();
  MpiLink(const MpiLink&) = delete;
  MpiLink& operator=(const MpiLink&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  // Packets of other renders are dropped (a credit can still be on its way when a render ends), except Job
  // and Quit, which start the next one (a rank adopts its number) or end the session.
  void setJob(std::uint32_t job) { job_ = job; }
  std::uint32_t job() const { return job_; }

  void post(int to, Packet kind, std::vector<char> bytes);
  template <class T>
  void postValue(int to, Packet kind, const T& value) {
    const char* p = reinterpret_cast<const char*>(&value);
    post(to, kind, std::vector<char>(p, p + sizeof value));
  }
  // Hands packets that have arrived to onPacket (at most `limit`); returns how many.
  using OnPacket = std::function<void(int from, Packet kind, std::span<const char> bytes)>;
  std::size_t poll(const OnPacket& onPacket, std::size_t limit = 64);
  // Completes the sends that have left; true when none is pending.
  bool progressSends();
  // Waits (polling MPI) until every send has left.
  void flushSends();

  const MpiTraffic& traffic() const { return traffic_; }

  // Says which rank failed and why on stderr, then ends every rank of the job (MPI_Abort).
  [[noreturn]] void abort(const std::string& cause) const;

 private:
  int rank_ = 0, size_ = 1;
  std::uint32_t job_ = 0;
  struct Pending;
  std::vector<Pending> pending_;
  std::vector<char> inbox_;
  MpiTraffic traffic_;
};

// One processor's progress, as a Progress packet carries it (an array of these). Under the paper's flow
// control (node::FifoFull::Lock) also what the host needs to prove a deadlock: whom the processor is locked
// on, the rays in that FIFO (or in flight towards that neighbour), and its steps that did something.
struct ProcessorProgress {
  std::uint32_t processor = 0;
  std::int32_t lockedOn = -1;  // a processor, or -1
  std::uint64_t segmentsEvaluated = 0;
  std::uint64_t stepsWorked = 0;
  std::uint64_t lockedRays = 0;
  bool operator==(const ProcessorProgress&) const = default;
};

// Calls each(entry) for every T of a packet's body (an array of T as bytes).
template <class T, class Each>
void forEachEntry(std::span<const char> bytes, Each&& each) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (bytes.size() % sizeof(T) != 0) throw std::runtime_error("a packet between ranks has a broken length");
  for (std::size_t at = 0; at < bytes.size(); at += sizeof(T)) {
    T entry;
    std::memcpy(&entry, bytes.data() + at, sizeof(T));
    each(entry);
  }
}

template <class T>
T packetValue(std::span<const char> bytes) {
  T value{};
  forEachEntry<T>(bytes, [&](const T& v) { value = v; });
  return value;
}

}  // namespace raycube::queues
