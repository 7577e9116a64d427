// Vertex pins set in the GUI are saved with their placed positions ("at") and load back onto the same vertices,
// also when the file's indices are stale (a renumbered mesh) and after a mesh change in the document.
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSignalSpy>
#include <QTreeWidget>
#include <fstream>

#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/qt/scene_panel.h"
#include "gui_test_support.h"

namespace drape::test {
namespace {

QJsonObject readJson(const std::filesystem::path& file) {
  QFile f(QString::fromStdString(file.string()));
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QJsonDocument::fromJson(f.readAll()).object();
}

void writeJson(const std::filesystem::path& file, const QJsonObject& root) {
  QFile f(QString::fromStdString(file.string()));
  ASSERT_TRUE(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
  f.write(QJsonDocument(root).toJson());
}

qt::SceneState stateOf(const std::filesystem::path& file) {
  qt::SceneState state;
  state.input = file;
  return state;
}

// The vertex with the smallest value of dir . position (a corner of the flat square tablecloth for a diagonal dir).
int extremeVertex(const Garment& g, const Eigen::Vector3d& dir) {
  int best = 0;
  for (int v = 1; v < g.vertexCount(); ++v)
    if (g.positions.row(v).dot(dir) < g.positions.row(best).dot(dir)) best = v;
  return best;
}

class VertexPinSaveTest : public ::testing::Test {
 protected:
  void SetUp() override {
    guiApplication();
    document.setBaseOverrides(coarseOverrides());
    ASSERT_TRUE(document.open(defaultScene()));
  }
  qt::SceneDocument document;
};

TEST_F(VertexPinSaveTest, SavedPinsCarryPositionsAndLoadBackOntoTheSameVertices) {
  const auto garment = document.garment();
  ASSERT_TRUE(garment);
  const int a = 3, b = garment->vertexCount() - 2;
  ASSERT_TRUE(document.togglePin(b));
  ASSERT_TRUE(document.togglePin(a));
  const std::vector<int> pinned = {std::min(a, b), std::max(a, b)};
  ASSERT_EQ(document.vertexPins(), pinned);

  const std::filesystem::path file = testOutputDir() / "gui_pin_at" / "pinned.json";
  std::filesystem::create_directories(file.parent_path());
  document.save(file);
  const QJsonArray pins = readJson(file)["pins"].toArray();
  ASSERT_EQ(pins.size(), 1);
  const QJsonObject pin = pins[0].toObject();
  const QJsonArray vertices = pin["vertices"].toArray(), at = pin["at"].toArray();
  ASSERT_EQ(vertices.size(), 2);
  ASSERT_EQ(at.size(), 2);
  for (int k = 0; k < 2; ++k) {
    const int v = vertices[k].toInt();
    EXPECT_EQ(v, pinned[k]);
    const QJsonArray p = at[k].toArray();
    ASSERT_EQ(p.size(), 3);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(p[c].toDouble(), garment->positions(v, c)) << "vertex " << v << " axis " << c;
  }

  // Loaded back (by a new document, and by the engine as the CLI does): the same vertices.
  qt::SceneDocument reopened;
  ASSERT_TRUE(reopened.open(file));
  EXPECT_EQ(reopened.vertexPins(), pinned);
  EXPECT_EQ(Simulation(loadScene(stateOf(file).request())).pinned(), pinned);

  // Stale indices in the file (as after a renumbering of the mesh): the positions still pin the same vertices.
  QJsonObject root = readJson(file);
  QJsonObject stale = pin;
  stale["vertices"] = QJsonArray{pinned[1], 0};
  root["pins"] = QJsonArray{stale};
  const std::filesystem::path staleFile = file.parent_path() / "stale.json";
  writeJson(staleFile, root);
  EXPECT_EQ(Simulation(loadScene(stateOf(staleFile).request())).pinned(), pinned);
  qt::SceneDocument staleDocument;
  ASSERT_TRUE(staleDocument.open(staleFile));
  EXPECT_EQ(staleDocument.vertexPins(), pinned) << "the document shows the vertices actually pinned";
  // The scene panel lists the vertices held, not the file's stale indices.
  const std::vector<std::vector<int>> held = staleDocument.heldVerticesPerPin();
  ASSERT_EQ(held.size(), 1u);
  EXPECT_EQ(held[0], pinned);  // each entry at its saved position
  qt::ScenePanel panel;
  panel.showScene(staleDocument.scene(), {}, held);
  const QTreeWidgetItem* pinsItem = panel.tree()->topLevelItem(2);
  ASSERT_EQ(pinsItem->childCount(), 1);
  EXPECT_EQ(pinsItem->child(0)->text(1),
            QString("2 vertex(es): %1, %2 (at saved positions)").arg(pinned[0]).arg(pinned[1]));
}

TEST_F(VertexPinSaveTest, CornerPinsFollowAMeshChangeAndInteriorPinsAreRefused) {
  const auto coarsePtr = document.garment();  // keeps the garment alive across edits
  const Garment& coarse = *coarsePtr;
  const int c0 = extremeVertex(coarse, Eigen::Vector3d(1, 0, 1)),
            c1 = extremeVertex(coarse, Eigen::Vector3d(-1, 0, -1));
  const Eigen::RowVector3d p0 = coarse.positions.row(c0), p1 = coarse.positions.row(c1);
  ASSERT_TRUE(document.togglePin(c0));
  ASSERT_TRUE(document.togglePin(c1));
  // A finer mesh keeps the corners where they were (perhaps under other indices): the pins follow them.
  ASSERT_TRUE(document.setSetting("mesh.target_edge_length", "0.07"));
  const auto finePtr = document.garment();
  const Garment& fine = *finePtr;
  ASSERT_NE(fine.vertexCount(), coarse.vertexCount());
  const std::vector<int> held = document.vertexPins();
  ASSERT_EQ(held.size(), 2u);
  std::vector<Eigen::RowVector3d> positions = {fine.positions.row(held[0]), fine.positions.row(held[1])};
  EXPECT_TRUE((positions[0] - p0).norm() < 1e-9 || (positions[0] - p1).norm() < 1e-9);
  EXPECT_TRUE((positions[1] - p0).norm() < 1e-9 || (positions[1] - p1).norm() < 1e-9);
  EXPECT_GT((positions[0] - positions[1]).norm(), 1.0);

  // An interior vertex whose place holds no vertex in a different mesh: the edit is refused with the pin named.
  document.undoStack()->undo();
  ASSERT_EQ(document.garment()->vertexCount(), coarse.vertexCount());
  const auto backPtr = document.garment();
  const Garment& back = *backPtr;
  // An interior vertex that no vertex of the 0.13 m mesh lies within 5 mm of (found with the engine's mesher).
  MeshingOptions other;
  other.targetEdgeLength = 0.13;
  const Garment coarser = buildGarment(document.scene().pattern, other);
  int interior = -1;
  for (int v = 0; v < back.vertexCount() && interior < 0; ++v) {
    const Eigen::RowVector3d p = back.positions.row(v);
    if ((p - p0).norm() < 0.2 || (p - p1).norm() < 0.2) continue;
    if ((coarser.positions.rowwise() - p).rowwise().norm().minCoeff() > 0.01) interior = v;
  }
  ASSERT_GE(interior, 0);
  ASSERT_TRUE(document.togglePin(interior));
  QSignalSpy errors(&document, &qt::SceneDocument::errorOccurred);
  EXPECT_FALSE(document.setSetting("mesh.target_edge_length", "0.13"));
  ASSERT_EQ(errors.count(), 1);
  const std::string message = errors.at(0).at(0).toString().toStdString();
  EXPECT_NE(message.find("pins set in the GUI: vertices["), std::string::npos) << message;
  EXPECT_NE(message.find("mm away"), std::string::npos) << message;
  EXPECT_NE(message.find("re-pin it"), std::string::npos) << message;
  EXPECT_EQ(document.garment()->vertexCount(), back.vertexCount()) << "the scene is kept";
  EXPECT_EQ(document.scene().settings.number("mesh.target_edge_length"), 0.1);
}

}  // namespace
}  // namespace drape::test
