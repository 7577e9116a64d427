#include "contact_sheet.h"

#ifdef DRAPE_WITH_GUI
#include <QFont>
#include <QFontMetrics>
#include <QGuiApplication>
#include <QImage>
#include <QPainter>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#endif

namespace drape::app {

#ifdef DRAPE_WITH_GUI
namespace {

constexpr int kTile = 256;       // pixels: thumbnail width and height
constexpr int kPad = 10;         // pixels between tiles and around the grid
constexpr int kLineHeight = 17;  // pixels per label line
constexpr int kTitleHeight = 30;

// Qt's debug and warning messages while the sheet is drawn ("XDG_RUNTIME_DIR not set" on a headless machine) say
// nothing the user can act on; critical and fatal ones still reach stderr.
void quietQtMessages(QtMsgType type, const QMessageLogContext&, const QString& message) {
  if (type == QtCriticalMsg || type == QtFatalMsg) std::fprintf(stderr, "drape: Qt: %s\n", qPrintable(message));
}

// Installs quietQtMessages for its lifetime.
struct QuietQtMessages {
  QtMessageHandler previous = qInstallMessageHandler(quietQtMessages);
  ~QuietQtMessages() { qInstallMessageHandler(previous); }
};

// Fonts and QImage text need a QGuiApplication; the batch command makes one on the offscreen platform, only here.
std::unique_ptr<QGuiApplication> offscreenApplication() {
  if (QGuiApplication::instance()) return nullptr;
  qputenv("QT_QPA_PLATFORM", "offscreen");
  static int argc = 1;
  static char name[] = "drape";
  static char* argv[] = {name, nullptr};
  return std::make_unique<QGuiApplication>(argc, argv);
}

void drawTile(QPainter& painter, const ContactSheetEntry& entry, const QRect& tile, const QFont& font) {
  const QImage image = entry.image.empty() ? QImage() : QImage(QString::fromStdString(entry.image.string()));
  painter.fillRect(tile, QColor(235, 235, 235));
  if (image.isNull()) {
    painter.setPen(QColor(120, 120, 120));
    painter.drawText(tile, Qt::AlignCenter, "no picture");
  } else {
    const QImage scaled = image.scaled(tile.size(), Qt::KeepAspectRatio, Qt::SmoothTransformation);
    painter.drawImage(tile.x() + (tile.width() - scaled.width()) / 2, tile.y() + (tile.height() - scaled.height()) / 2,
                      scaled);
  }
  painter.setPen(QPen(entry.failed ? QColor(200, 30, 30) : QColor(160, 160, 160), entry.failed ? 3 : 1));
  painter.drawRect(tile.adjusted(0, 0, -1, -1));
  painter.setFont(font);
  const QFontMetrics metrics(font);
  for (size_t i = 0; i < entry.label.size(); ++i) {
    const bool statusLine = i + 1 == entry.label.size();
    painter.setPen(statusLine && entry.failed ? QColor(200, 30, 30) : QColor(20, 20, 20));
    const QString text = metrics.elidedText(QString::fromStdString(entry.label[i]), Qt::ElideRight, kTile);
    const QRect line(tile.x(), tile.bottom() + 4 + static_cast<int>(i) * kLineHeight, kTile, kLineHeight);
    painter.drawText(line, Qt::AlignLeft | Qt::AlignVCenter, text);
  }
}

}  // namespace

bool writeContactSheet(const std::vector<ContactSheetEntry>& entries, const std::string& title,
                       const std::filesystem::path& file, std::string& note) {
  (void)note;
  const QuietQtMessages quiet;
  const auto application = offscreenApplication();
  const int count = std::max<int>(1, static_cast<int>(entries.size()));
  // One row for up to 5 jobs (a size run), a square grid for large batches.
  const int columns = std::min(count, std::max(5, static_cast<int>(std::ceil(std::sqrt(count)))));
  const int rows = (count + columns - 1) / columns;
  size_t lines = 1;
  for (const auto& e : entries) lines = std::max(lines, e.label.size());
  const int cellHeight = kTile + 8 + static_cast<int>(lines) * kLineHeight;
  QImage sheet(kPad + columns * (kTile + kPad), kTitleHeight + kPad + rows * (cellHeight + kPad), QImage::Format_RGB32);
  sheet.fill(Qt::white);
  {
    QPainter painter(&sheet);
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setRenderHint(QPainter::TextAntialiasing);
    QFont font("DejaVu Sans");
    font.setPixelSize(12);
    QFont titleFont = font;
    titleFont.setPixelSize(16);
    titleFont.setBold(true);
    painter.setFont(titleFont);
    painter.setPen(Qt::black);
    painter.drawText(QRect(kPad, 0, sheet.width() - 2 * kPad, kTitleHeight + kPad / 2),
                     Qt::AlignLeft | Qt::AlignVCenter, QString::fromStdString(title));
    for (size_t i = 0; i < entries.size(); ++i) {
      const int col = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
      const QRect tile(kPad + col * (kTile + kPad), kTitleHeight + kPad + row * (cellHeight + kPad), kTile, kTile);
      drawTile(painter, entries[i], tile, font);
    }
  }
  writeFileAtomically(file, [&](const std::filesystem::path& temp) {
    if (!sheet.save(QString::fromStdString(temp.string()), "PNG")) throw InputError("cannot encode the PNG");
  });
  return true;
}

#else

bool writeContactSheet(const std::vector<ContactSheetEntry>&, const std::string&, const std::filesystem::path&,
                       std::string& note) {
  note = "this build has no GUI (Qt), so no contact sheet is drawn";
  return false;
}

#endif

}  // namespace drape::app
