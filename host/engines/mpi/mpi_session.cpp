#include "host/engines/mpi/mpi_session.h"

#include <mpi.h>

#include <cstdlib>
#include <iostream>
#include <string>

#include "host/engines/mpi/mpi_machine.h"

namespace raycube::host {
namespace {

queues::MpiLink* gHostLink = nullptr;

// Variables every common launcher sets in its processes (Open MPI's mpirun, PMIx, MPICH's hydra, srun).
bool startedByLauncher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

constexpr const char* kUsage =
    "mpirun -np N raycube render ... --transport mpi, with N >= 2: rank 0 is the host, ranks 1..N-1 run the "
    "logical processors";

int serveAsHost(queues::MpiLink& link, const std::function<int()>& hostMain) {
  gHostLink = &link;
  int status = 1;
  try {
    status = hostMain();
  } catch (const std::exception& e) {
    std::cerr << "raycube: rank 0 (host): " + std::string(e.what()) + "\n";
  }
  gHostLink = nullptr;
  for (int r = 1; r < link.size(); ++r) link.postValue(r, queues::Packet::Quit, status);
  link.flushSends();
  return status;
}

int serveAsNodes(queues::MpiLink& link) {
  try {
    const int status = serveMachineJobs(link);
    if (status != 0)
      std::cerr << "raycube: rank " + std::to_string(link.rank()) +
                       ": stopping: the host (rank 0) failed with exit status " + std::to_string(status) +
                       "\n";
    return status;
  } catch (const std::exception& e) {
    link.abort(e.what());
  }
}

}  // namespace

queues::MpiLink* hostMpiLink() {
  return gHostLink;
}

int runUnderMpi(int argc, char** argv, const std::function<int()>& hostMain) {
  if (!startedByLauncher()) {
    std::cerr << "raycube: --transport mpi needs an MPI launcher: " << kUsage << "\n";
    return 2;
  }
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  int status = 2;
  {
    queues::MpiLink link;
    if (provided < MPI_THREAD_SERIALIZED) {
      if (link.rank() == 0) std::cerr << "raycube: this MPI library does not offer MPI_THREAD_SERIALIZED\n";
    } else if (link.size() < 2) {
      std::cerr << "raycube: --transport mpi got 1 rank: " << kUsage << "\n";
    } else {
      status = link.rank() == 0 ? serveAsHost(link, hostMain) : serveAsNodes(link);
    }
  }
  MPI_Finalize();
  return status;
}

}  // namespace raycube::host
