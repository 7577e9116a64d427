#pragma once
// The Simulation dock: the run buttons (Preview, Drape, Pause, Resume, Reset, Cancel), the speed <-> accuracy
// slider and, folded below, the advanced table of every setting. The buttons trigger the main window's
// actions, so the toolbar, the menu, the shortcuts and this dock share one enabled state.
#include <QString>
#include <QWidget>
#include <string>
#include <vector>

#include "drape/scene/settings.h"
#include "drape/trade/speed_accuracy_levels.h"

class QAction;
class QLabel;
class QSlider;

namespace drape::qt {

class SettingsTable;

struct SimulationActions {
  QAction* preview = nullptr;
  QAction* drape = nullptr;
  QAction* pause = nullptr;
  QAction* resume = nullptr;
  QAction* reset = nullptr;
  QAction* cancel = nullptr;
};

class SimulationPanel : public QWidget {
  Q_OBJECT

 public:
  SimulationPanel(const SimulationActions& actions, QWidget* parent = nullptr);

  // Positions the slider at the level nearest to settings and fills the advanced table.
  void showSettings(const Settings& settings);

  QSlider* speedAccuracySlider() const { return m_slider; }
  // Why the speed/accuracy levels could not be read (the InputError of speedAccuracyLevels()), or empty. Then the
  // slider is disabled and says so; every setting stays editable in the advanced table.
  const QString& levelsError() const { return m_levelsError; }
  SettingsTable* settingsTable() const { return m_table; }

 signals:
  // The slider moved to a level (index into speedAccuracyLevels()).
  void speedAccuracyChosen(int level);
  void settingEdited(std::string key, std::string value);

 private:
  void describeLevel(int level);

  const std::vector<trade::SpeedAccuracyLevel>* m_levels = nullptr;  // speedAccuracyLevels(), if readable
  QString m_levelsError;
  QSlider* m_slider = nullptr;
  QLabel* m_levelLabel = nullptr;
  SettingsTable* m_table = nullptr;
};

}  // namespace drape::qt
