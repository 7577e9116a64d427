#include "drape/qt/fabric_panel.h"

#include <QComboBox>
#include <QDoubleValidator>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>

#include "drape/scene/settings.h"

namespace drape::qt {
namespace {

struct Parameter {
  const char* key;
  const char* label;
  double Fabric::*field;
};

const Parameter kParameters[] = {
    {"fabric.stretch_warp", "Stretch (warp)", &Fabric::stretchWarp},
    {"fabric.stretch_weft", "Stretch (weft)", &Fabric::stretchWeft},
    {"fabric.shear", "Shear", &Fabric::shear},
    {"fabric.bend_warp", "Bending (warp)", &Fabric::bendWarp},
    {"fabric.bend_weft", "Bending (weft)", &Fabric::bendWeft},
    {"fabric.density", "Density", &Fabric::density},
    {"fabric.friction", "Friction", &Fabric::friction},
    {"fabric.thickness", "Thickness", &Fabric::thickness},
    {"fabric.damping", "Damping", &Fabric::damping},
};

}  // namespace

FabricPanel::FabricPanel(QWidget* parent) : QWidget(parent) {
  auto* form = new QFormLayout(this);
  m_preset = new QComboBox;
  for (const auto& name : fabricPresetNames()) m_preset->addItem(QString::fromStdString(name));
  m_preset->setToolTip(tr("Default fabric of every panel (assets/fabrics)"));
  form->addRow(tr("Preset"), m_preset);
  connect(m_preset, &QComboBox::textActivated, this,
          [this](const QString& name) { emit presetChosen(name.toStdString()); });

  for (const auto& p : kParameters) {
    const SettingSpec* spec = Settings::find(p.key);
    auto* edit = new QLineEdit;
    auto* validator = new QDoubleValidator(spec->min, spec->max, 12, edit);
    validator->setNotation(QDoubleValidator::ScientificNotation);
    validator->setLocale(QLocale::c());
    edit->setValidator(validator);
    edit->setToolTip(QString::fromStdString(spec->description));
    auto* row = new QWidget;
    auto* layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(edit, 1);
    auto* unit = new QLabel(QString::fromStdString(spec->unit));
    unit->setMinimumWidth(48);
    layout->addWidget(unit);
    form->addRow(tr(p.label), row);
    m_rows.push_back({p.key, p.field, edit});
    const std::string key = p.key;
    connect(edit, &QLineEdit::editingFinished, this, [this, edit, key] {
      if (edit->isModified()) {
        edit->setModified(false);
        emit parameterEdited(key, edit->text().trimmed().toStdString());
      }
    });
  }
}

void FabricPanel::showFabric(const Fabric& fabric, const std::string& preset) {
  const QSignalBlocker blocker(m_preset);
  m_preset->setCurrentText(QString::fromStdString(preset));
  for (const Row& row : m_rows) {
    row.edit->setText(QString::number(fabric.*(row.field), 'g', 6));
    row.edit->setModified(false);
  }
}

QLineEdit* FabricPanel::editor(const std::string& key) const {
  for (const Row& row : m_rows)
    if (row.key == key) return row.edit;
  return nullptr;
}

}  // namespace drape::qt
