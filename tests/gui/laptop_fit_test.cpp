// The main window fits a laptop's 1366 x 768 screen: less a title bar and a taskbar, 1366 x 700 is left. There the
// window needs no more room than that, every dock lies inside it, no dock's content is squeezed below the size it
// needs (what Qt cannot fit is cut off at the window's edge), and a panel that scrolls does so up and down only,
// never narrower than it needs.
#include <QDockWidget>
#include <QScrollArea>
#include <QScrollBar>

#include "drape/qt/main_window.h"
#include "gui_test_support.h"

namespace drape::test {
namespace {

TEST(LaptopFit, EveryDockIsWholeAndInsideTheWindowAt1366x768) {
  if (!guiHaveDisplay()) GTEST_SKIP() << "no display: run under xvfb-run -a";
  guiApplication();
  RecordingDialogs dialogs;
  auto window = openDefaultWindow(&dialogs);
  ASSERT_NE(window, nullptr);
  const QSize laptop(1366, 700);
  window->resize(laptop);
  QTest::qWait(200);
  const QSize needed = window->minimumSizeHint();
  EXPECT_LE(needed.width(), laptop.width());
  EXPECT_LE(needed.height(), laptop.height());
  EXPECT_LE(window->width(), laptop.width());
  EXPECT_LE(window->height(), laptop.height());
  const QList<QDockWidget*> docks = window->findChildren<QDockWidget*>();
  ASSERT_GE(docks.size(), 5);
  for (QDockWidget* dock : docks) {
    if (dock->isHidden()) continue;
    const std::string name = dock->windowTitle().toStdString();
    EXPECT_TRUE(window->rect().contains(dock->geometry())) << name;
    QWidget* content = dock->widget();
    ASSERT_NE(content, nullptr) << name;
    EXPECT_GE(content->width(), content->minimumSizeHint().width()) << name;
    EXPECT_GE(content->height(), content->minimumSizeHint().height()) << name;
    // A panel in a scroll area may scroll up and down, but is never narrower than it needs.
    if (auto* scroll = qobject_cast<QScrollArea*>(content)) {
      ASSERT_NE(scroll->widget(), nullptr) << name;
      EXPECT_GE(scroll->viewport()->width(), scroll->widget()->minimumSizeHint().width()) << name;
      EXPECT_GE(scroll->widget()->width(), scroll->widget()->minimumSizeHint().width()) << name;
    }
  }
  dialogs.answer = qt::UserDialogs::SaveChoice::Discard;
  window->close();
}

}  // namespace
}  // namespace drape::test
