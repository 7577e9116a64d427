#pragma once
// DXF-AAMA (ASTM D6673) pattern files: the exchange format of garment CAD systems. Each piece is a BLOCK,
// placed by an INSERT in ENTITIES; the layer of an entity says what it is. Format: docs/FORMATS.md
// "DXF-AAMA pattern files".
//
// Read (ASCII DXF, any version libdxflib parses):
//   layer 1   boundary: one closed POLYLINE / LWPOLYLINE, or open polylines and LINEs that chain into one loop.
//             Each point becomes a panel vertex and each segment a straight edge (a polyline bulge becomes a
//             circular arc); the loop is made counter-clockwise as drawn.
//   layer 4   notches (POINT, or the end of a LINE / polyline nearest the boundary); 80-85 (ASTM notch types) too
//   layer 7   grain line (LINE or polyline: first -> last point)
//   layer 8   internal lines (LINE or polyline)
//   TEXT / MTEXT "Piece Name: X" names the piece (else the block name); "UNITS: METRIC" (mm) or
//             "UNITS: ENGLISH" (inches), else $INSUNITS, else millimetres with a warning.
// Pieces keep the block's own coordinates (INSERT points are not applied) and hang side by side in front of a body
// at the origin (Panel::translation; rotation zero); there are no stitches. Duplicate piece names get a suffix ("FRONT_2") and a warning.
// Refused (InputError naming the file and the piece): unreadable, binary or truncated files, anything not DXF,
// no pieces, a piece without boundary, a boundary that is not one closed loop, has fewer than 3 distinct points,
// crosses itself or encloses no area, non-finite coordinates, pieces beyond the panel size limits.
#include <filesystem>

#include "drape/core/diagnostics.h"
#include "drape/pattern/pattern.h"

namespace drape {

// Reads a DXF-AAMA file into a validated Pattern (unitsInMeter from the file's units); warnings go to
// diagnostics. Throws InputError "<file>: piece '<name>': <problem>" on anything listed above.
Pattern readDxfAamaPattern(const std::filesystem::path& file, Diagnostics* diagnostics = nullptr);

// Writes the panels of pattern as DXF-AAMA (R12, millimetres: "UNITS: METRIC" and $INSUNITS = 4), atomically:
// one BLOCK per panel with its outline (curved edges sampled) as a closed POLYLINE on layer 1, the grain line on
// layer 7 (when the panel has none: along its x axis through its centroid), notches as short LINEs on layer 4
// starting at the notch, internal lines on layer 8 and the TEXT "Piece Name: <name>"; and one INSERT per block,
// side by side without overlap. Stitches are not written. Throws InputError naming file on failure.
void writeDxfAamaPattern(const Pattern& pattern, const std::filesystem::path& file);

// True when file's extension is .dxf (any case).
bool isDxfFile(const std::filesystem::path& file);

}  // namespace drape
