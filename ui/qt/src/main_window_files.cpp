// MainWindow: files (open, recent, drag and drop, save, export, screenshot) and closing.
#include <QAction>
#include <QCloseEvent>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QImage>
#include <QMenu>
#include <QMimeData>
#include <QSettings>
#include <QUrl>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "drape/io/mesh_export.h"
#include "drape/qt/main_window.h"
#include "drape/qt/scene_document.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/user_dialogs.h"
#include "drape/qt/viewport_widget.h"

namespace drape::qt {
namespace {

constexpr int kMaxRecent = 10;
const QStringList kMeshSuffixes = {"obj", "glb", "gltf", "fbx", "ply", "stl"};

std::filesystem::path toPath(const QString& file) {
  return std::filesystem::path(file.toStdString());
}
QString toQString(const std::filesystem::path& file) {
  return QString::fromStdString(file.string());
}

bool isMeshFile(const std::filesystem::path& file) {
  return kMeshSuffixes.contains(QFileInfo(toQString(file)).suffix().toLower());
}

}  // namespace

bool MainWindow::openFile(const std::filesystem::path& file) {
  const bool ok = isMeshFile(file) && m_document->hasScene() ? m_document->openAvatar(file) : m_document->open(file);
  if (ok) rememberRecent(file);
  return ok;
}

bool MainWindow::saveSceneAs(const std::filesystem::path& file) {
  try {
    m_document->save(file);
  } catch (const InputError& e) {
    showError(tr("Save scene"), QString::fromStdString(e.what()));
    return false;
  }
  log(tr("info"), tr("Saved %1").arg(toQString(file)));
  rememberRecent(file);
  updateTitle();
  return true;
}

bool MainWindow::save() {
  if (!m_document->hasScene()) return false;
  if (m_document->savePath().empty()) {
    onSaveAs();
    return !m_document->isModified();
  }
  return saveSceneAs(m_document->savePath());
}

bool MainWindow::exportGarment(const std::filesystem::path& file) {
  auto garment = m_document->garment();
  if (!garment || !m_snapshot || m_snapshot->positions.rows() != garment->vertexCount()) {
    showError(tr("Export"), tr("%1: no garment to export yet").arg(toQString(file)));
    return false;
  }
  try {
    drape::exportGarment(*garment, m_snapshot->positions, file);
  } catch (const InputError& e) {
    showError(tr("Export"), QString::fromStdString(e.what()));
    return false;
  }
  log(tr("info"), tr("Exported the garment at t = %1 s to %2").arg(m_snapshot->time, 0, 'f', 3).arg(toQString(file)));
  return true;
}

bool MainWindow::loadGarmentState(const std::filesystem::path& file) {
  if (!m_document->loadGarmentState(file)) return false;  // the document's error reaches the dialog
  log(tr("info"), tr("Loaded the garment state %1; Preview or Drape continues from it").arg(toQString(file)));
  return true;
}

bool MainWindow::saveScreenshot(const std::filesystem::path& file) {
  const QImage image = m_viewport->grabFramebuffer();
  try {
    if (image.isNull()) throw InputError(file.string() + ": the viewport has no image to save");
    writeFileAtomically(file, [&](const std::filesystem::path& temp) {
      if (!image.save(toQString(temp), "PNG")) throw InputError(file.string() + ": cannot write the PNG");
    });
  } catch (const InputError& e) {
    showError(tr("Save screenshot"), QString::fromStdString(e.what()));
    return false;
  }
  log(tr("info"), tr("Screenshot %1 (%2 x %3)").arg(toQString(file)).arg(image.width()).arg(image.height()));
  return true;
}

void MainWindow::onOpen() {
  const QString file = QFileDialog::getOpenFileName(this, tr("Open scene or pattern"), QString(),
                                                    tr("Scenes and patterns (*.json *.dxf);;All files (*)"));
  if (!file.isEmpty()) openFile(toPath(file));
}

void MainWindow::onOpenAvatar() {
  const QString file = QFileDialog::getOpenFileName(this, tr("Open avatar"), QString(),
                                                    tr("Meshes (*.obj *.glb *.gltf *.fbx *.ply *.stl);;All files (*)"));
  if (!file.isEmpty()) openFile(toPath(file));
}

void MainWindow::onSaveAs() {
  const QString file =
      QFileDialog::getSaveFileName(this, tr("Save scene"), toQString(m_document->savePath()), tr("Scenes (*.json)"));
  if (!file.isEmpty()) saveSceneAs(toPath(file));
}

void MainWindow::onExport() {
  const QString file = QFileDialog::getSaveFileName(this, tr("Export draped garment"), QStringLiteral("garment.obj"),
                                                    tr("Wavefront OBJ (*.obj);;glTF binary (*.glb);;glTF (*.gltf);;"
                                                       "PLY (*.ply);;STL (*.stl)"));
  if (!file.isEmpty()) exportGarment(toPath(file));
}

void MainWindow::onLoadState() {
  const QString file = QFileDialog::getOpenFileName(this, tr("Load garment state"), QString(),
                                                    tr("Garment state, Wavefront OBJ (*.obj)"));
  if (!file.isEmpty()) loadGarmentState(toPath(file));
}

void MainWindow::onScreenshot() {
  const QString file =
      QFileDialog::getSaveFileName(this, tr("Save screenshot"), QStringLiteral("drape.png"), tr("PNG images (*.png)"));
  if (!file.isEmpty()) saveScreenshot(toPath(file));
}

QStringList MainWindow::recentFiles() {
  return QSettings().value("recentFiles").toStringList();
}

void MainWindow::rememberRecent(const std::filesystem::path& file) {
  const QString path = QFileInfo(toQString(file)).absoluteFilePath();
  QStringList files = recentFiles();
  files.removeAll(path);
  files.prepend(path);
  while (files.size() > kMaxRecent) files.removeLast();
  QSettings().setValue("recentFiles", files);
  rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
  m_recentMenu->clear();
  const QStringList files = recentFiles();
  for (int i = 0; i < files.size(); ++i) {
    QAction* a = m_recentMenu->addAction(QStringLiteral("&%1 %2").arg(i + 1).arg(QFileInfo(files[i]).fileName()));
    a->setToolTip(files[i]);
    const QString file = files[i];
    connect(a, &QAction::triggered, this, [this, file] { openFile(toPath(file)); });
  }
  m_recentMenu->setEnabled(!files.isEmpty());
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (!event->mimeData()->hasUrls()) return;
  for (const QUrl& url : event->mimeData()->urls()) {
    const QString suffix = QFileInfo(url.toLocalFile()).suffix().toLower();
    if (url.isLocalFile() && (suffix == "json" || suffix == "dxf" || kMeshSuffixes.contains(suffix))) {
      event->acceptProposedAction();
      return;
    }
  }
}

void MainWindow::dropEvent(QDropEvent* event) {
  // Scenes and patterns first, so a dropped scene plus avatar end up together.
  QList<QUrl> urls = event->mimeData()->urls();
  auto isScene = [](const QUrl& url) {
    const QString suffix = QFileInfo(url.toLocalFile()).suffix().toLower();
    return suffix == "json" || suffix == "dxf";
  };
  std::stable_sort(urls.begin(), urls.end(), [&](const QUrl& a, const QUrl& b) { return isScene(a) && !isScene(b); });
  for (const QUrl& url : urls)
    if (url.isLocalFile()) openFile(toPath(url.toLocalFile()));
  event->acceptProposedAction();
}

bool MainWindow::maybeSave() {
  if (!m_document->isModified()) return true;
  switch (m_dialogs->askSaveChanges(this, m_document->displayName())) {
    case UserDialogs::SaveChoice::Save: return save();
    case UserDialogs::SaveChoice::Discard: return true;
    case UserDialogs::SaveChoice::Cancel: return false;
  }
  return false;
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!maybeSave()) {
    event->ignore();
    return;
  }
  // Interrupt a running step now; the destructor joins the worker thread.
  m_controller->cancel();
  event->accept();
}

}  // namespace drape::qt
