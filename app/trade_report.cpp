#include "trade_report.h"

#include <fstream>

#include "commands.h"
#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#ifdef DRAPE_WITH_GUI
#include "drape/qt/trade_plot.h"
#endif
#include "drape/trade/speed_accuracy_levels.h"

namespace drape::app {

nlohmann::json readTradeReport(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read the trade report");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    throw InputError(file.string() + ": not a trade report (not JSON)");
  }
  if (!j.is_object() || !j.contains("runs") || !j["runs"].is_array() || !j.contains("name"))
    throw InputError(file.string() + ": not a trade report (no \"name\" and \"runs\"; written by drape --bench -o)");
  for (size_t i = 0; i < j["runs"].size(); ++i) {
    const auto& r = j["runs"][i];
    if (!r.is_object() || !r.contains("run") || !r.contains("wall_time_s") || !r.contains("mean_distance_mm") ||
        !r["wall_time_s"].is_number() || !r["mean_distance_mm"].is_number())
      throw InputError(file.string() + ": run " + std::to_string(i) +
                       " has no \"run\", \"wall_time_s\" and \"mean_distance_mm\"");
  }
  return j;
}

void checkPlotPath(const std::filesystem::path& file) {
  if (file.extension() != ".png") throw InputError(file.string() + ": the trade plot is written as .png");
  checkWritableDirectory(file);
}

void plotTradeReports(const std::vector<nlohmann::json>& reports, const std::filesystem::path& file) {
#ifdef DRAPE_WITH_GUI
  std::vector<qt::TradeSeries> series;
  for (const auto& report : reports) {
    qt::TradeSeries s;
    s.name = report.value("name", std::string("scene")) + " (" + report.value("stage", std::string("drape")) + ")";
    // Labelled: the front and the scene's own settings; the "solver." of a setting's key left out.
    for (const auto& r : report["runs"]) {
      std::string label = r.value("run", std::string());
      if (label.rfind("solver.", 0) == 0) label = label.substr(7);
      const bool front = r.value("pareto", false);
      if (!front && label != "default") label.clear();
      s.points.push_back({label, r.value("wall_time_s", 0.0), r.value("mean_distance_mm", 0.0), front});
    }
    series.push_back(std::move(s));
  }
  qt::writeTradePlot(series, "Speed / accuracy trade", file);
#else
  (void)reports;
  throw InputError(file.string() + ": this drape was built without Qt (DRAPE_BUILD_GUI=OFF), which draws the plot");
#endif
}

int runTradePlot(const CliOptions& options, std::ostream& out) {
  checkPlotPath(options.output);
  std::vector<nlohmann::json> reports;
  for (const auto& f : options.reports) reports.push_back(readTradeReport(f));
  plotTradeReports(reports, options.output);
  out << "wrote " << options.output << " (" << reports.size() << " series)\n";
  return 0;
}

int runTradeLevels(const CliOptions& options, std::ostream& out) {
  std::vector<nlohmann::json> reports;
  for (const auto& f : options.reports) reports.push_back(readTradeReport(f));
  // The costs the slider shows are those on the bundled default scene, when it is among the reports.
  std::string referenceScene = reports.front().value("name", std::string());
  for (const auto& r : reports)
    if (r.value("name", std::string()) == "default") referenceScene = "default";
  const nlohmann::json levels = trade::levelsFromReports(reports, referenceScene);
  writeFileAtomically(options.output, levels.dump(2) + "\n");
  out << "wrote " << options.output << " (" << levels["levels"].size() << " levels, " << levels["dropped"].size()
      << " dropped)\n";
  return 0;
}

}  // namespace drape::app
