#pragma once
// Every question and error message the main window puts to the user goes through this interface, so tests
// can intercept them instead of blocking in a modal dialog. The default implementation uses QMessageBox.
#include <QString>

class QWidget;

namespace drape::qt {

class UserDialogs {
 public:
  enum class SaveChoice { Save, Discard, Cancel };

  virtual ~UserDialogs() = default;
  // An error the user must see (a bad file, a diverged step); text is the InputError message.
  virtual void showError(QWidget* parent, const QString& title, const QString& text);
  // Asked before unsaved changes would be lost (closing the window).
  virtual SaveChoice askSaveChanges(QWidget* parent, const QString& documentName);
};

}  // namespace drape::qt
