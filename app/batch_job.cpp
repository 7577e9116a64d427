#include "batch_job.h"

#include <sys/wait.h>

#include <cstring>
#include <fstream>

#include "batch_summary.h"
#include "child_process.h"
#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"

namespace drape::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::string> linesOf(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string withoutPrefix(const std::string& line, const std::string& prefix) {
  return line.rfind(prefix, 0) == 0 ? line.substr(prefix.size()) : line;
}

// Why the job failed, in one line: the signal that ended it, its error line on stderr, else its divergence or quality
// warnings on stdout.
std::string errorLine(const BatchJobFiles& files, int waitStatus) {
  if (WIFSIGNALED(waitStatus))
    return "killed by signal " + std::to_string(WTERMSIG(waitStatus)) + " (" + strsignal(WTERMSIG(waitStatus)) + ")";
  const int exit = exitStatusOf(waitStatus);
  if (exit == 0) return "";
  const auto errors = linesOf(files.errors);
  if (!errors.empty()) return withoutPrefix(errors.back(), "drape: ");
  std::string quality;
  for (const std::string& line : linesOf(files.log)) {
    if (line.rfind("drape: the ", 0) == 0 && line.find("diverged") != std::string::npos)
      return withoutPrefix(line, "drape: ");
    if (line.rfind("warning: quality: ", 0) == 0)
      quality += (quality.empty() ? "" : "; ") + withoutPrefix(line, "warning: quality: ");
  }
  return quality.empty() ? "exit status " + std::to_string(exit) : quality;
}

json readJson(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return nullptr;
  try {
    return json::parse(in);
  } catch (const json::exception&) {
    return nullptr;
  }
}

// The arguments that name the job's scene, avatar, fabric and settings.
std::vector<std::string> sceneArguments(const BatchJob& job) {
  std::vector<std::string> args = {job.scene.file.string()};
  if (!job.avatarMesh.empty()) args.insert(args.end(), {"--avatar", job.avatarMesh.string()});
  if (!job.fabric.empty()) args.insert(args.end(), {"--fabric", job.fabric});
  for (const auto& [key, value] : job.overrides) args.insert(args.end(), {"--set", key + "=" + value});
  return args;
}

}  // namespace

BatchJobFiles batchJobFiles(const BatchManifest& manifest, const BatchJob& job, const fs::path& outDir) {
  BatchJobFiles f;
  f.dir = outDir / job.id;
  const bool obj = manifest.wants("obj"), glb = manifest.wants("glb");
  f.mesh = f.dir / (glb && !obj ? "garment.glb" : "garment.obj");
  if (glb && obj) f.glb = f.dir / "garment.glb";
  if (manifest.wants("png")) f.png = f.dir / "garment.png";
  f.stats = f.dir / "stats.json";
  f.log = f.dir / "log.txt";
  f.errors = f.dir / "errors.txt";
  f.done = f.dir / "done.json";
  f.failed = f.dir / "failed.json";
  return f;
}

bool batchJobFinished(const BatchJobFiles& files) {
  std::error_code ec;
  return fs::exists(files.done, ec);
}

json recordedBatchRow(const BatchJobFiles& files) {
  const json done = readJson(files.done);
  return done.is_object() ? done : readJson(files.failed);
}

std::vector<std::string> batchJobArguments(const BatchManifest& manifest, const BatchJob& job,
                                           const BatchJobFiles& files, int threads) {
  std::vector<std::string> args = {"--simulate"};
  const auto scene = sceneArguments(job);
  args.insert(args.end(), scene.begin(), scene.end());
  args.insert(args.end(), {"-o", files.mesh.string(), "--stats", files.stats.string(), "--solver", manifest.solver});
  if (manifest.maxSimTime > 0) args.insert(args.end(), {"--max-sim-time", json(manifest.maxSimTime).dump()});
  if (!files.png.empty()) args.insert(args.end(), {"--png", files.png.string(), "--size", kBatchThumbnailSize});
  if (threads > 0) args.insert(args.end(), {"--threads", std::to_string(threads)});
  return args;
}

RunningBatchJob startBatchJob(const BatchManifest& manifest, const BatchJob& job, const BatchJobFiles& files,
                              int threads) {
  std::error_code ec;
  fs::remove_all(files.dir, ec);  // what a killed or failed run left
  fs::create_directories(files.dir, ec);
  if (ec) throw InputError(files.dir.string() + ": cannot create the job folder: " + ec.message());
  RunningBatchJob running;
  running.start = std::chrono::steady_clock::now();
  running.pid = spawnProcess(drapeExecutable(), batchJobArguments(manifest, job, files, threads), files.log, files.errors);
  return running;
}

json finishBatchJob(const BatchManifest& manifest, const BatchJob& job, const BatchJobFiles& files, int waitStatus,
                    double wallTime) {
  BatchJobOutcome outcome;
  outcome.exitStatus = exitStatusOf(waitStatus);
  outcome.stats = readJson(files.stats);
  outcome.error = errorLine(files, waitStatus);
  outcome.wallTime = wallTime;
  std::error_code ec;
  // --simulate writes one mesh: the glb is the obj's state written again by a --solver none run from it.
  if (!files.glb.empty() && fs::exists(files.mesh, ec)) {
    std::vector<std::string> args = {"--simulate"};
    const auto scene = sceneArguments(job);
    args.insert(args.end(), scene.begin(), scene.end());
    args.insert(args.end(), {"--solver", "none", "--from", files.mesh.string(), "-o", files.glb.string()});
    const int converted = waitForProcess(spawnProcess(drapeExecutable(), args, files.log, files.errors, true));
    if (exitStatusOf(converted) != 0 && outcome.exitStatus == 0) {
      outcome.exitStatus = exitStatusOf(converted);
      outcome.error = "glb: " + errorLine(files, converted);
    }
  }
  if (!manifest.wants("obj") && !manifest.wants("glb")) fs::remove(files.mesh, ec);
  if (!manifest.wants("stats")) fs::remove(files.stats, ec);
  // Paths relative to OUTDIR, so that the folder can be moved.
  std::vector<std::pair<std::string, std::string>> outputs;
  auto add = [&](const char* key, const fs::path& file) {
    if (!file.empty() && fs::exists(file, ec)) outputs.emplace_back(key, (fs::path(job.id) / file.filename()).string());
  };
  add(files.mesh.extension() == ".glb" ? "glb" : "obj", files.mesh);
  add("glb", files.glb);
  add("png", files.png);
  add("stats", files.stats);
  const json row = summaryRow(job, outcome, outputs);
  writeFileAtomically(rowFinished(row) ? files.done : files.failed, row.dump(2) + "\n");
  return row;
}

}  // namespace drape::app
