#include "core/nff_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <optional>
#include <system_error>
#include <vector>

#include "core/ray.h"

namespace raycube::core {

namespace {

// Sine of the angle between two edges (or between view direction and up) below which a normal or a
// camera basis is numerically meaningless. SPD prints 6 significant digits; real geometry sits far above
// (the teapot's thinnest patch corner has a sine of 0.09).
constexpr double kMinSine = 1e-9;

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

// What a line of numbers holds, for messages: its description, or a polygon's vertex, described only if a
// message needs it (formatted eagerly for each of sombrero 3's 97,000 vertices, it cost a fifth of the parse).
struct Subject {
  Subject(std::string_view description) : text(description) {}
  Subject(const char* description) : text(description) {}
  Subject(const std::string& description) : text(description) {}
  static Subject vertexOf(std::size_t vertex, std::size_t vertices, std::string_view keyword, int keywordLine,
                          std::string_view fields) {
    Subject s(fields);
    s.vertex = vertex;
    s.vertices = vertices;
    s.keyword = keyword;
    s.keywordLine = keywordLine;
    return s;
  }
  std::string str() const {
    if (vertex == 0) return std::string(text);
    return fmt::format("vertex {} of {} of the {} at line {} ({})", vertex, vertices, keyword, keywordLine, text);
  }

  std::string_view text;  // the description, or a vertex's fields ("x y z")
  std::size_t vertex = 0;  // 1-based; 0: not a vertex
  std::size_t vertices = 0;
  std::string_view keyword;
  int keywordLine = 0;
};

struct Token {
  std::string_view text;
  int column = 0;  // 1-based byte column
};

struct Line {
  int number = 0;     // 1-based
  int endColumn = 1;  // column just past the last character (before any comment)
  std::vector<Token> tokens;
};

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

class NffParser {
 public:
  NffParser(std::string_view text, std::string_view source) : source_(source) {
    std::size_t start = 0;
    while (true) {
      const std::size_t end = text.find('\n', start);
      lines_.push_back(
          text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
      if (end == std::string_view::npos) break;
      start = end + 1;
    }
  }

  Scene parse() {
    Scene scene;
    scene.name = std::filesystem::path(std::string(source_)).stem().string();
    scene.source = std::string(source_);
    while (std::optional<Line> line = nextLine()) {
      const std::string_view keyword = line->tokens[0].text;
      if (keyword == "v") {
        readView(*line, scene);
      } else if (keyword == "b") {
        const auto rgb = numbers<3>(*line, 1, "'b' (background red green blue)");
        scene.background = Color(rgb[0], rgb[1], rgb[2]);
      } else if (keyword == "l") {
        readLight(*line, scene);
      } else if (keyword == "f") {
        readMaterial(*line, scene);
      } else if (keyword == "s" || keyword == "c" || keyword == "p" || keyword == "pp") {
        requireObjectContext(*line, scene);
        Object object;
        object.material = static_cast<std::uint32_t>(scene.materials.size() - 1);
        object.line = line->number;
        if (keyword == "s") {
          readSphere(*line, object);
        } else if (keyword == "c") {
          readCone(*line, object);
        } else if (keyword == "p") {
          readPolygon(*line, object);
        } else {
          readPatch(*line, object);
        }
        scene.objects.push_back(std::move(object));
      } else {
        fail(
            line->number, line->tokens[0].column,
            fmt::format("expected one of the NFF keywords v, b, l, f, c, s, p, pp or a '#' comment, found {}",
                        quoted(keyword)));
      }
    }
    if (viewLine_ == 0) {
      failAtEnd("expected a 'v' block (from, at, up, angle, hither, resolution) before the first object");
    }
    return scene;
  }

 private:
  [[noreturn]] void fail(int line, int column, std::string_view message) const {
    throw SceneError(source_, line, column, message);
  }

  [[noreturn]] void failAtEnd(std::string_view expected) const {
    const int line = static_cast<int>(lines_.size());
    const int column = static_cast<int>(lines_.back().size()) + 1;
    fail(line, column, fmt::format("{}, found end of file", expected));
  }

  // Lines not yet consumed, blank or not: an upper bound on the vertices a file can still hold.
  std::size_t remainingLines() const { return lines_.size() - next_; }

  // The next line with a token, comments removed; nullopt at end of file.
  std::optional<Line> nextLine() {
    while (next_ < lines_.size()) {
      std::string_view text = lines_[next_];
      Line line;
      line.number = static_cast<int>(++next_);
      if (const std::size_t hash = text.find('#'); hash != std::string_view::npos)
        text = text.substr(0, hash);
      std::size_t i = 0;
      while (i < text.size()) {
        if (isSpace(text[i])) {
          ++i;
          continue;
        }
        const std::size_t start = i;
        while (i < text.size() && !isSpace(text[i])) ++i;
        line.tokens.push_back({text.substr(start, i - start), static_cast<int>(start) + 1});
      }
      std::size_t end = text.size();
      while (end > 0 && isSpace(text[end - 1])) --end;
      line.endColumn = static_cast<int>(end) + 1;
      if (!line.tokens.empty()) return line;
    }
    return std::nullopt;
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

  // Exactly N numbers in tokens [first, first + N) and nothing after them.
  template <std::size_t N>
  std::array<double, N> numbers(const Line& line, std::size_t first, const Subject& what) const {
    const std::size_t got = line.tokens.size() - std::min(first, line.tokens.size());
    if (got < N) {
      fail(line.number, line.endColumn, fmt::format("expected {} numbers for {}, got {}", N, what.str(), got));
    }
    if (got > N) {
      fail(line.number, line.tokens[first + N].column,
           fmt::format("expected end of line after the {} numbers of {}, found {}", N, what.str(),
                       quoted(line.tokens[first + N].text)));
    }
    std::array<double, N> values{};
    for (std::size_t i = 0; i < N; ++i) values[i] = number(line, first + i, i, what);
    return values;
  }

  double number(const Line& line, std::size_t index, std::size_t position, const Subject& what) const {
    const Token& token = line.tokens[index];
    const std::optional<double> value = parseDouble(token.text);
    if (!value) {
      fail(line.number, token.column,
           fmt::format("expected a finite number as the {} value of {}, found {}", ordinal(position), what.str(),
                       quoted(token.text)));
    }
    return *value;
  }

  static Vec3 vec(const double* v) { return Vec3(v[0], v[1], v[2]); }

  // The keyword line that must come next, e.g. "from" inside the "v" block.
  Line expectKeywordLine(std::string_view keyword, std::string_view context) {
    std::optional<Line> line = nextLine();
    if (!line) failAtEnd(fmt::format("expected '{}' line of {}", keyword, context));
    if (line->tokens[0].text != keyword) {
      fail(line->number, line->tokens[0].column,
           fmt::format("expected '{}' line of {}, found {}", keyword, context, quoted(line->tokens[0].text)));
    }
    return *std::move(line);
  }

  // A line holding exactly N numbers, e.g. a polygon vertex.
  template <std::size_t N>
  std::pair<std::array<double, N>, Line> expectNumberLine(const Subject& what) {
    std::optional<Line> line = nextLine();
    if (!line) failAtEnd(fmt::format("expected {} numbers for {}", N, what.str()));
    if (!parseDouble(line->tokens[0].text)) {
      fail(line->number, line->tokens[0].column,
           fmt::format("expected {} numbers for {}, found {}", N, what.str(), quoted(line->tokens[0].text)));
    }
    auto values = numbers<N>(*line, 0, what);
    return {values, *std::move(line)};
  }

  void expectEndOfLine(const Line& line, std::size_t count, std::string_view what) const {
    if (line.tokens.size() > count) {
      fail(line.number, line.tokens[count].column,
           fmt::format("expected end of line after {}, found {}", what, quoted(line.tokens[count].text)));
    }
  }

  void readView(const Line& v, Scene& scene) {
    if (viewLine_ != 0) {
      fail(v.number, v.tokens[0].column,
           fmt::format("expected a single 'v' block, found a second one (the first is at line {})",
                       viewLine_));
    }
    expectEndOfLine(v, 1, "'v' (the view parameters go on the next six lines)");
    viewLine_ = v.number;
    scene.camera.line = v.number;
    const std::string context = fmt::format("the 'v' block started at line {}", v.number);
    Camera& camera = scene.camera;

    const Line fromLine = expectKeywordLine("from", context);
    camera.from = vec(numbers<3>(fromLine, 1, "'from' (eye x y z)").data());
    const Line atLine = expectKeywordLine("at", context);
    camera.at = vec(numbers<3>(atLine, 1, "'at' (look-at x y z)").data());
    if (camera.at == camera.from) {
      fail(atLine.number, atLine.tokens[1].column,
           "expected 'at' to differ from 'from', found the same point");
    }
    const Line upLine = expectKeywordLine("up", context);
    camera.up = vec(numbers<3>(upLine, 1, "'up' (x y z)").data());
    if (!(sineBetween(camera.at - camera.from, camera.up) > kMinSine)) {
      fail(upLine.number, upLine.tokens[1].column,
           "expected an 'up' vector that is non-zero and not parallel to the view direction (at - from)");
    }
    const Line angleLine = expectKeywordLine("angle", context);
    camera.angleDegrees = numbers<1>(angleLine, 1, "'angle' (field of view in degrees)")[0];
    if (!(camera.angleDegrees > 0 && camera.angleDegrees < 180)) {
      fail(angleLine.number, angleLine.tokens[1].column,
           fmt::format("expected an 'angle' strictly between 0 and 180 degrees, found {}",
                       camera.angleDegrees));
    }
    const Line hitherLine = expectKeywordLine("hither", context);
    camera.hither = numbers<1>(hitherLine, 1, "'hither' (distance of the near plane)")[0];
    if (camera.hither < 0) {
      fail(hitherLine.number, hitherLine.tokens[1].column,
           fmt::format("expected a 'hither' distance >= 0, found {}", camera.hither));
    }
    const Line resolution = expectKeywordLine("resolution", context);
    std::array<int, 2> size{};
    for (std::size_t i = 0; i < 2; ++i) {
      if (resolution.tokens.size() <= i + 1) {
        fail(resolution.number, resolution.endColumn,
             fmt::format("expected 2 positive integers for 'resolution' (width height), got {}", i));
      }
      const Token& token = resolution.tokens[i + 1];
      const std::optional<long long> value = parseInteger(token.text);
      if (!value || *value <= 0 || *value > kMaxNffResolution) {
        fail(resolution.number, token.column,
             fmt::format("expected a whole number of pixels from 1 to {} as the 'resolution' {}, found {}",
                         kMaxNffResolution, i == 0 ? "width" : "height", quoted(token.text)));
      }
      size[i] = static_cast<int>(*value);
    }
    expectEndOfLine(resolution, 3, "'resolution' width height");
    camera.width = size[0];
    camera.height = size[1];
  }

  void readLight(const Line& line, Scene& scene) {
    if (scene.lights.size() >= kMaxLights) {
      fail(line.number, line.tokens[0].column,
           fmt::format("expected at most {} lights (a ray names its light in 16 bits), found one more",
                       kMaxLights));
    }
    Light light;
    light.line = line.number;
    if (line.tokens.size() == 4) {
      light.position = vec(numbers<3>(line, 1, "'l' (light x y z [r g b])").data());
    } else if (line.tokens.size() == 7) {
      const auto values = numbers<6>(line, 1, "'l' (light x y z r g b)");
      light.position = vec(values.data());
      light.color = vec(values.data() + 3);
      light.hasColor = true;
    } else {
      const std::size_t got = line.tokens.size() - 1;
      fail(line.number, got < 3 ? line.endColumn : line.tokens[got < 6 ? 4 : 7].column,
           fmt::format("expected 3 or 6 numbers after 'l' (x y z [r g b]), got {}", got));
    }
    scene.lights.push_back(light);
  }

  void readMaterial(const Line& line, Scene& scene) {
    const auto f = numbers<8>(line, 1, "'f' (red green blue Kd Ks Shine T index_of_refraction)");
    Material material;
    material.color = Color(f[0], f[1], f[2]);
    material.kd = f[3];
    material.ks = f[4];
    material.shine = f[5];
    material.transmission = f[6];
    material.ior = f[7];
    // SPD writes an index of 0 for opaque materials; only light that is transmitted needs a real one.
    if (material.transmission > 0 && material.ior <= 0) {
      fail(
          line.number, line.tokens[8].column,
          fmt::format("expected a positive index of refraction for a transmitting material (T > 0), found {}",
                      material.ior));
    }
    if (scene.materials.size() >= std::numeric_limits<std::uint32_t>::max()) {
      fail(line.number, line.tokens[0].column, "expected fewer than 2^32 materials");
    }
    scene.materials.push_back(material);
  }

  void requireObjectContext(const Line& line, const Scene& scene) const {
    const Token& keyword = line.tokens[0];
    if (viewLine_ == 0) {
      fail(line.number, keyword.column,
           fmt::format("expected the 'v' block (viewpoint) before the first object, found {}",
                       quoted(keyword.text)));
    }
    if (scene.materials.empty()) {
      fail(line.number, keyword.column,
           fmt::format("expected an 'f' line (material) before the first object, found {}",
                       quoted(keyword.text)));
    }
  }

  void readSphere(const Line& line, Object& object) {
    const auto s = numbers<4>(line, 1, "'s' (center x y z radius)");
    if (s[3] == 0) fail(line.number, line.tokens[4].column, "expected a non-zero sphere radius, found 0");
    object.insideVisible = s[3] < 0;
    object.shape = Sphere{vec(s.data()), std::abs(s[3])};
  }

  void readCone(const Line& line, Object& object) {
    std::array<double, 8> c{};
    int radiusLine = line.number;
    int radiusColumn = line.tokens[0].column;
    if (line.tokens.size() == 9) {
      c = numbers<8>(line, 1, "'c' (base x y z radius apex x y z radius)");
    } else if (line.tokens.size() == 1) {
      const std::string context =
          fmt::format("the cone base of the 'c' at line {} (x y z radius)", line.number);
      const auto [base, baseLine] = expectNumberLine<4>(context);
      const std::string apexContext =
          fmt::format("the cone apex of the 'c' at line {} (x y z radius)", line.number);
      const auto [apex, apexLine] = expectNumberLine<4>(apexContext);
      std::copy(base.begin(), base.end(), c.begin());
      std::copy(apex.begin(), apex.end(), c.begin() + 4);
      radiusLine = baseLine.number;
      radiusColumn = baseLine.tokens[3].column;
    } else {
      fail(
          line.number, line.tokens[1].column,
          fmt::format("expected 8 numbers after 'c', or none and base and apex on the next two lines, got {}",
                      line.tokens.size() - 1));
    }
    Cone cone{vec(c.data()), c[3], vec(c.data() + 4), c[7]};
    if (cone.base == cone.apex) {
      fail(line.number, line.tokens[0].column, "expected distinct cone base and apex, found the same point");
    }
    const bool negative = cone.baseRadius < 0 || cone.apexRadius < 0;
    const bool positive = cone.baseRadius > 0 || cone.apexRadius > 0;
    if (negative && positive) {
      fail(
          radiusLine, radiusColumn,
          fmt::format("expected cone radii of one sign (both negative means inside visible), found {} and {}",
                      cone.baseRadius, cone.apexRadius));
    }
    if (!negative && !positive)
      fail(radiusLine, radiusColumn, "expected a non-zero cone radius, found both 0");
    object.insideVisible = negative;
    cone.baseRadius = std::abs(cone.baseRadius);
    cone.apexRadius = std::abs(cone.apexRadius);
    object.shape = cone;
  }

  // "p N" or "pp N": N >= 3, and no more than the file can still hold (guards memory on a corrupt count).
  std::size_t vertexCount(const Line& line, std::string_view what) const {
    if (line.tokens.size() < 2) {
      fail(line.number, line.endColumn,
           fmt::format("expected a vertex count after {}, found end of line", what));
    }
    const Token& token = line.tokens[1];
    const std::optional<long long> count = parseInteger(token.text);
    if (!count) {
      fail(line.number, token.column,
           fmt::format("expected a whole vertex count after {}, found {}", what, quoted(token.text)));
    }
    if (*count < 3) {
      fail(line.number, token.column,
           fmt::format("expected at least 3 vertices for {}, found {}", what, *count));
    }
    if (static_cast<unsigned long long>(*count) > remainingLines()) {
      fail(line.number, token.column,
           fmt::format("expected {} vertex lines after {}, but the file has only {} lines left", *count, what,
                       remainingLines()));
    }
    expectEndOfLine(line, 2, fmt::format("{} vertex count", what));
    return static_cast<std::size_t>(*count);
  }

  void requirePlanarNormal(const Line& line, const std::vector<Vec3>& vertices, std::string_view what) const {
    if (!(sineBetween(vertices[1] - vertices[0], vertices[2] - vertices[0]) > kMinSine)) {
      fail(line.number, line.tokens[0].column,
           fmt::format(
               "expected {} whose first three vertices span a plane (they define its normal), found them "
               "coincident or collinear",
               what));
    }
  }

  void readPolygon(const Line& line, Object& object) {
    const std::size_t count = vertexCount(line, "'p'");
    std::vector<Vec3> vertices;
    vertices.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      const auto [v, vertexLine] = expectNumberLine<3>(Subject::vertexOf(i + 1, count, "'p'", line.number, "x y z"));
      vertices.push_back(vec(v.data()));
    }
    requirePlanarNormal(line, vertices, "a polygon");
    object.shape = Polygon(std::move(vertices));
  }

  void readPatch(const Line& line, Object& object) {
    const std::size_t count = vertexCount(line, "'pp'");
    Patch patch;
    patch.vertices.reserve(count);
    patch.normals.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      const auto [v, vertexLine] =
          expectNumberLine<6>(Subject::vertexOf(i + 1, count, "'pp'", line.number, "x y z nx ny nz"));
      Vec3 normal = vec(v.data() + 3);
      // Scale by the largest component first so tiny but valid normals do not underflow.
      const double largest = std::max({std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)});
      if (largest == 0) {
        fail(vertexLine.number, vertexLine.tokens[3].column,
             fmt::format("expected a non-zero normal for vertex {} of the 'pp' at line {}, found 0 0 0",
                         i + 1, line.number));
      }
      patch.vertices.push_back(vec(v.data()));
      patch.normals.push_back(glm::normalize(normal / largest));
    }
    requirePlanarNormal(line, patch.vertices, "a patch");
    object.shape = std::move(patch);
  }

  std::string_view source_;
  std::vector<std::string_view> lines_;
  std::size_t next_ = 0;  // index of the next unread line
  int viewLine_ = 0;      // line of the "v" block, 0 before it
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

Scene parseNff(std::string_view text, std::string_view sourceName) {
  return NffParser(text, sourceName).parse();
}

Scene readNff(const std::filesystem::path& path) {
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
  while (in.read(chunk.data(), chunk.size()) || in.gcount() > 0) text.append(chunk.data(), std::size_t(in.gcount()));
  if (in.bad()) throw SceneError(source, "cannot read the scene file");
  return parseNff(text, source);
}

}  // namespace raycube::core
