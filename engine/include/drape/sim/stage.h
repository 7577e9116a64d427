#pragma once
// The stage a simulation is in: the placed garment before its first step, the preview, the drape, or done (at
// rest). Its names are those of the statistics (drape --simulate --stats), the renders' captions and the GUI.
#include <ostream>

namespace drape {

enum class Stage { Placed, Preview, Drape, Done };

constexpr const char* stageName(Stage stage) {
  switch (stage) {
    case Stage::Placed: return "placed";
    case Stage::Preview: return "preview";
    case Stage::Drape: return "drape";
    case Stage::Done: return "done";
  }
  return "";
}

inline std::ostream& operator<<(std::ostream& out, Stage stage) {
  return out << stageName(stage);
}

}  // namespace drape
