#include "host/engines/mpi/mpi_session.h"

#include <mpi.h>
#include <sched.h>
#include <sys/sysinfo.h>

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

// Open MPI binds each rank to one core when it starts 2 processes or fewer (to a socket beyond): with
// `mpirun -np 2`, rank 1 would run every processor thread and its communication thread on one core of the
// machine, and the host on the other. raycube's ranks run several threads each, so a binding Open MPI chose
// by itself is undone (as `--bind-to none` does); one the user asked for (`--bind-to ...`, which Open MPI
// passes on as OMPI_MCA_hwloc_base_binding_policy) is kept.
void undoDefaultBinding() {
  if (std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr ||
      std::getenv("OMPI_MCA_hwloc_base_binding_policy") != nullptr)
    return;
  cpu_set_t every;
  CPU_ZERO(&every);
  for (int cpu = 0; cpu < get_nprocs_conf() && cpu < CPU_SETSIZE; ++cpu) CPU_SET(cpu, &every);
  sched_setaffinity(0, sizeof(every),
                    &every);  // the kernel keeps what a cgroup allows; failing, the binding stays
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
  undoDefaultBinding();
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
