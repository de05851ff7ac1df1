#include "core/nff_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/nff_writer.h"
#include "scene_equality.h"
#include "test_support.h"

namespace raycube::core {
namespace {

using testing_support::slurp;

const std::filesystem::path kScenes = testing_support::sourcePath("scenes");
const std::filesystem::path kInTheWild = testing_support::sourcePath("tests/data/nff");

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
  const char* where;    // "line:column"
  const char* phrase;   // part of the message a user acts on
  bool strict = false;  // refused only when read strictly (--strict)
};

std::ostream& operator<<(std::ostream& out, const BadCase& c) {
  return out << c.name;
}

class BadScene : public testing::TestWithParam<BadCase> {};

TEST_P(BadScene, ThrowsSceneErrorAtTheRightPlace) {
  const BadCase& c = GetParam();
  try {
    parseNff(c.text, "bad.nff", NffOptions{.strict = c.strict});
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
        BadCase{"TooFewNumbers", kHeader + "s 0 0 1\n", "9:8",
                "expected 4 numbers for the 's' at line 9 (center x y z radius), got 3, found end of file"},
        BadCase{"TooFewNumbersBeforeTheNextEntity", kHeader + "s 0 0 1\ns 0 0 0 1\n", "9:8",
                "got 3, found 's' at line 10"},
        BadCase{"TooManyNumbers", kHeader + "s 0 0 1 1 7\n", "9:11",
                "expected a keyword after the 's' at line 9 took its 4 numbers, found another number '7'"},
        BadCase{"MaterialShort", kView + "f 1 1 1 1 0 0 0\n", "8:16",
                "expected 8 numbers for the 'f' at line 8"},
        BadCase{"UnknownKeyword", kHeader + "sphere 0 0 0 1\n", "9:1", "found 'sphere'"},
        BadCase{"NaN", kHeader + "s 0 nan 0 1\n", "9:5", "expected a finite number"},
        BadCase{"Inf", kHeader + "s 0 0 0 inf\n", "9:9", "expected a finite number"},
        BadCase{"NegativeInfinity", kHeader + "p 3\n0 0 0\n1 0 -infinity\n0 1 0\n", "11:5", "finite number"},
        BadCase{"Overflow", kHeader + "s 1e999 0 0 1\n", "9:3", "finite number"},
        BadCase{"ZeroSphereRadius", kHeader + "s 0 0 0 0\n", "9:9", "non-zero sphere radius"},
        BadCase{"MixedConeRadii", kHeader + "c 0 0 0 1 0 0 1 -1\n", "9:9", "one sign"},
        BadCase{"ZeroConeRadii", kHeader + "c\n0 0 0 0\n0 0 1 0\n", "10:7", "non-zero cone radius"},
        BadCase{"CoincidentCone", kHeader + "c 0 0 0 1 0 0 0 0.5\n", "9:1", "distinct cone base and apex"},
        BadCase{
            "ConeMissingApex", kHeader + "c\n0 0 0 1\n", "10:8",
            "expected 8 numbers for the 'c' at line 9 (base x y z radius, apex x y z radius), got 4, found "
            "end of file"},
        BadCase{"ConeWrongCount", kHeader + "c 0 0 0 1\ns 0 0 0 1\n", "9:10", "got 4, found 's' at line 10"},
        BadCase{"PolygonTwoVertices", kHeader + "p 2\n0 0 0\n1 0 0\n", "9:3", "at least 3 vertices"},
        BadCase{"PolygonCollinear", kHeader + "p 3\n0 0 0\n1 0 0\n2 0 0\n", "9:1", "collinear", true},
        BadCase{"PolygonCoincident", kHeader + "p 4\n0 0 0\n0 0 0\n1 0 0\n1 1 0\n", "9:1", "collinear", true},
        // One vertex a line, one line short of a number: the error comes where the numbers run out, and
        // names the line that most likely lacks one.
        BadCase{"PolygonVertexShort", kHeader + "p 3\n0 0 0\n1 0\n0 1 0\n", "12:6",
                "vertex 3 of 3 of the 'p' at line 9 (x y z), got 2, found end of file (vertex 2 runs from "
                "line 11 to line 12: a number missing on line 11?)"},
        BadCase{"TruncatedPolygon", kHeader + "p 4\n0 0 0\n1 0 0\n", "11:6",
                "expected 3 numbers for vertex 3 of 4 of the 'p' at line 9 (x y z), found end of file"},
        BadCase{"TruncatedInlinePolygon", kHeader + "p 3 0 0 0 1 0 0", "9:16",
                "expected 3 numbers for vertex 3 of 3 of the 'p' at line 9 (x y z), found end of file"},
        BadCase{"TruncatedPolygonBeforeComments", kHeader + "p 4\n0 0 0\n1 0 0\n# end\n\n", "11:6",
                "vertex 3 of 4 of the 'p' at line 9 (x y z), found end of file"},
        BadCase{"PolygonRunsIntoNextEntity", kHeader + "p 4\n0 0 0\n1 0 0\ns 0 0 0 1\n", "11:6",
                "vertex 3 of 4 of the 'p' at line 9 (x y z), found 's' at line 12"},
        BadCase{
            "PolygonVertexCountTooSmall", kHeader + "p 3\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n", "13:1",
            "expected a keyword after the 'p' at line 9 took the 3 vertices its count gives, found another "
            "number '1'"},
        BadCase{"HugeVertexCount", kHeader + "p 999999999999\n0 0 0\n1 0 0\n0 1 0\n", "12:6",
                "vertex 4 of 999999999999 of the 'p' at line 9 (x y z), found end of file"},
        BadCase{"VertexCountOverflow", kHeader + "p 99999999999999999999999\n", "9:3", "whole vertex count"},
        BadCase{"VertexCountMissing", kHeader + "p\n", "9:2",
                "expected a vertex count after 'p', found end of file"},
        BadCase{"PatchZeroNormal", kHeader + "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n", "11:7",
                "non-zero normal"},
        BadCase{"PatchCollinear", kHeader + "pp 3\n0 0 0 0 0 1\n1 1 1 0 0 1\n2 2 2 0 0 1\n", "9:1",
                "collinear", true},
        BadCase{"PatchShortVertex", kHeader + "pp 3\n0 0 0 0 0 1\n1 0 0\n", "11:6",
                "expected 6 numbers for vertex 2 of 3 of the 'pp' at line 9 (x y z nx ny nz), got 3"},
        BadCase{"NoView", "f 1 1 1 1 0 0 0 1\n", "2:1", "expected a 'v' block"},
        BadCase{"EmptyFile", "", "1:1", "expected a 'v' block"},
        BadCase{"ObjectBeforeView", "f 1 1 1 1 0 0 0 1\ns 0 0 0 1\n" + kView, "2:1",
                "before the first object"},
        BadCase{"ObjectBeforeMaterial", kView + "s 0 0 0 1\n", "8:1", "expected an 'f' line"},
        BadCase{"ViewMissingHither", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 30\nresolution 4 4\n", "6:1",
                "expected 'hither' of the 'v' block started at line 1 (from, at, up, angle, hither, "
                "resolution, in "
                "this order), found 'resolution'"},
        BadCase{"ViewTruncated", "v\nfrom 0 0 5\nat 0 0 0\n", "4:1",
                "expected 'up' of the 'v' block started at line 1"},
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
                "7:13",
                "expected 2 positive integers for 'resolution' (width height), got 1, found end of file"},
        BadCase{"UpParallelToView", "v\nfrom 0 0 5\nat 0 0 0\nup 0 0 2\nangle 30\nhither 1\nresolution 4 4\n",
                "4:4", "not parallel"},
        BadCase{"FromEqualsAt", "v\nfrom 1 2 3\nat 1 2 3\nup 0 1 0\nangle 30\nhither 1\nresolution 4 4\n",
                "3:4", "differ from 'from'"},
        BadCase{"AngleOutOfRange", "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\nhither 1\nresolution 4 4\n",
                "5:7", "between 0 and 180"},
        BadCase{"LightFourNumbers", kHeader + "l 1 2 3 4\n", "9:10",
                "expected 6 numbers for the 'l' at line 9 (light x y z, and r g b when coloured), got 4"},
        BadCase{"LightColourMalformed", kHeader + "l 1 2 3 nan 1 1\n", "9:9",
                "expected a finite number as the fourth value of the 'l' at line 9"},
        // What NFF does not define stays refused, at the word: private keywords of other readers.
        BadCase{"PrivateFillKeyword", kHeader + "fp 1 1 1 1 0 0 0 1 0\n", "9:1",
                "expected one of the NFF keywords v, b, l, f, c, s, p, pp or a '#' comment, found 'fp'"},
        BadCase{"PrivateAreaLight", kHeader + "la 0 0 5 1 0 0 0 1 0\n", "9:1", "found 'la'"},
        BadCase{"PrivateTexture", kHeader + "tx marble.tx\ns 0 0 0 1\n", "9:1", "found 'tx'"},
        BadCase{
            "Sense8WorldToolKit", "nff\nversion 2.0\nmycube\n8\n", "1:1",
            "found Sense8 WorldToolKit's NFF, a different format under the same name (first line 'nff', then "
            "'version N')"},
        BadCase{"Sense8UpperCase", "NFF\nversion 1\n", "1:1", "Sense8 WorldToolKit"},
        BadCase{"VmprayCountNotANumber", kHeader + "number x\n", "9:8",
                "expected a whole number of objects after the 'number' at line 9 (VM_pRAY's object count), "
                "found 'x'"},
        BadCase{"VmprayBoxShort", kHeader + "g 0 1 0 1 0\ns 0 0 0 1\n", "9:12",
                "expected 6 numbers for the 'g' at line 9 (scene box xmin xmax ymin ymax zmin zmax), got 5"},
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
  const Scene tiny = parseNff(view("0 0 -5") +
                                  "f 1 1 1 1 0 0 0 0\np 3\n0 0 0\n1e-78 0 0\n0 1e-78 0\n"
                                  "pp 3\n0 0 0 0 0 1\n1e-300 0 0 0 0 1\n0 1e-300 0 0 0 1\n",
                              "tiny.nff");
  EXPECT_EQ(tiny.objects.size(), 2u);
  const std::string line = view("0 0 -5") + "f 1 1 1 1 0 0 0 0\np 3\n0 0 0\n1e-78 0 0\n2e-78 0 0\n";
  EXPECT_TRUE(parseNff(line, "line.nff").objects.empty());
  EXPECT_THROW(parseNff(line, "line.nff", NffOptions{.strict = true}), SceneError);
}

// ---- NFF as people wrote it (core/README.md, "NFF as raycube reads it") ----

// The reader normalises patch normals: a unit normal normalised again may move by an ulp or two.
constexpr double kRenormalised = 1e-15;

// NFF.TXT: "the rest of the line and possibly other lines contain further information about the entity".
TEST(NffInTheWild, AnyLayoutOfTheNumbersReadsAsOneEntityALine) {
  const Scene canonical = readNff(kInTheWild / "free_form_canonical.nff");
  ASSERT_EQ(canonical.objects.size(), 5u);
  EXPECT_TRUE(canonical.warnings.empty());
  const std::string freeForm = slurp(kInTheWild / "free_form.nff");
  ASSERT_NE(freeForm.find("\r\n"), std::string::npos) << "the file must keep its CRLF (.gitattributes)";
  ASSERT_NE(freeForm.find('\t'), std::string::npos);
  const Scene read = readNff(kInTheWild / "free_form.nff");
  EXPECT_TRUE(testing_support::sameScene(canonical, read));
  EXPECT_TRUE(read.warnings.empty());
  EXPECT_EQ(read.objects[1].line, 10);  // "s 0 0 0 0.5 s ..." holds two spheres, both of line 10
  EXPECT_EQ(read.objects[2].line, 10);
  EXPECT_TRUE(read.lights[1].hasColor);
  // The SPD readers' "up 0 1 0 angle 45 hither 0.01 resolution 512 512" on one line, and a file whose
  // every word stands on a line of its own.
  const std::string oneLineView =
      "v\nfrom 2.1 1.3 1.7\nat 0 0 0\nup 0 0 1 angle 45 hither 0.01 resolution 32 32\n";
  std::string words;
  std::istringstream in(slurp(kInTheWild / "free_form_canonical.nff"));
  for (std::string word; in >> word;) words += word + "\n";
  EXPECT_TRUE(testing_support::sameScene(canonical, parseNff(words, "words.nff")));
  const std::string text = slurp(kInTheWild / "free_form_canonical.nff");
  const std::size_t viewEnd = text.find("l 4 3 2");
  const Scene mixed =
      parseNff(text.substr(0, text.find("v\n")) + oneLineView + text.substr(viewEnd), "mixed.nff");
  EXPECT_TRUE(testing_support::sameScene(canonical, mixed));
}

TEST(NffInTheWild, AByteOrderMarkIsNoWord) {
  const Scene scene = parseNff("\xEF\xBB\xBF" + kHeader + "s 0 0 0 1\n", "bom.nff");
  EXPECT_EQ(scene.objects.size(), 1u);
  try {
    parseNff(
        "\xEF\xBB\xBF"
        "sphere\n",
        "bom.nff");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("bom.nff:1:1: ", 0), 0u)
        << e.what();  // columns as an editor shows them
  }
}

// A random scene of every kind of entity, with full-precision numbers (the writer prints each as the
// shortest text that reads back the same).
Scene randomScene(std::mt19937& random) {
  std::uniform_real_distribution<double> coordinate(-10, 10), unit(0, 1);
  const auto point = [&] { return Vec3(coordinate(random), coordinate(random), coordinate(random)); };
  Scene scene;
  scene.name = "random";
  scene.background = Color(unit(random), unit(random), unit(random));
  scene.camera.from = point();
  scene.camera.at = scene.camera.from + Vec3(0.5 + unit(random), unit(random), 0.25);
  scene.camera.up = Vec3(0, 0, 1);
  scene.camera.angleDegrees = 10 + 100 * unit(random);
  scene.camera.hither = unit(random);
  scene.camera.width = 1 + static_cast<int>(random() % 600);
  scene.camera.height = 1 + static_cast<int>(random() % 600);
  for (std::size_t i = random() % 4; i > 0; --i) {
    Light light;
    light.position = point();
    light.hasColor = random() % 2 == 0;
    if (light.hasColor) light.color = Color(unit(random), unit(random), unit(random));
    scene.lights.push_back(light);
  }
  const std::size_t objects = random() % 12;
  for (std::size_t i = 0; i < objects; ++i) {
    if (scene.materials.empty() || random() % 3 == 0) {
      scene.materials.push_back(Material{Color(unit(random), unit(random), unit(random)), unit(random),
                                         unit(random), 100 * unit(random), unit(random), 1 + unit(random)});
    }
    Object object;
    object.material = static_cast<std::uint32_t>(scene.materials.size() - 1);
    object.insideVisible = random() % 4 == 0;
    switch (random() % 4) {
      case 0:
        object.shape = Sphere{point(), 0.1 + unit(random)};
        break;
      case 1:
        object.shape = Cone{point(), 0.1 + unit(random), point(), unit(random)};
        break;
      case 2: {
        std::vector<Vec3> corners{point(), point(), point()};
        for (std::size_t extra = random() % 3; extra > 0; --extra) corners.push_back(point());
        object.insideVisible = false;
        object.shape = Polygon(std::move(corners));
        break;
      }
      default: {
        Patch patch;
        for (int v = 0; v < 3; ++v) {
          patch.vertices.push_back(point());
          patch.normals.push_back(glm::normalize(point()));
        }
        object.insideVisible = false;
        object.shape = std::move(patch);
      }
    }
    scene.objects.push_back(std::move(object));
  }
  return scene;
}

// The words of `text` (comments dropped), separated by random whitespace, line breaks and comments.
std::string relaidOut(const std::string& text, std::mt19937& random) {
  static const std::vector<std::string> kSeparators{" ",    "\t",      "\n",    "\r\n",           "  \t ",
                                                    "\n\n", " \r\n\t", "\v\f ", " # a comment\n", "\n#\n\t"};
  std::string out = random() % 2 ? kSeparators[random() % kSeparators.size()] : "";
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line.substr(0, line.find('#')));
    for (std::string word; words >> word;) out += word + kSeparators[random() % kSeparators.size()];
  }
  return out;
}

// Any scene nff_writer writes, its words laid out anew with any whitespace and line breaks between them,
// reads back as the same scene.
TEST(NffInTheWild, WrittenScenesReadBackTheSameWhateverTheLayout) {
  std::mt19937 random(45u);
  std::vector<Scene> scenes{readNff(kScenes / "balls1.nff"), readNff(kScenes / "jacks1.nff"),
                            readNff(kScenes / "teapot2.nff"),
                            readNff(kInTheWild / "free_form_canonical.nff")};
  for (int i = 0; i < 300; ++i) scenes.push_back(randomScene(random));
  int layouts = 0;
  for (const Scene& scene : scenes) {
    const std::string written = nffText(scene, "written by nff_reader_test");
    for (int layout = 0; layout < 3; ++layout) {
      const std::string text = relaidOut(written, random);
      SCOPED_TRACE(text.substr(0, 2000));
      const Scene read = parseNff(text, "relaid.nff");
      ASSERT_TRUE(testing_support::sameScene(scene, read, kRenormalised));
      ++layouts;
    }
  }
  EXPECT_EQ(layouts, 3 * 304);
}

// A polygon or patch whose first three vertices span no plane is skipped, counted, and warned about once;
// --strict refuses the file at the first, as before.
TEST(NffInTheWild, DegeneratePolygonsAreSkippedWithOneWarning) {
  const std::filesystem::path path = kInTheWild / "degenerate_mesh.nff";
  const Scene scene = readNff(path);
  ASSERT_EQ(scene.objects.size(), 6u);  // the ground, four triangles of the pyramid, the sphere
  EXPECT_EQ(countShapes<Patch>(scene), 4);
  EXPECT_EQ(countShapes<Polygon>(scene), 1);
  EXPECT_EQ(countShapes<Sphere>(scene), 1);
  EXPECT_EQ(scene.objects.back().line, 62);
  EXPECT_EQ(scene.objects.back().material, 2u);  // the skipped ones took no material with them
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0],
            "degenerate polygons: skipped 5 of the 10 polygons and patches, whose first three vertices are "
            "coincident or collinear (no plane, so no normal), the first at " +
                path.string() + ":38; --strict refuses the file instead");
  try {
    readNff(path, NffOptions{.strict = true});
    FAIL() << "a strict read accepted a degenerate patch";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              path.string() +
                  ":38:1: expected a patch whose first three vertices span a plane (they define its "
                  "normal), found them coincident or collinear");
  }
  // A degenerate view stays an error, strict or not.
  EXPECT_THROW(
      parseNff("v\nfrom 0 0 5\nat 0 0 5\nup 0 1 0\nangle 30\nhither 1\nresolution 4 4\n", "view.nff"),
      SceneError);
}

TEST(NffInTheWild, NoLightsIsWarnedAbout) {
  const std::filesystem::path path = kInTheWild / "no_lights.nff";
  const Scene scene = readNff(path);
  EXPECT_TRUE(scene.lights.empty());
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0],
            "no lights: " + path.string() +
                " has no 'l' line, so surfaces show the ambient term alone, at 0.5 (the SPD's "
                "sqrt(L)/(2L) at L = 1), rather than black");
  EXPECT_EQ(spdIntensity(0), 0.5);
  EXPECT_EQ(spdIntensity(1), 0.5);
  EXPECT_EQ(spdIntensity(4), 0.25);
}

// VM_pRAY's "number" and "g" are hints: read, checked, warned about when the file disagrees, never refused.
TEST(NffInTheWild, VmprayHintsAreCheckedNeverRefused) {
  const std::filesystem::path path = kInTheWild / "vmpray.nff";
  const std::string text = slurp(path);
  const Scene scene = parseNff(text, "vmpray.nff");
  EXPECT_EQ(scene.objects.size(), 4u);
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();

  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string changed = text;
    changed.replace(changed.find(from), from.size(), to);
    return changed;
  };
  const Scene miscounted = parseNff(replaced("number 4", "number 7"), "vmpray.nff");
  EXPECT_EQ(miscounted.objects.size(), 4u);
  ASSERT_EQ(miscounted.warnings.size(), 1u);
  EXPECT_EQ(miscounted.warnings[0], "VM_pRAY hint: vmpray.nff:10: 'number' gives 7 objects, the file has 4");

  const Scene small = parseNff(replaced("g -2 2 -2 2 -0.5 1.5", "g -2 2 -2 2 -0.5 1"), "vmpray.nff");
  ASSERT_EQ(small.warnings.size(), 1u);
  EXPECT_EQ(small.warnings[0],
            "VM_pRAY hint: vmpray.nff:11: the 'g' box does not hold the scene: the object at line 18 reaches "
            "out of it "
            "to z = 1.2 beyond zmax = 1");
  // A box printed with a few digits holds what it was computed for; a cone is held by its discs' true extent.
  EXPECT_TRUE(
      parseNff(replaced("g -2 2 -2 2 -0.5 1.5", "g -2 2 -2 2 -0.499999 1.2"), "v.nff").warnings.empty());
  // Anywhere in the file, more than once, in any layout.
  const Scene moved = parseNff(replaced("number 4\n", "") + "number\n5 g -1 1 -1 1 -1 1\n", "vmpray.nff");
  ASSERT_EQ(moved.warnings.size(), 2u);
  EXPECT_NE(moved.warnings[0].find("'number' gives 5 objects, the file has 4"), std::string::npos);
  EXPECT_NE(
      moved.warnings[1].find("4 of the 4 objects reach out of it, the first at line 15 to x = -1.3 beyond "
                             "xmin = -1"),
      std::string::npos)
      << moved.warnings[1];
  EXPECT_EQ(moved.objects.size(), 4u);
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
    EXPECT_EQ(
        std::string(e.what()).rfind(path.string() + ":9:8: expected 4 numbers for the 's' at line 9", 0), 0u)
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
