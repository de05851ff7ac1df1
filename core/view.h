#pragma once
// The eye, the screen and the samples: where eye rays go (SPD rule 6, NFF "v").
// Screen coordinates (u, v) are x/z and y/z in the eye frame, so a plane u = c is a plane through the eye:
// the faces of the paper's pyramidal regions (section 3.1).
#include <cstdint>

#include "core/ray.h"
#include "core/scene.h"

namespace raycube::core {

enum class Sampling : std::uint8_t {
  Centers,  // one eye ray through each pixel centre
  Corners,  // SPD rule 6: (W+1) x (H+1) eye rays through pixel corners, four averaged per pixel
};

class View {
 public:
  // raysPerSample > 1: that many eye rays per sample, stratified and jittered over the sample's pixel-sized
  // footprint with a fixed seed per sample, so the image never depends on who traces which ray.
  View(const Camera& camera, int width, int height, Sampling sampling, int raysPerSample = 1);

  int width() const { return width_; }
  int height() const { return height_; }
  Sampling sampling() const { return sampling_; }
  // The grid of eye-ray sample points: W x H for centres, (W+1) x (H+1) for corners.
  int samplesX() const { return samplesX_; }
  int samplesY() const { return samplesY_; }
  std::uint32_t sampleIndex(int sx, int sy) const { return std::uint32_t(sy) * samplesX_ + sx; }

  // Screen coordinates of the sample column sx / row sy, and of the boundary before column/row k
  // (k = 0 .. samples), which the region and cell grids use: each sample lies inside its boundaries.
  double sampleU(int sx) const;
  double sampleV(int sy) const;
  double boundaryU(int k) const { return sampleU(k) - 0.5 * pitch_; }
  double boundaryV(int k) const { return sampleV(k) + 0.5 * pitch_; }

  // Inverse of boundaryU / boundaryV: the continuous sample-boundary index of a screen coordinate.
  double boundaryIndexU(double u) const { return u / pitch_ + offsetPixels_ + 0.5 * width_; }
  double boundaryIndexV(double v) const { return 0.5 * height_ + offsetPixels_ - v / pitch_; }

  Ray eyeRay(int sx, int sy) const { return eyeRay(sx, sy, 0); }
  // The k-th of raysPerSample() eye rays of sample (sx, sy); with one ray per sample, through the sample.
  Ray eyeRay(int sx, int sy, int k) const;
  int raysPerSample() const { return raysPerSample_; }

  // The camera frame: x right, y up, z forward (depth); the machine's eye frame has y down (node/eye_frame_ray.h).
  // Inline: the machine takes every ray it evaluates or spawns into the eye frame.
  Vec3 toEye(const Vec3& world) const { return directionToEye(world - eye_); }
  Vec3 directionToEye(const Vec3& d) const {
    return Vec3(glm::dot(d, right_), glm::dot(d, up_), glm::dot(d, forward_));
  }
  Vec3 fromCamera(const Vec3& camera) const {
    return eye_ + camera.x * right_ + camera.y * up_ + camera.z * forward_;
  }
  const Vec3& eye() const { return eye_; }
  double hither() const { return hither_; }

 private:
  int width_, height_;
  Sampling sampling_;
  int samplesX_, samplesY_;
  Vec3 eye_, right_, up_, forward_;
  double pitch_;         // screen units between adjacent pixel centres
  double offsetPixels_;  // sample sx sits at pixel coordinate sx - offsetPixels_
  double hither_;
  int raysPerSample_;
};

}  // namespace raycube::core
