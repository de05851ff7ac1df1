#include "queues/interconnects/mpi_link.h"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

namespace raycube::queues {
namespace {

// The tag: the packet's kind and its render's number (modulo a bound every MPI offers: 32767).
constexpr std::uint32_t kJobsInTags = 32767 / kPacketKinds;
int tagOf(Packet kind, std::uint32_t job) {
  return int(kind) + kPacketKinds * int(job % kJobsInTags);
}

}  // namespace

struct MpiLink::Pending {
  MPI_Request request;
  std::vector<char> bytes;
};

MpiLink::MpiLink() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiLink::~MpiLink() = default;

void MpiLink::post(int to, Packet kind, std::vector<char> bytes) {
  if (bytes.size() > std::size_t(INT32_MAX))
    throw std::runtime_error("a packet over 2 GB cannot travel between ranks");
  ++traffic_.messagesSent;
  traffic_.bytesSent += bytes.size();
  pending_.push_back(Pending{MPI_REQUEST_NULL, std::move(bytes)});
  Pending& p = pending_.back();
  MPI_Isend(p.bytes.data(), int(p.bytes.size()), MPI_BYTE, to, tagOf(kind, job_), MPI_COMM_WORLD, &p.request);
}

std::size_t MpiLink::poll(const OnPacket& onPacket, std::size_t limit) {
  std::size_t handled = 0;
  while (handled < limit) {
    int arrived = 0;
    MPI_Message message;
    MPI_Status status;
    MPI_Improbe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &message, &status);
    if (!arrived) break;
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    inbox_.resize(std::size_t(count));
    MPI_Mrecv(inbox_.data(), count, MPI_BYTE, &message, MPI_STATUS_IGNORE);
    ++traffic_.messagesReceived;
    traffic_.bytesReceived += std::size_t(count);
    const auto kind = Packet(status.MPI_TAG % kPacketKinds);
    const auto job = std::uint32_t(status.MPI_TAG / kPacketKinds);
    if (kind == Packet::Job) job_ = job;
    const bool current = job == job_ % kJobsInTags;
    if (current || kind == Packet::Job || kind == Packet::Quit)
      onPacket(status.MPI_SOURCE, kind, std::span<const char>(inbox_.data(), inbox_.size()));
    ++handled;
  }
  return handled;
}

bool MpiLink::progressSends() {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    int done = 0;
    MPI_Test(&pending_[i].request, &done, MPI_STATUS_IGNORE);
    if (!done) {
      if (kept != i) pending_[kept] = std::move(pending_[i]);
      ++kept;
    }
  }
  pending_.resize(kept);
  return pending_.empty();
}

void MpiLink::abort(const std::string& cause) const {
  std::fprintf(stderr, "raycube: rank %d of %d: %s\n", rank_, size_, cause.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::abort();
}

void MpiLink::flushSends() {
  while (!progressSends()) std::this_thread::yield();
}

}  // namespace raycube::queues
