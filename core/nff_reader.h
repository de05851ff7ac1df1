#pragma once
// Reader of Eric Haines' Neutral File Format (shared/spd/NFF.TXT), the language of the SPD scenes.
//
// NFF as people wrote it: the text is a stream of tokens, so an entity's numbers may be laid out over any
// whitespace and line breaks ("p 3 x y z x y z x y z" on one line, the "v" block on one line, CRLF, tabs),
// as the SPD's own fscanf-based readers accept. A file either becomes a Scene that every renderer can trust,
// or the reader throws a SceneError naming file, line and column where it found what it did not expect
// ("balls2.nff:12:7: expected a finite number as the third value of ..."). What is accepted beyond
// NFF.TXT, what is warned about (Scene::warnings) and what is refused: core/README.md.
// Choices where NFF.TXT is silent or permissive:
//  - the "v" block is mandatory, comes before the first object, and has its six parts in NFF order;
//  - an object before the first "f" is an error (no invented default material);
//  - negative radii are NFF's inside-visible convention (stored positive, Object::insideVisible);
//    zero radii, mixed-sign cone radii and NaN/Inf anywhere are errors;
//  - a polygon or patch whose first three vertices span no plane is skipped with a warning (refused with
//    NffOptions::strict); a degenerate view is always an error;
//  - "pp" normals are normalised on read; "b" may repeat (the last wins); "l" may follow objects;
//  - VM_pRAY's "number N" and "g xmin xmax ymin ymax zmin zmax" (IRISA's dialect) are hints, checked and
//    warned about, never refused; Sense8 WorldToolKit's NFF, another format, is named as such.
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

struct NffOptions {
  // Refuse a polygon or patch whose first three vertices span no plane, instead of skipping it with a
  // warning (raycube --strict).
  bool strict = false;
};

// Parses NFF text. sourceName prefixes error messages and warnings; its stem becomes Scene::name.
Scene parseNff(std::string_view text, std::string_view sourceName, const NffOptions& options = {});

// Reads and parses an NFF file; SceneError also when the file cannot be read.
Scene readNff(const std::filesystem::path& path, const NffOptions& options = {});

}  // namespace raycube::core
