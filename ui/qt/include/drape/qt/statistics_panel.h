#pragma once
// The Statistics dock: the latest step (stage, time, step time, iterations, residual, kinetic energy,
// contacts, max strain), the quality verdict of the last finished stage (each check with its value and threshold),
// and a plot of kinetic energy and residual against simulated time (QtCharts, log axes).
#include <QString>
#include <QTimer>
#include <QWidget>
#include <map>
#include <vector>

#include "drape/sim/drape_quality.h"
#include "drape/sim/simulation.h"

class QLabel;
class QTableWidget;
class QLineSeries;
class QLogValueAxis;
class QValueAxis;
class QChartView;

namespace drape::qt {

class StatisticsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit StatisticsPanel(QWidget* parent = nullptr);

  // Queues a step's report; the figures and the plot refresh at most every kRefreshMs (a fast preview reports
  // hundreds of steps per second, more than a chart can redraw), with every queued point plotted.
  void addReport(const StepReport& report);
  static constexpr int kRefreshMs = 40;
  void setStage(const QString& stage);
  // Clears the plot, the figures and the verdict (new scene, reset).
  void clear();
  // Shows the quality verdict of a finished stage: passed or failed, and a row per check (check, value, threshold;
  // a failed row in red, its message with the place as tooltip).
  void setQuality(const QualityReport& report);
  // Back to no verdict (a stage running again).
  void clearQuality();
  QString qualityVerdict() const;  // "passed", "failed (n of m checks)", or "-" without a verdict
  int qualityRows() const;
  QString qualityCell(int row, int column) const;  // columns: 0 check, 1 value, 2 threshold

  int steps() const { return m_steps; }  // reports shown so far (queued ones count after the next refresh)
  // Points in the residual series (the plot keeps at most ~2000 per series, thinning older ones).
  int plottedPoints() const;
  QString figure(const QString& name) const;  // the text of one figure ("iterations", "residual", ...)

 private:
  void setFigure(const QString& name, const QString& text);
  void flush();  // shows the queued reports

  QChartView* m_view = nullptr;
  QLineSeries* m_kinetic = nullptr;
  QLineSeries* m_residual = nullptr;
  QValueAxis* m_timeAxis = nullptr;
  QLogValueAxis* m_kineticAxis = nullptr;
  QLogValueAxis* m_residualAxis = nullptr;
  std::map<QString, QLabel*> m_figures;
  QLabel* m_verdict = nullptr;
  QTableWidget* m_quality = nullptr;
  std::vector<StepReport> m_pending;
  QTimer m_refresh;
  int m_steps = 0;
  double m_totalWall = 0.0;
  double m_minKinetic = 1e300, m_maxKinetic = 0, m_minResidual = 1e300, m_maxResidual = 0;
};

}  // namespace drape::qt
