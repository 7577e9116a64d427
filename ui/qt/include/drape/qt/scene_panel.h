#pragma once
// The Scene dock: the pattern's panels with the fabric of each (a chooser per panel), the avatar and its
// units, the colliders and the pins of the scene.
#include <QWidget>
#include <map>
#include <string>
#include <vector>

#include "drape/scene/scene.h"

class QComboBox;
class QLabel;
class QTreeWidget;

namespace drape::qt {

class ScenePanel : public QWidget {
  Q_OBJECT

 public:
  explicit ScenePanel(QWidget* parent = nullptr);

  // panelPresets: the user's per-panel choices (SceneState::panelPresets), shown over the file's. heldVertices:
  // per pin, the vertices it holds on the current garment (SceneDocument::heldVerticesPerPin), shown for vertex
  // pins instead of the file's indices, which saved positions may have corrected; empty: the file's indices.
  void showScene(const Scene& scene, const std::map<std::string, std::string>& panelPresets,
                 const std::vector<std::vector<int>>& heldVertices = {});

  QTreeWidget* tree() const { return m_tree; }
  // The fabric chooser of a panel (first item: the default fabric), null for an unknown panel.
  QComboBox* panelFabricChooser(const std::string& panel) const;
  // Makes panel p's row the current one (none for -1), without emitting panelClicked.
  void selectPanel(int panel);

 signals:
  void panelFabricChosen(std::string panel, std::string preset);  // empty preset: the default fabric
  void openAvatarRequested();
  void avatarUnitsChosen(std::string units);
  // A click on panel p's row (p indexes the pattern's panels): the selection shared with the pattern view and 3D.
  void panelClicked(int panel);

 private:
  QTreeWidget* m_tree = nullptr;
  QLabel* m_avatar = nullptr;
  QComboBox* m_avatarUnits = nullptr;
  std::map<std::string, QComboBox*> m_choosers;
  std::map<std::string, std::string> m_presetDisplayNames;  // preset stem -> Fabric::name
};

}  // namespace drape::qt
