#pragma once
// What a run over MPI reports (the MPI engine): per rank, the processors and objects it held, its peak
// memory, and the MPI messages and bytes it sent and received.
#include <nlohmann/json.hpp>
#include <string>

#include "host/machine/machine_report.h"

namespace raycube::host {

std::string mpiTable(const MachineReport& report);
nlohmann::json mpiJson(const MachineReport& report);

}  // namespace raycube::host
