// The speed/accuracy trade plot: a PNG of the asked size with each scene's points in its colour, the
// point labels and the Pareto fronts drawn; bad file names are refused with the file named.
#include "drape/qt/trade_plot.h"

#include <QColor>
#include <QImage>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "drape/core/input_error.h"
#include "gui_test_support.h"

namespace drape::test {
namespace {

const QColor kBlue("#1f77b4");    // series 0, as trade_plot.h documents
const QColor kOrange("#ff7f0e");  // series 1

// One directory per test: ctest runs the tests in parallel processes.
std::filesystem::path outputDir(const std::string& test) {
  const std::filesystem::path dir = std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "trade_plot" / test;
  std::filesystem::create_directories(dir);
  return dir;
}

// Two scenes: the default one with its reference at distance 0, and a skirt.
std::vector<qt::TradeSeries> twoScenes(bool labels = true, bool fronts = true) {
  auto label = [&](const char* text) { return labels ? std::string(text) : std::string(); };
  qt::TradeSeries def{"default",
                      {{label("reference"), 40.0, 0.0, fronts},
                       {label("Fast"), 2.0, 3.5, fronts},
                       {label("Balanced"), 6.0, 0.9, fronts},
                       {label("solver.newton.h_max=2e-3"), 9.0, 1.4, false}}};
  qt::TradeSeries skirt{"aline_skirt",
                        {{label("Fastest"), 1.2, 12.0, fronts},
                         {label("Accurate"), 15.0, 0.25, fronts},
                         {label("pcg.tol=1e-2"), 20.0, 0.6, false}}};
  return {def, skirt};
}

// Pixels whose channels are all within 12 of colour.
int pixelsOf(const QImage& image, const QColor& colour) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      if (std::abs(c.red() - colour.red()) <= 12 && std::abs(c.green() - colour.green()) <= 12 &&
          std::abs(c.blue() - colour.blue()) <= 12)
        ++count;
    }
  return count;
}

int pixelsDiffering(const QImage& a, const QImage& b) {
  int count = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) count += a.pixel(x, y) != b.pixel(x, y) ? 1 : 0;
  return count;
}

QImage drawAndLoad(const std::vector<qt::TradeSeries>& series, const std::filesystem::path& file, int width,
                   int height) {
  std::filesystem::remove(file);
  qt::writeTradePlot(series, "speed / accuracy", file, width, height);
  return QImage(QString::fromStdString(file.string()));
}

TEST(TradePlot, WritesAPngOfTheAskedSizeWithEachSceneInItsColour) {
  guiApplication();
  const QImage image = drawAndLoad(twoScenes(), outputDir("size") / "two_scenes.png", 900, 600);
  ASSERT_FALSE(image.isNull()) << "the PNG does not load";
  EXPECT_EQ(image.width(), 900);
  EXPECT_EQ(image.height(), 600);
  const int white = pixelsOf(image, Qt::white);
  const int total = image.width() * image.height();
  EXPECT_GT(white, total / 2) << "the background is white";
  EXPECT_GT(total - white, total / 50) << "axes, grid, labels and points";
  // The markers, the front and the legend marker of each scene: several hundred pixels of its colour (about 850 and
  // 650 when this test was written; without the fronts, about 250 and 200).
  EXPECT_GT(pixelsOf(image, kBlue), 300);
  EXPECT_GT(pixelsOf(image, kOrange), 300);
  // Only the PNG is left in the directory: the temporary file was renamed.
  for (const auto& entry : std::filesystem::directory_iterator(outputDir("size")))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

TEST(TradePlot, DrawsThePointLabelsAndTheFronts) {
  guiApplication();
  const std::filesystem::path dir = outputDir("content");
  const QImage full = drawAndLoad(twoScenes(), dir / "full.png", 1000, 700);
  const QImage unlabelled = drawAndLoad(twoScenes(false, true), dir / "unlabelled.png", 1000, 700);
  const QImage noFronts = drawAndLoad(twoScenes(true, false), dir / "no_fronts.png", 1000, 700);
  ASSERT_FALSE(full.isNull());
  ASSERT_EQ(unlabelled.size(), full.size());
  ASSERT_EQ(noFronts.size(), full.size());
  // Six labels of several characters each.
  EXPECT_GT(pixelsDiffering(full, unlabelled), 600);
  // A front is a 2-pixel line across a good part of the plot.
  EXPECT_GT(pixelsOf(full, kBlue), pixelsOf(noFronts, kBlue) + 200);
  EXPECT_GT(pixelsOf(full, kOrange), pixelsOf(noFronts, kOrange) + 200);
}

TEST(TradePlot, DefaultSizeIs1200By800) {
  guiApplication();
  const std::filesystem::path file = outputDir("default_size") / "default_size.png";
  std::filesystem::remove(file);
  qt::writeTradePlot(twoScenes(), "default size", file);
  const QImage image(QString::fromStdString(file.string()));
  ASSERT_FALSE(image.isNull());
  EXPECT_EQ(image.width(), 1200);
  EXPECT_EQ(image.height(), 800);
}

// The message of the InputError writeTradePlot throws, or "(no error)".
std::string errorOf(const std::vector<qt::TradeSeries>& series, const std::filesystem::path& file) {
  try {
    qt::writeTradePlot(series, "trade", file, 400, 300);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(TradePlot, AMissingDirectoryIsAnInputErrorNamingTheFile) {
  guiApplication();
  const std::filesystem::path file = outputDir("missing_directory") / "no_such_directory" / "trade.png";
  std::filesystem::remove_all(file.parent_path());
  const std::string message = errorOf(twoScenes(), file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(TradePlot, ANameNotEndingInPngIsRefused) {
  guiApplication();
  for (const char* name : {"trade.jpg", "trade", "trade.png.txt"}) {
    const std::filesystem::path file = outputDir("extension") / name;
    std::filesystem::remove(file);
    const std::string message = errorOf(twoScenes(), file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find(".png"), std::string::npos) << message;
    EXPECT_FALSE(std::filesystem::exists(file)) << file;
  }
}

TEST(TradePlot, AWallTimeThatCannotSitOnTheLogAxisIsRefused) {
  guiApplication();
  auto series = twoScenes();
  series[1].points[2].wallSeconds = 0.0;
  const std::filesystem::path file = outputDir("zero_time") / "zero_time.png";
  std::filesystem::remove(file);
  const std::string message = errorOf(series, file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("pcg.tol=1e-2"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(file));
}

}  // namespace
}  // namespace drape::test
