#include "drape/render/render_options.h"

namespace drape::render {

std::string_view displayModeName(DisplayMode mode) {
  switch (mode) {
    case DisplayMode::Shaded: return "shaded";
    case DisplayMode::Wireframe: return "wireframe";
    case DisplayMode::Strain: return "strain";
    case DisplayMode::Domains: return "domains";
    case DisplayMode::Contacts: return "contacts";
    case DisplayMode::Print: return "print";
  }
  return "shaded";
}

std::optional<DisplayMode> parseDisplayMode(std::string_view name) {
  for (DisplayMode m : {DisplayMode::Shaded, DisplayMode::Wireframe, DisplayMode::Strain, DisplayMode::Domains,
                        DisplayMode::Contacts, DisplayMode::Print})
    if (displayModeName(m) == name) return m;
  return std::nullopt;
}

}  // namespace drape::render
