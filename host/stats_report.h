#pragma once
// The final summary on stdout and the same numbers as JSON (--stats).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/scene.h"
#include "host/render_result.h"

namespace raycube::host {

std::string summaryText(const core::Scene& scene, const RenderResult& result);
nlohmann::json statsJson(const core::Scene& scene, const RenderResult& result);
void writeJson(const nlohmann::json& json, const std::filesystem::path& path);

}  // namespace raycube::host
