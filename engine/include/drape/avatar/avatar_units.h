#pragma once
// Length units of avatar files, and the check that a loaded body is as tall as a human body: a body exported in
// centimetres and loaded as metres is some 170 m tall, and a garment placed around a human-sized origin ends up
// inside it, with no contact and nothing else to say what went wrong.
#include <string>

namespace drape {

// "m" -> 1, "cm" -> 100, "mm" -> 1000, "in" -> 1 / 0.0254 (file units per metre); anything else raises InputError
// listing the valid names.
double unitsInMeterFromName(const std::string& name);

// The heights a human body has, metres (a small child to the tallest adult, with room for a raised arm).
constexpr double kMinBodyHeight = 0.3;
constexpr double kMaxBodyHeight = 2.5;

// The length unit a file declares for itself (FBX: GlobalSettings' UnitScaleFactor, centimetres per file unit).
struct DeclaredUnit {
  double unitsInMeter = 0.0;  // file units per metre; 0: the file declares none
  std::string source;         // where it says so, e.g. "FBX UnitScaleFactor 1"
};

// The warning for an avatar `height` metres tall along y (the up axis: gravity acts along -y) when its file was
// read at `unitsInMeter` file units per metre; empty when kMinBodyHeight <= height <= kMaxBodyHeight. When another
// of the units above (m, cm, mm, in) gives a height in that range, the warning names the one nearest a typical
// adult's 1.7 m (the declared unit, when it is one of them) and the option that loads the file in it:
//   "body.obj: the avatar is 171.99 m tall; it looks like centimetres: load it with --avatar-units cm (scene:
//   "avatar": {"units": "cm"})"
// else it says the height is outside a human body's range and names the option. A declared unit is said after the
// height ("(the file declares centimetres: FBX UnitScaleFactor 1)").
std::string avatarHeightWarning(const std::string& file, double height, double unitsInMeter,
                                const DeclaredUnit& declared = {});

}  // namespace drape
