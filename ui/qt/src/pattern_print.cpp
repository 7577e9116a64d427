#include "drape/qt/pattern_print.h"

#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <QSvgGenerator>
#include <algorithm>
#include <cctype>
#include <string>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "drape/pattern/dxf_aama.h"
#include "drape/pattern/pattern_writer.h"
#include "drape/qt/pattern_sheet.h"
#include "offscreen_application.h"

namespace drape::qt {
namespace {

constexpr double kMarginMm = 10.0;
constexpr double kSvgPixelsPerMm = 10.0;  // SVG user units per millimetre (254 dpi)

std::string lowerExtension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

bool isPrintFile(const std::filesystem::path& file) {
  const std::string ext = lowerExtension(file);
  return ext == ".pdf" || ext == ".svg";
}

void printPattern(const Pattern& pattern, const std::filesystem::path& file) {
  if (!isPrintFile(file)) throw InputError(file.string() + ": a printed pattern is written as .pdf or .svg");
  const QuietQtMessages quiet;
  const auto application = offscreenApplication(file, "the pattern");  // outlives the sheet
  PatternSheet sheet;
  sheet.setEditable(false);
  sheet.setBackgroundBrush(Qt::white);
  sheet.setPattern(pattern);
  sheet.setCheckSquare(true);  // also lays the items out now
  const QRectF content =
      (sheet.panelsRect() | sheet.checkSquareRect()).adjusted(-kMarginMm, -kMarginMm, kMarginMm, kMarginMm);
  const bool pdf = lowerExtension(file) == ".pdf";
  writeFileAtomically(file, [&](const std::filesystem::path& temporary) {
    const QString path = QString::fromStdString(temporary.string());
    if (pdf) {
      QPdfWriter writer(path);
      writer.setCreator("Drape");
      writer.setTitle(QString::fromStdString(pattern.source));
      writer.setPageSize(QPageSize(content.size(), QPageSize::Millimeter, QString(), QPageSize::ExactMatch));
      writer.setPageMargins(QMarginsF(0, 0, 0, 0));
      writer.setResolution(600);
      QPainter painter(&writer);
      if (!painter.isActive()) throw InputError("Qt cannot open it for drawing");
      sheet.render(&painter, QRectF(0, 0, writer.width(), writer.height()), content, Qt::IgnoreAspectRatio);
      painter.end();
    } else {
      QSvgGenerator generator;
      generator.setFileName(path);
      generator.setTitle(QString::fromStdString(pattern.source));
      generator.setDescription("Drape: the pattern at full scale, with a 10 cm check square");
      const QSizeF size = content.size() * kSvgPixelsPerMm;
      generator.setSize(size.toSize());
      generator.setViewBox(QRectF(QPointF(0, 0), size));
      generator.setResolution(static_cast<int>(kSvgPixelsPerMm * 25.4));
      QPainter painter(&generator);
      if (!painter.isActive()) throw InputError("Qt cannot open it for drawing");
      sheet.render(&painter, QRectF(QPointF(0, 0), size), content, Qt::IgnoreAspectRatio);
      painter.end();
    }
  });
}

void writePatternFile(const Pattern& pattern, const std::filesystem::path& file) {
  const std::string ext = lowerExtension(file);
  if (ext == ".json")
    savePattern(pattern, file);
  else if (ext == ".dxf")
    writeDxfAamaPattern(pattern, file);
  else if (isPrintFile(file))
    printPattern(pattern, file);
  else
    throw InputError(file.string() + ": a pattern is written as .json (GarmentCode), .dxf (DXF-AAMA), .pdf or .svg");
}

}  // namespace drape::qt
