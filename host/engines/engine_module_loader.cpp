#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>

#include "host/engines/engine_module.h"

namespace raycube::host {
namespace {

const EngineModule* gEngines = nullptr;  // constant-initialised: safe to set from static initialisers

constexpr const char* kModuleName = "raycube_engines.so";

// Where the module may be: RAYCUBE_ENGINES if set; beside the program (the build tree); <prefix>/lib/raycube
// for a program installed in <prefix>/bin.
std::vector<std::filesystem::path> moduleCandidates() {
  if (const char* path = std::getenv("RAYCUBE_ENGINES"); path != nullptr && *path != '\0') return {path};
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {kModuleName};
  const std::filesystem::path dir = self.parent_path();
  return {dir / kModuleName, dir.parent_path() / "lib" / "raycube" / kModuleName};
}

void loadModule() {
  std::string failures;
  for (const std::filesystem::path& path : moduleCandidates()) {
    // RTLD_NOW: a symbol the module misses fails here, not in the middle of a render. Its static
    // initialiser provides the engines.
    if (dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL) != nullptr && gEngines != nullptr) return;
    const char* why = dlerror();
    failures +=
        "; " + (why != nullptr ? std::string(why) : path.string() + ": loaded, but provides no engines");
  }
  throw std::runtime_error(
      "the SimGrid and MPI engines (" + std::string(kModuleName) +
      ") could not be loaded: build the target raycube_engines, or set RAYCUBE_ENGINES to "
      "its path" +
      failures);
}

}  // namespace

void provideEngineModule(const EngineModule& engines) {
  gEngines = &engines;
}

const EngineModule& engineModule() {
  static std::mutex loading;
  const std::lock_guard lock(loading);
  if (gEngines == nullptr) loadModule();
  return *gEngines;
}

bool hostsMpiRanks() {
  return gEngines != nullptr && gEngines->hostsMpiRanks();
}

bool asksForMpi(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--transport=mpi") == 0) return true;
    if (std::strcmp(argv[i], "--transport") == 0 && i + 1 < argc && std::strcmp(argv[i + 1], "mpi") == 0)
      return true;
  }
  return false;
}

}  // namespace raycube::host
