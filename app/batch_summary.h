#pragma once
// The summary of a batch: one row per job (what it draped, how it ended, the numbers of its --stats and where its
// outputs are), written as OUTDIR/summary.csv and OUTDIR/summary.json.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch_manifest.h"

namespace drape::app {

// What a finished child process left: its exit status (128 + signal when killed), its --stats (null when it wrote
// none), the line that says why it failed (empty on success) and its wall time.
struct BatchJobOutcome {
  int exitStatus = 0;
  nlohmann::json stats;
  std::string error;
  double wallTime = 0.0;  // seconds
};

// The job's row: id, scene, avatar, size, fabric, set, status (the stats' end status, or "Failed" without stats),
// exit_status, error, wall_time_s, sim_time_s, steps, max_strain, inside_vertices, self_intersections, at_rest,
// quality_passed and the output paths relative to OUTDIR (obj, glb, png, stats; empty when not written).
// Numbers the stats do not hold are null.
nlohmann::json summaryRow(const BatchJob& job, const BatchJobOutcome& outcome,
                          const std::vector<std::pair<std::string, std::string>>& outputs);

// The row's status for the progress line: "AtRest", "MaxSimTime (exit 4: quality failed)", "Failed (exit 1)".
std::string statusText(const nlohmann::json& row);

// True when the row is of a job that succeeded (exit status 0).
bool rowSucceeded(const nlohmann::json& row);
// True when the row is of a job that ran to its end: succeeded, or drape written with its quality verdict failed
// (exit status 4, marked in the row). A rerun of the batch skips it, as a drape is deterministic.
bool rowFinished(const nlohmann::json& row);

// Writes summary.json (an array of the rows) and summary.csv (a header line and one line per row) atomically.
void writeBatchSummary(const std::vector<nlohmann::json>& rows, const std::filesystem::path& outDir);

}  // namespace drape::app
