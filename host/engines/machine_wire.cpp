#include "host/engines/machine_wire.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <variant>

#include "core/overloaded.h"

namespace raycube::host {
namespace {

static_assert(std::is_trivially_copyable_v<core::View>, "the view travels as bytes");
static_assert(std::is_trivially_copyable_v<ProcessorReport>);
static_assert(std::is_trivially_copyable_v<RankReport>);

// ---- A database (3.2 step 1): objects, lights, materials and camera (a region's, see RegionDatabase).

void writeObject(WireWriter& out, const core::Object& object) {
  out.value(std::uint8_t(object.shape.index()));
  std::visit(core::Overloaded{[&](const core::Sphere& s) { out.value(s); },
                              [&](const core::Cone& c) { out.value(c); },
                              [&](const core::Polygon& p) { out.vector(p.vertices.toVector()); },
                              [&](const core::Patch& p) {
                                out.vector(p.vertices);
                                out.vector(p.normals);
                              }},
             object.shape);
  out.value(object.material);
  out.value(object.insideVisible);
  out.value(object.line);
}

core::Object readObject(WireReader& in) {
  core::Object object;
  switch (in.value<std::uint8_t>()) {
    case 0:
      object.shape = in.value<core::Sphere>();
      break;
    case 1:
      object.shape = in.value<core::Cone>();
      break;
    case 2:
      object.shape = core::Polygon{in.vector<core::Vec3>()};
      break;
    case 3: {
      core::Patch patch;
      patch.vertices = in.vector<core::Vec3>();
      patch.normals = in.vector<core::Vec3>();
      object.shape = std::move(patch);
      break;
    }
    default:
      throw std::runtime_error("a message between ranks holds an unknown shape");
  }
  object.material = in.value<std::uint32_t>();
  object.insideVisible = in.value<bool>();
  object.line = in.value<int>();
  return object;
}

void writeScene(WireWriter& out, const core::Scene& scene) {
  out.string(scene.name);
  out.string(scene.source);
  out.value(scene.camera);
  out.value(scene.background);
  out.vector(scene.lights);
  out.vector(scene.materials);
  out.value(std::uint64_t(scene.objects.size()));
  for (const core::Object& o : scene.objects) writeObject(out, o);
}

core::Scene readScene(WireReader& in) {
  core::Scene scene;
  scene.name = in.string();
  scene.source = in.string();
  scene.camera = in.value<core::Camera>();
  scene.background = in.value<core::Color>();
  scene.lights = in.vector<core::Light>();
  scene.materials = in.vector<core::Material>();
  scene.objects.resize(in.value<std::uint64_t>());
  for (core::Object& o : scene.objects) o = readObject(in);
  return scene;
}

// ---- The context every processor shares: the partition travels as its areas, the lines as the view.
// The objects travel in each processor's setup: its region database, not the whole scene.

void writeContext(WireWriter& out, const node::MachineContext& context) {
  out.value(context.view);
  out.value(context.shading);
  std::vector<node::SampleRect> areas;
  for (int p = 0; p < context.regions.processors(); ++p) areas.push_back(context.regions.areaOf(p));
  out.vector(areas);
  out.value(context.regions.gridColumns());
  out.vector(context.sceneBounds);
  out.vector(context.regionBounds);
  out.value(context.fifoFull);
}

node::MachineContext readContext(WireReader& in) {
  const auto view = in.value<core::View>();
  const auto shading = in.value<core::ShadingOptions>();
  auto areas = in.vector<node::SampleRect>();
  const int gridColumns = in.value<int>();
  auto sceneBounds = in.vector<core::Box>();
  auto regionBounds = in.vector<core::Box>();
  const auto fifoFull = in.value<node::FifoFull>();
  return node::MachineContext{view,
                              shading,
                              node::RegionMap(std::move(areas), node::ScreenLines(view), gridColumns),
                              std::move(sceneBounds),
                              std::move(regionBounds),
                              fifoFull};
}

// ---- A processor's setup (3.2 step 2, 3.7.2).

void writeLightSources(WireWriter& out, const node::LightSources& sources) {
  out.value(sources.eyeBox);
  out.vector(sources.corners);
  out.value(std::uint64_t(sources.volumeObjects.size()));
  for (std::size_t l = 0; l < sources.volumeObjects.size(); ++l) {
    out.vector(sources.volumeObjects[l]);
    out.vector(sources.volumeBoxes[l]);
  }
}

node::LightSources readLightSources(WireReader& in) {
  node::LightSources sources;
  sources.eyeBox = in.value<core::Box>();
  sources.corners = in.vector<core::Vec3>();
  const auto lights = in.value<std::uint64_t>();
  if (lights > core::kMaxLights) throw std::runtime_error("a job gives more light volumes than lights");
  for (std::uint64_t l = 0; l < lights; ++l) {
    sources.volumeObjects.push_back(in.vector<std::uint32_t>());
    sources.volumeBoxes.push_back(in.vector<node::EyeBox>());
    if (sources.volumeBoxes.back().size() != sources.volumeObjects.back().size())
      throw std::runtime_error("a job gives a light volume's objects without an eye box each");
  }
  return sources;
}

void writeDatabase(WireWriter& out, const node::RegionDatabase& database) {
  // Its indices name the host's scene, which the other address space does not have.
  if (database.inPlace)
    throw std::logic_error("a database read in place cannot be sent to another address space");
  writeScene(out, database.scene);
  out.vector(database.globalIds);
}

std::shared_ptr<const node::RegionDatabase> readDatabase(WireReader& in) {
  auto database = std::make_shared<node::RegionDatabase>();
  database->scene = readScene(in);
  database->globalIds = in.vector<std::uint32_t>();
  return database;
}

// Processors holding the same objects share one database (host/render/render_machine.cpp): it travels once
// per job, and the setups name it by its place in the job's table, so the rank shares it again.
using DatabaseTable = std::vector<const node::RegionDatabase*>;

DatabaseTable databasesOf(std::span<const node::NodeSetup> setups) {
  DatabaseTable table;
  for (const node::NodeSetup& s : setups)
    if (std::find(table.begin(), table.end(), s.database.get()) == table.end())
      table.push_back(s.database.get());
  return table;
}

void writeSetup(WireWriter& out, const node::NodeSetup& setup, const DatabaseTable& databases) {
  out.value(setup.id);
  out.value(setup.cells);
  out.value(setup.cellLevel);
  out.value(
      std::uint64_t(std::find(databases.begin(), databases.end(), setup.database.get()) - databases.begin()));
  out.vector(setup.objects);
  out.vector(setup.objectBoxes);
  out.vector(setup.rearObjects);
  out.value(setup.lightRays);
  out.value(setup.lightRaysWalkCells);
  writeLightSources(out, setup.lightSources);
  writeLightSources(out, setup.rearLightSources);
  out.value(std::uint64_t(setup.lightObjects));
  out.value(std::uint64_t(setup.extraLightObjects));
}

node::NodeSetup readSetup(WireReader& in,
                          const std::vector<std::shared_ptr<const node::RegionDatabase>>& databases) {
  node::NodeSetup setup;
  setup.id = in.value<int>();
  setup.cells = in.value<node::CellStructure>();
  setup.cellLevel = in.value<int>();
  const std::uint64_t database = in.value<std::uint64_t>();
  if (database >= databases.size())
    throw std::runtime_error("a job names a region database it does not hold");
  setup.database = databases[database];
  setup.objects = in.vector<std::uint32_t>();
  setup.objectBoxes = in.vector<node::EyeBox>();
  if (setup.objectBoxes.size() != setup.objects.size())
    throw std::runtime_error("a job gives a processor's objects without an eye box each");
  setup.rearObjects = in.vector<std::uint32_t>();
  setup.lightRays = in.value<node::LightRayMode>();
  setup.lightRaysWalkCells = in.value<bool>();
  setup.lightSources = readLightSources(in);
  setup.rearLightSources = readLightSources(in);
  setup.lightObjects = in.value<std::uint64_t>();
  setup.extraLightObjects = in.value<std::uint64_t>();
  return setup;
}

}  // namespace

std::vector<char> encodeJob(const JobSettings& settings, const node::MachineContext& context,
                            std::span<const node::NodeSetup> setups) {
  WireWriter out;
  out.value(settings.precision);
  out.value(settings.queueCapacity);
  out.value(settings.rayBatch);
  out.value(settings.jitterSeed);
  out.value(settings.stallPeriodMs);
  out.value(settings.stallAStep);
  out.value(settings.loseTheToken);
  out.vector(settings.rankOf);
  writeContext(out, context);
  const DatabaseTable databases = databasesOf(setups);
  out.value(std::uint64_t(databases.size()));
  for (const node::RegionDatabase* d : databases) writeDatabase(out, *d);
  out.value(std::uint64_t(setups.size()));
  for (const node::NodeSetup& s : setups) writeSetup(out, s, databases);
  return out.take();
}

MachineJob decodeJob(std::span<const char> bytes) {
  WireReader in(bytes);
  JobSettings settings;
  settings.precision = in.value<core::Precision>();
  settings.queueCapacity = in.value<std::uint64_t>();
  settings.rayBatch = in.value<std::uint64_t>();
  settings.jitterSeed = in.value<unsigned>();
  settings.stallPeriodMs = in.value<std::int64_t>();
  settings.stallAStep = in.value<bool>();
  settings.loseTheToken = in.value<bool>();
  settings.rankOf = in.vector<int>();
  MachineJob job{std::move(settings), readContext(in), {}};
  std::vector<std::shared_ptr<const node::RegionDatabase>> databases(in.value<std::uint64_t>());
  for (auto& d : databases) d = readDatabase(in);
  job.setups.resize(in.value<std::uint64_t>());
  for (node::NodeSetup& s : job.setups) s = readSetup(in, databases);
  return job;
}

std::vector<char> encodeResults(const RankResults& results) {
  WireWriter out;
  out.value(results.rank);
  out.vector(results.processors);
  return out.take();
}

RankResults decodeResults(std::span<const char> bytes) {
  WireReader in(bytes);
  RankResults results;
  results.rank = in.value<RankReport>();
  results.processors = in.vector<ProcessorReport>();
  return results;
}

}  // namespace raycube::host
