#pragma once
// The scene as NFF describes it (shared/spd/NFF.TXT): one camera, a background, positional lights,
// materials ("f" lines) and primitives. The renderers and the machine read only this.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/precision.h"
#include "core/vec.h"

namespace raycube::core {

// NFF "v" block. angle is the field of view in degrees between the centres of the top and bottom pixel rows.
struct Camera {
  Vec3 from{0, 0, 0};
  Vec3 at{0, 0, -1};
  Vec3 up{0, 1, 0};
  double angleDegrees = 45;
  double hither = 0;
  int width = 512;
  int height = 512;
  int line = 0;  // of the NFF "v" line; 0 for scenes built in code
};

// NFF "l": hasColor is false when the file gives no colour; intensities then follow SPD's sqrt(L)/(2L).
struct Light {
  Vec3 position{0, 0, 0};
  Color color{1, 1, 1};
  bool hasColor = false;
  int line = 0;  // NFF line; 0 for scenes built in code
};

// NFF "f": colour, Kd, Ks, Phong exponent, transmission T and index of refraction.
struct Material {
  Color color{1, 1, 1};
  double kd = 0;
  double ks = 0;
  double shine = 0;
  double transmission = 0;
  double ior = 1;
};

// NFF "s". A negative radius in the file (inside visible) is kept as insideVisible with a positive radius.
struct Sphere {
  Vec3 center{0, 0, 0};
  double radius = 1;
};

// NFF "c": open cone or cylinder, no caps.
struct Cone {
  Vec3 base{0, 0, 0};
  double baseRadius = 1;
  Vec3 apex{0, 0, 1};
  double apexRadius = 1;
};

class PolygonOutline;

// A triangle is tested as itself (the fan of one); a polygon of more corners carries its outline, whose test
// takes about constant time (a fan's grows with the corners, and covers a concave polygon's notches too;
// intersection_benchmark compares them). A triangle's outline is faster alone but rendered no faster on a
// scene of triangles, which would hold more memory.
inline constexpr std::size_t kMostFanVertices = 3;

// A polygon's corners, in place for a triangle (the SPD's usual polygon: copied into a processor's database
// without an allocation, tested without a pointer to follow), on the heap for more.
class Corners {
 public:
  static constexpr std::size_t kInPlace = 3;
  Corners() = default;
  explicit Corners(std::vector<Vec3> points) : size_(points.size()) {
    if (size_ <= kInPlace)
      std::copy(points.begin(), points.end(), inPlace_.begin());
    else
      heap_ = std::move(points);
  }

  std::size_t size() const { return size_; }
  const Vec3* data() const { return size_ <= kInPlace ? inPlace_.data() : heap_.data(); }
  const Vec3* begin() const { return data(); }
  const Vec3* end() const { return data() + size_; }
  const Vec3& operator[](std::size_t i) const { return data()[i]; }
  std::vector<Vec3> toVector() const { return std::vector<Vec3>(begin(), end()); }
  friend bool operator==(const Corners& a, const Corners& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end());
  }

 private:
  std::array<Vec3, kInPlace> inPlace_{};
  std::vector<Vec3> heap_;  // more than kInPlace corners
  std::size_t size_ = 0;
};

// NFF "p": planar convex-or-not polygon, counter-clockwise; normal from the first three vertices (NFF: "the
// first two edges must form a non-zero convex angle"). See core/polygon_outline.h.
struct Polygon {
  explicit Polygon(std::vector<Vec3> vertices);

  Corners vertices;                               // to move them, make a new Polygon: the outline follows
  std::shared_ptr<const PolygonOutline> outline;  // null for a triangle; shared by every copy of the object
};

// NFF "pp": polygon with per-vertex normals for smooth shading (triangles in the SPD).
struct Patch {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;
};

using Shape = std::variant<Sphere, Cone, Polygon, Patch>;

// One primitive of the database: its shape and the material in force when it was read.
struct Object {
  Shape shape;
  std::uint32_t material = 0;
  bool insideVisible = false;  // negative radius in NFF
  int line = 0;                // NFF line of its keyword; 0 for scenes built in code
};

// What a scene uses, so a renderer never pays for a feature it does not need.
struct SceneFeatures {
  bool transmission = false;  // some material has T > 0
  bool reflection = false;    // some material has Ks > 0
  bool cones = false;
  bool patches = false;
  bool polygons = false;
  bool spheres = false;
  std::size_t lightCount = 0;
};

struct Scene {
  std::string name;
  std::string source;  // the file it was read from, for messages; empty for scenes built in code
  // What reading found worth telling the user without refusing the file, one line each, "what: details"
  // ("no lights: ..."); core/README.md lists them. Nothing in core prints them: the command line does.
  std::vector<std::string> warnings;
  Camera camera;
  Color background{0, 0, 0};
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<Object> objects;

  SceneFeatures features() const;
  // Largest magnitude of any coordinate or radius in the scene (camera, lights, objects).
  double largestCoordinate() const;
};

// The intensity of each uncoloured light and of the ambient term with `lights` lights: the SPD's
// sqrt(L) / (2 L) (SPD-README). At L = 0 the formula has no value; the ambient is then 0.5, the formula's
// value at L = 1 and its largest: a scene without lights looks like the same scene with one light that
// reaches nothing, never black, and never brighter than a lit scene's ambient (core/README.md).
double spdIntensity(std::size_t lights);

// Every length of the scene times `factor`: camera position, target and hither, lights, and all geometry.
// Directions (up, patch normals), angles, colours and materials are unit-free and stay.
Scene scaledBy(Scene scene, double factor);

// The scene rescaled by a power of two (exact) so that its largest coordinate is about 1, when the
// arithmetic of `precision` needs it: float squares and cubes of coordinates leave float's range from about
// 1e9 and 1e-13 (normals overflow, triangle tests underflow), double's from about 1e100. Whitted shading
// has no distance term, so the picture does not change; nullopt when the scene is fine as it is.
std::optional<Scene> rescaledFor(const Scene& scene, Precision precision);

// Throws std::invalid_argument, naming the element at fault (file:line when the scene was read from one),
// when no render in `precision` could be trusted: more lights than a ray can index (kMaxLights), or a
// dynamic range (largest coordinate over smallest object) that rescaling cannot bring into the precision's
// range (kMaxSpanExponentOf), where everything but the farthest element would vanish.
void requireRenderable(const Scene& scene, Precision precision);

}  // namespace raycube::core
