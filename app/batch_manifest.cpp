#include "batch_manifest.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>

#include "batch_manifest_reader.h"
#include "drape/core/input_error.h"

namespace drape::app {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const std::vector<std::string> kTopKeys = {"description", "solver", "max_sim_time", "outputs", "set", "grid", "jobs"};
const std::vector<std::string> kGridKeys = {"scenes", "avatars", "sizes", "fabrics", "sets"};
const std::vector<std::string> kSizesKeys = {"measurements", "scales"};
const std::vector<std::string> kSizeKeys = {"name", "scale"};
// A graded size's scale: beyond these a garment is another garment, not another size.
constexpr double kMinSizeScale = 0.5, kMaxSizeScale = 2.0;
const std::vector<std::string> kJobKeys = {"id", "scene", "avatar", "fabric", "set"};
const std::vector<std::string> kOutputs = {"obj", "glb", "png", "stats"};
const std::vector<std::string> kSolvers = {"none", "preview", "drape", "full"};

std::string setLabel(const SettingOverrides& overrides) {
  std::string label;
  for (const auto& [key, value] : overrides) label += (label.empty() ? "" : " ") + key + "=" + value;
  return label;
}

// scene__avatar__fabric__set from the parts that are given (file stems for files; for a graded size its part instead
// of the avatar's).
std::string derivedId(const BatchJob& job, const std::string& setPart, const std::string& sizePart = "") {
  std::vector<std::string> parts = {fs::path(job.scene.text).stem().string()};
  if (!sizePart.empty()) parts.push_back(sizePart);
  else if (!job.avatar.empty()) parts.push_back(fs::path(job.avatar.text).stem().string());
  if (!job.fabric.empty()) parts.push_back(job.fabric);
  if (!setPart.empty()) parts.push_back(setPart);
  return sanitizeJobId(joinedList(parts, "__"));
}

// grid.sizes: {"measurements": FILE, "scales": [{"name": "S", "scale": 0.96}, ...]}, one avatar entry per size: the
// measurements' mannequin, both it and the pattern scaled (grading.scale). The id part is "<index>_<name>", the index
// zero-padded, so that the sorted job list keeps the sizes in the manifest's order.
std::vector<std::pair<BatchJob, std::string>> gradedSizes(const ManifestReader& reader, const json& sizes) {
  if (!sizes.is_object()) reader.fail("grid.sizes", "must be an object with 'measurements' and 'scales'");
  reader.checkKeys(sizes, "grid.sizes.", kSizesKeys);
  if (!sizes.contains("measurements"))
    reader.fail("grid.sizes.measurements", "missing (the body-measurement file of scale 1)");
  if (!sizes.contains("scales")) reader.fail("grid.sizes.scales", "missing (a list of {\"name\", \"scale\"})");
  BatchJob base;
  reader.avatar(sizes.at("measurements"), "grid.sizes.measurements", base);
  if (!base.avatarIsMeasurements)
    reader.fail("grid.sizes.measurements", "must be a body-measurement file (.yaml, .yml, .json), not a mesh");
  const json& list = reader.list(sizes.at("scales"), "grid.sizes.scales");
  const size_t digits = std::to_string(list.size() - 1).size();
  std::vector<std::pair<BatchJob, std::string>> entries;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string at = "grid.sizes.scales[" + std::to_string(i) + "]";
    if (!list[i].is_object()) reader.fail(at, "must be an object {\"name\": ..., \"scale\": ...}");
    reader.checkKeys(list[i], at + ".", kSizeKeys);
    if (!list[i].contains("name")) reader.fail(at + ".name", "missing");
    if (!list[i].contains("scale")) reader.fail(at + ".scale", "missing");
    BatchJob job = base;
    job.size = reader.text(list[i].at("name"), at + ".name");
    const json& scale = list[i].at("scale");
    if (!scale.is_number() || !(scale.get<double>() >= kMinSizeScale && scale.get<double>() <= kMaxSizeScale))
      reader.fail(at + ".scale", "must be a number from 0.5 to 2, got " + scale.dump());
    job.sizeScale = scale.get<double>();
    reader.mannequinOf(job.avatar.file, job.sizeScale, at + ".scale");
    std::string index = std::to_string(i);
    index.insert(0, digits - index.size(), '0');
    const std::string idPart = sanitizeJobId(index + "_" + job.size);
    entries.emplace_back(std::move(job), idPart);
  }
  return entries;
}

// The grid's cross product, in the order scenes x avatars (or sizes) x fabrics x sets. Each axis is validated once; an axis that
// is not given is one empty entry: the scene's own avatar or fabric, no extra settings.
void expandGrid(const ManifestReader& reader, const json& grid, const SettingOverrides& common,
                std::vector<std::pair<BatchJob, std::string>>& jobs) {
  if (!grid.is_object()) reader.fail("grid", "must be an object");
  reader.checkKeys(grid, "grid.", kGridKeys);
  if (!grid.contains("scenes")) reader.fail("grid.scenes", "missing (a grid needs at least one scene or pattern)");
  auto axis = [&](const char* key, auto parse) {
    using Entry = decltype(parse(json(), std::string()));
    std::vector<std::pair<Entry, bool>> entries;  // (value, given)
    if (!grid.contains(key)) return decltype(entries){{Entry{}, false}};
    const json& list = reader.list(grid.at(key), std::string("grid.") + key);
    for (size_t i = 0; i < list.size(); ++i)
      entries.emplace_back(parse(list[i], std::string("grid.") + key + "[" + std::to_string(i) + "]"), true);
    return entries;
  };
  const auto scenes = axis("scenes", [&](const json& j, const std::string& at) { return reader.file(j, at); });
  if (grid.contains("sizes") && grid.contains("avatars"))
    reader.fail("grid.sizes", "not with grid.avatars: each size drapes on its own mannequin");
  // (avatar fields, id part): the avatars given, or the sizes, or one entry for the scene's own avatar.
  std::vector<std::pair<BatchJob, std::string>> avatars;
  if (grid.contains("sizes")) {
    avatars = gradedSizes(reader, grid.at("sizes"));
  } else {
    for (auto& [holder, given_] : axis("avatars", [&](const json& j, const std::string& at) {
           BatchJob holder;
           reader.avatar(j, at, holder);
           return holder;
         }))
      avatars.emplace_back(std::move(holder), "");
  }
  const auto fabrics = axis("fabrics", [&](const json& j, const std::string& at) { return reader.fabric(j, at); });
  const auto sets = axis("sets", [&](const json& j, const std::string& at) { return reader.overrides(j, at); });
  for (size_t s = 0; s < scenes.size(); ++s)
    for (size_t a = 0; a < avatars.size(); ++a)
      for (size_t f = 0; f < fabrics.size(); ++f)
        for (size_t v = 0; v < sets.size(); ++v) {
          BatchJob job = avatars[a].first;  // the avatar fields, or none
          job.scene = scenes[s].first;
          job.fabric = fabrics[f].first;
          job.overrides = common;
          job.overrides.insert(job.overrides.end(), sets[v].first.begin(), sets[v].first.end());
          if (!job.size.empty()) job.overrides.emplace_back("grading.scale", json(job.sizeScale).dump());
          job.setLabel = setLabel(sets[v].first);
          job.id = derivedId(job, sets[v].second ? "set" + std::to_string(v) : "", avatars[a].second);
          const std::string element = "grid (scenes[" + std::to_string(s) + "], " +
                                      (job.size.empty() ? "avatars[" : "sizes.scales[") + std::to_string(a) +
                                      "], fabrics[" + std::to_string(f) + "], sets[" + std::to_string(v) + "])";
          jobs.emplace_back(std::move(job), element);
        }
}

BatchJob explicitJob(const ManifestReader& reader, const json& entry, const std::string& element,
                     const SettingOverrides& common) {
  if (!entry.is_object()) reader.fail(element, "must be an object");
  reader.checkKeys(entry, element + ".", kJobKeys);
  if (!entry.contains("scene")) reader.fail(element + ".scene", "missing (the scene or pattern file to drape)");
  BatchJob job;
  job.scene = reader.file(entry.at("scene"), element + ".scene");
  if (entry.contains("avatar")) reader.avatar(entry.at("avatar"), element + ".avatar", job);
  if (entry.contains("fabric")) job.fabric = reader.fabric(entry.at("fabric"), element + ".fabric");
  job.overrides = common;
  if (entry.contains("set")) {
    const SettingOverrides own = reader.overrides(entry.at("set"), element + ".set");
    job.overrides.insert(job.overrides.end(), own.begin(), own.end());
    job.setLabel = setLabel(own);
  }
  if (entry.contains("id")) {
    job.id = reader.text(entry.at("id"), element + ".id");
    if (sanitizeJobId(job.id) != job.id)
      reader.fail(element + ".id", "'" + job.id + "' may hold only A-Z a-z 0-9 _ . - and not start with '.'");
  } else {
    job.id = derivedId(job, sanitizeJobId(job.setLabel));
  }
  return job;
}

}  // namespace

bool BatchManifest::wants(const std::string& output) const {
  return listContains(outputs, output);
}

std::string sanitizeJobId(const std::string& text) {
  std::string id = text;
  for (char& c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-') c = '_';
  if (!id.empty() && id[0] == '.') id[0] = '_';  // no hidden folders, no "." or ".."
  return id;
}

BatchManifest loadBatchManifest(const fs::path& file) {
  const ManifestReader reader(file);
  std::ifstream in(file);
  if (!fs::is_regular_file(file) || !in) throw InputError(file.string() + ": cannot read the batch manifest");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    reader.fail("JSON", e.what());
  }
  if (!root.is_object()) reader.fail("top level", "must be an object");
  reader.checkKeys(root, "", kTopKeys);

  BatchManifest manifest;
  manifest.file = file;
  if (root.contains("description")) reader.text(root.at("description"), "description");  // for people; not used
  if (root.contains("solver")) {
    manifest.solver = reader.text(root.at("solver"), "solver");
    if (!listContains(kSolvers, manifest.solver))
      reader.fail("solver", "'" + manifest.solver + "' is not one of " + joinedList(kSolvers, "|"));
  }
  if (root.contains("max_sim_time")) {
    const json& t = root.at("max_sim_time");
    if (!t.is_number() || !(t.get<double>() > 0) || !std::isfinite(t.get<double>()))
      reader.fail("max_sim_time", "must be a positive number of seconds");
    manifest.maxSimTime = t.get<double>();
  }
  std::vector<std::string> outputs = {"obj", "png", "stats"};
  if (root.contains("outputs")) {
    outputs.clear();
    const json& list = reader.list(root.at("outputs"), "outputs");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string element = "outputs[" + std::to_string(i) + "]";
      outputs.push_back(reader.text(list[i], element));
      if (!listContains(kOutputs, outputs.back()))
        reader.fail(element, "'" + outputs.back() + "' is not one of " + joinedList(kOutputs));
    }
  }
  for (const auto& o : kOutputs)
    if (listContains(outputs, o)) manifest.outputs.push_back(o);
  const SettingOverrides common = root.contains("set") ? reader.overrides(root.at("set"), "set") : SettingOverrides{};

  std::vector<std::pair<BatchJob, std::string>> jobs;  // each with its element, for the duplicate message
  if (root.contains("grid")) expandGrid(reader, root.at("grid"), common, jobs);
  if (root.contains("jobs")) {
    const json& list = reader.list(root.at("jobs"), "jobs");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string element = "jobs[" + std::to_string(i) + "]";
      jobs.emplace_back(explicitJob(reader, list[i], element, common), element);
    }
  }
  if (jobs.empty()) reader.fail("jobs", "the manifest has no jobs (give 'jobs' or a 'grid')");
  std::map<std::string, std::string> seen;  // id -> element
  for (const auto& [job, element] : jobs) {
    if (job.id.size() > 200)  // a folder name; file systems allow 255 bytes
      reader.fail(element, "job id '" + job.id.substr(0, 40) + "...' is longer than 200 characters (give it an 'id')");
    const auto [it, fresh] = seen.emplace(job.id, element);
    if (!fresh)
      reader.fail(element, "job id '" + job.id + "' is also the id of " + it->second + " (give the jobs distinct ids)");
  }
  for (auto& entry : jobs) manifest.jobs.push_back(std::move(entry.first));
  std::sort(manifest.jobs.begin(), manifest.jobs.end(),
            [](const BatchJob& a, const BatchJob& b) { return a.id < b.id; });
  return manifest;
}

}  // namespace drape::app
