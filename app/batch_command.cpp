// drape --batch MANIFEST -o OUTDIR [--jobs N] [--list]: every job of a batch manifest on this machine, up to N child
// processes at a time. A job whose done.json exists is skipped, so running the command again finishes a killed or
// partly failed batch. At the end: summary.csv, summary.json and contact_sheet.png in OUTDIR.
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <ostream>
#include <thread>

#include "batch_job.h"
#include "batch_manifest.h"
#include "batch_summary.h"
#include "commands.h"
#include "contact_sheet.h"
#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/core/input_error.h"
#include "drape/io/mesh_export.h"

namespace drape::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// --list: one line per job, tab-separated: id, scene, avatar, fabric, set ("-" for what the scene decides).
void listJobs(const BatchManifest& manifest, std::ostream& out) {
  auto orDash = [](const std::string& s) { return s.empty() ? std::string("-") : s; };
  for (const BatchJob& job : manifest.jobs)
    out << job.id << "\t" << job.scene.text << "\t" << orDash(job.avatar.text) << "\t" << orDash(job.fabric) << "\t"
        << orDash(job.setLabel) << "\n";
}

// "<stem>_<hash of the path>.obj": one file per measurement file, the same in every run (FNV-1a, not std::hash, whose
// value may change between builds).
std::string mannequinFileName(const fs::path& measurements) {
  std::uint32_t hash = 2166136261u;
  for (unsigned char c : measurements.string()) hash = (hash ^ c) * 16777619u;
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", hash);
  return sanitizeJobId(measurements.stem().string()) + "_" + hex + ".obj";
}

// The mannequin of each body-measurement avatar the pending jobs use (drape --make-avatar's code), made once into
// OUTDIR/.mannequins/ (job ids never start with '.') and reused by later runs of the batch.
void prepareMannequins(BatchManifest& manifest, const std::vector<size_t>& pending, const fs::path& outDir,
                       std::ostream& out) {
  for (size_t i : pending) {
    BatchJob& job = manifest.jobs[i];
    if (!job.avatarIsMeasurements) continue;
    job.avatarMesh = outDir / ".mannequins" / mannequinFileName(job.avatar.file);
    std::error_code ec;
    if (fs::exists(job.avatarMesh, ec)) continue;
    fs::create_directories(job.avatarMesh.parent_path(), ec);
    out << "making the mannequin of " << job.avatar.text << " ... " << std::flush;
    exportMesh(makeMannequin(loadBodyMeasurements(job.avatar.file)), job.avatarMesh);
    out << "wrote " << job.avatarMesh.string() << "\n";
  }
}

// The row of a job that could not even be started.
json unstartedRow(const BatchJob& job, const std::string& error) {
  BatchJobOutcome outcome;
  outcome.exitStatus = 1;
  outcome.error = error;
  return summaryRow(job, outcome, {});
}

ContactSheetEntry sheetEntry(const json& row, const fs::path& outDir) {
  auto stem = [](const std::string& file) { return fs::path(file).stem().string(); };
  const std::string avatar = row.at("avatar").get<std::string>();
  const std::string fabric = row.at("fabric").get<std::string>();
  const std::string set = row.at("set").get<std::string>();
  ContactSheetEntry entry;
  const std::string png = row.at("png").get<std::string>();
  if (!png.empty()) entry.image = outDir / png;
  // What the scene decides itself (its avatar, its fabric) is left out of the label.
  entry.label = {stem(row.at("scene").get<std::string>()) + (avatar.empty() ? "" : " on " + stem(avatar)),
                 (fabric.empty() ? "scene fabric" : fabric) + (set.empty() ? "" : ", " + set), statusText(row)};
  entry.failed = !rowSucceeded(row);
  return entry;
}

}  // namespace

int runBatch(const CliOptions& options, std::ostream& out) {
  BatchManifest manifest = loadBatchManifest(options.batch);
  if (options.list) {
    listJobs(manifest, out);
    return 0;
  }
  const auto start = Clock::now();
  const fs::path outDir = options.output;
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec || !fs::is_directory(outDir)) throw InputError(outDir.string() + ": cannot create the output folder");

  const size_t total = manifest.jobs.size();
  std::vector<BatchJobFiles> files;
  std::vector<size_t> pending;  // indices of the jobs without done.json, in id order
  for (size_t i = 0; i < total; ++i) {
    files.push_back(batchJobFiles(manifest, manifest.jobs[i], outDir));
    if (!batchJobFinished(files.back())) pending.push_back(i);
  }
  prepareMannequins(manifest, pending, outDir, out);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const size_t slots = options.jobs > 0 ? static_cast<size_t>(options.jobs) : cores;
  out << "batch " << manifest.file.string() << ": " << total << " jobs, " << total - pending.size()
      << " finished before; running " << pending.size() << ", up to " << slots << " at a time\n"
      << std::flush;

  const auto jobsStart = Clock::now();
  std::vector<json> rows(total);                                  // this run's rows
  std::map<pid_t, std::pair<size_t, Clock::time_point>> running;  // pid -> (job, start)
  size_t next = 0, finishedNow = 0;
  // The jobs finished before count as their rows say (a drape whose quality verdict failed is finished, not done).
  int succeeded = 0, failed = 0;
  for (size_t i = 0, p = 0; i < total; ++i) {
    if (p < pending.size() && pending[p] == i) {
      ++p;
      continue;
    }
    const json row = recordedBatchRow(files[i]);
    (row.is_object() && rowSucceeded(row) ? succeeded : failed) += 1;
  }
  auto report = [&](size_t i) {
    ++finishedNow;
    (rowSucceeded(rows[i]) ? succeeded : failed) += 1;
    const double elapsed = secondsSince(start);
    // From the rate of this run's jobs so far (the mannequins made before them do not count).
    const double left =
        secondsSince(jobsStart) / static_cast<double>(finishedNow) * static_cast<double>(pending.size() - finishedNow);
    char line[160];
    std::snprintf(line, sizeof line, "[%d/%d/%zu] %.1f s, about %.0f s left, last: ", succeeded, failed, total, elapsed,
                  left);
    out << line << manifest.jobs[i].id << " " << statusText(rows[i]) << "\n" << std::flush;
  };
  while (next < pending.size() || !running.empty()) {
    while (running.size() < slots && next < pending.size()) {
      const size_t i = pending[next++];
      try {
        running[startBatchJob(manifest, manifest.jobs[i], files[i]).pid] = {i, Clock::now()};
      } catch (const InputError& e) {
        rows[i] = unstartedRow(manifest.jobs[i], e.what());
        report(i);
      }
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw InputError(std::string("waiting for the batch's jobs failed: ") + std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not one of the jobs
    const auto [i, jobStart] = it->second;
    running.erase(it);
    rows[i] = finishBatchJob(manifest, manifest.jobs[i], files[i], status, secondsSince(jobStart));
    report(i);
  }

  std::vector<ContactSheetEntry> sheet;
  for (size_t i = 0; i < total; ++i) {
    if (rows[i].is_null()) rows[i] = recordedBatchRow(files[i]);
    if (rows[i].is_null())
      rows[i] = unstartedRow(manifest.jobs[i], "no record of this job in " + files[i].dir.string());
    sheet.push_back(sheetEntry(rows[i], outDir));
  }
  writeBatchSummary(rows, outDir);
  const std::string title = manifest.file.filename().string() + ": " + std::to_string(total) + " jobs, " +
                            std::to_string(succeeded) + " done, " + std::to_string(failed) + " failed";
  std::string note;
  const bool drewSheet = writeContactSheet(sheet, title, outDir / "contact_sheet.png", note);
  out << "batch: " << succeeded << " of " << total << " jobs done, " << failed << " failed, in "
      << static_cast<int>(secondsSince(start) + 0.5) << " s; wrote " << (outDir / "summary.csv").string() << ", "
      << (outDir / "summary.json").string();
  if (drewSheet)
    out << ", " << (outDir / "contact_sheet.png").string() << "\n";
  else
    out << "\nnote: " << note << "\n";
  return failed == 0 ? 0 : kBatchJobsFailedExit;
}

}  // namespace drape::app
