#include "core/nff_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <system_error>
#include <utility>
#include <vector>

#include "core/box.h"
#include "core/overloaded.h"
#include "core/ray.h"

namespace raycube::core {

namespace {

// Sine of the angle between two edges (or between view direction and up) below which a normal or a
// camera basis is numerically meaningless. SPD prints 6 significant digits; real geometry sits far above
// (the teapot's thinnest patch corner has a sine of 0.09).
constexpr double kMinSine = 1e-9;

// VM_pRAY's "g" box is a hint printed with a few digits, like the rest of the file: an object that sticks
// out of it by less than this fraction of the box's scale (its largest extent plus its largest coordinate)
// is held. A box 6 digits can print is at most 5e-6 of that scale away from the one it was computed as.
constexpr double kHintBoxSlackRelative = 1e-5;

// Longest token echoed back in an error message; a mutated file may hold a megabyte on one line.
constexpr std::size_t kMaxEchoedToken = 32;

// Sine of the angle between a and b, each scaled by its largest component first so that neither huge nor
// tiny (but finite, non-zero) vectors overflow or underflow in the lengths; 0 when either is zero.
double sineBetween(Vec3 a, Vec3 b) {
  const double largestA = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
  const double largestB = std::max({std::abs(b.x), std::abs(b.y), std::abs(b.z)});
  if (!(largestA > 0 && largestB > 0)) return 0;
  a /= largestA;
  b /= largestB;
  return glm::length(glm::cross(a, b)) / (glm::length(a) * glm::length(b));
}

std::string formatMessage(std::string_view source, int line, int column, std::string_view message) {
  if (line <= 0) return fmt::format("{}: {}", source, message);
  return fmt::format("{}:{}:{}: {}", source, line, column, message);
}

// A token as a user should see it in a message: quoted, printable, short.
std::string quoted(std::string_view token) {
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMaxEchoedToken; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += fmt::format("\\x{:02x}", c);
    }
  }
  if (token.size() > kMaxEchoedToken) out += "...";
  out += "'";
  return out;
}

const char* ordinal(std::size_t n) {
  static constexpr std::array<const char*, 8> kNames{"first", "second", "third",   "fourth",
                                                     "fifth", "sixth",  "seventh", "eighth"};
  return n < kNames.size() ? kNames[n] : "next";
}

// A word of the text with its position; an empty text is the end of the file.
struct Token {
  std::string_view text;
  int line = 0;    // 1-based
  int column = 0;  // 1-based byte column
  bool atEnd() const { return text.empty(); }
};

// A token as a message names what was found.
std::string describe(const Token& token) {
  return token.atEnd() ? std::string("end of file") : quoted(token.text);
}

// What was found where a number is missing, reported at `at` (just past the last number read): with its
// line when that is another one.
std::string describeFrom(const Token& token, const Token& at) {
  if (token.atEnd() || token.line == at.line) return describe(token);
  return fmt::format("{} at line {}", quoted(token.text), token.line);
}

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// The words that start an entity or a part of the "v" block (VM_pRAY's "number" and "g" included): where
// one of these stands, an entity before it ran out of numbers.
bool isKeyword(std::string_view text) {
  static constexpr std::array<std::string_view, 16> kKeywords{
      "v",    "b",  "l",  "f",     "c",      "s",          "p",      "pp",
      "from", "at", "up", "angle", "hither", "resolution", "number", "g"};
  return std::find(kKeywords.begin(), kKeywords.end(), text) != kKeywords.end();
}

// A word that was meant as a number, well formed or not ("0.5", "1.2.3", "-x", "nan").
bool looksNumeric(std::string_view text) {
  if (text.empty()) return false;
  if (std::string_view("0123456789+-.").find(text[0]) != std::string_view::npos) return true;
  const auto startsWith = [&](std::string_view prefix) {
    return text.size() >= prefix.size() &&
           std::equal(prefix.begin(), prefix.end(), text.begin(),
                      [](char p, char t) { return p == std::tolower(static_cast<unsigned char>(t)); });
  };
  return startsWith("nan") || startsWith("inf");
}

// NFF text as a stream of words separated by any whitespace and line breaks, as NFF.TXT's general rule has
// it ("the rest of the line and possibly other lines contain further information about the entity") and
// the SPD's fscanf-based readers read it. '#' starts a comment that runs to the end of its line.
class TokenStream {
 public:
  explicit TokenStream(std::string_view text) : text_(text) {
    // A UTF-8 byte order mark, which some editors put before the first line of a saved file, is no word.
    if (text_.starts_with("\xEF\xBB\xBF")) position_ = lineStart_ = 3;
    advance();
  }

  const Token& peek() const { return next_; }
  Token take() {
    last_ = next_;
    advance();
    return last_;
  }
  // Just past the last word taken (line 1, column 1 before the first): where a missing number belongs.
  Token pastLast() const {
    return Token{{}, std::max(last_.line, 1), last_.column + static_cast<int>(last_.text.size())};
  }
  // Bytes from the next word on: a bound on the numbers the file can still hold (each takes a character and
  // a separator), so that no count in the file reserves more memory than the file could fill.
  std::size_t remainingBytes() const { return text_.size() - position_ + next_.text.size(); }

 private:
  void advance() {
    while (position_ < text_.size()) {
      const char c = text_[position_];
      if (c == '\n') {
        ++line_;
        lineStart_ = ++position_;
      } else if (isSpace(c)) {
        ++position_;
      } else if (c == '#') {
        position_ = std::min(text_.find('\n', position_), text_.size());
      } else {
        break;
      }
    }
    const std::size_t start = position_;
    while (position_ < text_.size() && !isSpace(text_[position_]) && text_[position_] != '#') ++position_;
    next_ = Token{text_.substr(start, position_ - start), line_, static_cast<int>(start - lineStart_) + 1};
  }

  std::string_view text_;
  std::size_t position_ = 0;   // of the first byte not yet scanned
  std::size_t lineStart_ = 0;  // of the current line's first byte
  int line_ = 1;
  Token next_;
  Token last_{{}, 0, 1};
};

// What a run of numbers belongs to, for messages, formatted only if a message needs it (formatted eagerly
// for each of sombrero 3's 97,000 vertices, it cost a fifth of the parse).
struct Subject {
  std::string_view keyword;  // "s", "from", ...
  int line = 0;              // the keyword's
  std::string_view fields;   // "center x y z radius"
  std::size_t vertex = 0;    // 1-based; 0: not a vertex
  std::size_t vertices = 0;

  std::string str() const {
    if (vertex == 0) return fmt::format("the '{}' at line {} ({})", keyword, line, fields);
    return fmt::format("vertex {} of {} of the '{}' at line {} ({})", vertex, vertices, keyword, line,
                       fields);
  }
};

// N numbers read in a row, with where each stood.
template <std::size_t N>
struct Numbers {
  std::array<double, N> values{};
  std::array<Token, N> tokens{};
  Vec3 vec(std::size_t first) const { return Vec3(values[first], values[first + 1], values[first + 2]); }
};

// A VM_pRAY hint, checked once the scene is read.
struct CountHint {
  int line = 0;
  long long count = 0;
};
struct BoxHint {
  int line = 0;
  Box box;
};

// The object's exact bounding box: a cone's end discs by their true extent, not boundsOf's cubes (a box
// hint that holds the discs exactly must not be reported as too small).
Box tightBoundsOf(const Object& object) {
  Box box;
  std::visit(Overloaded{[&](const Sphere& s) {
                          box.extend(s.center - Vec3(s.radius));
                          box.extend(s.center + Vec3(s.radius));
                        },
                        [&](const Cone& c) {
                          const Vec3 axis = glm::normalize(c.apex - c.base);
                          const Vec3 across = glm::sqrt(glm::max(Vec3(0), Vec3(1) - axis * axis));
                          for (const auto& [centre, radius] :
                               {std::pair{c.base, c.baseRadius}, std::pair{c.apex, c.apexRadius}}) {
                            box.extend(centre - radius * across);
                            box.extend(centre + radius * across);
                          }
                        },
                        [&](const Polygon& p) {
                          for (const Vec3& v : p.vertices) box.extend(v);
                        },
                        [&](const Patch& p) {
                          for (const Vec3& v : p.vertices) box.extend(v);
                        }},
             object.shape);
  return box;
}

class NffParser {
 public:
  NffParser(std::string_view text, std::string_view source, const NffOptions& options)
      : tokens_(text), source_(source), options_(options) {}

  Scene parse() {
    Scene scene;
    scene.name = std::filesystem::path(std::string(source_)).stem().string();
    scene.source = std::string(source_);
    rejectWorldToolKit();
    while (!tokens_.peek().atEnd()) {
      const Token keyword = tokens_.take();
      // The entity read before this one, for a number found where a keyword should stand.
      const Token previous = std::exchange(entity_, keyword);
      const std::size_t previousNumbers = std::exchange(numbersTaken_, 0);
      const std::size_t previousVertices = std::exchange(vertexCount_, 0);
      const std::string_view k = keyword.text;
      if (k == "v") {
        readView(keyword, scene);
      } else if (k == "b") {
        scene.background = numbers<3>({k, keyword.line, "background red green blue"}).vec(0);
      } else if (k == "l") {
        readLight(keyword, scene);
      } else if (k == "f") {
        readMaterial(keyword, scene);
      } else if (k == "s" || k == "c" || k == "p" || k == "pp") {
        requireObjectContext(keyword, scene);
        Object object;
        object.material = static_cast<std::uint32_t>(scene.materials.size() - 1);
        object.line = keyword.line;
        bool kept = true;
        if (k == "s") {
          readSphere(keyword, object);
        } else if (k == "c") {
          readCone(keyword, object);
        } else if (k == "p") {
          kept = readPolygon(keyword, object);
        } else {
          kept = readPatch(keyword, object);
        }
        ++objectsInFile_;
        if (kept) scene.objects.push_back(std::move(object));
      } else if (k == "number") {
        readCountHint(keyword);
      } else if (k == "g") {
        boxHints_.push_back(
            {keyword.line, boxOf(numbers<6>({k, keyword.line, "scene box xmin xmax ymin ymax zmin zmax"}))});
      } else {
        failUnexpected(keyword, previous, previousNumbers, previousVertices);
      }
    }
    if (viewLine_ == 0) {
      fail(
          tokens_.peek(),
          "expected a 'v' block (from, at, up, angle, hither, resolution) before the first object, found end "
          "of file");
    }
    addWarnings(scene);
    return scene;
  }

 private:
  [[noreturn]] void fail(const Token& where, std::string_view message) const {
    throw SceneError(source_, where.line, where.column, message);
  }

  // Sense8 WorldToolKit wrote another format under the same name, whose first line is "nff" and second
  // "version N": say so, rather than that "nff" is no NFF keyword.
  void rejectWorldToolKit() {
    const Token first = tokens_.peek();
    if (first.text.size() != 3) return;
    std::string lower(first.text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower != "nff") return;
    tokens_.take();
    const Token second = tokens_.peek();
    fail(first,
         fmt::format("expected Eric Haines' NFF (the SPD's NFF.TXT), found Sense8 WorldToolKit's NFF, a "
                     "different format under the same name (first line 'nff'{}); convert it to Haines' "
                     "NFF first",
                     second.text == "version" ? ", then 'version N'" : ""));
  }

  // A word where an entity should start: a number one too many for the entity before, or no keyword at all.
  [[noreturn]] void failUnexpected(const Token& found, const Token& previous, std::size_t previousNumbers,
                                   std::size_t previousVertices) const {
    if (looksNumeric(found.text) && previous.line > 0) {
      const std::string took =
          previousVertices > 0
              ? fmt::format("the {} vertices its count gives", previousVertices)
              : fmt::format("its {} number{}", previousNumbers, previousNumbers == 1 ? "" : "s");
      fail(found, fmt::format("expected a keyword after the '{}' at line {} took {}, found another number {}",
                              previous.text, previous.line, took, quoted(found.text)));
    }
    fail(found,
         fmt::format("expected one of the NFF keywords v, b, l, f, c, s, p, pp or a '#' comment, found {}",
                     quoted(found.text)));
  }

  // A finite double; locale-independent. A leading '+' is tolerated (hand-written files use it).
  static std::optional<double> parseDouble(std::string_view text) {
    if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
    double value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
      return std::nullopt;
    return value;
  }

  static std::optional<long long> parseInteger(std::string_view text) {
    if (text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
    long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
  }

  // The next word, which must be a number: the index-th (0-based) of the `count` numbers of `what`. A
  // keyword or the end of the file there means the entity is short of numbers; anything else is a
  // malformed number.
  std::pair<double, Token> number(const Subject& what, std::size_t index, std::size_t count) {
    const Token token = tokens_.peek();
    if (const std::optional<double> value = parseDouble(token.text)) {
      tokens_.take();
      ++numbersTaken_;
      return {*value, token};
    }
    if (token.atEnd() || isKeyword(token.text)) {
      const Token at = tokens_.pastLast();
      fail(at, fmt::format("expected {} numbers for {}, {}found {}{}", count, what.str(),
                           index > 0 ? fmt::format("got {}, ", index) : "", describeFrom(token, at), hint_));
    }
    fail(token, fmt::format("expected a finite number as the {} value of {}, found {}{}", ordinal(index),
                            what.str(), quoted(token.text), hint_));
  }

  template <std::size_t N>
  Numbers<N> numbers(const Subject& what) {
    Numbers<N> n;
    for (std::size_t i = 0; i < N; ++i) std::tie(n.values[i], n.tokens[i]) = number(what, i, N);
    return n;
  }

  // The next word, which must be a whole number (a count or a size): nullopt, with the word left
  // unread, when it is not one.
  std::optional<long long> integer() {
    const std::optional<long long> value = parseInteger(tokens_.peek().text);
    if (value) {
      tokens_.take();
      ++numbersTaken_;
    }
    return value;
  }

  // The next part of the "v" block, which NFF.TXT orders from, at, up, angle, hither, resolution.
  Token viewPart(std::string_view name) {
    const Token token = tokens_.peek();
    if (token.text != name) {
      fail(token,
           fmt::format("expected '{}' of the 'v' block started at line {} (from, at, up, angle, hither, "
                       "resolution, in this order), found {}",
                       name, viewLine_, describe(token)));
    }
    entity_ = tokens_.take();
    numbersTaken_ = 0;
    return token;
  }

  void readView(const Token& v, Scene& scene) {
    if (viewLine_ != 0) {
      fail(v, fmt::format("expected a single 'v' block, found a second one (the first is at line {})",
                          viewLine_));
    }
    viewLine_ = v.line;
    Camera& camera = scene.camera;
    camera.line = v.line;

    camera.from = numbers<3>({"from", viewPart("from").line, "eye x y z"}).vec(0);
    const auto at = numbers<3>({"at", viewPart("at").line, "look-at x y z"});
    camera.at = at.vec(0);
    if (camera.at == camera.from)
      fail(at.tokens[0], "expected 'at' to differ from 'from', found the same point");
    const auto up = numbers<3>({"up", viewPart("up").line, "x y z"});
    camera.up = up.vec(0);
    if (!(sineBetween(camera.at - camera.from, camera.up) > kMinSine)) {
      fail(up.tokens[0],
           "expected an 'up' vector that is non-zero and not parallel to the view direction (at - from)");
    }
    const auto angle = numbers<1>({"angle", viewPart("angle").line, "field of view in degrees"});
    camera.angleDegrees = angle.values[0];
    if (!(camera.angleDegrees > 0 && camera.angleDegrees < 180)) {
      fail(angle.tokens[0], fmt::format("expected an 'angle' strictly between 0 and 180 degrees, found {}",
                                        camera.angleDegrees));
    }
    const auto hither = numbers<1>({"hither", viewPart("hither").line, "distance of the near plane"});
    camera.hither = hither.values[0];
    if (camera.hither < 0)
      fail(hither.tokens[0], fmt::format("expected a 'hither' distance >= 0, found {}", camera.hither));
    viewPart("resolution");
    std::array<int, 2> size{};
    for (std::size_t i = 0; i < 2; ++i) {
      const Token token = tokens_.peek();
      if (token.atEnd() || isKeyword(token.text)) {
        const Token at = tokens_.pastLast();
        fail(at, fmt::format("expected 2 positive integers for 'resolution' (width height), got {}, found {}",
                             i, describeFrom(token, at)));
      }
      const std::optional<long long> value = integer();
      if (!value || *value <= 0 || *value > kMaxNffResolution) {
        fail(token,
             fmt::format("expected a whole number of pixels from 1 to {} as the 'resolution' {}, found {}",
                         kMaxNffResolution, i == 0 ? "width" : "height", quoted(token.text)));
      }
      size[i] = static_cast<int>(*value);
    }
    camera.width = size[0];
    camera.height = size[1];
  }

  void readLight(const Token& keyword, Scene& scene) {
    if (scene.lights.size() >= kMaxLights) {
      fail(keyword,
           fmt::format("expected at most {} lights (a ray names its light in 16 bits), found one more",
                       kMaxLights));
    }
    const Subject what{"l", keyword.line, "light x y z, and r g b when coloured"};
    Light light;
    light.line = keyword.line;
    std::array<double, 6> values{};
    for (std::size_t i = 0; i < 3; ++i) values[i] = number(what, i, 3).first;
    light.position = Vec3(values[0], values[1], values[2]);
    // Anything meant as a number after x y z is the colour; a keyword starts the next entity.
    if (looksNumeric(tokens_.peek().text)) {
      for (std::size_t i = 3; i < 6; ++i) values[i] = number(what, i, 6).first;
      light.color = Color(values[3], values[4], values[5]);
      light.hasColor = true;
    }
    scene.lights.push_back(light);
  }

  void readMaterial(const Token& keyword, Scene& scene) {
    const auto f = numbers<8>({"f", keyword.line, "red green blue Kd Ks Shine T index_of_refraction"});
    Material material;
    material.color = f.vec(0);
    material.kd = f.values[3];
    material.ks = f.values[4];
    material.shine = f.values[5];
    material.transmission = f.values[6];
    material.ior = f.values[7];
    // SPD writes an index of 0 for opaque materials; only light that is transmitted needs a real one.
    if (material.transmission > 0 && material.ior <= 0) {
      fail(
          f.tokens[7],
          fmt::format("expected a positive index of refraction for a transmitting material (T > 0), found {}",
                      material.ior));
    }
    if (scene.materials.size() >= std::numeric_limits<std::uint32_t>::max())
      fail(keyword, "expected fewer than 2^32 materials");
    scene.materials.push_back(material);
  }

  void requireObjectContext(const Token& keyword, const Scene& scene) const {
    if (viewLine_ == 0) {
      fail(keyword, fmt::format("expected the 'v' block (viewpoint) before the first object, found {}",
                                quoted(keyword.text)));
    }
    if (scene.materials.empty()) {
      fail(keyword, fmt::format("expected an 'f' line (material) before the first object, found {}",
                                quoted(keyword.text)));
    }
  }

  void readSphere(const Token& keyword, Object& object) {
    const auto s = numbers<4>({"s", keyword.line, "center x y z radius"});
    if (s.values[3] == 0) fail(s.tokens[3], "expected a non-zero sphere radius, found 0");
    object.insideVisible = s.values[3] < 0;
    object.shape = Sphere{s.vec(0), std::abs(s.values[3])};
  }

  // "c" with its 8 numbers; files lay them out on the "c" line or as base and apex on the next two.
  void readCone(const Token& keyword, Object& object) {
    const auto c = numbers<8>({"c", keyword.line, "base x y z radius, apex x y z radius"});
    Cone cone{c.vec(0), c.values[3], c.vec(4), c.values[7]};
    if (cone.base == cone.apex) fail(keyword, "expected distinct cone base and apex, found the same point");
    const bool negative = cone.baseRadius < 0 || cone.apexRadius < 0;
    const bool positive = cone.baseRadius > 0 || cone.apexRadius > 0;
    if (negative && positive) {
      fail(
          c.tokens[3],
          fmt::format("expected cone radii of one sign (both negative means inside visible), found {} and {}",
                      cone.baseRadius, cone.apexRadius));
    }
    if (!negative && !positive) fail(c.tokens[3], "expected a non-zero cone radius, found both 0");
    object.insideVisible = negative;
    cone.baseRadius = std::abs(cone.baseRadius);
    cone.apexRadius = std::abs(cone.apexRadius);
    object.shape = cone;
  }

  // The count of "p N" or "pp N": a whole number, at least 3.
  std::size_t vertexCount(const Token& keyword) {
    const Token token = tokens_.peek();
    if (token.atEnd() || isKeyword(token.text)) {
      const Token at = tokens_.pastLast();
      fail(at, fmt::format("expected a vertex count after '{}', found {}", keyword.text,
                           describeFrom(token, at)));
    }
    const std::optional<long long> count = integer();
    if (!count) {
      fail(token, fmt::format("expected a whole vertex count after '{}', found {}", keyword.text,
                              quoted(token.text)));
    }
    if (*count < 3)
      fail(token, fmt::format("expected at least 3 vertices for '{}', found {}", keyword.text, *count));
    return static_cast<std::size_t>(*count);
  }

  // The `count` vertices of a "p" or "pp", PerVertex numbers each, handed to vertex(numbers, index). Their
  // layout is free, but a file that gives its first vertex a line of its own means one vertex a line: the
  // first vertex that spans two lines then most likely lacks a number, which a later error names.
  template <std::size_t PerVertex, class OnVertex>
  void readVertices(const Token& keyword, std::size_t count, std::string_view fields, OnVertex&& vertex) {
    vertexCount_ = count;
    bool onePerLine = false;
    for (std::size_t i = 0; i < count; ++i) {
      const auto n = numbers<PerVertex>({keyword.text, keyword.line, fields, i + 1, count});
      const int first = n.tokens.front().line, last = n.tokens.back().line;
      if (i == 0) {
        onePerLine = first == last && first > keyword.line;
      } else if (onePerLine && first != last && hint_.empty()) {
        hint_ = fmt::format(" (vertex {} runs from line {} to line {}: a number missing on line {}?)", i + 1,
                            first, last, first);
      }
      vertex(n, i);
    }
    hint_.clear();
  }

  // Memory for `count` vertices, or for as many as the rest of the file can hold: a corrupt count must not
  // reserve gigabytes.
  std::size_t plausibleVertices(std::size_t count, std::size_t perVertex) const {
    return std::min(count, tokens_.remainingBytes() / (2 * perVertex) + 1);
  }

  // NFF.TXT: "the first two edges must form a non-zero convex angle", which gives the normal. A polygon or
  // patch without one is skipped (false) and counted, unless the options are strict: real meshes carry them
  // (a teapot's collinear patches at its poles, a zero-area triangle among a converted mesh's thousands).
  bool spansPlane(const Token& keyword, const std::vector<Vec3>& vertices, std::string_view what) {
    if (sineBetween(vertices[1] - vertices[0], vertices[2] - vertices[0]) > kMinSine) return true;
    if (options_.strict) {
      fail(keyword,
           fmt::format("expected {} whose first three vertices span a plane (they define its normal), "
                       "found them coincident or collinear",
                       what));
    }
    if (skipped_ == 0) firstSkippedLine_ = keyword.line;
    ++skipped_;
    return false;
  }

  bool readPolygon(const Token& keyword, Object& object) {
    const std::size_t count = vertexCount(keyword);
    std::vector<Vec3> vertices;
    vertices.reserve(plausibleVertices(count, 3));
    readVertices<3>(keyword, count, "x y z",
                    [&](const Numbers<3>& v, std::size_t) { vertices.push_back(v.vec(0)); });
    ++polygonsInFile_;
    if (!spansPlane(keyword, vertices, "a polygon")) return false;
    object.shape = Polygon(std::move(vertices));
    return true;
  }

  bool readPatch(const Token& keyword, Object& object) {
    const std::size_t count = vertexCount(keyword);
    Patch patch;
    patch.vertices.reserve(plausibleVertices(count, 6));
    patch.normals.reserve(plausibleVertices(count, 6));
    readVertices<6>(keyword, count, "x y z nx ny nz", [&](const Numbers<6>& v, std::size_t i) {
      const Vec3 normal = v.vec(3);
      // Scale by the largest component first so tiny but valid normals do not underflow.
      const double largest = std::max({std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)});
      if (largest == 0) {
        fail(v.tokens[3],
             fmt::format("expected a non-zero normal for vertex {} of the 'pp' at line {}, found 0 0 0",
                         i + 1, keyword.line));
      }
      patch.vertices.push_back(v.vec(0));
      patch.normals.push_back(glm::normalize(normal / largest));
    });
    ++polygonsInFile_;
    if (!spansPlane(keyword, patch.vertices, "a patch")) return false;
    object.shape = std::move(patch);
    return true;
  }

  // VM_pRAY's "number N": the count of objects it wrote, a hint.
  void readCountHint(const Token& keyword) {
    const Token token = tokens_.peek();
    const std::optional<long long> count = integer();
    if (!count || *count < 0) {
      fail(token.atEnd() ? tokens_.pastLast() : token,
           fmt::format("expected a whole number of objects after the 'number' at line {} (VM_pRAY's object "
                       "count), found {}",
                       keyword.line, describe(token)));
    }
    countHints_.push_back({keyword.line, *count});
  }

  // VM_pRAY's "g xmin xmax ymin ymax zmin zmax".
  static Box boxOf(const Numbers<6>& g) {
    return Box{Vec3(g.values[0], g.values[2], g.values[4]), Vec3(g.values[1], g.values[3], g.values[5])};
  }

  // Where the scene sticks out of a "g" box hint, or nullopt when the box holds it.
  std::optional<std::string> outsideOf(const BoxHint& hint, const Scene& scene) const {
    const Box& box = hint.box;
    const Vec3 magnitude = glm::max(glm::abs(box.lo), glm::abs(box.hi));
    const Vec3 extent = glm::abs(box.extent());
    const double slack = kHintBoxSlackRelative * (std::max({extent.x, extent.y, extent.z}) +
                                                  std::max({magnitude.x, magnitude.y, magnitude.z}));
    std::size_t outside = 0;
    int firstLine = 0;
    std::string first;  // "to z = 1.2 beyond zmax = 1"
    for (const Object& object : scene.objects) {
      const Box bounds = tightBoundsOf(object);
      std::string where;
      for (int a = 0; a < 3 && where.empty(); ++a) {
        const char axis = "xyz"[a];
        if (bounds.lo[a] < box.lo[a] - slack) {
          where = fmt::format("to {} = {:g} beyond {}min = {:g}", axis, bounds.lo[a], axis, box.lo[a]);
        } else if (bounds.hi[a] > box.hi[a] + slack) {
          where = fmt::format("to {} = {:g} beyond {}max = {:g}", axis, bounds.hi[a], axis, box.hi[a]);
        }
      }
      if (where.empty()) continue;
      if (outside++ > 0) continue;
      firstLine = object.line;
      first = std::move(where);
    }
    if (outside == 0) return std::nullopt;
    if (outside == 1) return fmt::format("the object at line {} reaches out of it {}", firstLine, first);
    return fmt::format("{} of the {} objects reach out of it, the first at line {} {}", outside,
                       scene.objects.size(), firstLine, first);
  }

  void addWarnings(Scene& scene) const {
    if (skipped_ > 0) {
      scene.warnings.push_back(fmt::format(
          "degenerate polygons: skipped {} of the {} polygons and patches, whose first three vertices are "
          "coincident or collinear (no plane, so no normal), the first at {}:{}; --strict refuses the file "
          "instead",
          skipped_, polygonsInFile_, source_, firstSkippedLine_));
    }
    for (const CountHint& hint : countHints_) {
      if (hint.count != static_cast<long long>(objectsInFile_)) {
        scene.warnings.push_back(
            fmt::format("VM_pRAY hint: {}:{}: 'number' gives {} objects, the file has {}", source_, hint.line,
                        hint.count, objectsInFile_));
      }
    }
    for (const BoxHint& hint : boxHints_) {
      if (const std::optional<std::string> outside = outsideOf(hint, scene)) {
        scene.warnings.push_back(fmt::format("VM_pRAY hint: {}:{}: the 'g' box does not hold the scene: {}",
                                             source_, hint.line, *outside));
      }
    }
    if (scene.lights.empty()) {
      scene.warnings.push_back(fmt::format(
          "no lights: {} has no 'l' line, so surfaces show the ambient term alone, at {:g} (the SPD's "
          "sqrt(L)/(2L) at L = 1), rather than black",
          source_, spdIntensity(0)));
    }
  }

  TokenStream tokens_;
  std::string_view source_;
  NffOptions options_;
  int viewLine_ = 0;  // line of the "v" block, 0 before it
  // The entity being read (a part of the "v" block counts as one), the numbers it took and, for a polygon
  // or patch, its vertex count: what a message says when a number stands where the next keyword should.
  Token entity_;
  std::size_t numbersTaken_ = 0;
  std::size_t vertexCount_ = 0;
  std::string hint_;                // appended to a message about a missing number (readVertices)
  std::size_t objectsInFile_ = 0;   // "s", "c", "p" and "pp", skipped ones included
  std::size_t polygonsInFile_ = 0;  // "p" and "pp", skipped ones included
  std::size_t skipped_ = 0;
  int firstSkippedLine_ = 0;
  std::vector<CountHint> countHints_;
  std::vector<BoxHint> boxHints_;
};

const char* describe(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::character:
      return "a character device";
    case std::filesystem::file_type::block:
      return "a block device";
    case std::filesystem::file_type::fifo:
      return "a FIFO (named pipe)";
    case std::filesystem::file_type::socket:
      return "a socket";
    default:
      return "something that is not a regular file";
  }
}

}  // namespace

SceneError::SceneError(std::string_view source, int line, int column, std::string_view message)
    : std::runtime_error(formatMessage(source, line, column, message)),
      source_(source),
      line_(line),
      column_(column) {}

SceneError::SceneError(std::string_view source, std::string_view message)
    : SceneError(source, 0, 0, message) {}

Scene parseNff(std::string_view text, std::string_view sourceName, const NffOptions& options) {
  return NffParser(text, sourceName, options).parse();
}

Scene readNff(const std::filesystem::path& path, const NffOptions& options) {
  const std::string source = path.string();
  // Only a regular file has an end: a device (/dev/zero) would be read until memory runs out, and opening
  // a FIFO with no writer blocks forever.
  std::error_code error;
  const std::filesystem::file_type type = std::filesystem::status(path, error).type();
  if (type == std::filesystem::file_type::directory)
    throw SceneError(source, "expected a scene file, found a directory");
  if (type != std::filesystem::file_type::regular && type != std::filesystem::file_type::not_found &&
      type != std::filesystem::file_type::none)
    throw SceneError(source, fmt::format("expected a regular scene file, found {}", describe(type)));
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw SceneError(source, fmt::format("cannot open the scene file: {}",
                                         std::error_code(errno, std::generic_category()).message()));
  }
  // Read in one piece into a string of the file's size (a stream copied into a string grew it by doubling,
  // then copied it once more); a file that changes size meanwhile is read to its end all the same.
  std::string text;
  std::array<char, 1 << 16> chunk;
  if (const auto size = std::filesystem::file_size(path, error); !error) text.reserve(size);
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0)
    text.append(chunk.data(), std::size_t(in.gcount()));
  if (in.bad()) throw SceneError(source, "cannot read the scene file");
  return parseNff(text, source, options);
}

}  // namespace raycube::core
