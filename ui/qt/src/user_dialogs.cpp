#include "drape/qt/user_dialogs.h"

#include <QMessageBox>

namespace drape::qt {

void UserDialogs::showError(QWidget* parent, const QString& title, const QString& text) {
  QMessageBox::critical(parent, title, text);
}

UserDialogs::SaveChoice UserDialogs::askSaveChanges(QWidget* parent, const QString& documentName) {
  const auto answer = QMessageBox::warning(
      parent, QObject::tr("Unsaved changes"),
      QObject::tr("The scene \"%1\" has unsaved changes. Save them before closing?").arg(documentName),
      QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
  if (answer == QMessageBox::Save) return SaveChoice::Save;
  if (answer == QMessageBox::Discard) return SaveChoice::Discard;
  return SaveChoice::Cancel;
}

}  // namespace drape::qt
