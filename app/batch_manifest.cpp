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
const std::vector<std::string> kGridKeys = {"scenes", "avatars", "fabrics", "sets"};
const std::vector<std::string> kJobKeys = {"id", "scene", "avatar", "fabric", "set"};
const std::vector<std::string> kOutputs = {"obj", "glb", "png", "stats"};
const std::vector<std::string> kSolvers = {"none", "preview", "drape", "full"};

std::string setLabel(const SettingOverrides& overrides) {
  std::string label;
  for (const auto& [key, value] : overrides) label += (label.empty() ? "" : " ") + key + "=" + value;
  return label;
}

// scene__avatar__fabric__set from the parts that are given (file stems for files).
std::string derivedId(const BatchJob& job, const std::string& setPart) {
  std::vector<std::string> parts = {fs::path(job.scene.text).stem().string()};
  if (!job.avatar.empty()) parts.push_back(fs::path(job.avatar.text).stem().string());
  if (!job.fabric.empty()) parts.push_back(job.fabric);
  if (!setPart.empty()) parts.push_back(setPart);
  return sanitizeJobId(joinedList(parts, "__"));
}

// The grid's cross product, in the order scenes x avatars x fabrics x sets. Each axis is validated once; an axis that
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
  const auto avatars = axis("avatars", [&](const json& j, const std::string& at) {
    BatchJob holder;
    reader.avatar(j, at, holder);
    return holder;
  });
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
          job.setLabel = setLabel(sets[v].first);
          job.id = derivedId(job, sets[v].second ? "set" + std::to_string(v) : "");
          const std::string element = "grid (scenes[" + std::to_string(s) + "], avatars[" + std::to_string(a) +
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
