#include "slurm_submit.h"

#include <fstream>
#include <sstream>

#include "child_process.h"
#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"

namespace drape::app {
namespace {

namespace fs = std::filesystem;

// A word for /bin/sh: in single quotes, each ' written as '\''.
std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// The #SBATCH lines (the logs' paths go on sbatch's command line: OUTDIR may hold spaces).
std::string header(const SlurmRequest& request, const std::string& name) {
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "#SBATCH --job-name=" << name << "\n"
    << "#SBATCH --ntasks=1\n";
  if (request.cpusPerTask > 0) s << "#SBATCH --cpus-per-task=" << request.cpusPerTask << "\n";
  if (!request.partition.empty()) s << "#SBATCH --partition=" << request.partition << "\n";
  if (!request.timeLimit.empty()) s << "#SBATCH --time=" << request.timeLimit << "\n";
  return s.str();
}

std::string batchCommand(const SlurmRequest& request) {
  return "exec " + shellQuoted(request.drape.string()) + " --batch " + shellQuoted(request.manifest.string()) +
         " -o " + shellQuoted(request.outDir.string());
}

std::string readFirstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

// Runs sbatch with arguments; returns the job id it prints (--parsable: "ID" or "ID;CLUSTER").
std::string sbatch(const fs::path& program, const std::vector<std::string>& arguments, const fs::path& folder) {
  const fs::path out = folder / "sbatch.out", err = folder / "sbatch.err";
  const int status = waitForProcess(spawnProcess(program, arguments, out, err));
  const std::string id = readFirstLine(out);
  if (exitStatusOf(status) != 0 || id.empty() || id.find_first_not_of("0123456789;_-.abcdefghijklmnopqrstuvwxyz") !=
                                                     std::string::npos) {
    std::string why = readFirstLine(err);
    if (why.empty()) why = "exit status " + std::to_string(exitStatusOf(status));
    throw InputError("--slurm: sbatch " + arguments.back() + " failed: " + why);
  }
  return id.substr(0, id.find(';'));
}

// The jobs of the last submission into this OUTDIR that Slurm still lists (pending or running), from squeue.
std::string stillQueued(const fs::path& folder) {
  std::ifstream in(folder / "submitted.txt");
  std::string ids;
  std::getline(in, ids);
  const fs::path squeue = findOnPath("squeue");
  if (ids.empty() || squeue.empty()) return "";
  const fs::path out = folder / "squeue.out", err = folder / "squeue.err";
  // squeue refuses ids it has forgotten (exit 1): then none of them is queued.
  waitForProcess(spawnProcess(squeue, {"-h", "-o", "%i", "-j", ids}, out, err));
  std::ifstream listed(out);
  std::string line, queued;
  while (std::getline(listed, line))
    if (!line.empty()) queued += (queued.empty() ? "" : " ") + line;
  return queued;
}

}  // namespace

std::string slurmArraySpec(const std::vector<int>& indices) {
  std::string spec;
  for (size_t i = 0; i < indices.size();) {
    size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    spec += (spec.empty() ? "" : ",") + std::to_string(indices[i]);
    if (j > i) spec += "-" + std::to_string(indices[j]);
    i = j + 1;
  }
  return spec;
}

std::string slurmArrayScript(const SlurmRequest& request) {
  return header(request, request.name) +
         "#SBATCH --array=" + slurmArraySpec(request.shards) + "\n" +
         "# Written by drape --batch --slurm: array task I drapes the batch's jobs whose index is I modulo " +
         std::to_string(request.shardCount) + ".\n" + batchCommand(request) + " --shard \"$SLURM_ARRAY_TASK_ID/" +
         std::to_string(request.shardCount) + "\"\n";
}

std::string slurmGatherScript(const SlurmRequest& request) {
  SlurmRequest one = request;
  one.cpusPerTask = 1;  // drawing the contact sheet needs no more
  return header(one, request.name + "-gather") +
         "# Written by drape --batch --slurm: the summary and contact sheet once the array has ended.\n" +
         batchCommand(request) + " --gather\n";
}

SlurmSubmission submitToSlurm(const SlurmRequest& request) {
  const fs::path program = findOnPath("sbatch");
  if (program.empty())
    throw InputError("--slurm: sbatch is not on PATH (run this on a Slurm login node, or start a local one: "
                     "scripts/slurm-local.sh start)");
  const fs::path folder = request.outDir / ".slurm";
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError(folder.string() + ": cannot create the folder: " + ec.message());
  // A task of an earlier submission still running a job that a new one would start again would clash with it.
  if (const std::string queued = stillQueued(folder); !queued.empty())
    throw InputError("--slurm: " + request.outDir.string() + " has Slurm jobs still queued or running (" + queued +
                     "); wait for them (squeue) or cancel them (scancel) first");
  SlurmSubmission submission;
  submission.arrayScript = folder / "array.sbatch";
  submission.gatherScript = folder / "gather.sbatch";
  writeFileAtomically(submission.arrayScript, slurmArrayScript(request));
  writeFileAtomically(submission.gatherScript, slurmGatherScript(request));
  submission.arrayJob = sbatch(
      program, {"--parsable", "--output=" + (folder / "task-%A_%a.log").string(), submission.arrayScript.string()},
      folder);
  // Recorded before the gathering job is submitted, so that its array is seen as queued even if that submission fails.
  writeFileAtomically(folder / "submitted.txt", submission.arrayJob + "\n");
  submission.gatherJob = sbatch(program,
                                {"--parsable", "--output=" + (folder / "gather-%j.log").string(),
                                 "--dependency=afterany:" + submission.arrayJob, submission.gatherScript.string()},
                                folder);
  writeFileAtomically(folder / "submitted.txt", submission.arrayJob + "," + submission.gatherJob + "\n");
  return submission;
}

}  // namespace drape::app
