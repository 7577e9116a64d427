#include "drape/qt/simulation_panel.h"

#include <QAction>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QSlider>
#include <QToolButton>
#include <QVBoxLayout>

#include "drape/core/input_error.h"
#include "drape/qt/settings_table.h"
#include "drape/qt/speed_accuracy.h"

namespace drape::qt {
namespace {

QToolButton* buttonFor(QAction* action) {
  auto* button = new QToolButton;
  button->setDefaultAction(action);
  button->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  button->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
  return button;
}

}  // namespace

SimulationPanel::SimulationPanel(const SimulationActions& actions, QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* buttons = new QGridLayout;
  buttons->addWidget(buttonFor(actions.preview), 0, 0);
  buttons->addWidget(buttonFor(actions.drape), 0, 1);
  buttons->addWidget(buttonFor(actions.pause), 1, 0);
  buttons->addWidget(buttonFor(actions.resume), 1, 1);
  buttons->addWidget(buttonFor(actions.reset), 2, 0);
  buttons->addWidget(buttonFor(actions.cancel), 2, 1);
  layout->addLayout(buttons);

  auto* trade = new QGroupBox(tr("Speed / accuracy"));
  auto* tradeLayout = new QGridLayout(trade);
  // A missing or bad levels file costs the slider only: it is disabled with the reason, and the main window logs it.
  try {
    m_levels = &speedAccuracyLevels();
  } catch (const InputError& e) {
    m_levelsError = QString::fromStdString(e.what());
  }
  m_slider = new QSlider(Qt::Horizontal);
  m_slider->setRange(0, m_levels ? static_cast<int>(m_levels->size()) - 1 : 0);
  m_slider->setEnabled(m_levels != nullptr);
  m_slider->setPageStep(1);
  m_slider->setTickPosition(QSlider::TicksBelow);
  m_slider->setTickInterval(1);
  tradeLayout->addWidget(new QLabel(tr("Speed")), 0, 0);
  tradeLayout->addWidget(m_slider, 0, 1);
  tradeLayout->addWidget(new QLabel(tr("Accuracy")), 0, 2);
  m_levelLabel = new QLabel;
  m_levelLabel->setWordWrap(true);
  tradeLayout->addWidget(m_levelLabel, 1, 0, 1, 3);
  layout->addWidget(trade);
  connect(m_slider, &QSlider::valueChanged, this, [this](int level) { describeLevel(level); });
  // Announce on release (or keyboard), not on every intermediate position of a drag.
  connect(m_slider, &QSlider::sliderReleased, this, [this] {
    if (m_levels) emit speedAccuracyChosen(m_slider->value());
  });
  connect(m_slider, &QSlider::actionTriggered, this, [this](int action) {
    if (m_levels && action != QAbstractSlider::SliderMove)
      QMetaObject::invokeMethod(
          this, [this] { emit speedAccuracyChosen(m_slider->value()); }, Qt::QueuedConnection);
  });

  auto* advanced = new QGroupBox(tr("Advanced: every setting"));
  advanced->setCheckable(true);
  advanced->setChecked(false);
  auto* advancedLayout = new QVBoxLayout(advanced);
  m_table = new SettingsTable;
  m_table->setVisible(false);
  advancedLayout->addWidget(m_table);
  connect(advanced, &QGroupBox::toggled, m_table, &QWidget::setVisible);
  layout->addWidget(advanced, 0);
  layout->addStretch(1);
  // Folded, the section is a title line; unfolded, it takes the spare height of the dock.
  connect(advanced, &QGroupBox::toggled, this, [layout, advanced](bool open) {
    layout->setStretchFactor(advanced, open ? 1 : 0);
    layout->setStretch(layout->count() - 1, open ? 0 : 1);
  });
  connect(m_table, &SettingsTable::settingEdited, this, &SimulationPanel::settingEdited);
  describeLevel(m_slider->value());
}

void SimulationPanel::showSettings(const Settings& settings) {
  if (m_levels) {
    const QSignalBlocker blocker(m_slider);
    m_slider->setValue(nearestSpeedAccuracyLevel(settings));
  }
  describeLevel(m_slider->value());
  m_table->showSettings(settings);
}

void SimulationPanel::describeLevel(int level) {
  if (!m_levels) {
    m_levelLabel->setText(tr("<b>No speed/accuracy levels</b>: %1").arg(m_levelsError.toHtmlEscaped()));
    m_slider->setToolTip(m_levelLabel->text());
    return;
  }
  // "<b>Fast</b>: about 4 s to rest, 1.2 mm from the reference on the default scene" (what the level costs and buys,
  // measured), then the settings it sets.
  const SpeedAccuracyLevel& l = m_levels->at(level);
  QStringList parts;
  for (const auto& [key, value] : l.settings)
    parts << QStringLiteral("%1 = %2").arg(
        QString::fromStdString(key.rfind("solver.", 0) == 0 ? key.substr(7) : key.substr(key.find('.') + 1)),
        QString::fromStdString(value));
  m_levelLabel->setText(QStringLiteral("<b>%1</b>: %2<br>%3")
                            .arg(QString::fromStdString(l.name).toHtmlEscaped(),
                                 QString::fromStdString(l.summary).toHtmlEscaped(), parts.join(", ").toHtmlEscaped()));
  m_slider->setToolTip(m_levelLabel->text());
}

}  // namespace drape::qt
