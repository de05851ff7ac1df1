#include "core/nff_reader.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace raycube::core {
namespace {

using testing_support::slurp;

const std::filesystem::path kScenes = testing_support::sourcePath("scenes");


// What the file holds, counted from its text alone (first word of each line), independent of the reader.
std::map<std::string, int> keywordCounts(const std::string& text) {
  std::map<std::string, int> counts;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string first;
    if (words >> first) ++counts[first];
  }
  return counts;
}

template <class T>
int countShapes(const Scene& scene) {
  int n = 0;
  for (const Object& object : scene.objects) n += std::holds_alternative<T>(object.shape) ? 1 : 0;
  return n;
}

class SharedScene : public testing::TestWithParam<const char*> {};

TEST_P(SharedScene, LoadsWithEveryEntityOfTheFile) {
  const std::filesystem::path path = kScenes / GetParam();
  const std::map<std::string, int> counts = keywordCounts(slurp(path));
  const auto count = [&](const char* keyword) {
    const auto it = counts.find(keyword);
    return it == counts.end() ? 0 : it->second;
  };
  const Scene scene = readNff(path);
  EXPECT_EQ(scene.name, path.stem().string());
  EXPECT_EQ(countShapes<Sphere>(scene), count("s"));
  EXPECT_EQ(countShapes<Polygon>(scene), count("p"));
  EXPECT_EQ(countShapes<Patch>(scene), count("pp"));
  EXPECT_EQ(countShapes<Cone>(scene), count("c"));
  EXPECT_EQ(static_cast<int>(scene.objects.size()), count("s") + count("p") + count("pp") + count("c"));
  EXPECT_EQ(static_cast<int>(scene.lights.size()), count("l"));
  EXPECT_EQ(static_cast<int>(scene.materials.size()), count("f"));
  EXPECT_GT(scene.camera.width, 0);
  for (const Object& object : scene.objects) {
    EXPECT_LT(object.material, scene.materials.size());
    EXPECT_FALSE(object.insideVisible);
  }
}

INSTANTIATE_TEST_SUITE_P(Spd, SharedScene,
                         testing::Values("balls1.nff", "balls2.nff", "balls3.nff", "balls4.nff", "gears1.nff",
                                         "jacks1.nff", "teapot2.nff", "tree1.nff"));

TEST(NffReader, ReadsBalls1Exactly) {
  const Scene scene = readNff(kScenes / "balls1.nff");
  EXPECT_EQ(scene.background, Color(0.078, 0.361, 0.753));
  EXPECT_EQ(scene.camera.from, Vec3(2.1, 1.3, 1.7));
  EXPECT_EQ(scene.camera.at, Vec3(0, 0, 0));
  EXPECT_EQ(scene.camera.up, Vec3(0, 0, 1));
  EXPECT_EQ(scene.camera.angleDegrees, 45);
  EXPECT_EQ(scene.camera.hither, 0.01);
  EXPECT_EQ(scene.camera.width, 512);
  EXPECT_EQ(scene.camera.height, 512);
  ASSERT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.lights[1].position, Vec3(1, -4, 4));
  EXPECT_FALSE(scene.lights[1].hasColor);
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[1].color, Color(1, 0.9, 0.7));
  EXPECT_EQ(scene.materials[1].ks, 0.5);
  EXPECT_EQ(scene.materials[1].shine, 3.0827);
  EXPECT_EQ(scene.materials[1].ior, 1);
  ASSERT_EQ(scene.objects.size(), 11u);
  EXPECT_EQ(scene.objects[0].material, 0u);
  const Corners& corners = std::get<Polygon>(scene.objects[0].shape).vertices;
  ASSERT_EQ(corners.size(), 4u);  // the ground quad
  EXPECT_EQ(corners[2], Vec3(-12, -12, -0.5));
  EXPECT_EQ(scene.objects[1].material, 1u);
  const auto& sphere = std::get<Sphere>(scene.objects[2].shape);
  EXPECT_EQ(sphere.center, Vec3(0.272166, 0.272166, 0.544331));
  EXPECT_EQ(sphere.radius, 0.166667);
}

TEST(NffReader, ReadsConesOnOneLineOrTwo) {
  const Scene jacks = readNff(kScenes / "jacks1.nff");
  const auto& cone = std::get<Cone>(jacks.objects.at(0).shape);
  EXPECT_EQ(cone.base, Vec3(-0.704769, -0.128258, -0.222149));
  EXPECT_EQ(cone.apexRadius, 0.075);

  const std::string header =
      "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4 4\nf 1 1 1 1 0 0 0 1\n";
  const Scene scene = parseNff(header + "c\n0 0 0 -2\n0 0 1 -1 # inside\n", "two.nff");
  const auto& split = std::get<Cone>(scene.objects.at(0).shape);
  EXPECT_EQ(split.base, Vec3(0, 0, 0));
  EXPECT_EQ(split.baseRadius, 2);
  EXPECT_EQ(split.apex, Vec3(0, 0, 1));
  EXPECT_EQ(split.apexRadius, 1);
  EXPECT_TRUE(scene.objects[0].insideVisible);
}

TEST(NffReader, ReadsPatchesColoredLightsCommentsAndInsideSpheres) {
  const std::string text =
      "# a comment line\n"
      "b 0.1 0.2 0.3   # trailing comment\n"
      "v\n"
      "from 0 0 5\r\n"  // CRLF lines too
      "at 0 0 0\n"
      "up 0 1 0\n"
      "angle 30\n"
      "hither 1\n"
      "resolution 64 32\n"
      "\n"
      "l 1 2 3 0.5 0.25 1\n"
      "f 1 1 1 1 0 0 0 1.5\n"
      "s 0 0 0 -2\n"
      "pp 3\n"
      "0 0 0 0 0 2\n"
      "\t1 0 0  0 0 3\n"
      "0 1 0 0 0 1\n";
  const Scene scene = parseNff(text, "dir/small.nff");
  EXPECT_EQ(scene.name, "small");
  EXPECT_EQ(scene.background, Color(0.1, 0.2, 0.3));
  EXPECT_EQ(scene.camera.width, 64);
  EXPECT_EQ(scene.camera.height, 32);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_TRUE(scene.lights[0].hasColor);
  EXPECT_EQ(scene.lights[0].color, Color(0.5, 0.25, 1));
  EXPECT_EQ(scene.materials.at(0).ior, 1.5);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_TRUE(scene.objects[0].insideVisible);
  EXPECT_EQ(std::get<Sphere>(scene.objects[0].shape).radius, 2);
  const auto& patch = std::get<Patch>(scene.objects[1].shape);
  ASSERT_EQ(patch.normals.size(), 3u);
  EXPECT_EQ(patch.normals[1], Vec3(0, 0, 1));  // normalised
}

// ---- errors: each category names file:line:column and says what was expected ----

const std::string kView =
    "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4 4\n";  // lines 1-7
const std::string kHeader = kView + "f 1 1 1 1 0 0 0 1\n";                      // line 8

struct BadCase {
  const char* name;
  std::string text;
  const char* where;   // "line:column"
  const char* phrase;  // part of the message a user acts on
};

std::ostream& operator<<(std::ostream& out, const BadCase& c) {
  return out << c.name;
}

class BadScene : public testing::TestWithParam<BadCase> {};

TEST_P(BadScene, ThrowsSceneErrorAtTheRightPlace) {
  const BadCase& c = GetParam();
  try {
    parseNff(c.text, "bad.nff");
    FAIL() << "accepted: " << c.text;
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(std::string("bad.nff:") + c.where + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.phrase), std::string::npos) << message;
    EXPECT_EQ(e.source(), "bad.nff");
    EXPECT_GT(e.line(), 0);
    EXPECT_GT(e.column(), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Categories, BadScene,
    testing::Values(
        BadCase{"MalformedNumber", kHeader + "s 0 0 1.2.3 1\n", "9:7", "found '1.2.3'"},
        BadCase{"NumberWithJunk", kHeader + "s 0 0 0 1x\n", "9:9", "found '1x'"},
        BadCase{"CommaDecimal", kHeader + "s 0,5 0 0 1\n", "9:3", "found '0,5'"},
        BadCase{"TooFewNumbers", kHeader + "s 0 0 1\n", "9:8", "expected 4 numbers for 's'"},
        BadCase{"TooManyNumbers", kHeader + "s 0 0 1 1 7\n", "9:11", "expected end of line"},
        BadCase{"MaterialShort", kView + "f 1 1 1 1 0 0 0\n", "8:16", "expected 8 numbers for 'f'"},
        BadCase{"UnknownKeyword", kHeader + "sphere 0 0 0 1\n", "9:1", "found 'sphere'"},
        BadCase{"NaN", kHeader + "s 0 nan 0 1\n", "9:5", "expected a finite number"},
        BadCase{"Inf", kHeader + "s 0 0 0 inf\n", "9:9", "expected a finite number"},
        BadCase{"NegativeInfinity", kHeader + "p 3\n0 0 0\n1 0 -infinity\n0 1 0\n", "11:5", "finite number"},
        BadCase{"Overflow", kHeader + "s 1e999 0 0 1\n", "9:3", "finite number"},
        BadCase{"ZeroSphereRadius", kHeader + "s 0 0 0 0\n", "9:9", "non-zero sphere radius"},
        BadCase{"MixedConeRadii", kHeader + "c 0 0 0 1 0 0 1 -1\n", "9:1", "one sign"},
        BadCase{"ZeroConeRadii", kHeader + "c\n0 0 0 0\n0 0 1 0\n", "10:7", "non-zero cone radius"},
        BadCase{"CoincidentCone", kHeader + "c 0 0 0 1 0 0 0 0.5\n", "9:1", "distinct cone base and apex"},
        BadCase{"ConeMissingApex", kHeader + "c\n0 0 0 1\n", "11:1",
                "cone apex of the 'c' at line 9 (x y z radius), found end of file"},
        BadCase{"ConeWrongCount", kHeader + "c 0 0 0 1\n", "9:3", "expected 8 numbers after 'c'"},
        BadCase{"PolygonTwoVertices", kHeader + "p 2\n0 0 0\n1 0 0\n", "9:3", "at least 3 vertices"},
        BadCase{"PolygonCollinear", kHeader + "p 3\n0 0 0\n1 0 0\n2 0 0\n", "9:1", "collinear"},
        BadCase{"PolygonCoincident", kHeader + "p 4\n0 0 0\n0 0 0\n1 0 0\n1 1 0\n", "9:1", "collinear"},
        BadCase{"PolygonVertexShort", kHeader + "p 3\n0 0 0\n1 0\n0 1 0\n", "11:4", "vertex 2 of 3"},
        BadCase{"TruncatedPolygon", kHeader + "p 4\n0 0 0\n1 0 0\n", "9:3",
                "expected 4 vertex lines after 'p'"},
        BadCase{"TruncatedPolygonBeforeComments", kHeader + "p 4\n0 0 0\n1 0 0\n# end\n\n", "14:1",
                "vertex 3 of 4 of the 'p' at line 9 (x y z), found end of file"},
        BadCase{"PolygonRunsIntoNextEntity", kHeader + "p 4\n0 0 0\n1 0 0\ns 0 0 0 1\n", "12:1",
                "vertex 3 of 4 of the 'p' at line 9 (x y z), found 's'"},
        BadCase{"HugeVertexCount", kHeader + "p 999999999999\n0 0 0\n1 0 0\n0 1 0\n", "9:3", "lines left"},
        BadCase{"VertexCountOverflow", kHeader + "p 99999999999999999999999\n", "9:3", "whole vertex count"},
        BadCase{"VertexCountMissing", kHeader + "p\n", "9:2", "expected a vertex count"},
        BadCase{"PatchZeroNormal", kHeader + "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n", "11:7",
                "non-zero normal"},
        BadCase{"PatchCollinear", kHeader + "pp 3\n0 0 0 0 0 1\n1 1 1 0 0 1\n2 2 2 0 0 1\n", "9:1",
                "collinear"},
        BadCase{"PatchShortVertex", kHeader + "pp 3\n0 0 0 0 0 1\n1 0 0\n", "11:6", "expected 6 numbers"},
        BadCase{"NoView", "f 1 1 1 1 0 0 0 1\n", "2:1", "expected a 'v' block"},
        BadCase{"EmptyFile", "", "1:1", "expected a 'v' block"},
        BadCase{"ObjectBeforeView", "f 1 1 1 1 0 0 0 1\ns 0 0 0 1\n" + kView, "2:1",
                "before the first object"},
        BadCase{"ObjectBeforeMaterial", kView + "s 0 0 0 1\n", "8:1", "expected an 'f' line"},
        BadCase{"ViewMissingHither", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nresolution 4 4\n", "6:1",
                "expected 'hither' line of the 'v' block started at line 1, found 'resolution'"},
        BadCase{"ViewTruncated", "v\nfrom 0 0 5\nat 0 0 0\n", "4:1", "expected 'up' line"},
        BadCase{"ViewTwice", kView + kView, "8:1", "second one"},
        BadCase{"ResolutionZero", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 0 4\n",
                "7:12", "whole number of pixels"},
        BadCase{"ResolutionNegative",
                "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4 -4\n", "7:14", "height"},
        BadCase{"ResolutionFraction",
                "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4.5 4\n", "7:12",
                "found '4.5'"},
        BadCase{"ResolutionHuge",
                "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4 99999999\n", "7:14",
                "whole number of pixels"},
        BadCase{"ResolutionMissing", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4\n",
                "7:13", "expected 2 positive integers"},
        BadCase{"UpParallelToView", "v\nfrom 0 0 5\nat 0 0 0\nup 0 0 2\nangle 30\nhither 1\nresolution 4 4\n",
                "4:4", "not parallel"},
        BadCase{"FromEqualsAt", "v\nfrom 1 2 3\nat 1 2 3\nup 0 1 0\nangle 30\nhither 1\nresolution 4 4\n",
                "3:4", "differ from 'from'"},
        BadCase{"AngleOutOfRange", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\nhither 1\nresolution 4 4\n",
                "5:7", "between 0 and 180"},
        BadCase{"LightFourNumbers", kHeader + "l 1 2 3 4\n", "9:9", "3 or 6 numbers"},
        BadCase{"BadIndexOfRefraction", kView + "f 1 1 1 1 0 0 0.5 0\n", "8:19", "index of refraction"}),
    [](const testing::TestParamInfo<BadCase>& info) { return std::string(info.param.name); });

TEST(NffReader, RejectsNanAndInfInEveryKindOfField) {
  for (const char* bad : {"nan", "NaN", "-nan", "nan(0x1)", "inf", "-Inf", "INFINITY", "1e999", "-1e400"}) {
    const std::string b(bad);
    for (const std::string& text : {
             "b 0 " + b + " 0\n" + kHeader,
             "v\nfrom 0 0 " + b + "\nat 0 0 0\nup 0 1 0\nangle 30\nhither 1\nresolution 4 4\n",
             "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle " + b + "\nhither 1\nresolution 4 4\n",
             kHeader + "l 1 2 3 1 " + b + " 1\n",
             kView + "f 1 1 1 " + b + " 0 0 0 1\n",
             kHeader + "s 0 0 0 " + b + "\n",
             kHeader + "c 0 0 0 1 0 " + b + " 1 1\n",
             kHeader + "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 " + b + " 1\n",
         }) {
      try {
        parseNff(text, "nan.nff");
        ADD_FAILURE() << "accepted " << bad << " in:\n" << text;
      } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("expected a finite number"), std::string::npos) << e.what();
      }
    }
  }
}

// Lengths are scaled before they are squared: an eye at 1e200 is not "parallel to up", a triangle at 1e-78
// is not "collinear".
TEST(NffReader, HugeAndTinyButValidGeometryIsAccepted) {
  const auto view = [](const char* from) {
    return std::string("v\nfrom ") + from + "\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0\nresolution 4 4\n";
  };
  EXPECT_NO_THROW(parseNff(view("0 0 -1e200") + "f 1 1 1 1 0 0 0 0\ns 0 0 0 1\n", "far.nff"));
  EXPECT_NO_THROW(parseNff(view("0 0 -1e-300") + "f 1 1 1 1 0 0 0 0\ns 0 0 0 1e-301\n", "near.nff"));
  const Scene tiny = parseNff(view("0 0 -5") + "f 1 1 1 1 0 0 0 0\np 3\n0 0 0\n1e-78 0 0\n0 1e-78 0\n"
                                               "pp 3\n0 0 0 0 0 1\n1e-300 0 0 0 0 1\n0 1e-300 0 0 0 1\n",
                              "tiny.nff");
  EXPECT_EQ(tiny.objects.size(), 2u);
  EXPECT_THROW(parseNff(view("0 0 -5") + "f 1 1 1 1 0 0 0 0\np 3\n0 0 0\n1e-78 0 0\n2e-78 0 0\n", "line.nff"),
               SceneError);
}

TEST(NffReader, MissingFileNamesThePath) {
  try {
    readNff("/nonexistent/raycube/nothing.nff");
    FAIL() << "opened a missing file";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/raycube/nothing.nff: cannot open"), std::string::npos)
        << e.what();
  }
}

TEST(NffReader, ErrorsInAFileNameTheFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "raycube_nff_reader_test_bad.nff";
  {
    std::ofstream out(path, std::ios::binary);
    out << kHeader << "s 0 0 0\n";
  }
  try {
    readNff(path);
    FAIL() << "accepted a sphere with 3 numbers";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path.string() + ":9:8: expected 4 numbers for 's'", 0), 0u)
        << e.what();
  }
  std::filesystem::remove(path);
}

// ---- fuzz: damaged files parse or throw SceneError; nothing else, no crash, no hang ----

// Returns "" when the text parsed or failed with SceneError (then sets rejected), else what went wrong.
std::string parseOutcome(const std::string& text, bool& rejected) {
  rejected = false;
  try {
    parseNff(text, "fuzz.nff");
  } catch (const SceneError& e) {
    rejected = true;
    if (std::string(e.what()).rfind("fuzz.nff:", 0) != 0) return std::string("bad message: ") + e.what();
  } catch (const std::exception& e) {
    return std::string("unexpected exception: ") + e.what();
  } catch (...) {
    return "unexpected non-std exception";
  }
  return "";
}

TEST(NffReaderFuzz, EveryTruncationOfBalls2) {
  const std::string text = slurp(kScenes / "balls2.nff");
  ASSERT_GT(text.size(), 1000u);
  int parsed = 0;
  for (std::size_t length = 0; length <= text.size(); ++length) {
    bool rejected = false;
    ASSERT_EQ(parseOutcome(text.substr(0, length), rejected), "") << "truncated at byte " << length;
    parsed += rejected ? 0 : 1;
  }
  EXPECT_GT(parsed, 0);  // cuts at a line end after the first sphere are valid scenes
  EXPECT_LT(parsed, static_cast<int>(text.size()));
}

TEST(NffReaderFuzz, RandomByteMutationsOfBalls2) {
  const std::string original = slurp(kScenes / "balls2.nff");
  ASSERT_FALSE(original.empty());
  std::mt19937 random(20240601u);
  // Bytes that steer the parser into its interesting corners, plus any byte at all.
  static constexpr char kInteresting[] = "0123456789-+.eE \t\n\r#vblfcsp nainfNAN\0\xff";
  const std::string interesting(kInteresting, sizeof kInteresting - 1);
  const auto pickByte = [&] {
    if (random() % 4 == 0) return static_cast<char>(random() % 256);
    return interesting[random() % interesting.size()];
  };
  int rejected = 0;
  constexpr int kMutants = 20000;
  for (int i = 0; i < kMutants; ++i) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = random() % (text.size() + 1);
      switch (random() % 4) {
        case 0:
          if (at < text.size()) text[at] = pickByte();
          break;
        case 1:
          text.insert(text.begin() + static_cast<std::ptrdiff_t>(at), pickByte());
          break;
        case 2:
          if (at < text.size()) text.erase(at, 1 + random() % 3);
          break;
        default: {  // duplicate or drop a whole line
          const std::size_t lineStart = text.rfind('\n', at == 0 ? 0 : at - 1);
          const std::size_t begin = lineStart == std::string::npos ? 0 : lineStart + 1;
          const std::size_t end = std::min(text.size(), text.find('\n', begin) + 1);
          if (begin >= end) break;
          const std::string line = text.substr(begin, end - begin);
          if (random() % 2) {
            text.erase(begin, end - begin);
          } else {
            text.insert(begin, line);
          }
        }
      }
    }
    bool wasRejected = false;
    ASSERT_EQ(parseOutcome(text, wasRejected), "") << "mutant " << i << ":\n" << text;
    rejected += wasRejected ? 1 : 0;
  }
  // The mutations must exercise both paths, or the test proves nothing.
  EXPECT_GT(rejected, kMutants / 10);
  EXPECT_LT(rejected, kMutants);
}

}  // namespace
}  // namespace raycube::core
