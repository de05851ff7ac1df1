#include "tests/fuzz/differential_oracle.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/image.h"
#include "core/nff_reader.h"
#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"

namespace raycube::fuzz {
namespace {

// Small enough for thousands of inputs a minute, large enough for every mode's machinery (regions, BSP,
// light volumes, reflections) to take part.
constexpr int kMaxSide = 8;
constexpr int kDepth = 3;

// The machine's own watchdog, short: a render of at most 8x8 takes milliseconds. A stall is an error the
// oracle reports; a hang the machine cannot report (a step that never returns) is the HangWatch's.
constexpr std::chrono::milliseconds kStallPeriod{5000};

// The per-render time limit (RAYCUBE_ORACLE_SECONDS, default 30): a render still running then hangs. It
// cannot be returned from, so the watch names it and aborts: libFuzzer keeps the input as a crash, ctest
// fails, neither waits forever.
class HangWatch {
 public:
  static HangWatch& instance() {
    static HangWatch watch;
    return watch;
  }
  void start(const std::string& label) {
    {
      const std::lock_guard lock(mutex_);
      label_ = label;
    }
    deadline_.store((std::chrono::steady_clock::now() + limit_).time_since_epoch().count());
  }
  void stop() { deadline_.store(0); }

 private:
  HangWatch() : limit_(limitFromEnvironment()) {
    std::thread([this] { watch(); }).detach();
  }
  static std::chrono::seconds limitFromEnvironment() {
    const char* value = std::getenv("RAYCUBE_ORACLE_SECONDS");
    return std::chrono::seconds(value != nullptr && std::atoi(value) > 0 ? std::atoi(value) : 30);
  }
  [[noreturn]] void watch() {
    for (;;) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      const auto deadline = deadline_.load();
      if (deadline == 0 || std::chrono::steady_clock::now().time_since_epoch().count() < deadline) continue;
      const std::lock_guard lock(mutex_);
      std::fprintf(stderr, "ORACLE: HANG: %s still running after %lld s\n", label_.c_str(),
                   static_cast<long long>(limit_.count()));
      std::fflush(stderr);
      std::abort();
    }
  }
  const std::chrono::seconds limit_;
  std::atomic<std::chrono::steady_clock::rep> deadline_{0};
  std::mutex mutex_;
  std::string label_;
};

struct Mode {
  std::string name;
  std::function<host::RenderResult(const core::Scene&, const host::RenderSettings&)> render;
};

std::vector<Mode> modesFor(const host::RenderSettings& settings) {
  std::vector<Mode> modes{{"image-parallel", [](const core::Scene& s, const host::RenderSettings& r) {
                             host::RenderSettings twoThreads = r;
                             twoThreads.threads = 2;
                             return host::renderImageParallel(s, twoThreads);
                           }}};
  struct Machine {
    const char* name;
    int rows, columns;
    host::Balance balance;
    std::size_t capacity;
    node::LightRayMode lightRays;
    node::CellStructure cells;
  };
  // Threads at 2x2 (a region's BVH and the paper's cells) and a BSP with light rays as messages, besides
  // strips, tiny FIFOs and every light-ray mode (issue 41).
  const Machine machines[] = {
      {"machine uniform 2x2, FIFO 1, light pyramids", 2, 2, host::Balance::Uniform, 1,
       node::LightRayMode::Pyramid, node::CellStructure::Auto},
      {"machine uniform 2x2, paper cells", 2, 2, host::Balance::Uniform, 512, node::LightRayMode::Pyramid,
       node::CellStructure::Paper},
      {"machine bsp 2x2, FIFO 4, light-ray messages", 2, 2, host::Balance::Bsp, 4,
       node::LightRayMode::Messages, node::CellStructure::Auto},
      {"machine bsp 1x3, FIFO 128, light cones", 1, 3, host::Balance::Bsp, 128, node::LightRayMode::Cone,
       node::CellStructure::Auto},
      {"machine uniform 3x1, FIFO 2, light-ray messages", 3, 1, host::Balance::Uniform, 2,
       node::LightRayMode::Messages, node::CellStructure::Auto},
  };
  for (const Machine& m : machines) {
    host::MachineSettings machine;
    machine.rows = std::min(m.rows, settings.height);
    machine.columns = std::min(m.columns, settings.width);
    machine.balance = m.balance;
    machine.queueCapacity = m.capacity;
    machine.lightRays = m.lightRays;
    machine.cells = m.cells;
    machine.subsampleWindow = 2;
    machine.stallPeriod = kStallPeriod;
    modes.push_back({m.name, [machine](const core::Scene& s, const host::RenderSettings& r) {
                       return host::renderMachine(s, r, machine);
                     }});
  }
  return modes;
}

// "source:line:column: message" with both positions positive.
std::string checkParseError(const core::SceneError& e, std::string_view source) {
  const std::string prefix = fmt::format("{}:{}:{}: ", source, e.line(), e.column());
  if (e.line() < 1 || e.column() < 1 || std::string_view(e.what()).substr(0, prefix.size()) != prefix)
    return fmt::format("parse error without source:line:column: {}", e.what());
  return "";
}

// The render's image, or the message of the std::invalid_argument it refused the scene with, or of any
// other error it ended with (a stalled machine's).
struct Outcome {
  std::optional<core::Image> image;
  std::string refusal;
  std::string error;
};

Outcome run(const Mode& mode, const core::Scene& scene, const host::RenderSettings& settings) {
  HangWatch::instance().start(fmt::format("{} ({})", mode.name, core::nameOf(settings.precision)));
  Outcome outcome;
  try {
    outcome.image = mode.render(scene, settings).image;
  } catch (const std::invalid_argument& e) {
    outcome.refusal = e.what();
  } catch (const std::exception& e) {
    outcome.error = e.what();
  }
  HangWatch::instance().stop();
  return outcome;
}

}  // namespace

std::string checkInput(std::string_view text, std::string_view source) {
  core::Scene scene;
  try {
    scene = core::parseNff(text, source);
  } catch (const core::SceneError& e) {
    return checkParseError(e, source);
  }
  host::RenderSettings settings;
  settings.width = std::min(scene.camera.width, kMaxSide);
  settings.height = std::min(scene.camera.height, kMaxSide);
  settings.shading.maxDepth = kDepth;
  settings.progress = false;
  const std::vector<Mode> modes = modesFor(settings);
  for (const core::Precision precision : {core::Precision::Double, core::Precision::Float}) {
    settings.precision = precision;
    const Mode reference{"reference", host::renderReference};
    const Outcome expected = run(reference, scene, settings);
    if (!expected.error.empty())
      return fmt::format("reference ({}): {}", core::nameOf(precision), expected.error);
    for (const Mode& mode : modes) {
      const Outcome got = run(mode, scene, settings);
      const std::string label = fmt::format("{} ({})", mode.name, core::nameOf(precision));
      if (!got.error.empty()) return fmt::format("{}: {}", label, got.error);
      if (expected.image.has_value() != got.image.has_value())
        return fmt::format("{}: {} where the reference {}", label,
                           got.image ? "rendered" : "refused the scene (" + got.refusal + ")",
                           expected.image ? "rendered" : "refused it (" + expected.refusal + ")");
      if (got.image && !core::bitIdentical(*got.image, *expected.image)) {
        const core::ImageDifference d = core::compareImages(*got.image, *expected.image);
        return fmt::format("{}: image differs from the reference (max {:.3g}, {} pixels over 1/255)", label,
                           d.maxAbs, d.pixelsOver);
      }
    }
  }
  return "";
}

}  // namespace raycube::fuzz
