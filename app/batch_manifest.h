#pragma once
// A batch manifest (docs/FORMATS.md, "Batch manifests"): explicit jobs and/or a grid of scenes x avatars (or graded
// sizes) x fabrics x set variations, expanded into a job list sorted by id. Every problem is found here, before any job runs.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace drape::app {

using SettingOverrides = std::vector<std::pair<std::string, std::string>>;

// One input file as the manifest wrote it and where it resolves to (relative to the manifest file).
struct BatchInput {
  std::string text;            // as written in the manifest; empty: not given
  std::filesystem::path file;  // resolved
  bool empty() const { return text.empty(); }
};

// One drape: a scene or bare pattern, optionally on another avatar, in another fabric, with extra --set overrides.
struct BatchJob {
  std::string id;                     // stable, [A-Za-z0-9_.-]; the job's output folder is OUTDIR/<id>
  BatchInput scene;                   // scene file or bare pattern file
  BatchInput avatar;                  // avatar mesh or body-measurement file; empty: the scene's own avatar
  bool avatarIsMeasurements = false;  // .yaml/.yml/.json: a mannequin is made from it (drape --make-avatar)
  std::filesystem::path avatarMesh;   // the mesh the job drapes on: avatar.file, or the mannequin made from it
  std::string size;                   // a graded size's name (grid `sizes`); empty: none
  double sizeScale = 1.0;             // its scale of the pattern and of the mannequin's measurements
  std::string fabric;                 // preset name; empty: the scene's fabric
  SettingOverrides overrides;         // the manifest's common `set`, then the job's own
  std::string setLabel;               // the job's own overrides as "KEY=VALUE KEY=VALUE" (for the summary)
};

struct BatchManifest {
  std::filesystem::path file;
  std::string solver = "drape";      // none|preview|drape|full
  double maxSimTime = -1.0;          // seconds; <= 0: the scenes' own solver.max_sim_time
  std::vector<std::string> outputs;  // subset of obj, glb, png, stats, in that order
  std::vector<BatchJob> jobs;        // sorted by id, ids unique
  bool wants(const std::string& output) const;
};

// Reads, validates and expands the manifest. Throws InputError "MANIFEST: <element>: <what is wrong>" for an
// unknown key, a wrong type, a missing file, an unknown fabric preset or setting, an empty grid axis, no jobs at all
// or two jobs with the same id.
BatchManifest loadBatchManifest(const std::filesystem::path& file);

// text with every character outside [A-Za-z0-9_.-] replaced by '_'.
std::string sanitizeJobId(const std::string& text);

}  // namespace drape::app
