#pragma once
// Writes a drape::Pattern as a GarmentCode JSON pattern (docs/FORMATS.md "Pattern files") that loadPattern reads
// back into the same Pattern: every number round-trips exactly, curvature is written in relative coordinates
// (circle arcs as radius and flags), panels in their order (and as "panel_order"), edge and panel labels,
// right_wrong stitches and the panel markings (grain line, notches, internal lines). Pattern::source is not
// written. Keys GarmentCode has and Drape does not read ("parameters", ...) are not reproduced.
#include <filesystem>
#include <string>

#include "drape/pattern/pattern.h"

namespace drape {

// The pattern as JSON text (2-space indent; short arrays and objects on one line; ends with a newline).
// Throws std::invalid_argument when the pattern cannot be written faithfully: two panels of one name, a stitch
// or edge referring to a missing panel, edge or vertex, a curve with the wrong number of control points, a
// non-finite number.
std::string patternToJson(const Pattern& pattern);

// Writes patternToJson(pattern) to file atomically (temporary file + rename; drape/io/atomic_file.h): a reader
// never sees a half-written file, and a failure leaves the old file in place. Throws InputError naming the file
// when it cannot be written, std::invalid_argument as patternToJson.
void savePattern(const Pattern& pattern, const std::filesystem::path& file);

}  // namespace drape
