#pragma once
// The Fabric dock: the default fabric's preset and its parameters with units. Editing a parameter announces a
// fabric.* setting (so it is saved with the scene and undoable); choosing a preset announces the preset.
#include <QWidget>
#include <string>
#include <vector>

#include "drape/fabric/fabric.h"

class QComboBox;
class QLineEdit;

namespace drape::qt {

class FabricPanel : public QWidget {
  Q_OBJECT

 public:
  explicit FabricPanel(QWidget* parent = nullptr);

  // Shows fabric and selects preset in the chooser.
  void showFabric(const Fabric& fabric, const std::string& preset);

  QComboBox* presetChooser() const { return m_preset; }
  // The editor of a fabric.* setting ("fabric.stretch_warp"), null for an unknown key.
  QLineEdit* editor(const std::string& key) const;

 signals:
  void presetChosen(std::string preset);
  void parameterEdited(std::string key, std::string value);

 private:
  struct Row {
    std::string key;
    double Fabric::*field;
    QLineEdit* edit;
  };
  QComboBox* m_preset = nullptr;
  std::vector<Row> m_rows;
};

}  // namespace drape::qt
