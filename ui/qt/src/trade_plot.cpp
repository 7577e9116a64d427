#include "drape/qt/trade_plot.h"

#include <QApplication>

#include "offscreen_application.h"
#include <QBuffer>
#include <QByteArray>
#include <QFont>
#include <QFontMetricsF>
#include <QGraphicsLayout>
#include <QGraphicsScene>
#include <QGraphicsSimpleTextItem>
#include <QImage>
#include <QLegendMarker>
#include <QLineSeries>
#include <QLogValueAxis>
#include <QPainter>
#include <QScatterSeries>
#include <QThread>
#include <QtCharts/QChart>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"

namespace drape::qt {
namespace {

constexpr double kMarkerSize = 10.0;  // pixels: scatter marker diameter
constexpr int kLabelPixels = 11;      // pixels: point label font size
constexpr int kNoteHeight = 20;       // pixels kept under the chart for the note on where 0 mm is drawn

// Tableau 10, the palette the header documents.
constexpr std::array<const char*, 10> kPalette = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                  "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};


bool endsInPng(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".png";
}

void validate(const std::vector<TradeSeries>& series, const std::filesystem::path& file, int width, int height) {
  if (!endsInPng(file)) throw InputError(file.string() + ": a trade plot is written as PNG: the name must end in .png");
  if (width <= 0 || height <= 0)
    throw InputError(file.string() + ": the plot size " + std::to_string(width) + " x " + std::to_string(height) +
                     " is not positive");
  for (const auto& s : series)
    for (const auto& p : s.points) {
      const std::string where = file.string() + ": series '" + s.name + "' point '" + p.label + "': ";
      if (!std::isfinite(p.wallSeconds) || p.wallSeconds <= 0.0)
        throw InputError(where + "wall time " + std::to_string(p.wallSeconds) + " s is not positive");
      if (!std::isfinite(p.distanceMm) || p.distanceMm < 0.0)
        throw InputError(where + "distance " + std::to_string(p.distanceMm) + " mm is not >= 0");
    }
}

// A log axis' range: whole decades around [lo, hi], with a margin so that no point sits on the frame.
std::pair<double, double> decadeRange(double lo, double hi) {
  return {std::pow(10.0, std::floor(std::log10(lo) - 0.05)), std::pow(10.0, std::ceil(std::log10(hi) + 0.05))};
}

// Where the plot's axes go, and where distance 0 is drawn.
struct PlotRanges {
  double xMin = 0.1, xMax = 10.0;
  double yMin = 0.01, yMax = 1.0;
  double yZero = 0.01;  // mm: the y at which the reference (distance 0) is drawn, a labelled decade line
  bool hasZero = false;
};

PlotRanges plotRanges(const std::vector<TradeSeries>& series) {
  double xLo = std::numeric_limits<double>::infinity(), xHi = 0.0;
  double yLo = std::numeric_limits<double>::infinity(), yHi = 0.0;
  PlotRanges r;
  for (const auto& s : series)
    for (const auto& p : s.points) {
      xLo = std::min(xLo, p.wallSeconds);
      xHi = std::max(xHi, p.wallSeconds);
      if (p.distanceMm > 0.0) {
        yLo = std::min(yLo, p.distanceMm);
        yHi = std::max(yHi, p.distanceMm);
      } else {
        r.hasZero = true;
      }
    }
  if (xHi > 0.0) std::tie(r.xMin, r.xMax) = decadeRange(xLo, xHi);
  if (yHi > 0.0) {
    std::tie(r.yMin, r.yMax) = decadeRange(yLo, yHi);
    r.yZero = std::pow(10.0, std::floor(std::log10(yLo)) - 1.0);
  }
  // The reference sits on a labelled decade line a quarter decade above the bottom of the frame, so that its marker
  // is whole.
  if (r.hasZero) r.yMin = r.yZero / std::pow(10.0, 0.25);
  return r;
}

QLogValueAxis* logAxis(const QString& title, double lo, double hi, const QFont& labelFont, const QFont& titleFont) {
  auto* axis = new QLogValueAxis;
  axis->setBase(10.0);
  axis->setRange(lo, hi);
  axis->setLabelFormat("%g");
  axis->setMinorTickCount(8);
  axis->setMinorGridLineColor(QColor(235, 235, 235));
  axis->setGridLineColor(QColor(200, 200, 200));
  axis->setLabelsFont(labelFont);
  axis->setTitleText(title);
  axis->setTitleFont(titleFont);
  return axis;
}

bool saysReference(const std::string& label) {
  std::string lower = label;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("reference") != std::string::npos;
}

// A point's label to place: its text and the chart position of its marker.
struct PendingLabel {
  QString text;
  QPointF at;
  QColor colour;
};

// Places each label beside its marker, above or below and right or left of it, at the first of those four places
// that stays in the plot area and covers neither a marker nor a label already placed (the least covering one when
// none is free).
void placeLabels(QChart* chart, const std::vector<PendingLabel>& labels, const QFont& font) {
  const QRectF area = chart->plotArea();
  const QFontMetricsF metrics(font);
  std::vector<QRectF> taken;
  for (const auto& l : labels)
    taken.emplace_back(l.at.x() - kMarkerSize / 2, l.at.y() - kMarkerSize / 2, kMarkerSize, kMarkerSize);
  const double gap = kMarkerSize / 2 + 2.0;
  for (const auto& l : labels) {
    const QSizeF size = metrics.size(Qt::TextSingleLine, l.text);
    const std::array<QPointF, 4> corners = {QPointF(l.at.x() + gap, l.at.y() - gap - size.height()),
                                            QPointF(l.at.x() + gap, l.at.y() + gap - 2.0),
                                            QPointF(l.at.x() - gap - size.width(), l.at.y() - gap - size.height()),
                                            QPointF(l.at.x() - gap - size.width(), l.at.y() + gap - 2.0)};
    QRectF best;
    double bestCost = std::numeric_limits<double>::infinity();
    for (const auto& corner : corners) {
      const QRectF rect(corner, size);
      double cost = area.contains(rect) ? 0.0 : 1e9;
      for (const auto& t : taken) {
        const QRectF overlap = rect.intersected(t);
        cost += overlap.width() * overlap.height();
      }
      if (cost < bestCost) {
        bestCost = cost;
        best = rect;
      }
      if (cost == 0.0) break;
    }
    taken.push_back(best);
    auto* item = new QGraphicsSimpleTextItem(l.text, chart);
    item->setFont(font);
    item->setBrush(l.colour);
    item->setPos(best.topLeft());
    item->setZValue(100.0);
  }
}

}  // namespace

void writeTradePlot(const std::vector<TradeSeries>& series, const std::string& title, const std::filesystem::path& file,
                    int width, int height, const PlotAxes& axes) {
  validate(series, file, width, height);
  const QuietQtMessages quiet;
  const auto application = offscreenApplication(file, "the trade plot");  // declared before the scene: outlives it and the chart
  const PlotRanges ranges = plotRanges(series);

  QFont labelFont("DejaVu Sans");
  labelFont.setPixelSize(kLabelPixels);
  QFont axisFont = labelFont;
  axisFont.setPixelSize(12);
  QFont axisTitleFont = axisFont;
  axisTitleFont.setPixelSize(13);
  QFont titleFont = axisFont;
  titleFont.setPixelSize(16);
  titleFont.setBold(true);

  QGraphicsScene scene;
  auto* chart = new QChart;  // owned by the scene
  scene.addItem(chart);
  scene.setSceneRect(0, 0, width, height);
  chart->setAnimationOptions(QChart::NoAnimation);
  chart->setTheme(QChart::ChartThemeLight);
  chart->setBackgroundBrush(Qt::white);
  chart->setBackgroundRoundness(0);
  chart->setDropShadowEnabled(false);
  chart->setTitle(QString::fromStdString(title));
  chart->setTitleFont(titleFont);
  chart->legend()->setAlignment(Qt::AlignTop);
  chart->legend()->setFont(axisFont);
  chart->setMargins(QMargins(10, 10, 20, ranges.hasZero ? 10 + kNoteHeight : 10));
  chart->setGeometry(QRectF(0, 0, width, height));

  auto* xAxis = logAxis(QString::fromStdString(axes.x), ranges.xMin, ranges.xMax, axisFont, axisTitleFont);
  auto* yAxis = logAxis(QString::fromStdString(axes.y), ranges.yMin, ranges.yMax, axisFont, axisTitleFont);
  chart->addAxis(xAxis, Qt::AlignBottom);
  chart->addAxis(yAxis, Qt::AlignLeft);

  auto y = [&](const TradePoint& p) { return p.distanceMm > 0.0 ? p.distanceMm : ranges.yZero; };
  std::vector<std::pair<QScatterSeries*, const TradeSeries*>> scatters;
  for (size_t i = 0; i < series.size(); ++i) {
    const TradeSeries& s = series[i];
    const QColor colour(kPalette[i % kPalette.size()]);
    std::vector<const TradePoint*> front;
    for (const auto& p : s.points)
      if (p.pareto) front.push_back(&p);
    std::stable_sort(front.begin(), front.end(),
                     [](const TradePoint* a, const TradePoint* b) { return a->wallSeconds < b->wallSeconds; });
    if (front.size() > 1) {
      auto* line = new QLineSeries;
      line->setName(QString::fromStdString(s.name + " front"));
      line->setPen(QPen(colour, 2.0));
      for (const TradePoint* p : front) line->append(p->wallSeconds, y(*p));
      chart->addSeries(line);
      line->attachAxis(xAxis);
      line->attachAxis(yAxis);
      for (QLegendMarker* marker : chart->legend()->markers(line)) marker->setVisible(false);
    }
    auto* scatter = new QScatterSeries;
    scatter->setName(QString::fromStdString(s.name));
    scatter->setMarkerShape(QScatterSeries::MarkerShapeCircle);
    scatter->setMarkerSize(kMarkerSize);
    scatter->setColor(colour);
    scatter->setBorderColor(colour.darker(130));
    for (const auto& p : s.points) scatter->append(p.wallSeconds, y(p));
    chart->addSeries(scatter);
    scatter->attachAxis(xAxis);
    scatter->attachAxis(yAxis);
    scatters.emplace_back(scatter, &s);
  }

  // The chart lays itself out on a posted event; labels need its final plot area.
  QCoreApplication::sendPostedEvents(chart, QEvent::LayoutRequest);
  chart->layout()->activate();

  std::vector<PendingLabel> labels;
  for (size_t i = 0; i < scatters.size(); ++i) {
    const auto& [scatter, s] = scatters[i];
    const QColor colour = QColor(kPalette[i % kPalette.size()]).darker(150);
    for (const auto& p : s->points) {
      std::string text = p.label;
      if (p.distanceMm <= 0.0 && !saysReference(text)) text += text.empty() ? "reference" : " (reference)";
      if (text.empty()) continue;  // an unlabelled point
      labels.push_back(
          {QString::fromStdString(text), chart->mapToPosition(QPointF(p.wallSeconds, y(p)), scatter), colour});
    }
  }
  placeLabels(chart, labels, labelFont);
  if (ranges.hasZero) {
    auto* note = new QGraphicsSimpleTextItem(
        QStringLiteral("The reference drape (distance 0) is drawn at %1 mm.").arg(ranges.yZero, 0, 'g', 3), chart);
    note->setFont(labelFont);
    note->setBrush(QColor(90, 90, 90));
    note->setPos(chart->plotArea().left(), height - kNoteHeight - 2);
  }

  QImage image(width, height, QImage::Format_RGB32);
  image.fill(Qt::white);
  {
    QPainter painter(&image);
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setRenderHint(QPainter::TextAntialiasing);
    painter.setRenderHint(QPainter::SmoothPixmapTransform);
    scene.render(&painter, QRectF(0, 0, width, height), QRectF(0, 0, width, height));
  }
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  if (!image.save(&buffer, "PNG")) throw InputError(file.string() + ": cannot encode the PNG");
  writeFileAtomically(file, std::string(bytes.constData(), static_cast<size_t>(bytes.size())));
}

}  // namespace drape::qt
