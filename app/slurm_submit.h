#pragma once
// A batch on a Slurm cluster: the sbatch script of one job array whose task I runs `drape --batch MANIFEST -o OUTDIR
// --shard I/N` (the local batch's own code, on the jobs whose index is I modulo N), and the script of a job that runs
// `drape --batch ... --gather` once the array has ended, however its tasks ended. Both are written into
// OUTDIR/.slurm/ (job ids never start with '.'), with the tasks' logs; nothing but the drape executable is needed on
// the nodes, and OUTDIR must be on a filesystem they share.
#include <filesystem>
#include <string>
#include <vector>

namespace drape::app {

struct SlurmRequest {
  std::filesystem::path drape;     // the executable the tasks run (absolute)
  std::filesystem::path manifest;  // absolute
  std::filesystem::path outDir;    // absolute
  std::string name;                // the jobs' name: drape-<manifest stem>
  int shardCount = 1;              // N of --shard I/N
  std::vector<int> shards;         // the array's task indices: the shards with unfinished jobs, ascending
  std::string partition;           // empty: the cluster's default
  std::string timeLimit;           // empty: the partition's default
  int cpusPerTask = 0;             // 0: the cluster's default
};

struct SlurmSubmission {
  std::string arrayJob;   // the job id sbatch gave the array
  std::string gatherJob;  // the job id of the gathering job
  std::filesystem::path arrayScript, gatherScript;
};

// "0-3", "1,4-6,9": the indices as sbatch --array takes them.
std::string slurmArraySpec(const std::vector<int>& indices);

// The text of the two scripts.
std::string slurmArrayScript(const SlurmRequest& request);
std::string slurmGatherScript(const SlurmRequest& request);

// Writes the scripts and submits them with sbatch (found on PATH). Throws InputError with sbatch's own error line
// when it is missing or refuses a script.
SlurmSubmission submitToSlurm(const SlurmRequest& request);

}  // namespace drape::app
