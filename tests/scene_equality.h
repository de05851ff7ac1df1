#pragma once
// Exact comparison of two scenes, element by element (what a user sees: camera, background, lights,
// materials, objects with their shapes and materials; not the NFF line numbers or the source file), with the
// first difference named.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>

#include "core/scene.h"

namespace raycube::testing_support {

inline std::string describe(const core::Vec3& v) {
  return fmt::format("({}, {}, {})", v.x, v.y, v.z);
}

// Patch normals are normalised when read, and normalising a unit vector again may move it by an ulp:
// normalTolerance allows for that (0: exact).
inline bool sameNormals(const std::vector<core::Vec3>& a, const std::vector<core::Vec3>& b,
                        double normalTolerance) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const core::Vec3 d = a[i] - b[i];
    if (std::abs(d.x) > normalTolerance || std::abs(d.y) > normalTolerance || std::abs(d.z) > normalTolerance)
      return false;
  }
  return true;
}

inline ::testing::AssertionResult sameShape(const core::Shape& a, const core::Shape& b,
                                            double normalTolerance = 0) {
  using namespace core;
  if (a.index() != b.index()) return ::testing::AssertionFailure() << "different kinds of shape";
  bool same = false;
  if (const auto* s = std::get_if<Sphere>(&a)) {
    const auto& t = std::get<Sphere>(b);
    same = s->center == t.center && s->radius == t.radius;
  } else if (const auto* c = std::get_if<Cone>(&a)) {
    const auto& t = std::get<Cone>(b);
    same = c->base == t.base && c->apex == t.apex && c->baseRadius == t.baseRadius &&
           c->apexRadius == t.apexRadius;
  } else if (const auto* p = std::get_if<Polygon>(&a)) {
    const auto& t = std::get<Polygon>(b);
    same = p->vertices == t.vertices && (p->outline == nullptr) == (t.outline == nullptr);
  } else {
    const auto& q = std::get<Patch>(a);
    const auto& t = std::get<Patch>(b);
    same = q.vertices == t.vertices && sameNormals(q.normals, t.normals, normalTolerance);
  }
  return same ? ::testing::AssertionSuccess() : ::testing::AssertionFailure() << "different geometry";
}

inline ::testing::AssertionResult sameMaterial(const core::Material& a, const core::Material& b) {
  if (a.color == b.color && a.kd == b.kd && a.ks == b.ks && a.shine == b.shine &&
      a.transmission == b.transmission && a.ior == b.ior) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << "color " << describe(a.color) << " vs " << describe(b.color) << ", kd " << a.kd << " vs " << b.kd
         << ", ks " << a.ks << " vs " << b.ks << ", shine " << a.shine << " vs " << b.shine;
}

inline ::testing::AssertionResult sameScene(const core::Scene& a, const core::Scene& b,
                                            double normalTolerance = 0) {
  const core::Camera& ca = a.camera;
  const core::Camera& cb = b.camera;
  if (ca.from != cb.from || ca.at != cb.at || ca.up != cb.up || ca.angleDegrees != cb.angleDegrees ||
      ca.hither != cb.hither || ca.width != cb.width || ca.height != cb.height) {
    return ::testing::AssertionFailure()
           << "cameras differ: from " << describe(ca.from) << " vs " << describe(cb.from);
  }
  if (a.background != b.background) return ::testing::AssertionFailure() << "backgrounds differ";
  if (a.lights.size() != b.lights.size()) {
    return ::testing::AssertionFailure() << a.lights.size() << " lights vs " << b.lights.size();
  }
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    const core::Light& la = a.lights[i];
    const core::Light& lb = b.lights[i];
    if (la.position != lb.position || la.hasColor != lb.hasColor || (la.hasColor && la.color != lb.color))
      return ::testing::AssertionFailure() << "light " << i << " differs";
  }
  if (a.materials.size() != b.materials.size()) {
    return ::testing::AssertionFailure() << a.materials.size() << " materials vs " << b.materials.size();
  }
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    if (auto same = sameMaterial(a.materials[i], b.materials[i]); !same)
      return same << " (material " << i << ")";
  }
  if (a.objects.size() != b.objects.size()) {
    return ::testing::AssertionFailure() << a.objects.size() << " objects vs " << b.objects.size();
  }
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const core::Object& oa = a.objects[i];
    const core::Object& ob = b.objects[i];
    if (oa.material != ob.material || oa.insideVisible != ob.insideVisible) {
      return ::testing::AssertionFailure()
             << "object " << i << ": material " << oa.material << " vs " << ob.material << ", inside visible "
             << oa.insideVisible << " vs " << ob.insideVisible;
    }
    if (auto same = sameShape(oa.shape, ob.shape, normalTolerance); !same) {
      return same << " (object " << i << ", NFF line " << ob.line << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace raycube::testing_support
