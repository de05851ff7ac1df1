#pragma once
// What the SPD library (Eric Haines' libpr*.c, libply.c) prints in NFF when a generator calls its
// lib_output_* functions with OUTPUT_CURVES (spheres and cylinders as such, the ray-tracing timing format),
// collected as a Scene instead of text. Every number goes through the SPD's "%g" (6 significant digits),
// so a built-in generator's scene is the database the SPD program prints, number for number.
#include <string>
#include <vector>

#include "core/scene.h"

namespace raycube::core {

// x as the SPD prints it ("%g") and any NFF reader reads it back.
double spdPrinted(double x);
Vec3 spdPrinted(const Vec3& v);

class SpdOutput {
 public:
  explicit SpdOutput(std::string sceneName);

  void background(const Color& color);  // lib_output_background_color
  void viewpoint(const Vec3& from, const Vec3& at, const Vec3& up, double angleDegrees, double hither,
                 int width, int height);  // lib_output_viewpoint
  void light(const Vec3& position);       // lib_output_light
  // lib_output_color: the highlight's half angle becomes NFF's Phong exponent.
  void color(const Color& color, double kd, double ks, double highlightDegrees, double kt, double ior);
  void sphere(const Vec3& center, double radius);  // lib_output_sphere
  void cylcone(const Vec3& base, double baseRadius, const Vec3& apex,
               double apexRadius);  // lib_output_cylcone
  // lib_output_polygon: adjacent vertices closer than the SPD's EPSILON2 merge; fewer than 3 left prints
  // nothing.
  void polygon(std::vector<Vec3> vertices);

  void reserve(std::size_t objects) { scene_.objects.reserve(objects); }
  Scene finish() && { return std::move(scene_); }

 private:
  void add(Shape shape);

  Scene scene_;
};

}  // namespace raycube::core
