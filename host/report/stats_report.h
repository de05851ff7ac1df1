#pragma once
// The final summary on stdout and the same numbers as JSON (--stats).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/scene.h"
#include "host/machine/render_result.h"
#include "host/machine/render_settings.h"

namespace raycube::host {

// One line naming the scene and the settings a picture came from (the caption of every chart).
std::string runCaption(const core::Scene& scene, const RenderSettings& settings, const RenderResult& result);
std::string summaryText(const core::Scene& scene, const RenderResult& result);
nlohmann::json statsJson(const core::Scene& scene, const RenderResult& result);
void writeJson(const nlohmann::json& json, const std::filesystem::path& path);

}  // namespace raycube::host
