#pragma once
// Reader of Eric Haines' Neutral File Format (shared/spd/NFF.TXT), the language of the SPD scenes.
//
// Strict by design: a file either becomes a Scene that every renderer can trust, or the reader throws a
// SceneError naming file, line and column ("balls2.nff:12:7: expected 4 numbers after 's', got 3").
// Choices where NFF.TXT is silent or permissive:
//  - the "v" block is mandatory, comes before the first object, and has all six lines in NFF order;
//  - an object before the first "f" is an error (no invented default material);
//  - "c" accepts both layouts found in the wild: 8 numbers on the "c" line, or two lines of 4;
//  - negative radii are NFF's inside-visible convention (stored positive, Object::insideVisible);
//    zero radii, mixed-sign cone radii and NaN/Inf anywhere are errors;
//  - "pp" normals are normalised on read; "b" may repeat (the last wins); "l" may follow objects.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/scene.h"

namespace raycube::core {

// A scene file that cannot be read. what() is "source:line:column: message" (line and column 1-based;
// both omitted when the error has no position, e.g. a file that cannot be opened).
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string_view source, int line, int column, std::string_view message);
  SceneError(std::string_view source, std::string_view message);

  const std::string& source() const { return source_; }
  int line() const { return line_; }      // 0 when unknown
  int column() const { return column_; }  // 0 when unknown

 private:
  std::string source_;
  int line_ = 0;
  int column_ = 0;
};

// Largest accepted image side; a larger "resolution" is almost surely a typo, and its framebuffer would
// need gigabytes.
inline constexpr int kMaxNffResolution = 16384;

// Parses NFF text. sourceName prefixes error messages; its stem becomes Scene::name.
Scene parseNff(std::string_view text, std::string_view sourceName);

// Reads and parses an NFF file; SceneError also when the file cannot be read.
Scene readNff(const std::filesystem::path& path);

}  // namespace raycube::core
