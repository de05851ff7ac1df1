// What travels between the host and a rank (host/engines/machine_wire.h) comes back exactly as it left: the
// context, every field of a setup with its region database (every kind of shape), and the reports; a
// message cut short is an error, never a read past its end.
#include "host/engines/machine_wire.h"

#include <gtest/gtest.h>

#include <cstring>

#include "core/spd/balls.h"
#include "node/region_database.h"

namespace raycube::host {
namespace {

// Balls 1 (spheres and a polygon) with a cone and a patch added.
core::Scene everyShape() {
  core::Scene scene = core::makeBalls(1);
  scene.objects.push_back(core::Object{core::Cone{{0, 0, 0}, 0.5, {0, 1, 0}, 0.25}, 0, false, 7});
  scene.objects.push_back(core::Object{
      core::Patch{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 0, 1}, {0.6, 0, 0.8}}}, 0, true, 9});
  return scene;
}

node::MachineContext contextOf(const core::Scene& scene) {
  const core::View view(scene.camera, 20, 12, core::Sampling::Corners, 2);
  return node::MachineContext{view,
                              core::ShadingOptions{4, 0.01, 2},
                              node::RegionMap::grid({0, 7, 21}, {0, 5, 13}, node::ScreenLines(view)),
                              {core::Box{{-1, -2, -3}, {1, 0.5, 0}}, core::Box{{2, 2, 2}, {3, 4, 5}}},
                              {core::Box{{-1, -2, -3}, {0, 0.5, 0}}, core::Box{},
                               core::Box{{2, 2, 2}, {3, 4, 4}}, core::Box{{0, 1, 2}, {3, 4, 5}}}};
}

node::NodeSetup setupOf(const core::Scene& scene, const node::MachineContext& context) {
  node::NodeSetup s;
  s.id = 3;
  s.cells = node::CellStructure::Bvh;
  s.cellLevel = 1;
  std::vector<node::EyeBox> boxes;
  for (const core::Object& o : scene.objects) boxes.push_back(node::eyeBoxOf(o, context.view, 100));
  s.objects = {1, 4, std::uint32_t(scene.objects.size() - 2), std::uint32_t(scene.objects.size() - 1)};
  s.rearObjects = {0};
  s.lightRays = node::LightRayMode::Pyramid;
  s.lightSources.eyeBox.extend(core::Vec3(1, 2, 3));
  s.lightSources.corners = {core::Vec3(4, 5, 6)};
  // The paper's cells in emulated time: each light's volume travels, for its cells.
  s.lightRaysWalkCells = true;
  s.lightSources.volumeObjects = {{1, 4}, {}};
  s.lightSources.volumeBoxes = {node::eyeBoxesOf(boxes, {1, 4}), {}};
  // Light volumes holding objects 2, 3 and 5 besides the region's (only their counts travel).
  std::vector<std::uint32_t> lightObjects{2, 3, 5};
  s.lightObjects = 3;
  s.extraLightObjects = 3;
  std::vector<std::uint32_t>* lists[] = {&s.objects, &s.rearObjects, &lightObjects};
  s.objectBoxes = node::eyeBoxesOf(boxes, s.objects);
  s.database = std::make_shared<const node::RegionDatabase>(node::gatherRegionDatabase(scene, lists));
  return s;
}

template <class T>
bool sameBytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

void expectSameObject(const core::Object& a, const core::Object& b) {
  ASSERT_EQ(a.shape.index(), b.shape.index());
  EXPECT_EQ(a.material, b.material);
  EXPECT_EQ(a.insideVisible, b.insideVisible);
  EXPECT_EQ(a.line, b.line);
  if (const auto* s = std::get_if<core::Sphere>(&a.shape)) {
    EXPECT_TRUE(sameBytes(*s, std::get<core::Sphere>(b.shape)));
  }
  if (const auto* c = std::get_if<core::Cone>(&a.shape)) {
    EXPECT_TRUE(sameBytes(*c, std::get<core::Cone>(b.shape)));
  }
  if (const auto* p = std::get_if<core::Polygon>(&a.shape)) {
    EXPECT_EQ(p->vertices, std::get<core::Polygon>(b.shape).vertices);
  }
  if (const auto* p = std::get_if<core::Patch>(&a.shape)) {
    EXPECT_EQ(p->vertices, std::get<core::Patch>(b.shape).vertices);
    EXPECT_EQ(p->normals, std::get<core::Patch>(b.shape).normals);
  }
}

TEST(MachineWireTest, JobComesBackAsItLeft) {
  const core::Scene scene = everyShape();
  const node::MachineContext context = contextOf(scene);
  const node::NodeSetup setup = setupOf(scene, context);
  JobSettings settings;
  settings.precision = core::Precision::Float;
  settings.queueCapacity = 3;
  settings.rayBatch = 5;
  settings.jitterSeed = 11;
  settings.rankOf = {1, 1, 2, 2};
  const std::vector<char> bytes = encodeJob(settings, context, std::span(&setup, 1));
  const MachineJob job = decodeJob(bytes);

  EXPECT_EQ(job.settings.precision, core::Precision::Float);
  EXPECT_EQ(job.settings.queueCapacity, 3u);
  EXPECT_EQ(job.settings.rayBatch, 5u);
  EXPECT_EQ(job.settings.jitterSeed, 11u);
  EXPECT_EQ(job.settings.rankOf, settings.rankOf);
  EXPECT_TRUE(sameBytes(job.context.view, context.view));
  EXPECT_TRUE(sameBytes(job.context.shading, context.shading));
  ASSERT_EQ(job.context.regions.processors(), 4);
  EXPECT_EQ(job.context.regions.gridColumns(), context.regions.gridColumns());
  ASSERT_EQ(job.context.sceneBounds.size(), context.sceneBounds.size());
  for (std::size_t b = 0; b < context.sceneBounds.size(); ++b)
    EXPECT_TRUE(sameBytes(job.context.sceneBounds[b], context.sceneBounds[b]));
  ASSERT_EQ(job.context.regionBounds.size(), context.regionBounds.size());
  for (std::size_t b = 0; b < context.regionBounds.size(); ++b)
    EXPECT_TRUE(sameBytes(job.context.regionBounds[b], context.regionBounds[b]));
  for (int p = 0; p < 4; ++p) {
    EXPECT_TRUE(sameBytes(job.context.regions.areaOf(p), context.regions.areaOf(p)));
    EXPECT_EQ(job.context.regions.neighbours(p), context.regions.neighbours(p));
  }
  for (int axis = 0; axis < 2; ++axis)
    for (int k = 0; k <= context.lines().samples(axis); ++k)
      EXPECT_EQ(job.context.lines().at(axis, k), context.lines().at(axis, k));

  ASSERT_EQ(job.setups.size(), 1u);
  const node::NodeSetup& s = job.setups[0];
  EXPECT_EQ(s.id, setup.id);
  EXPECT_EQ(s.cells, setup.cells);
  EXPECT_EQ(s.cellLevel, setup.cellLevel);
  EXPECT_EQ(s.objects, setup.objects);
  EXPECT_EQ(s.rearObjects, setup.rearObjects);
  EXPECT_EQ(s.lightRays, setup.lightRays);
  EXPECT_TRUE(sameBytes(s.lightSources.eyeBox, setup.lightSources.eyeBox));
  EXPECT_EQ(s.lightSources.corners, setup.lightSources.corners);
  EXPECT_EQ(s.lightRaysWalkCells, setup.lightRaysWalkCells);
  EXPECT_EQ(s.lightSources.volumeObjects, setup.lightSources.volumeObjects);
  ASSERT_EQ(s.lightSources.volumeBoxes.size(), 2u);
  ASSERT_EQ(s.lightSources.volumeBoxes[0].size(), 2u);
  EXPECT_TRUE(sameBytes(s.lightSources.volumeBoxes[0][1], setup.lightSources.volumeBoxes[0][1]));
  EXPECT_EQ(s.lightObjects, setup.lightObjects);
  EXPECT_EQ(s.extraLightObjects, setup.extraLightObjects);
  EXPECT_EQ(s.database->globalIds, setup.database->globalIds);
  ASSERT_EQ(s.objectBoxes.size(), setup.objectBoxes.size());
  for (std::size_t k = 0; k < s.objectBoxes.size(); ++k)
    EXPECT_TRUE(sameBytes(s.objectBoxes[k], setup.objectBoxes[k]));
  const core::Scene& held = s.database->scene;
  EXPECT_EQ(held.name, scene.name);
  // Field by field: the camera has padding, which no copy need keep.
  EXPECT_EQ(held.camera.from, scene.camera.from);
  EXPECT_EQ(held.camera.at, scene.camera.at);
  EXPECT_EQ(held.camera.up, scene.camera.up);
  EXPECT_EQ(held.camera.angleDegrees, scene.camera.angleDegrees);
  EXPECT_EQ(held.camera.hither, scene.camera.hither);
  EXPECT_EQ(held.camera.width, scene.camera.width);
  EXPECT_EQ(held.camera.height, scene.camera.height);
  EXPECT_EQ(held.camera.line, scene.camera.line);
  EXPECT_EQ(held.lights.size(), scene.lights.size());
  EXPECT_EQ(held.materials.size(), scene.materials.size());
  ASSERT_EQ(held.objects.size(), setup.database->scene.objects.size());
  for (std::size_t k = 0; k < held.objects.size(); ++k)
    expectSameObject(held.objects[k], setup.database->scene.objects[k]);
  // The cone and the patch are among the objects held (the last two of the scene).
  EXPECT_EQ(held.objects.back().shape.index(), 3u);
}

TEST(MachineWireTest, SharedDatabaseTravelsOnceAndArrivesShared) {
  const core::Scene scene = everyShape();
  const node::MachineContext context = contextOf(scene);
  std::vector<node::NodeSetup> setups(3, setupOf(scene, context));
  setups[1].id = 4;
  setups[2] = setupOf(scene, context);  // the same objects, but a copy of its own
  setups[2].id = 5;
  const std::vector<char> one = encodeJob(JobSettings{}, context, std::span(setups.data(), 1));
  const std::vector<char> two = encodeJob(JobSettings{}, context, std::span(setups.data(), 2));
  const std::vector<char> three = encodeJob(JobSettings{}, context, setups);
  const std::size_t databaseBytes = three.size() - two.size() - (two.size() - one.size());
  EXPECT_GT(databaseBytes, 0u) << "a distinct database travels; a shared one does not travel again";
  const MachineJob job = decodeJob(three);
  ASSERT_EQ(job.setups.size(), 3u);
  EXPECT_EQ(job.setups[0].database, job.setups[1].database);
  EXPECT_NE(job.setups[0].database, job.setups[2].database);
  EXPECT_EQ(job.setups[2].database->globalIds, setups[2].database->globalIds);
}

TEST(MachineWireTest, ResultsComeBackAsTheyLeft) {
  RankResults results;
  results.rank.rank = 2;
  results.rank.processors = 1;
  results.rank.peakRssBytes = 123456;
  ProcessorReport p;
  p.node.id = 7;
  p.node.sent = {1, 2, 3, 4};
  p.idleSeconds = 0.5;
  results.processors = {p};
  const RankResults back = decodeResults(encodeResults(results));
  EXPECT_TRUE(sameBytes(back.rank, results.rank));
  ASSERT_EQ(back.processors.size(), 1u);
  EXPECT_EQ(back.processors[0].node.id, 7);
  EXPECT_EQ(back.processors[0].node.sent, p.node.sent);
  EXPECT_EQ(back.processors[0].idleSeconds, 0.5);
}

TEST(MachineWireTest, MessageCutShortIsAnError) {
  const core::Scene scene = everyShape();
  const node::MachineContext context = contextOf(scene);
  const node::NodeSetup setup = setupOf(scene, context);
  const std::vector<char> bytes =
      encodeJob(JobSettings{.rankOf = {1, 1, 1, 1}}, context, std::span(&setup, 1));
  for (std::size_t cut : {std::size_t(0), std::size_t(3), bytes.size() / 2, bytes.size() - 1})
    EXPECT_THROW(decodeJob(std::span(bytes.data(), cut)), std::runtime_error) << "cut at " << cut;
}

// A database read in place names the host's scene by index: another address space has no such scene.
TEST(MachineWireTest, ADatabaseReadInPlaceDoesNotTravel) {
  const core::Scene scene = everyShape();
  const node::MachineContext context = contextOf(scene);
  node::NodeSetup setup = setupOf(scene, context);
  setup.database = std::make_shared<const node::RegionDatabase>(
      node::regionDatabaseIn(scene, scene.features(), {0, 1, 2}));
  EXPECT_THROW(encodeJob(JobSettings{}, context, std::span(&setup, 1)), std::logic_error);
}

}  // namespace
}  // namespace raycube::host
