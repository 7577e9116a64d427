#include "drape/qt/settings_table.h"

#include <QComboBox>
#include <QHeaderView>

namespace drape::qt {
namespace {

enum Column { KeyColumn, ValueColumn, UnitColumn, GroupColumn };

QString describeRange(const SettingSpec& spec) {
  QString text = QString::fromStdString(spec.description);
  if (spec.type == SettingType::Number || spec.type == SettingType::Integer) {
    if (spec.min > -1e299 || spec.max < 1e299)
      text += QStringLiteral("\nrange [%1, %2]").arg(spec.min, 0, 'g', 6).arg(spec.max, 0, 'g', 6);
  }
  text += QStringLiteral("\ndefault: %1")
              .arg(spec.defaultValue.empty() ? QStringLiteral("(unset)") : QString::fromStdString(spec.defaultValue));
  return text;
}

}  // namespace

SettingsTable::SettingsTable(QWidget* parent) : QTableWidget(parent) {
  const auto& specs = Settings::specs();
  setColumnCount(4);
  setRowCount(static_cast<int>(specs.size()));
  setHorizontalHeaderLabels({tr("Setting"), tr("Value"), tr("Unit"), tr("Group")});
  verticalHeader()->hide();
  horizontalHeader()->setSectionResizeMode(KeyColumn, QHeaderView::ResizeToContents);
  horizontalHeader()->setSectionResizeMode(ValueColumn, QHeaderView::Stretch);
  horizontalHeader()->setSectionResizeMode(UnitColumn, QHeaderView::ResizeToContents);
  horizontalHeader()->setSectionResizeMode(GroupColumn, QHeaderView::ResizeToContents);
  setAlternatingRowColors(true);
  setSelectionMode(QAbstractItemView::SingleSelection);
  for (int row = 0; row < static_cast<int>(specs.size()); ++row) {
    const SettingSpec& spec = specs[row];
    auto* key = new QTableWidgetItem(QString::fromStdString(spec.key));
    key->setFlags(key->flags() & ~Qt::ItemIsEditable);
    key->setToolTip(describeRange(spec));
    setItem(row, KeyColumn, key);
    auto* unit = new QTableWidgetItem(QString::fromStdString(spec.unit));
    unit->setFlags(unit->flags() & ~Qt::ItemIsEditable);
    setItem(row, UnitColumn, unit);
    auto* group = new QTableWidgetItem(QString::fromUtf8(settingGroupName(spec.group)));
    group->setFlags(group->flags() & ~Qt::ItemIsEditable);
    group->setToolTip(QString::fromUtf8(settingGroupTitle(spec.group)));
    setItem(row, GroupColumn, group);
    auto* value = new QTableWidgetItem;
    value->setToolTip(describeRange(spec));
    setItem(row, ValueColumn, value);
    if (spec.type == SettingType::Choice || spec.type == SettingType::Boolean) {
      auto* combo = new QComboBox;
      if (spec.type == SettingType::Boolean) combo->addItems({"true", "false"});
      for (const auto& choice : spec.choices) combo->addItem(QString::fromStdString(choice));
      combo->setToolTip(describeRange(spec));
      setCellWidget(row, ValueColumn, combo);
      connect(combo, &QComboBox::textActivated, this, [this, row](const QString& text) { announce(row, text); });
    }
  }
  connect(this, &QTableWidget::itemChanged, this, [this](QTableWidgetItem* item) {
    if (!m_updating && item->column() == ValueColumn) announce(item->row(), item->text());
  });
}

void SettingsTable::showSettings(const Settings& settings) {
  m_updating = true;
  const auto& specs = Settings::specs();
  for (int row = 0; row < static_cast<int>(specs.size()); ++row) {
    const std::string& key = specs[row].key;
    const QString value = settings.has(key) ? QString::fromStdString(settings.text(key)) : QString();
    item(row, ValueColumn)->setText(value);
    if (auto* combo = qobject_cast<QComboBox*>(cellWidget(row, ValueColumn))) {
      const QSignalBlocker blocker(combo);
      combo->setCurrentText(value);
    }
    // Settings that differ from their default are bold.
    QFont font = item(row, KeyColumn)->font();
    font.setBold(value.toStdString() != specs[row].defaultValue);
    item(row, KeyColumn)->setFont(font);
  }
  m_updating = false;
}

int SettingsTable::rowOf(const std::string& key) const {
  const auto& specs = Settings::specs();
  for (int row = 0; row < static_cast<int>(specs.size()); ++row)
    if (specs[row].key == key) return row;
  return -1;
}

QString SettingsTable::valueText(int row) const {
  return item(row, ValueColumn)->text();
}

void SettingsTable::editValue(const std::string& key, const QString& value) {
  const int row = rowOf(key);
  if (row < 0) return;
  item(row, ValueColumn)->setText(value);  // itemChanged announces it
}

void SettingsTable::announce(int row, const QString& value) {
  const std::string key = Settings::specs()[row].key;
  emit settingEdited(key, value.trimmed().toStdString());
}

}  // namespace drape::qt
