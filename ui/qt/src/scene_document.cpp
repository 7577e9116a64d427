#include "drape/qt/scene_document.h"

#include <QFileInfo>
#include <QUndoCommand>
#include <exception>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"

namespace drape::qt {

SceneRequest SceneState::request() const {
  SceneRequest r;
  r.input = input;
  r.avatarFile = avatarFile;
  r.avatarUnits = avatarUnits;
  r.overrides.assign(overrides.begin(), overrides.end());
  return r;
}

Scene buildScene(const SceneState& state) {
  if (state.input.empty()) throw InputError("no scene file given");
  Scene scene = loadScene(state.request());
  for (const auto& [panel, preset] : state.panelPresets) {
    const std::string where = state.input.string() + ": panel_fabrics '" + panel + "'";
    if (scene.pattern.panelIndex(panel) < 0) throw InputError(where + ": the pattern has no panel of that name");
    if (preset.empty()) {
      scene.panelFabrics.erase(panel);
      continue;
    }
    try {
      scene.panelFabrics[panel] = loadFabricPreset(preset);
    } catch (const InputError& e) {
      throw InputError(where + ": " + e.what());
    }
  }
  return scene;
}

// One undoable edit: the state before and after. The first redo installs the scene built when the command was
// made; later undo/redo rebuild from the files.
class StateCommand : public QUndoCommand {
 public:
  StateCommand(SceneDocument* document, SceneState before, SceneState after, SceneDocument::Built built,
               const QString& text)
      : QUndoCommand(text),
        m_document(document),
        m_before(std::move(before)),
        m_after(std::move(after)),
        m_built(std::move(built)) {}

  void redo() override {
    if (m_built.scene) {
      m_document->install(m_after, std::move(m_built));
      m_built = {};
    } else {
      m_document->restore(m_after);
    }
  }
  void undo() override { m_document->restore(m_before); }

 private:
  SceneDocument* m_document;
  SceneState m_before, m_after;
  SceneDocument::Built m_built;
};

SceneDocument::SceneDocument(QObject* parent) : QObject(parent) {}

SceneDocument::~SceneDocument() = default;

SceneDocument::Built SceneDocument::build(const SceneState& state) const {
  Built built;
  built.scene = std::make_shared<Scene>(buildScene(state));
  // The Simulation validates what the loaders cannot (pins that hold no vertex, meshing failures).
  built.simulation = std::make_shared<Simulation>(*built.scene);
  return built;
}

void SceneDocument::install(const SceneState& state, Built built) {
  const bool newFile = state.input != m_state.input;
  m_state = state;
  m_scene = std::move(built.scene);
  m_garment = std::make_shared<const Garment>(built.simulation->garment());
  if (newFile) m_savePath = isPatternFile(state.input) ? std::filesystem::path() : state.input;
  QStringList warnings;
  for (const auto& w : built.simulation->scene().diagnostics.warnings()) warnings << QString::fromStdString(w);
  if (!warnings.isEmpty()) emit warningsReported(warnings);
  emit sceneChanged(std::move(built.simulation));
}

void SceneDocument::restore(const SceneState& state) {
  try {
    install(state, build(state));
  } catch (const InputError& e) {
    emit errorOccurred(QString::fromStdString(e.what()));
  } catch (const std::exception& e) {  // an engine bug: still reported, never a crash of the UI
    emit errorOccurred(QString::fromStdString(state.input.string() + ": unexpected error: " + e.what()));
  }
}

bool SceneDocument::change(const SceneState& next, const QString& text) {
  if (next == m_state && m_scene) return true;
  Built built;
  try {
    built = build(next);
  } catch (const InputError& e) {
    emit errorOccurred(QString::fromStdString(e.what()));
    return false;
  } catch (const std::exception& e) {  // an engine bug: still reported, never a crash of the UI
    emit errorOccurred(QString::fromStdString(next.input.string() + ": unexpected error: " + e.what()));
    return false;
  }
  if (!m_scene) {
    // The first scene is where the document starts: nothing to undo back to.
    install(next, std::move(built));
    m_undo.clear();
    return true;
  }
  m_undo.push(new StateCommand(this, m_state, next, std::move(built), text));
  return true;
}

bool SceneDocument::open(const std::filesystem::path& file) {
  SceneState next;
  next.input = file;
  for (const auto& [key, value] : m_baseOverrides) next.overrides[key] = value;
  return change(next, tr("Open %1").arg(QString::fromStdString(file.filename().string())));
}

bool SceneDocument::openAvatar(const std::filesystem::path& file, const std::string& units) {
  SceneState next = m_state;
  next.avatarFile = file.string();
  next.avatarUnits = units;
  return change(next, tr("Open avatar %1").arg(QString::fromStdString(file.filename().string())));
}

bool SceneDocument::setSetting(const std::string& key, const std::string& value) {
  return setSettings({{key, value}}, tr("Set %1 = %2").arg(QString::fromStdString(key), QString::fromStdString(value)));
}

bool SceneDocument::setSettings(const std::map<std::string, std::string>& values, const QString& text) {
  SceneState next = m_state;
  for (const auto& [key, value] : values) next.overrides[key] = value;
  return change(next, text);
}

bool SceneDocument::setFabricPreset(const std::string& preset) {
  SceneState next = m_state;
  for (auto it = next.overrides.begin(); it != next.overrides.end();) {
    if (it->first.rfind("fabric.", 0) == 0)
      it = next.overrides.erase(it);
    else
      ++it;
  }
  // A parameter the scene file sets stays unless cleared: clear every fabric override of the file too.
  if (m_scene)
    for (const auto& [key, value] : m_scene->settings.changed())
      if (key.rfind("fabric.", 0) == 0 && key != "fabric.preset") next.overrides[key] = "";
  next.overrides["fabric.preset"] = preset;
  return change(next, tr("Fabric preset %1").arg(QString::fromStdString(preset)));
}

bool SceneDocument::setPanelFabric(const std::string& panel, const std::string& preset) {
  SceneState next = m_state;
  next.panelPresets[panel] = preset;
  return change(
      next, tr("Fabric of panel %1: %2")
                .arg(QString::fromStdString(panel), preset.empty() ? tr("default") : QString::fromStdString(preset)));
}

void SceneDocument::save(const std::filesystem::path& file) {
  if (!m_scene) throw InputError(file.string() + ": no scene to save");
  writeFileAtomically(file, sceneFileText(*m_scene, m_state, file));
  m_savePath = file;
  m_undo.setClean();
}

QString SceneDocument::displayName() const {
  if (m_state.input.empty()) return tr("Untitled");
  const std::filesystem::path& shown = m_savePath.empty() ? m_state.input : m_savePath;
  return QString::fromStdString(shown.filename().string());
}

}  // namespace drape::qt
