// sceneFileText: a scene file reproducing the document (scene_document.h).
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QStringList>

#include "drape/qt/scene_document.h"

namespace drape::qt {
namespace {

QJsonObject readObject(const std::filesystem::path& file) {
  QFile f(QString::fromStdString(file.string()));
  if (!f.open(QIODevice::ReadOnly)) return {};
  const QJsonDocument doc = QJsonDocument::fromJson(f.readAll());
  return doc.isObject() ? doc.object() : QJsonObject();
}

QJsonValue typedValue(const std::string& key, const std::string& value) {
  const SettingSpec* spec = Settings::find(key);
  const QString text = QString::fromStdString(value);
  if (!spec) return text;
  switch (spec->type) {
    case SettingType::Number: return text.toDouble();
    case SettingType::Integer: return text.toLongLong();
    case SettingType::Boolean: return value == "true";
    case SettingType::Vector3: {
      QJsonArray array;
      for (const QString& part : text.split(',')) array.append(part.trimmed().toDouble());
      return array;
    }
    default: return text;
  }
}

// Sets root["a"]["b"]["c"] = value for the dotted key "a.b.c".
void setDotted(QJsonObject& root, const QStringList& parts, int index, const QJsonValue& value) {
  const QString& part = parts[index];
  if (index + 1 == parts.size()) {
    root[part] = value;
    return;
  }
  QJsonObject child = root[part].toObject();
  setDotted(child, parts, index + 1, value);
  root[part] = child;
}

QString relativePath(const std::filesystem::path& file, const std::filesystem::path& target) {
  const std::filesystem::path absolute = std::filesystem::absolute(file).lexically_normal();
  const std::filesystem::path folder = std::filesystem::absolute(target).parent_path().lexically_normal();
  std::filesystem::path rel = absolute.lexically_relative(folder);
  return QString::fromStdString((rel.empty() ? absolute : rel).generic_string());
}

}  // namespace

std::string sceneFileText(const Scene& scene, const SceneState& state, const std::filesystem::path& target) {
  // Keep the structure of an opened scene file (name, description, pins, colliders); a bare pattern starts empty.
  QJsonObject root;
  if (!state.input.empty() && !isPatternFile(state.input)) root = readObject(state.input);
  for (const std::string& section : sceneSettingSections()) root.remove(QString::fromStdString(section));
  root.remove("pattern");

  root["pattern"] = relativePath(scene.patternFile, target);
  for (const auto& [key, value] : scene.settings.changed()) {
    if (key == "pattern" || key == "avatar.file" || value.empty()) continue;
    setDotted(root, QString::fromStdString(key).split('.'), 0, typedValue(key, value));
  }
  if (!scene.avatarFile.empty()) setDotted(root, {"avatar", "file"}, 0, relativePath(scene.avatarFile, target));

  if (state.vertexPins) {
    // The GUI's vertex pins replace the file's vertex pins; edge and region pins stay as written.
    QJsonArray pins;
    for (const QJsonValue& pin : root["pins"].toArray())
      if (!pin.toObject().contains("vertices")) pins.append(pin);
    if (!state.vertexPins->empty()) {
      QJsonArray vertices;
      for (int v : *state.vertexPins) vertices.append(v);
      QJsonObject pin{{"vertices", vertices}};
      // The placed positions make the pin survive a renumbered mesh (docs/FORMATS.md, "pins").
      if (state.vertexPinPositions.size() == state.vertexPins->size()) {
        QJsonArray at;
        for (const auto& p : state.vertexPinPositions) at.append(QJsonArray{p[0], p[1], p[2]});
        pin["at"] = at;
      }
      pins.append(pin);
    }
    if (pins.isEmpty())
      root.remove("pins");
    else
      root["pins"] = pins;
  }

  QJsonObject panelFabrics = root["panel_fabrics"].toObject();
  for (const auto& [panel, preset] : state.panelPresets) {
    if (preset.empty())
      panelFabrics.remove(QString::fromStdString(panel));
    else
      panelFabrics[QString::fromStdString(panel)] = QString::fromStdString(preset);
  }
  if (panelFabrics.isEmpty())
    root.remove("panel_fabrics");
  else
    root["panel_fabrics"] = panelFabrics;
  return QJsonDocument(root).toJson(QJsonDocument::Indented).toStdString();
}

}  // namespace drape::qt
