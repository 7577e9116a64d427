#pragma once
// The advanced section of the Simulation dock: every setting of Settings::specs() in one table (key, value,
// unit, group; rows in the groups' order), a description in each row's tooltip. Choices and flags are combo boxes, numbers and text are
// editable cells. An edit is announced, not applied: the document validates it and the table is refreshed.
#include <QTableWidget>
#include <string>

#include "drape/scene/settings.h"

namespace drape::qt {

class SettingsTable : public QTableWidget {
  Q_OBJECT

 public:
  explicit SettingsTable(QWidget* parent = nullptr);

  // Shows the values of settings (an unset optional setting shows an empty cell).
  void showSettings(const Settings& settings);
  // Row of key, -1 when absent.
  int rowOf(const std::string& key) const;
  QString valueText(int row) const;
  // Sets the value cell of key as a user would and announces the edit (used by tests).
  void editValue(const std::string& key, const QString& value);

 signals:
  void settingEdited(std::string key, std::string value);

 private:
  void announce(int row, const QString& value);
  bool m_updating = false;
};

}  // namespace drape::qt
