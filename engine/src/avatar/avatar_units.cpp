#include "drape/avatar/avatar_units.h"

#include <cmath>
#include <cstdio>

#include "drape/core/input_error.h"

namespace drape {
namespace {

struct LengthUnit {
  const char* name;  // as --avatar-units and the scene's "avatar": {"units"} take it
  const char* words;
  double unitsInMeter;
};

constexpr LengthUnit kUnits[] = {
    {"m", "metres", 1.0}, {"cm", "centimetres", 100.0}, {"mm", "millimetres", 1000.0}, {"in", "inches", 1.0 / 0.0254}};

constexpr double kTypicalHeight = 1.7;  // metres: the unit that comes nearest it wins when several fit

bool sameUnit(double a, double b) {
  return std::abs(a / b - 1.0) < 1e-6;
}

const LengthUnit* unitOf(double unitsInMeter) {
  for (const LengthUnit& u : kUnits)
    if (sameUnit(u.unitsInMeter, unitsInMeter)) return &u;
  return nullptr;
}

bool humanHeight(double height) {
  return height >= kMinBodyHeight && height <= kMaxBodyHeight;
}

// "171.99", "0.0172": two decimals from a metre on, three significant digits below.
std::string formatMetres(double value) {
  char text[64];
  std::snprintf(text, sizeof text, value >= 1.0 ? "%.2f" : "%.3g", value);
  return text;
}

std::string unitNames() {
  std::string names;
  for (const LengthUnit& u : kUnits) names += std::string(names.empty() ? "" : "|") + u.name;
  return names;
}

}  // namespace

double unitsInMeterFromName(const std::string& name) {
  std::string valid;
  for (const LengthUnit& u : kUnits) {
    if (name == u.name) return u.unitsInMeter;
    valid += std::string(valid.empty() ? "" : ", ") + u.name;
  }
  throw InputError("unknown length unit '" + name + "' (valid: " + valid + ")");
}

std::string avatarHeightWarning(const std::string& file, double height, double unitsInMeter,
                                const DeclaredUnit& declared) {
  if (humanHeight(height)) return "";
  std::string said = file + ": the avatar is " + formatMetres(height) + " m tall";
  if (declared.unitsInMeter > 0.0) {
    const LengthUnit* unit = unitOf(declared.unitsInMeter);
    said += " (the file declares " +
            (unit ? std::string(unit->words) : "1 unit = " + formatMetres(100.0 / declared.unitsInMeter) + " cm") +
            ": " + declared.source + ")";
  }
  // The file's extent in its own units, read in each other unit.
  const double fileHeight = height * unitsInMeter;
  const LengthUnit* best = nullptr;
  double bestDistance = 0.0;
  for (const LengthUnit& u : kUnits) {
    if (sameUnit(u.unitsInMeter, unitsInMeter) || !humanHeight(fileHeight / u.unitsInMeter)) continue;
    double distance = std::abs(std::log(fileHeight / u.unitsInMeter / kTypicalHeight));
    const bool isDeclared = declared.unitsInMeter > 0.0 && sameUnit(u.unitsInMeter, declared.unitsInMeter);
    if (isDeclared) distance = -1.0;  // what the file says wins over a guess
    if (!best || distance < bestDistance) {
      best = &u;
      bestDistance = distance;
    }
  }
  if (best) {
    return said + "; it looks like " + best->words + ": load it with --avatar-units " + best->name +
           " (scene: \"avatar\": {\"units\": \"" + best->name + "\"})";
  }
  char range[80];
  std::snprintf(range, sizeof range, "%g-%g m", kMinBodyHeight, kMaxBodyHeight);
  return said + ", outside the range of a human body (" + range +
         "); if it is a body, give its file's length unit with --avatar-units " + unitNames() +
         " (scene: \"avatar\": {\"units\": ...})";
}

}  // namespace drape
