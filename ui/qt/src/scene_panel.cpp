#include "drape/qt/scene_panel.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>
#include <exception>

namespace drape::qt {
namespace {

// held: the vertices a vertex pin holds on the current garment (empty: unknown, the file's indices are shown).
QString describePin(const PinSpec& pin, const std::vector<int>& held) {
  if (pin.byRegion) {
    return QObject::tr("region [%1, %2, %3] - [%4, %5, %6] m")
        .arg(pin.region.min.x(), 0, 'g', 3)
        .arg(pin.region.min.y(), 0, 'g', 3)
        .arg(pin.region.min.z(), 0, 'g', 3)
        .arg(pin.region.max.x(), 0, 'g', 3)
        .arg(pin.region.max.y(), 0, 'g', 3)
        .arg(pin.region.max.z(), 0, 'g', 3);
  }
  if (!pin.vertices.empty()) {
    const std::vector<int>& shown = held.size() == pin.vertices.size() ? held : pin.vertices;
    QStringList indices;
    for (size_t i = 0; i < shown.size() && i < 12; ++i) indices << QString::number(shown[i]);
    if (shown.size() > 12) indices << QStringLiteral("...");
    const QString text =
        QObject::tr("%n vertex(es): %1", nullptr, static_cast<int>(shown.size())).arg(indices.join(", "));
    return pin.at.empty() ? text : QObject::tr("%1 (at saved positions)").arg(text);
  }
  const QString edge = pin.edgeLabel.empty() ? QString::number(pin.edge) : QString::fromStdString(pin.edgeLabel);
  return QObject::tr("panel %1, edge %2").arg(QString::fromStdString(pin.panel), edge);
}

}  // namespace

ScenePanel::ScenePanel(QWidget* parent) : QWidget(parent) {
  for (const auto& name : fabricPresetNames()) {
    try {
      m_presetDisplayNames[name] = loadFabricPreset(name).name;
    } catch (const std::exception&) {
      m_presetDisplayNames[name] = name;
    }
  }
  auto* layout = new QVBoxLayout(this);
  m_tree = new QTreeWidget;
  m_tree->setColumnCount(2);
  m_tree->setHeaderLabels({tr("Item"), tr("Fabric / details")});
  m_tree->header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  connect(m_tree, &QTreeWidget::itemClicked, this, [this](QTreeWidgetItem* item) {
    if (const QVariant panel = item->data(0, Qt::UserRole); panel.isValid()) emit panelClicked(panel.toInt());
  });
  m_tree->setRootIsDecorated(true);
  layout->addWidget(m_tree, 1);

  auto* avatarRow = new QHBoxLayout;
  m_avatar = new QLabel(tr("Avatar: none"));
  m_avatar->setTextInteractionFlags(Qt::TextSelectableByMouse);
  avatarRow->addWidget(m_avatar, 1);
  m_avatarUnits = new QComboBox;
  m_avatarUnits->addItems({"m", "cm", "mm", "in"});
  m_avatarUnits->setToolTip(tr("Length unit of the avatar file"));
  avatarRow->addWidget(m_avatarUnits);
  auto* openAvatar = new QPushButton(tr("Avatar..."));
  openAvatar->setToolTip(tr("Open an avatar mesh (obj, glb, gltf, fbx, ply, stl)"));
  avatarRow->addWidget(openAvatar);
  layout->addLayout(avatarRow);
  connect(openAvatar, &QPushButton::clicked, this, &ScenePanel::openAvatarRequested);
  connect(m_avatarUnits, &QComboBox::textActivated, this,
          [this](const QString& units) { emit avatarUnitsChosen(units.toStdString()); });
}

void ScenePanel::selectPanel(int panel) {
  QTreeWidgetItem* panels = m_tree->topLevelItemCount() ? m_tree->topLevelItem(0) : nullptr;
  m_tree->setCurrentItem(panels && panel >= 0 && panel < panels->childCount() ? panels->child(panel) : nullptr);
}

void ScenePanel::showScene(const Scene& scene, const std::map<std::string, std::string>& panelPresets,
                           const std::vector<std::vector<int>>& heldVertices) {
  m_tree->clear();
  m_choosers.clear();
  auto* panels = new QTreeWidgetItem(m_tree, {tr("Panels (%1)").arg(scene.pattern.panels.size())});
  for (const auto& panel : scene.pattern.panels) {
    auto* item = new QTreeWidgetItem(panels, {QString::fromStdString(panel.name)});
    item->setData(0, Qt::UserRole, panels->childCount() - 1);
    auto* chooser = new QComboBox;
    chooser->addItem(tr("default (%1)").arg(QString::fromStdString(scene.fabric.name)), QString());
    for (const auto& [stem, display] : m_presetDisplayNames)
      chooser->addItem(QString::fromStdString(display), QString::fromStdString(stem));
    // The user's choice, else the file's panel fabric (matched by its name), else the default.
    auto chosen = panelPresets.find(panel.name);
    int index = 0;
    if (chosen != panelPresets.end()) {
      index = std::max(0, chooser->findData(QString::fromStdString(chosen->second)));
    } else if (auto it = scene.panelFabrics.find(panel.name); it != scene.panelFabrics.end()) {
      index = std::max(0, chooser->findText(QString::fromStdString(it->second.name)));
    }
    chooser->setCurrentIndex(index);
    const std::string name = panel.name;
    connect(chooser, &QComboBox::activated, this, [this, chooser, name](int i) {
      emit panelFabricChosen(name, chooser->itemData(i).toString().toStdString());
    });
    m_tree->setItemWidget(item, 1, chooser);
    m_choosers[panel.name] = chooser;
  }
  panels->setExpanded(true);

  auto* colliders =
      new QTreeWidgetItem(m_tree, {tr("Colliders (%1)").arg(scene.colliders.size() + (scene.hasAvatar() ? 1 : 0))});
  if (scene.hasAvatar())
    new QTreeWidgetItem(colliders, {tr("avatar"), tr("%1 triangles").arg(scene.avatar.triangleCount())});
  for (const auto& c : scene.colliders)
    new QTreeWidgetItem(colliders, {QString::fromStdString(c.name), tr("%1 triangles").arg(c.mesh.triangleCount())});
  colliders->setExpanded(true);

  auto* pins = new QTreeWidgetItem(m_tree, {tr("Pins (%1)").arg(scene.pins.size())});
  for (size_t i = 0; i < scene.pins.size(); ++i)
    new QTreeWidgetItem(pins,
                        {tr("pin %1").arg(i),
                         describePin(scene.pins[i], i < heldVertices.size() ? heldVertices[i] : std::vector<int>{})});
  pins->setExpanded(true);

  m_avatar->setText(scene.avatarFile.empty()
                        ? tr("Avatar: none")
                        : tr("Avatar: %1").arg(QString::fromStdString(scene.avatarFile.filename().string())));
  m_avatar->setToolTip(QString::fromStdString(scene.avatarFile.string()));
  const QSignalBlocker blocker(m_avatarUnits);
  m_avatarUnits->setCurrentText(QString::fromStdString(scene.settings.text("avatar.units")));
}

QComboBox* ScenePanel::panelFabricChooser(const std::string& panel) const {
  auto it = m_choosers.find(panel);
  return it == m_choosers.end() ? nullptr : it->second;
}

}  // namespace drape::qt
