// SPD sombrero.c (Alexander Enzmann, Eduard Schwan): the height field of a damped cosine ripple, printed as
// triangles. One light. Size s samples a 32*2^(s-1) square grid.
#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "core/spd/generators.h"
#include "core/spd/output.h"

namespace raycube::core {

namespace {

// sombrero.c create_sombrero(): heights in float, as the SPD stores them, sampled from (x0, y0) in steps of
// (x1 - x0) / samples (one step short of x1). Row i runs along x at y = y0 + i * step.
std::vector<std::vector<float>> sombreroHeights(int samples, double x0, double x1, double y0, double y1) {
  constexpr double kA = 1.0;
  constexpr double kB = 1.0;
  constexpr double kC = 3.0;
  const double twoPiA = 2.0 * 3.14159265358 * kA;  // sombrero.c's own pi
  const double dx = (x1 - x0) / double(samples);
  const double dy = (y1 - y0) / double(samples);
  std::vector<std::vector<float>> heights(samples, std::vector<float>(samples));
  double y = y0;
  for (int i = 0; i < samples; ++i, y += dy) {
    double x = x0;
    for (int j = 0; j < samples; ++j, x += dx) {
      const double r = std::sqrt(x * x + y * y);
      heights[i][j] = static_cast<float>(kC * std::cos(twoPiA * r) * std::exp(-kB * r) / 3.0);
    }
  }
  return heights;
}

// libply.c lib_output_polygon_height(): two triangles per grid square, the height field's y up; rows along
// z from z0 to z1, columns along x from x0 to x1.
void outputHeightField(SpdOutput& out, const std::vector<std::vector<float>>& data, double x0, double x1,
                       double y0, double z0, double z1) {
  const int rows = static_cast<int>(data.size());
  const int columns = static_cast<int>(data[0].size());
  const double dx = (x1 - x0) / double(columns - 1);
  const double dz = (z1 - z0) / double(rows - 1);
  const auto vertex = [&](int i, int j) { return Vec3(x0 + j * dx, y0 + data[i][j], z0 + i * dz); };
  for (int i = 0; i < rows - 1; ++i) {
    for (int j = 0; j < columns - 1; ++j) {
      out.polygon({vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
      out.polygon({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)});
    }
  }
}

}  // namespace

Scene makeSombrero(int size) {
  requireSpdSize(
      "sombrero", size, kMaxSombreroSize,
      "the height field's resolution, 32*2^(size-1) samples a side: 1 gives 1922 triangles, 3 gives "
      "32258");
  SpdOutput out(fmt::format("sombrero{}", size));
  out.background(Color(0.078, 0.361, 0.753));
  out.viewpoint(Vec3(0, 5, -8), Vec3(0, 0, 0), Vec3(0, 0, 1), 40.0, 0.01, 512, 512);
  out.light(Vec3(10, 10, -10));
  out.color(Color(1, 0.1, 0.1), 0.8, 0.0, 40.0, 0.0, 1.0);  // shiny red (a highlight, no mirror)

  const int samples = 32 << (size - 1);
  out.reserve(2 * std::size_t(samples - 1) * (samples - 1));
  outputHeightField(out, sombreroHeights(samples, -4.0, 4.0, -4.0, 4.0), -4.0, 4.0, -3.0, -4.0, 4.0);
  return std::move(out).finish();
}

}  // namespace raycube::core
