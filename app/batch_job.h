#pragma once
// One job of a batch: a child process of this same `drape` executable running --simulate with the job's inputs, so
// that a crash takes down only that job and its exit status is recorded. Its files live in OUTDIR/<id>/; done.json,
// written atomically after everything else, marks it finished.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch_manifest.h"

namespace drape::app {

// The files of one job.
struct BatchJobFiles {
  std::filesystem::path dir;     // OUTDIR/<id>
  std::filesystem::path mesh;    // -o of --simulate: garment.obj, or garment.glb when only glb is wanted
  std::filesystem::path glb;     // garment.glb made from garment.obj when both are wanted, else empty
  std::filesystem::path png;     // garment.png when png is wanted, else empty
  std::filesystem::path stats;   // stats.json (always written: the summary row comes from it)
  std::filesystem::path log;     // the child's stdout
  std::filesystem::path errors;  // the child's stderr
  std::filesystem::path done;    // done.json: the summary row of a job that succeeded
  std::filesystem::path failed;  // failed.json: the summary row of a job that failed (it runs again next time)
};
BatchJobFiles batchJobFiles(const BatchManifest& manifest, const BatchJob& job, const std::filesystem::path& outDir);

// Pixel size of each job's PNG (the contact sheet's thumbnails).
constexpr const char* kBatchThumbnailSize = "256x256";

// True when OUTDIR/<id>/done.json exists: the job is not run again.
bool batchJobFinished(const BatchJobFiles& files);

// The row that done.json, else failed.json, holds; null when the job has neither (never run, or unreadable).
nlohmann::json recordedBatchRow(const BatchJobFiles& files);

// The arguments of the job's `drape --simulate` (without the executable); threads > 0 caps its threads.
std::vector<std::string> batchJobArguments(const BatchManifest& manifest, const BatchJob& job,
                                           const BatchJobFiles& files, int threads);

struct RunningBatchJob {
  pid_t pid = -1;
  std::chrono::steady_clock::time_point start;
};

// Empties the job's folder and starts its child (stdin /dev/null, stdout to log.txt, stderr to errors.txt). Throws
// InputError when the folder cannot be made or the process cannot be started.
RunningBatchJob startBatchJob(const BatchManifest& manifest, const BatchJob& job, const BatchJobFiles& files,
                              int threads);

// After the child ended with waitStatus (as waitpid reports it): reads its stats and the line that says why it failed,
// makes the glb when asked, removes what the manifest did not ask for, writes done.json (exit status 0) or
// failed.json, and returns the job's summary row.
nlohmann::json finishBatchJob(const BatchManifest& manifest, const BatchJob& job, const BatchJobFiles& files,
                              int waitStatus, double wallTime);

}  // namespace drape::app
