#include "host/studies/tradeoff.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "host/render/render_machine.h"
#include "host/render/sequential_renderers.h"
#include "host/report/machine_stats.h"

namespace raycube::host {
namespace {

struct Setting {
  const char* knob;
  std::string value;
  RenderSettings settings;
};

// Each knob swept from cheap to accurate, the others at the SPD defaults (depth 5, 1 ray, no cut-off,
// double).
std::vector<Setting> sweeps(const RenderSettings& base) {
  std::vector<Setting> s;
  for (int depth : {1, 2, 3, 4, 5, 8}) {
    RenderSettings r = base;
    r.shading.maxDepth = depth;
    s.push_back({"depth", std::to_string(depth), r});
  }
  for (double w : {0.5, 0.2, 0.1, 0.05, 0.02, 0.0}) {
    RenderSettings r = base;
    r.shading.minWeight = w;
    s.push_back({"min-weight", fmt::format("{:g}", w), r});
  }
  for (int spp : {1, 4, 9, 16}) {
    RenderSettings r = base;
    r.shading.raysPerSample = spp;
    s.push_back({"spp", std::to_string(spp), r});
  }
  for (core::Precision p : {core::Precision::Float, core::Precision::Double}) {
    RenderSettings r = base;
    r.precision = p;
    s.push_back({"precision", core::nameOf(p), r});
  }
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

std::vector<TradeoffRow> measureTradeoff(const core::Scene& scene, const RenderSettings& base,
                                         const TradeoffOptions& options,
                                         const std::function<void(const TradeoffRow&)>& progress) {
  RenderSettings converged = base;
  converged.shading.maxDepth = options.referenceDepth;
  converged.shading.raysPerSample = options.referenceRaysPerSample;
  converged.shading.minWeight = 0;
  converged.precision = core::Precision::Double;
  const core::Image reference = renderImageParallel(scene, converged).image;
  std::vector<TradeoffRow> rows;
  RenderSettings defaults = base;
  defaults.shading = core::ShadingOptions{};
  defaults.precision = core::Precision::Double;
  for (const Setting& s : sweeps(defaults)) {
    TradeoffRow row;
    row.knob = s.knob;
    row.setting = s.value;
    std::vector<double> times;
    for (int run = 0; run < std::max(1, options.runs); ++run) {
      const RenderResult r = renderImageParallel(scene, s.settings);
      times.push_back(r.preprocessSeconds + r.traceSeconds);
      if (run == 0) {
        row.counters = r.counters;
        const core::ImageDifference d = core::compareImages(r.image, reference);
        row.rmse = d.rmse;
        row.psnr = d.psnr;
        row.maxAbs = d.maxAbs;
      }
    }
    row.seconds = median(times);
    if (progress) progress(row);
    rows.push_back(row);
  }
  return rows;
}

std::string tradeoffTable(const std::vector<TradeoffRow>& rows) {
  std::string text =
      "knob        setting   seconds      eye   reflected  refracted      light       rmse   psnr dB    max "
      "err\n";
  for (const TradeoffRow& r : rows)
    text += fmt::format("{:<11} {:>7} {:>9.4f} {:>8} {:>11} {:>10} {:>10} {:>10.3g} {:>9.2f} {:>10.3g}\n",
                        r.knob, r.setting, r.seconds, r.counters.of(core::RayKind::Eye),
                        r.counters.of(core::RayKind::Reflected), r.counters.of(core::RayKind::Refracted),
                        r.counters.of(core::RayKind::Light), r.rmse, r.psnr, r.maxAbs);
  return text;
}

std::vector<SubsampleRow> measureSubsampling(const core::Scene& scene, const RenderSettings& base,
                                             int processors, int runs) {
  std::vector<SubsampleRow> rows;
  for (int window : {16, 8, 4, 2, 1}) {
    MachineSettings machine;
    machine.rows = 1;
    machine.columns = processors;
    machine.subsampleWindow = window;
    machine.balance = Balance::Bsp;  // the balance a window buys is the BSP's
    SubsampleRow row;
    row.window = window;
    std::vector<double> times;
    for (int run = 0; run < std::max(1, runs); ++run) {
      MachineReport report;
      times.push_back(renderMachine(scene, base, machine, &report).preprocessSeconds);
      if (run > 0) continue;
      const LoadBalance b = loadBalanceOf(report);
      row.raysMaxOverMean = b.raysMaxOverMean;
      row.raysMinOverMean = b.raysMinOverMean;
      row.costMaxOverMean = b.costMaxOverMean;
    }
    row.preprocessSeconds = median(times);
    rows.push_back(row);
  }
  return rows;
}

std::string subsampleTable(const std::vector<SubsampleRow>& rows) {
  std::string text = "subsample  preprocessing s  rays max/mean  rays min/mean  cost max/mean\n";
  for (const SubsampleRow& r : rows)
    text += fmt::format("{:>6}x{:<3} {:>15.4f} {:>14.2f} {:>14.2f} {:>14.2f}\n", r.window, r.window,
                        r.preprocessSeconds, r.raysMaxOverMean, r.raysMinOverMean, r.costMaxOverMean);
  return text;
}

void writeTradeoffCsv(const std::vector<TradeoffRow>& rows, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  out << "knob,setting,seconds,eye_rays,reflected_rays,refracted_rays,light_rays,rmse,psnr_db,max_error\n";
  for (const TradeoffRow& r : rows)
    out << fmt::format("{},{},{:.6f},{},{},{},{},{:.6g},{:.4f},{:.6g}\n", r.knob, r.setting, r.seconds,
                       r.counters.of(core::RayKind::Eye), r.counters.of(core::RayKind::Reflected),
                       r.counters.of(core::RayKind::Refracted), r.counters.of(core::RayKind::Light), r.rmse,
                       std::isinf(r.psnr) ? 999.0 : r.psnr, r.maxAbs);
  if (!out) throw std::runtime_error("failed writing " + path.string());
}

std::vector<TradeoffRow> readTradeoffCsv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::vector<TradeoffRow> rows;
  std::string line;
  std::getline(in, line);  // the header
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream text(line);
    for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
    if (fields.size() != 10)
      throw std::runtime_error(fmt::format("{}:{}: expected 10 comma-separated fields, got {}", path.string(),
                                           number, fields.size()));
    TradeoffRow r;
    r.knob = fields[0];
    r.setting = fields[1];
    try {
      r.seconds = std::stod(fields[2]);
      for (int k = 0; k < core::kRayKinds; ++k) r.counters.rays[k] = std::stoull(fields[3 + k]);
      r.rmse = std::stod(fields[7]);
      r.psnr = std::stod(fields[8]);
      r.maxAbs = std::stod(fields[9]);
    } catch (const std::logic_error&) {
      throw std::runtime_error(
          fmt::format("{}:{}: not a number where one was expected", path.string(), number));
    }
    rows.push_back(r);
  }
  return rows;
}

LineChart tradeoffPlot(const std::vector<TradeoffRow>& rows, std::string caption) {
  LineChart chart;
  chart.title = "Speed against accuracy: each knob swept from cheap to accurate";
  chart.caption = std::move(caption);
  chart.preferredWidth = 960;  // room between the settings that cluster at one ray per pixel
  chart.preferredHeight = 600;
  chart.x = {.label = "render time, median (s)", .scale = AxisScale::Log};
  chart.y = {.label = "RMSE against the converged reference (linear RGB)", .scale = AxisScale::Log};
  for (const char* knob : kKnobs) {
    Series series{.name = knob};
    for (const TradeoffRow& r : rows) {
      if (r.knob != knob) continue;
      series.x.push_back(r.seconds);
      series.y.push_back(r.rmse);
      series.pointLabels.push_back(r.setting);
    }
    chart.series.push_back(std::move(series));
  }
  return chart;
}

}  // namespace raycube::host
