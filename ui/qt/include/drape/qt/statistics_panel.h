#pragma once
// The Statistics dock: the latest step (stage, time, step time, iterations, residual, kinetic energy,
// contacts, max strain) and a plot of kinetic energy and residual against simulated time (QtCharts, log axes).
#include <QString>
#include <QWidget>
#include <map>

#include "drape/sim/simulation.h"

class QLabel;
class QLineSeries;
class QLogValueAxis;
class QValueAxis;
class QChartView;

namespace drape::qt {

class StatisticsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit StatisticsPanel(QWidget* parent = nullptr);

  void addReport(const StepReport& report);
  void setStage(const QString& stage);
  // Clears the plot and the figures (new scene, reset).
  void clear();

  int steps() const { return m_steps; }
  // Points in the residual series (the plot keeps at most ~2000 per series, thinning older ones).
  int plottedPoints() const;
  QString figure(const QString& name) const;  // the text of one figure ("iterations", "residual", ...)

 private:
  void setFigure(const QString& name, const QString& text);

  QChartView* m_view = nullptr;
  QLineSeries* m_kinetic = nullptr;
  QLineSeries* m_residual = nullptr;
  QValueAxis* m_timeAxis = nullptr;
  QLogValueAxis* m_kineticAxis = nullptr;
  QLogValueAxis* m_residualAxis = nullptr;
  std::map<QString, QLabel*> m_figures;
  int m_steps = 0;
  double m_totalWall = 0.0;
  double m_minKinetic = 1e300, m_maxKinetic = 0, m_minResidual = 1e300, m_maxResidual = 0;
};

}  // namespace drape::qt
