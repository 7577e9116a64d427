#include "drape/qt/statistics_panel.h"

#include <QChart>
#include <QChartView>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineSeries>
#include <QLogValueAxis>
#include <QTableWidget>
#include <QVBoxLayout>
#include <QValueAxis>
#include <algorithm>
#include <cmath>

namespace drape::qt {
namespace {

constexpr int kMaxPoints = 2000;
constexpr double kFloor = 1e-30;      // log axes need positive values
constexpr double kMaxDecades = 1e-8;  // the plot spans at most 8 decades below its maximum

// Keeps every other point when a series grows past kMaxPoints.
void thin(QLineSeries* series) {
  if (series->count() <= kMaxPoints) return;
  QList<QPointF> points = series->points();
  QList<QPointF> kept;
  kept.reserve(points.size() / 2 + 1);
  for (qsizetype i = 0; i < points.size(); i += 2) kept.push_back(points[i]);
  if (kept.back() != points.back()) kept.push_back(points.back());
  series->replace(kept);
}

// A check's value or threshold in the unit that reads best: percent for stretch and fractions, mm for depths.
QString qualityFigure(const std::string& name, double v) {
  if (name == "max_strain" || name.find("fraction") != std::string::npos)
    return QStringLiteral("%1 %").arg(v * 100.0, 0, 'f', 2);
  if (name == "penetration_depth") return QStringLiteral("%1 mm").arg(v * 1e3, 0, 'f', 2);
  if (name == "at_rest") return v > 0.0 ? QObject::tr("yes") : QObject::tr("no");
  return QString::number(v, 'g', 6);
}

double niceLower(double v) {
  return std::pow(10.0, std::floor(std::log10(std::max(v, kFloor))));
}
double niceUpper(double v) {
  return std::pow(10.0, std::ceil(std::log10(std::max(v, kFloor)) + 1e-9));
}

}  // namespace

StatisticsPanel::StatisticsPanel(QWidget* parent) : QWidget(parent) {
  m_refresh.setSingleShot(true);
  m_refresh.setInterval(kRefreshMs);
  connect(&m_refresh, &QTimer::timeout, this, &StatisticsPanel::flush);
  auto* layout = new QVBoxLayout(this);
  auto* grid = new QGridLayout;
  const QStringList names = {tr("stage"),    tr("time"),           tr("step time"), tr("iterations"),
                             tr("residual"), tr("kinetic energy"), tr("contacts"),  tr("max strain"),
                             tr("unbalanced force"), tr("last step moved")};
  for (int i = 0; i < names.size(); ++i) {
    auto* caption = new QLabel(names[i] + ":");
    caption->setStyleSheet("color: palette(mid);");
    auto* value = new QLabel(QStringLiteral("-"));
    value->setTextInteractionFlags(Qt::TextSelectableByMouse);
    grid->addWidget(caption, i / 2, (i % 2) * 2);
    grid->addWidget(value, i / 2, (i % 2) * 2 + 1);
    m_figures[names[i]] = value;
  }
  grid->setColumnStretch(1, 1);
  grid->setColumnStretch(3, 1);
  layout->addLayout(grid);

  auto* quality = new QHBoxLayout;
  auto* qualityCaption = new QLabel(tr("quality:"));
  qualityCaption->setStyleSheet("color: palette(mid);");
  m_verdict = new QLabel(QStringLiteral("-"));
  m_verdict->setTextInteractionFlags(Qt::TextSelectableByMouse);
  quality->addWidget(qualityCaption);
  quality->addWidget(m_verdict, 1);
  layout->addLayout(quality);
  m_quality = new QTableWidget(0, 3);
  m_quality->setHorizontalHeaderLabels({tr("check"), tr("value"), tr("threshold")});
  m_quality->verticalHeader()->hide();
  m_quality->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  m_quality->setEditTriggers(QAbstractItemView::NoEditTriggers);
  m_quality->setSelectionMode(QAbstractItemView::NoSelection);
  m_quality->setMaximumHeight(170);
  layout->addWidget(m_quality);

  auto* chart = new QChart;
  chart->setTitle(tr("Convergence"));
  chart->legend()->setAlignment(Qt::AlignBottom);
  chart->setMargins(QMargins(4, 4, 4, 4));
  m_kinetic = new QLineSeries;
  m_kinetic->setName(tr("kinetic energy (J, p99)"));
  m_residual = new QLineSeries;
  m_residual->setName(tr("residual"));
  chart->addSeries(m_kinetic);
  chart->addSeries(m_residual);
  m_timeAxis = new QValueAxis;
  m_timeAxis->setTitleText(tr("simulated time (s)"));
  m_timeAxis->setLabelFormat("%.2f");
  m_timeAxis->setRange(0, 0.1);
  m_kineticAxis = new QLogValueAxis;
  m_kineticAxis->setLabelFormat("%.0e");
  m_kineticAxis->setRange(1e-10, 1);
  m_residualAxis = new QLogValueAxis;
  m_residualAxis->setLabelFormat("%.0e");
  m_residualAxis->setRange(1e-6, 1);
  chart->addAxis(m_timeAxis, Qt::AlignBottom);
  chart->addAxis(m_kineticAxis, Qt::AlignLeft);
  chart->addAxis(m_residualAxis, Qt::AlignRight);
  m_kinetic->attachAxis(m_timeAxis);
  m_kinetic->attachAxis(m_kineticAxis);
  m_residual->attachAxis(m_timeAxis);
  m_residual->attachAxis(m_residualAxis);
  m_kineticAxis->setLinePenColor(m_kinetic->color());
  m_residualAxis->setLinePenColor(m_residual->color());
  m_view = new QChartView(chart);
  m_view->setRenderHint(QPainter::Antialiasing);
  m_view->setMinimumHeight(200);
  layout->addWidget(m_view, 1);
}

void StatisticsPanel::setFigure(const QString& name, const QString& text) {
  auto it = m_figures.find(name);
  if (it != m_figures.end()) it->second->setText(text);
}

QString StatisticsPanel::figure(const QString& name) const {
  auto it = m_figures.find(name);
  return it == m_figures.end() ? QString() : it->second->text();
}

int StatisticsPanel::plottedPoints() const {
  return static_cast<int>(m_residual->count());
}

void StatisticsPanel::setStage(const QString& stage) {
  setFigure(tr("stage"), stage);
}

void StatisticsPanel::clear() {
  m_pending.clear();
  m_refresh.stop();
  m_kinetic->clear();
  m_residual->clear();
  m_steps = 0;
  m_totalWall = 0.0;
  m_minKinetic = m_minResidual = 1e300;
  m_maxKinetic = m_maxResidual = 0.0;
  m_timeAxis->setRange(0, 0.1);
  for (auto& [name, label] : m_figures)
    if (name != tr("stage")) label->setText(QStringLiteral("-"));
  clearQuality();
}

void StatisticsPanel::clearQuality() {
  m_verdict->setText(QStringLiteral("-"));
  m_verdict->setStyleSheet(QString());
  m_quality->setRowCount(0);
}

void StatisticsPanel::setQuality(const QualityReport& report) {
  int failed = 0;
  m_quality->setRowCount(static_cast<int>(report.checks.size()));
  for (int row = 0; row < static_cast<int>(report.checks.size()); ++row) {
    const QualityCheck& c = report.checks[row];
    failed += !c.passed;
    const QStringList cells = {QString::fromStdString(c.name), qualityFigure(c.name, c.value),
                               qualityFigure(c.name, c.threshold)};
    for (int column = 0; column < cells.size(); ++column) {
      auto* item = new QTableWidgetItem(cells[column]);
      item->setToolTip(QString::fromStdString(c.message));
      if (!c.passed) item->setForeground(QColor("#c0392b"));
      m_quality->setItem(row, column, item);
    }
  }
  m_verdict->setText(report.passed ? tr("passed")
                                   : tr("failed (%1 of %2 checks)").arg(failed).arg(report.checks.size()));
  m_verdict->setStyleSheet(report.passed ? "color: #1e8449; font-weight: bold;" : "color: #c0392b; font-weight: bold;");
}

QString StatisticsPanel::qualityVerdict() const {
  return m_verdict->text();
}

int StatisticsPanel::qualityRows() const {
  return m_quality->rowCount();
}

QString StatisticsPanel::qualityCell(int row, int column) const {
  const QTableWidgetItem* item = m_quality->item(row, column);
  return item ? item->text() : QString();
}

void StatisticsPanel::addReport(const StepReport& report) {
  m_pending.push_back(report);
  if (!m_refresh.isActive()) m_refresh.start();
}

void StatisticsPanel::flush() {
  if (m_pending.empty()) return;
  const std::vector<StepReport> reports = std::move(m_pending);
  m_pending.clear();
  QList<QPointF> kinetic, residual;
  for (const StepReport& r : reports) {
    ++m_steps;
    m_totalWall += r.wallTime;
    // Log axes: zero values (velocities zeroed during the initial relaxation) are left out of the plot.
    if (std::isfinite(r.kineticEnergy) && r.kineticEnergy > kFloor) {
      kinetic.append(QPointF(r.time, r.kineticEnergy));
      m_minKinetic = std::min(m_minKinetic, r.kineticEnergy);
      m_maxKinetic = std::max(m_maxKinetic, r.kineticEnergy);
    }
    if (std::isfinite(r.residual) && r.residual > kFloor) {
      residual.append(QPointF(r.time, r.residual));
      m_minResidual = std::min(m_minResidual, r.residual);
      m_maxResidual = std::max(m_maxResidual, r.residual);
    }
  }
  const StepReport& report = reports.back();
  setFigure(tr("stage"), QString(stageName(report.stage)) + (report.atRest ? tr(" (at rest)") : QString()));
  setFigure(tr("time"), tr("%1 s (step %2)").arg(report.time, 0, 'f', 4).arg(m_steps));
  setFigure(tr("step time"),
            tr("%1 ms (h = %2 ms)").arg(report.wallTime * 1e3, 0, 'f', 1).arg(report.h * 1e3, 0, 'g', 3));
  // What the stage's solver iterates: the drape Newton and CG, the preview L-BFGS and its line searches' evaluations.
  if (report.quasiNewton)
    setFigure(tr("iterations"),
              tr("%1 L-BFGS, %2 evaluations").arg(report.iterations).arg(report.lineSearchEvaluations));
  else
    setFigure(tr("iterations"), tr("%1 Newton, %2 CG").arg(report.iterations).arg(report.cgIterations));
  setFigure(tr("residual"), QString::number(report.residual, 'e', 2));
  setFigure(tr("kinetic energy"), QStringLiteral("%1 J").arg(report.kineticEnergy, 0, 'e', 2));
  setFigure(tr("contacts"), QString::number(report.contacts));
  setFigure(tr("max strain"), QStringLiteral("%1 %").arg(report.maxStrain * 100.0, 0, 'f', 2));
  // Equilibrium: the unbalanced force per vertex as a share of its weight, RMS and largest.
  setFigure(tr("unbalanced force"), tr("%1 % RMS, %2 % largest of the weight")
                                        .arg(report.forceRms * 100.0, 0, 'g', 3)
                                        .arg(report.forceMax * 100.0, 0, 'g', 3));
  setFigure(tr("last step moved"), tr("%1 mm at most").arg(report.displacementMax * 1e3, 0, 'g', 3));
  if (!kinetic.isEmpty()) {
    m_kinetic->append(kinetic);
    thin(m_kinetic);
    m_kineticAxis->setRange(std::max(niceLower(m_minKinetic), niceUpper(m_maxKinetic) * kMaxDecades),
                            niceUpper(m_maxKinetic));
  }
  if (!residual.isEmpty()) {
    m_residual->append(residual);
    thin(m_residual);
    m_residualAxis->setRange(std::max(niceLower(m_minResidual), niceUpper(m_maxResidual) * kMaxDecades),
                             niceUpper(m_maxResidual));
  }
  m_timeAxis->setRange(0, std::max(0.1, report.time * 1.05));
}

}  // namespace drape::qt
