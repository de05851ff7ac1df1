#pragma once
// `raycube ... --transport mpi` under mpirun: MPI is started before the command line runs; rank 0 runs the
// command line (the host) with the MPI engine at hand, the other ranks serve the renders it sends.
#include <functional>

#include "queues/interconnects/mpi_link.h"

namespace raycube::host {

// Starts MPI, runs hostMain on rank 0 and the processors' service on the others, stops MPI; returns this
// rank's exit status. Outside an MPI launcher, or with one rank, says so and returns 2 without hanging.
int runUnderMpi(int argc, char** argv, const std::function<int()>& hostMain);

// Rank 0's link to the other ranks while hostMain runs; null otherwise.
queues::MpiLink* hostMpiLink();

}  // namespace raycube::host
