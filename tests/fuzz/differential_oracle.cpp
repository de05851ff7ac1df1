#include "tests/fuzz/differential_oracle.h"

#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>
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
  };
  const Machine machines[] = {
      {"machine uniform 2x2, FIFO 1, light pyramids", 2, 2, host::Balance::Uniform, 1,
       node::LightRayMode::Pyramid},
      {"machine bsp 1x3, FIFO 128, light cones", 1, 3, host::Balance::Bsp, 128, node::LightRayMode::Cone},
      {"machine uniform 3x1, FIFO 2, light-ray messages", 3, 1, host::Balance::Uniform, 2,
       node::LightRayMode::Messages},
  };
  for (const Machine& m : machines) {
    host::MachineSettings machine;
    machine.rows = std::min(m.rows, settings.height);
    machine.columns = std::min(m.columns, settings.width);
    machine.balance = m.balance;
    machine.queueCapacity = m.capacity;
    machine.lightRays = m.lightRays;
    machine.subsampleWindow = 2;
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

// The render's image, or the message of the std::invalid_argument it refused the scene with.
struct Outcome {
  std::optional<core::Image> image;
  std::string refusal;
};

Outcome run(const Mode& mode, const core::Scene& scene, const host::RenderSettings& settings) {
  try {
    return Outcome{mode.render(scene, settings).image, ""};
  } catch (const std::invalid_argument& e) {
    return Outcome{std::nullopt, e.what()};
  }
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
    for (const Mode& mode : modes) {
      const Outcome got = run(mode, scene, settings);
      const std::string label = fmt::format("{} ({})", mode.name, core::nameOf(precision));
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
