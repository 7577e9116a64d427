// drape --batch MANIFEST -o OUTDIR [--jobs N] [--list]: every job of a batch manifest on this machine, up to N child
// processes at a time. A job whose done.json exists is skipped, so running the command again finishes a killed or
// partly failed batch. At the end: summary.csv, summary.json and contact_sheet.png in OUTDIR.
// --shard I/N runs only the jobs whose index is I modulo N and writes no summary; --gather writes the summary of what
// has run; --slurm submits the shards with unfinished jobs as a Slurm job array (slurm_submit.h).
#include <sched.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <ostream>
#include <thread>

#include "batch_job.h"
#include "batch_manifest.h"
#include "batch_summary.h"
#include "child_process.h"
#include "commands.h"
#include "contact_sheet.h"
#include "slurm_submit.h"
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

// --list: one line per job, tab-separated: id, scene, avatar, size and its scale, fabric, set ("-" for what the scene
// decides or what is not given).
void listJobs(const BatchManifest& manifest, std::ostream& out) {
  auto orDash = [](const std::string& s) { return s.empty() ? std::string("-") : s; };
  for (const BatchJob& job : manifest.jobs)
    out << job.id << "\t" << job.scene.text << "\t" << orDash(job.avatar.text) << "\t"
        << (job.size.empty() ? "-" : job.size + " x" + json(job.sizeScale).dump()) << "\t" << orDash(job.fabric)
        << "\t" << orDash(job.setLabel) << "\n";
}

// "<stem>_<hash of the path and scale>.obj": one file per measurement file and graded size, the same in every run
// (FNV-1a, not std::hash, whose value may change between builds).
std::string mannequinFileName(const fs::path& measurements, double scale) {
  std::uint32_t hash = 2166136261u;
  const std::string key = measurements.string() + (scale == 1.0 ? "" : "@" + json(scale).dump());
  for (unsigned char c : key) hash = (hash ^ c) * 16777619u;
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
    job.avatarMesh = outDir / ".mannequins" / mannequinFileName(job.avatar.file, job.sizeScale);
    std::error_code ec;
    if (fs::exists(job.avatarMesh, ec)) continue;
    fs::create_directories(job.avatarMesh.parent_path(), ec);
    out << "making the mannequin of " << job.avatar.text;
    if (!job.size.empty()) out << " in size " << job.size << " (x" << job.sizeScale << ")";
    out << " ... " << std::flush;
    exportMesh(makeMannequin(scaledBodyMeasurements(loadBodyMeasurements(job.avatar.file), job.sizeScale)),
               job.avatarMesh);
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
  const std::string size = row.value("size", std::string());
  ContactSheetEntry entry;
  const std::string png = row.at("png").get<std::string>();
  if (!png.empty()) entry.image = outDir / png;
  // What the scene decides itself (its avatar, its fabric) is left out of the label.
  entry.label = {stem(row.at("scene").get<std::string>()) +
                     (!size.empty() ? ", size " + size : avatar.empty() ? "" : " on " + stem(avatar)),
                 (fabric.empty() ? "scene fabric" : fabric) + (set.empty() ? "" : ", " + set), statusText(row)};
  entry.failed = !rowSucceeded(row);
  return entry;
}

// The cores this process may use: those Slurm gave the job on this node, else those of its CPU affinity.
int availableCores() {
  if (const char* slurm = std::getenv("SLURM_CPUS_ON_NODE")) {
    const int n = std::atoi(slurm);
    if (n > 0) return n;
  }
  cpu_set_t set;
  if (::sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Writes summary.csv, summary.json and contact_sheet.png from the rows (a job without one gets its recorded row, else a
// failed row) and says so. Returns the batch's exit status: 0 when every job succeeded.
int writeSummaries(const BatchManifest& manifest, const std::vector<BatchJobFiles>& files, std::vector<json> rows,
                   const fs::path& outDir, Clock::time_point start, std::ostream& out) {
  const size_t total = manifest.jobs.size();
  rows.resize(total);
  std::vector<ContactSheetEntry> sheet;
  int succeeded = 0;
  for (size_t i = 0; i < total; ++i) {
    if (rows[i].is_null()) rows[i] = recordedBatchRow(files[i]);
    if (rows[i].is_null())
      rows[i] = unstartedRow(manifest.jobs[i], "no record of this job in " + files[i].dir.string());
    succeeded += rowSucceeded(rows[i]) ? 1 : 0;
    sheet.push_back(sheetEntry(rows[i], outDir));
  }
  const size_t failed = total - static_cast<size_t>(succeeded);
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

// --slurm: the array's shards are those holding unfinished jobs; the mannequins are made here first, so that the tasks
// only read them.
int submitBatch(const CliOptions& options, BatchManifest& manifest, const std::vector<size_t>& pending,
                const fs::path& outDir, std::ostream& out) {
  const size_t total = manifest.jobs.size();
  if (pending.empty()) {
    out << "batch " << manifest.file.string() << ": all " << total
        << " jobs have finished; nothing to submit (--gather writes the summary)\n";
    return 0;
  }
  const int shardCount =
      options.tasks > 0 ? options.tasks : static_cast<int>(std::min<size_t>(total, size_t(kMaxArrayTasks)));
  SlurmRequest request;
  request.drape = drapeExecutable();
  request.manifest = fs::absolute(manifest.file);
  request.outDir = fs::absolute(outDir);
  request.name = "drape-" + sanitizeJobId(manifest.file.stem().string());
  request.shardCount = shardCount;
  for (size_t i : pending) request.shards.push_back(static_cast<int>(i % static_cast<size_t>(shardCount)));
  std::sort(request.shards.begin(), request.shards.end());
  request.shards.erase(std::unique(request.shards.begin(), request.shards.end()), request.shards.end());
  request.partition = options.partition;
  request.timeLimit = options.timeLimit;
  request.cpusPerTask = options.cpusPerTask;
  prepareMannequins(manifest, pending, outDir, out);
  const SlurmSubmission submission = submitToSlurm(request);
  out << "batch " << manifest.file.string() << ": " << pending.size() << " of " << total
      << " jobs submitted to Slurm as job array " << submission.arrayJob << " (tasks "
      << slurmArraySpec(request.shards) << " of shards 0-" << shardCount - 1 << "), then job "
      << submission.gatherJob << ", which writes " << (request.outDir / "summary.csv").string()
      << " and the contact sheet; logs in " << (request.outDir / ".slurm").string() << "\n";
  return 0;
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

  std::vector<BatchJobFiles> files;
  for (const BatchJob& job : manifest.jobs) files.push_back(batchJobFiles(manifest, job, outDir));
  if (options.gather) return writeSummaries(manifest, files, {}, outDir, start, out);

  // This run's jobs: all, or those of its shard; pending: those of them without done.json, in id order.
  const bool sharded = options.shardCount > 0;
  std::vector<size_t> mine, pending;
  for (size_t i = 0; i < manifest.jobs.size(); ++i) {
    if (sharded && i % static_cast<size_t>(options.shardCount) != static_cast<size_t>(options.shardIndex)) continue;
    mine.push_back(i);
    if (!batchJobFinished(files[i])) pending.push_back(i);
  }
  if (options.slurm) return submitBatch(options, manifest, pending, outDir, out);
  prepareMannequins(manifest, pending, outDir, out);
  const size_t total = mine.size();
  // --threads caps the cores the batch shares among its jobs.
  const int cores = options.threads > 0 ? std::min(options.threads, availableCores()) : availableCores();
  const size_t slots = options.jobs > 0 ? static_cast<size_t>(options.jobs) : static_cast<size_t>(cores);
  // The cores are shared among the jobs that run at once, so that N jobs do not each start a thread per core.
  const int threads = std::max(1, cores / static_cast<int>(std::max<size_t>(1, std::min(slots, pending.size()))));
  // CHOLMOD's OpenMP threads too (libgomp reads this when a job starts).
  ::setenv("OMP_NUM_THREADS", std::to_string(threads).c_str(), 1);
  out << "batch " << manifest.file.string();
  if (sharded) out << " shard " << options.shardIndex << "/" << options.shardCount;
  out << ": " << total << " jobs, " << total - pending.size() << " finished before; running " << pending.size()
      << ", up to " << slots << " at a time, " << threads << (threads == 1 ? " thread" : " threads") << " each\n"
      << std::flush;

  const auto jobsStart = Clock::now();
  std::vector<json> rows(manifest.jobs.size());                   // this run's rows
  std::map<pid_t, std::pair<size_t, Clock::time_point>> running;  // pid -> (job, start)
  size_t next = 0, finishedNow = 0;
  // The jobs finished before count as their rows say (a drape whose quality verdict failed is finished, not done).
  int succeeded = 0, failed = 0;
  for (size_t i : mine) {
    if (std::binary_search(pending.begin(), pending.end(), i)) continue;
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
        running[startBatchJob(manifest, manifest.jobs[i], files[i], threads).pid] = {i, Clock::now()};
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
  if (!sharded) return writeSummaries(manifest, files, std::move(rows), outDir, start, out);
  // A shard leaves the summary to --gather, which sees every shard's records.
  out << "batch shard " << options.shardIndex << "/" << options.shardCount << ": " << succeeded << " of " << total
      << " jobs done, " << failed << " failed, in " << static_cast<int>(secondsSince(start) + 0.5) << " s\n";
  return failed == 0 ? 0 : kBatchJobsFailedExit;
}

}  // namespace drape::app
