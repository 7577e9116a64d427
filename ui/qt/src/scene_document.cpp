#include "drape/qt/scene_document.h"

#include <QFileInfo>
#include <QUndoCommand>
#include <algorithm>
#include <exception>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "drape/pattern/pattern_edit.h"
#include "drape/pattern/pattern_writer.h"
#include "drape/scene/pins.h"
#include "drape/sim/scene_garment.h"

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
  if (state.pattern) scene.pattern = *state.pattern;
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
  if (state.vertexPins) {
    std::erase_if(scene.pins, [](const PinSpec& pin) { return !pin.vertices.empty(); });
    if (!state.vertexPins->empty()) {
      PinSpec pin;
      pin.vertices = *state.vertexPins;
      if (state.vertexPinPositions.size() == state.vertexPins->size())
        for (const auto& p : state.vertexPinPositions) pin.at.emplace_back(p[0], p[1], p[2]);
      pin.where = state.input.string() + ": pins set in the GUI";
      scene.pins.push_back(std::move(pin));
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
  std::optional<ResumeState> resume;
  if (m_resumeSource && keepsMesh(state)) resume = m_resumeSource();
  if (m_resumeSource && m_garment && !keepsMesh(state) && keepsMeshSettings(state)) {
    // An edited pattern: the Simulation carries the running state to its new mesh through the pattern coordinates.
    resume = m_resumeSource();
    if (resume) resume->garment = m_garment;
  }
  if (resume) {
    // The simulation continues in the stage it was in; the document's scene (what Save writes) keeps its own.
    Scene running = *built.scene;
    running.settings.set("solver.stage", stageName(resume->stage), "simulation");
    built.simulation = std::make_shared<Simulation>(std::move(running), *resume);
  } else {
    built.simulation = std::make_shared<Simulation>(*built.scene);
  }
  return built;
}

bool SceneDocument::keepsMesh(const SceneState& state) const {
  return keepsMeshSettings(state) && state.pattern == m_state.pattern;
}

bool SceneDocument::keepsMeshSettings(const SceneState& state) const {
  if (!m_scene || state.input != m_state.input || state.avatarFile != m_state.avatarFile ||
      state.avatarUnits != m_state.avatarUnits)
    return false;
  auto meshOverrides = [](const SceneState& s) {
    std::map<std::string, std::string> m;
    for (const auto& [key, value] : s.overrides)
      if (key.rfind("mesh.", 0) == 0 || key.rfind("avatar.", 0) == 0) m[key] = value;
    return m;
  };
  return meshOverrides(state) == meshOverrides(m_state);
}

std::vector<std::vector<int>> SceneDocument::heldVerticesPerPin() const {
  std::vector<std::vector<int>> out;
  if (!m_scene) return out;
  for (const PinSpec& pin : m_scene->pins) {
    std::vector<int>& held = out.emplace_back();
    if (pin.vertices.empty()) continue;
    held = pin.vertices;
    if (m_garment) {
      try {
        held = pinVertices(pin, *m_scene, *m_garment);  // saved positions ("at") may correct the indices
      } catch (const std::exception&) {
        // Unresolvable saved positions: building the scene reports that error; show the file's indices meanwhile.
      }
    }
  }
  return out;
}

std::vector<int> SceneDocument::vertexPins() const {
  std::vector<int> vertices;
  for (const std::vector<int>& held : heldVerticesPerPin()) vertices.insert(vertices.end(), held.begin(), held.end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

bool SceneDocument::togglePin(int vertex) {
  if (!m_scene || !m_garment || vertex < 0 || vertex >= m_garment->vertexCount()) return false;
  std::vector<int> vertices = vertexPins();
  const auto it = std::lower_bound(vertices.begin(), vertices.end(), vertex);
  const bool pinned = it != vertices.end() && *it == vertex;
  if (!pinned) {
    // Held by an edge or region pin of the file? Then there is nothing to toggle here.
    for (const PinSpec& pin : m_scene->pins) {
      if (!pin.vertices.empty()) continue;
      try {
        const std::vector<int> held = pinVertices(pin, *m_scene, *m_garment);
        if (std::find(held.begin(), held.end(), vertex) != held.end()) {
          emit warningsReported({tr("vertex %1 is held by %2; edit that pin in the scene file")
                                     .arg(vertex)
                                     .arg(QString::fromStdString(pin.where))});
          return false;
        }
      } catch (const std::exception&) {
        // Unresolvable saved positions: building the scene reports that error; show the file's indices meanwhile.
      }
    }
    vertices.insert(it, vertex);
  } else {
    vertices.erase(it);
  }
  SceneState next = m_state;
  next.vertexPins = vertices;
  next.vertexPinPositions.clear();
  for (int v : vertices)
    next.vertexPinPositions.push_back(
        {m_garment->positions(v, 0), m_garment->positions(v, 1), m_garment->positions(v, 2)});
  return change(next, pinned ? tr("Unpin vertex %1").arg(vertex) : tr("Pin vertex %1").arg(vertex));
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

bool SceneDocument::loadGarmentState(const std::filesystem::path& file) {
  if (!m_scene || !m_garment) {
    emit errorOccurred(QString::fromStdString(file.string() + ": open a scene before loading a garment state"));
    return false;
  }
  std::shared_ptr<Simulation> simulation;
  try {
    Scene running = *m_scene;
    const StagePlan plan = running.settings.stagePlan();
    if (plan != StagePlan::Drape && plan != StagePlan::Preview) running.settings.set("solver.stage", "full", "simulation");
    simulation = simulationFromStateFile(std::move(running), file);
  } catch (const InputError& e) {
    emit errorOccurred(QString::fromStdString(e.what()));
    return false;
  } catch (const std::exception& e) {  // an engine bug: still reported, never a crash of the UI
    emit errorOccurred(QString::fromStdString(file.string() + ": unexpected error: " + e.what()));
    return false;
  }
  emit sceneChanged(std::move(simulation));
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

bool SceneDocument::setPattern(const Pattern& pattern, const QString& text) {
  if (!m_scene) return false;
  SceneState next = m_state;
  Diagnostics diagnostics;
  try {
    next.pattern = std::make_shared<const Pattern>(validatedPattern(pattern, &diagnostics));
  } catch (const InputError& e) {
    emit errorOccurred(QString::fromStdString(e.what()));
    return false;
  }
  if (!change(next, text)) return false;
  QStringList warnings;
  for (const auto& w : diagnostics.warnings()) warnings << QString::fromStdString(w);
  if (!warnings.isEmpty()) emit warningsReported(warnings);
  return true;
}

void SceneDocument::savePattern(const std::filesystem::path& file) const {
  if (!m_scene) throw InputError(file.string() + ": no pattern to save");
  drape::savePattern(m_scene->pattern, file);
}

void SceneDocument::save(const std::filesystem::path& file) {
  if (!m_scene) throw InputError(file.string() + ": no scene to save");
  if (m_state.pattern) {
    // The edited pattern goes beside the scene, which names it.
    Scene scene = *m_scene;
    scene.patternFile = file.parent_path() / (file.stem().string() + ".pattern.json");
    drape::savePattern(scene.pattern, scene.patternFile);
    writeFileAtomically(file, sceneFileText(scene, m_state, file));
  } else {
    writeFileAtomically(file, sceneFileText(*m_scene, m_state, file));
  }
  m_savePath = file;
  m_undo.setClean();
}

QString SceneDocument::displayName() const {
  if (m_state.input.empty()) return tr("Untitled");
  const std::filesystem::path& shown = m_savePath.empty() ? m_state.input : m_savePath;
  return QString::fromStdString(shown.filename().string());
}

}  // namespace drape::qt
