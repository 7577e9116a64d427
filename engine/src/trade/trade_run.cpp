#include "drape/trade/trade_run.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "drape/collision/avatar_collider.h"
#include "drape/collision/surface_distance.h"
#include "drape/core/input_error.h"
#include "drape/core/percentile.h"
#include "drape/geometry/strain.h"
#include "drape/io/atomic_file.h"
#include "drape/sim/simulation.h"

namespace drape::trade {
namespace {

constexpr int kReferenceFormat = 1;

void addTerms(std::vector<std::string>& into, const std::vector<std::string>& terms) {
  for (const auto& t : terms)
    if (std::find(into.begin(), into.end(), t) == into.end()) into.push_back(t);
}

nlohmann::json settingsJson(const SettingList& settings) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [k, v] : settings) out.push_back({k, v});
  return out;
}

}  // namespace

TradeConfig referenceConfig() {
  return {"reference",
          "",
          "drape",
          {{"solver.newton.h_max", "2.5e-4"}, {"solver.newton.tolerance", "1e-5"}, {"solver.cg.tolerance", "1e-4"}}};
}

TradeOutcome runTrade(const SceneRequest& base, const TradeConfig& config) {
  SceneRequest request = base;
  request.overrides.insert(request.overrides.end(), config.settings.begin(), config.settings.end());
  request.overrides.emplace_back("solver.stage", config.stage);
  TradeOutcome out;
  out.config = config;
  const auto start = std::chrono::steady_clock::now();
  Simulation sim(loadScene(request));
  addTerms(out.terms, sim.terms());
  Stage stage = sim.stage();
  StepReport last;
  while (!sim.finished()) {
    last = sim.step();
    if (sim.stage() != stage) {
      stage = sim.stage();
      addTerms(out.terms, sim.terms());
    }
    if (last.status == StepStatus::Diverged) break;
  }
  out.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.status = last.status == StepStatus::Diverged ? "Diverged" : sim.endReason();
  out.simTime = sim.time();
  out.steps = sim.steps();
  out.profile = sim.profile();
  out.garment.vertices = sim.positions();
  out.garment.triangles = sim.garment().triangles;
  const Eigen::VectorXd stretch = triangleStretch(sim.garment().rest, out.garment.vertices, sim.garment().triangles);
  out.maxStrain = stretch.size() ? stretch.maxCoeff() : 0.0;
  if (sim.collider() && out.garment.vertices.allFinite()) {
    const double thickness = sim.contactThickness();
    for (int v = 0; v < out.garment.vertexCount(); ++v)
      if (sim.collider()->signedDistance(out.garment.vertices.row(v).transpose()) < -thickness) ++out.insideVertices;
  }
  return out;
}

std::string referenceKey(const SceneRequest& base, const TradeConfig& reference) {
  const nlohmann::json key = {{"scene", base.input.lexically_normal().generic_string()},
                              {"avatar", base.avatarFile},
                              {"avatar_units", base.avatarUnits},
                              {"fabric", base.fabricPreset},
                              {"set", settingsJson(base.overrides)},
                              {"stage", reference.stage},
                              {"reference", settingsJson(reference.settings)}};
  return key.dump();
}

void writeReference(const std::filesystem::path& file, const TradeOutcome& reference, const std::string& key) {
  nlohmann::json vertices = nlohmann::json::array(), triangles = nlohmann::json::array();
  for (int v = 0; v < reference.garment.vertexCount(); ++v)
    vertices.push_back(
        {reference.garment.vertices(v, 0), reference.garment.vertices(v, 1), reference.garment.vertices(v, 2)});
  for (int f = 0; f < reference.garment.triangleCount(); ++f)
    triangles.push_back(
        {reference.garment.triangles(f, 0), reference.garment.triangles(f, 1), reference.garment.triangles(f, 2)});
  const nlohmann::json out = {{"drape_reference", kReferenceFormat},
                              {"key", nlohmann::json::parse(key)},
                              {"status", reference.status},
                              {"wall_time_s", reference.wallSeconds},
                              {"sim_time_s", reference.simTime},
                              {"steps", reference.steps},
                              {"max_strain", reference.maxStrain},
                              {"inside_vertices", reference.insideVertices},
                              {"terms", reference.terms},
                              {"vertices", vertices},
                              {"triangles", triangles}};
  writeFileAtomically(file, out.dump() + "\n");
}

TradeOutcome readReference(const std::filesystem::path& file, const std::string& key) {
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in) throw InputError(name + ": cannot read the reference drape");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    throw InputError(name + ": not a reference drape (not JSON)");
  }
  if (!j.is_object() || j.value("drape_reference", 0) != kReferenceFormat)
    throw InputError(name + ": not a reference drape written by drape --bench --reference");
  if (!j.contains("key") || j["key"].dump() != nlohmann::json::parse(key).dump())
    throw InputError(name + ": the reference was made for another scene or settings (" +
                     (j.contains("key") ? j["key"].dump() : std::string("no key")) +
                     "); name another --reference file or delete this one");
  TradeOutcome out;
  out.config = referenceConfig();
  try {
    out.status = j.at("status").get<std::string>();
    out.wallSeconds = j.at("wall_time_s").get<double>();
    out.simTime = j.at("sim_time_s").get<double>();
    out.steps = j.at("steps").get<int>();
    out.maxStrain = j.at("max_strain").get<double>();
    out.insideVertices = j.at("inside_vertices").get<int>();
    out.terms = j.at("terms").get<std::vector<std::string>>();
    const auto& v = j.at("vertices");
    const auto& f = j.at("triangles");
    out.garment.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
    out.garment.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (size_t i = 0; i < v.size(); ++i)
      for (int c = 0; c < 3; ++c) out.garment.vertices(static_cast<Eigen::Index>(i), c) = v.at(i).at(c).get<double>();
    for (size_t i = 0; i < f.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const int index = f.at(i).at(c).get<int>();
        if (index < 0 || index >= out.garment.vertexCount())
          throw InputError(name + ": triangle " + std::to_string(i) + " names vertex " + std::to_string(index) +
                           " of " + std::to_string(out.garment.vertexCount()));
        out.garment.triangles(static_cast<Eigen::Index>(i), c) = index;
      }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name + ": reference drape: " + e.what());
  }
  return out;
}

Distances distanceToReference(const TriangleMesh& run, const TriangleMesh& reference) {
  Distances out;
  if (reference.vertexCount() == 0) return out;
  const Eigen::VectorXd d = collision::distancesToSurface(reference.vertices, run);
  out.meanMm = 1e3 * d.mean();
  out.maxMm = 1e3 * d.maxCoeff();
  out.p95Mm = 1e3 * percentile(std::vector<double>(d.data(), d.data() + d.size()), 0.95);
  if (run.vertexCount() == reference.vertexCount() && run.triangleCount() == reference.triangleCount() &&
      run.triangles == reference.triangles)
    out.vertexMeanMm = 1e3 * (run.vertices - reference.vertices).rowwise().norm().mean();
  return out;
}

}  // namespace drape::trade
