#pragma once
// The document the main window edits: which files make the scene plus the user's edits (settings, panel
// fabrics), the Scene loaded from them, and the undo stack. Every edit (a fabric parameter, a setting, an
// opened file) is a new SceneState pushed as one undoable command. A state is applied only after its scene
// and its Simulation were built without error, so a bad file or value leaves the current scene intact.
#include <QObject>
#include <QString>
#include <QUndoStack>
#include <array>
#include <filesystem>
#include <map>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drape/garment/garment.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"

namespace drape::qt {

// Everything needed to rebuild the scene: files plus edits applied over them.
struct SceneState {
  std::filesystem::path input;                      // scene .json or pattern .json; empty: no scene
  std::string avatarFile;                           // replaces the scene's avatar when set
  std::string avatarUnits;                          // m, cm or mm; empty: the scene's
  std::map<std::string, std::string> overrides;     // setting key -> value, applied after the file
  std::map<std::string, std::string> panelPresets;  // panel name -> fabric preset, over the file's
  // Garment vertices pinned in the GUI (sorted, unique). When set, they replace the vertex pins of the file
  // ("pins": [{"vertices": [...]}]) by one vertex pin (none when empty); unset: the file's pins as they are.
  std::optional<std::vector<int>> vertexPins;
  // Placed position (metres, Garment::positions) of each vertexPins entry, same order: the pin's "at", which keeps
  // it on the same cloth point when the mesh is renumbered (PinSpec::at). Empty: indices only.
  std::vector<std::array<double, 3>> vertexPinPositions;
  // The pattern as edited in the pattern view (validated), in place of the file's; null: the file's pattern.
  std::shared_ptr<const Pattern> pattern;

  bool operator==(const SceneState&) const = default;
  SceneRequest request() const;
};

// Loads the state's scene (loadScene plus panel presets and GUI vertex pins); throws InputError.
Scene buildScene(const SceneState& state);

// The scene file that reproduces scene and state: the original file's structure (name, pins, colliders) with
// every setting that differs from its default, the GUI vertex pins (with their placed positions, "at"), and paths
// relative to target's folder.
// Returns JSON text.
std::string sceneFileText(const Scene& scene, const SceneState& state, const std::filesystem::path& target);

class SceneDocument : public QObject {
  Q_OBJECT

 public:
  explicit SceneDocument(QObject* parent = nullptr);
  ~SceneDocument() override;

  // Builds next; on success pushes an undoable command named text (the first scene of the document is installed
  // without one) and returns true. On InputError emits errorOccurred with the message and returns false:
  // nothing changes.
  bool change(const SceneState& next, const QString& text);
  // Convenience edits, each one undoable command.
  bool open(const std::filesystem::path& file);  // a scene or a bare pattern
  bool openAvatar(const std::filesystem::path& file, const std::string& units = "");
  bool setSetting(const std::string& key, const std::string& value);
  bool setSettings(const std::map<std::string, std::string>& values, const QString& text);
  bool setFabricPreset(const std::string& preset);  // default fabric; drops fabric.* parameter overrides
  bool setPanelFabric(const std::string& panel, const std::string& preset);  // empty preset: the default
  // Replaces the pattern by an edit of it (same panels, by name and order). It is checked as the loader checks a
  // file (an invalid one emits errorOccurred with the loader's message and changes nothing). The running stage
  // continues on the new mesh from its current state, carried over through the pattern coordinates.
  bool setPattern(const Pattern& pattern, const QString& text);
  // Writes the current pattern (as edited) as GarmentCode JSON, atomically; throws InputError.
  void savePattern(const std::filesystem::path& file) const;
  // Pins garment vertex when no vertex pin holds it, else unpins it (one undoable command). A vertex held by
  // an edge or region pin of the file cannot be unpinned here: warningsReported says so, returns false.
  bool togglePin(int vertex);
  // Vertices the scene's vertex pins hold (sorted, unique), as resolved on the current garment.
  std::vector<int> vertexPins() const;
  // Per entry of scene().pins: the vertices a vertex pin holds on the current garment, in its order (its saved
  // positions may have corrected the file's indices); empty for edge and region pins.
  std::vector<std::vector<int>> heldVerticesPerPin() const;

  // Where the running simulation is (the controller's latestResumeState). When set, the simulation of an edit
  // that keeps the garment mesh (same files and mesh settings) continues from it: a preview from its current
  // state, a drape from its last preview state. Undo and redo continue the same way.
  void setResumeSource(std::function<std::optional<ResumeState>()> source) { m_resumeSource = std::move(source); }

  // Continues the current scene from a garment state: the vertex positions of an OBJ that Export (or drape
  // --simulate) wrote for this garment (drape::readGarmentState, checkGarmentState). The preview starts from them at
  // rest (a scene whose stage is drape: the drape, as from a preview's hand-over). The scene is not edited, so
  // nothing is pushed on the undo stack; later edits continue from the running state as usual. On InputError (the
  // file cannot be read, or belongs to another garment) emits errorOccurred and returns false: nothing changes.
  bool loadGarmentState(const std::filesystem::path& file);

  // Writes the scene file atomically (drape::writeFileAtomically) and marks the document clean; throws
  // InputError when it cannot be written. An edited pattern is written beside it (STEM.pattern.json), and the scene
  // names that file.
  void save(const std::filesystem::path& file);

  bool hasScene() const { return m_scene != nullptr; }
  const Scene& scene() const { return *m_scene; }
  const SceneState& state() const { return m_state; }
  // The file Save writes to: the opened scene file, or the last file saved; empty for a bare pattern.
  const std::filesystem::path& savePath() const { return m_savePath; }
  // The garment of the current simulation (immutable), for export; null without a scene.
  std::shared_ptr<const Garment> garment() const { return m_garment; }
  QUndoStack* undoStack() { return &m_undo; }
  bool isModified() const { return !m_undo.isClean(); }
  QString displayName() const;

  // Overrides applied to every opened file (the command line's --set), e.g. a coarse mesh in tests.
  void setBaseOverrides(std::vector<std::pair<std::string, std::string>> overrides) {
    m_baseOverrides = std::move(overrides);
  }

 signals:
  // A new scene is current; simulation (already validated) should go to the worker.
  void sceneChanged(std::shared_ptr<drape::Simulation> simulation);
  void errorOccurred(QString message);
  // Warnings of the loaders and the mesher, for the log.
  void warningsReported(QStringList warnings);

 private:
  friend class StateCommand;
  struct Built {
    std::shared_ptr<Scene> scene;
    std::shared_ptr<Simulation> simulation;
  };
  // Throws InputError. Continues from the resume source when state keeps the current garment mesh.
  Built build(const SceneState& state) const;
  bool keepsMesh(const SceneState& state) const;
  // Same files and mesh settings, the pattern aside.
  bool keepsMeshSettings(const SceneState& state) const;
  // Makes state current with its prebuilt scene and announces it.
  void install(const SceneState& state, Built built);
  // Rebuilds state (undo/redo); reports an error and keeps the current scene on failure.
  void restore(const SceneState& state);

  SceneState m_state;
  std::shared_ptr<Scene> m_scene;
  std::shared_ptr<const Garment> m_garment;
  std::filesystem::path m_savePath;
  std::vector<std::pair<std::string, std::string>> m_baseOverrides;
  std::function<std::optional<ResumeState>()> m_resumeSource;
  QUndoStack m_undo;
};

}  // namespace drape::qt
