#pragma once
// Trade reports (`drape --bench -o REPORT.json`, docs/TRADE.md) read back, drawn and turned into the GUI's levels.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

namespace drape::app {

// Reads a trade report. Throws InputError naming the file when it cannot be read or is not a trade report.
nlohmann::json readTradeReport(const std::filesystem::path& file);

// Throws InputError unless file ends in .png and its directory is writable.
void checkPlotPath(const std::filesystem::path& file);

// The Pareto plot of the reports (wall time against mean distance to the reference), one series per report, written
// to file (PNG). Throws InputError when drape was built without Qt, or the file cannot be written.
void plotTradeReports(const std::vector<nlohmann::json>& reports, const std::filesystem::path& file);

}  // namespace drape::app
