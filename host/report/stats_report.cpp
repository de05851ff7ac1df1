#include "host/report/stats_report.h"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace raycube::host {
namespace {

double megaRaysPerSecond(const RenderResult& r) {
  return r.traceSeconds > 0 ? double(r.counters.totalRays()) / r.traceSeconds / 1e6 : 0.0;
}

}  // namespace

std::string runCaption(const core::Scene& scene, const RenderSettings& settings, const RenderResult& result) {
  return fmt::format("{}, {}x{}, {} ({} workers), depth {}, spp {}, min-weight {:g}, {}", scene.name,
                     result.image.width, result.image.height, result.mode, result.workers,
                     settings.shading.maxDepth, settings.shading.raysPerSample, settings.shading.minWeight,
                     nameOf(result.precision));
}

std::string summaryText(const core::Scene& scene, const RenderResult& result) {
  const core::TraceCounters& c = result.counters;
  std::string text = fmt::format("scene {} ({} objects, {} lights), {}x{}, mode {} ({} workers), {} rays\n",
                                 scene.name, scene.objects.size(), scene.lights.size(), result.image.width,
                                 result.image.height, result.mode, result.workers, nameOf(result.precision));
  text += fmt::format("  preprocessing {:.3f} s, tracing {:.3f} s\n", result.preprocessSeconds,
                      result.traceSeconds);
  text += fmt::format("  rays: eye {}, reflected {}, refracted {}, light {}, total {}\n",
                      c.of(core::RayKind::Eye), c.of(core::RayKind::Reflected),
                      c.of(core::RayKind::Refracted), c.of(core::RayKind::Light), c.totalRays());
  text += fmt::format("  intersection tests {}, box tests {}, {:.2f} Mrays/s\n", c.intersectionTests,
                      c.boxTests, megaRaysPerSecond(result));
  if (c.nonFinite > 0) text += fmt::format("  WARNING: {} contributions were NaN or infinite\n", c.nonFinite);
  return text;
}

nlohmann::json statsJson(const core::Scene& scene, const RenderResult& result) {
  const core::TraceCounters& c = result.counters;
  nlohmann::json rays;
  for (int k = 0; k < core::kRayKinds; ++k) rays[core::rayKindName(core::RayKind(k))] = c.rays[k];
  return nlohmann::json{
      {"scene",
       {{"name", scene.name},
        {"objects", scene.objects.size()},
        {"lights", scene.lights.size()},
        {"warnings", scene.warnings}}},
      {"image", {{"width", result.image.width}, {"height", result.image.height}}},
      {"mode", result.mode},
      {"workers", result.workers},
      {"precision", nameOf(result.precision)},
      {"seconds", {{"preprocessing", result.preprocessSeconds}, {"tracing", result.traceSeconds}}},
      {"rays", rays},
      {"totalRays", c.totalRays()},
      {"intersectionTests", c.intersectionTests},
      {"boxTests", c.boxTests},
      {"contributions", c.contributions},
      {"nonFiniteContributions", c.nonFinite},
      {"megaRaysPerSecond", megaRaysPerSecond(result)},
  };
}

void writeJson(const nlohmann::json& json, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write stats file " + path.string());
  out << json.dump(2) << '\n';
  if (!out) throw std::runtime_error("failed writing stats file " + path.string());
}

}  // namespace raycube::host
