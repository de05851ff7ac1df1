#pragma once
// Just enough drawing for the charts raycube writes (figure 15, the speed/accuracy plot): rectangles and
// lines, clipped to the image.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/image.h"

namespace raycube::core {

// Fills the half-open rectangle [x0, x1) x [y0, y1), clipped to the image.
inline void fillRect(Image& image, int x0, int y0, int x1, int y1, const Color& color) {
  for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) image.at(x, y) = color;
}

// A line `width` pixels thick from (x0, y0) to (x1, y1) (Bresenham), clipped to the image.
inline void drawLine(Image& image, int x0, int y0, int x1, int y1, const Color& color, int width = 2) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int error = dx + dy;
  for (;;) {
    fillRect(image, x0 - width / 2, y0 - width / 2, x0 - width / 2 + width, y0 - width / 2 + width, color);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * error;
    if (e2 >= dy) {
      error += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      error += dx;
      y0 += sy;
    }
  }
}

}  // namespace raycube::core
