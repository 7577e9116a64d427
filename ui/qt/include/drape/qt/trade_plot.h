#pragma once
// The speed <-> accuracy trade as a picture: a scatter plot of wall time against the distance of each
// run's drape to the reference drape, one colour per scene, with each scene's Pareto front drawn through it.
#include <filesystem>
#include <string>
#include <vector>

namespace drape::qt {

struct TradePoint {
  std::string label;         // e.g. "solver.newton.h_max=2e-3", "reference", a level name "Fast"; empty: none
  double wallSeconds = 0.0;  // x: wall time of the run, seconds (> 0, finite)
  double distanceMm = 0.0;   // y: mean distance of the run's drape to the reference drape, mm (>= 0; the reference: 0)
  bool pareto = false;       // on the Pareto front of its series (computed by the caller)
};

struct TradeSeries {
  std::string name;  // one series per scene, e.g. "default", "aline_skirt", "shirt on mean_all"
  std::vector<TradePoint> points;
};

// The axes' titles. The trade plot's by default; another log-log plot drawn by the same machinery (drape
// --scaling-plot: time and memory against the vertex count) gives its own and puts its x in a point's wallSeconds and
// its y in distanceMm.
struct PlotAxes {
  std::string x = "wall time (s)";
  std::string y = "mean distance to the reference drape (mm)";
};

// Draws the trade as a scatter plot (wall time in seconds, log axis, against mean distance to the reference in mm,
// log axis), one coloured series per scene with its name in the legend, each point labelled with its label, and each
// series' Pareto front as a line in the series' colour through its `pareto` points in order of wall time (not in the
// legend); writes it atomically as a width x height PNG on a white background.
//
// Distance 0 (the reference drape itself) cannot sit on a log axis: such points are drawn on the lowest labelled
// line of the distance axis, one decade below the decade of the smallest positive distance (0.01 mm when there is
// none), their label gets " (reference)" unless it already says "reference" (an empty one becomes "reference"), and a
// note under the plot says where 0 mm is drawn.
//
// Series i is drawn in colour i % 10 of the Tableau 10 palette: #1f77b4 (blue), #ff7f0e (orange), #2ca02c, #d62728,
// #9467bd, #8c564b, #e377c2, #7f7f7f, #bcbd22, #17becf; point labels are in a darker shade of it.
//
// Needs a QApplication (QChart is a QGraphicsWidget): makes one on the "offscreen" platform for the call when there
// is no application; call it from the application's thread. Qt's debug and warning messages are silenced while it
// draws. Throws drape::InputError naming `file` when file does not end in .png, width or height is not positive, a
// point's wall time is not positive and finite or its distance not >= 0 and finite (the message names the series and
// point), the process has a QCoreApplication or QGuiApplication but no QApplication, or the file cannot be written
// (missing directory, ...); a failed write leaves any previous file intact.
void writeTradePlot(const std::vector<TradeSeries>& series, const std::string& title, const std::filesystem::path& file,
                    int width = 1200, int height = 800, const PlotAxes& axes = {});

}  // namespace drape::qt
