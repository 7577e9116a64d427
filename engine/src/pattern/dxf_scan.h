#pragma once
// Private: the first pass over an ASCII DXF file, before libdxflib sees it. It checks that the text is DXF
// (group code / value line pairs from a SECTION to the EOF marker), notes numbers that are not finite, and
// passes on only what the AAMA reader uses (HEADER variables; BLOCK, POINT, LINE, POLYLINE, VERTEX, LWPOLYLINE,
// TEXT, MTEXT and INSERT in BLOCKS and ENTITIES). libdxflib trusts the counts in the file (an LWPOLYLINE's
// vertex count sizes a buffer) and loops forever on a line longer than its buffer; the filtered text is rewritten
// so that neither can happen.
#include <map>
#include <string>
#include <vector>

namespace drape::detail {

struct DxfScan {
  std::string text;  // filtered group pairs, "code\nvalue\n", for DL_Dxf::in(std::istream&)
  // Per block name ("" = ENTITIES): the first number that is not finite, as "LINE on layer 7 (line 42):
  // '1e999' is not a finite number"; and the entities passed over that sit on an AAMA layer, as
  // "SPLINE on layer 1".
  std::map<std::string, std::string> badNumbers;
  std::map<std::string, std::vector<std::string>> skipped;
};

// bytes: the whole file. Throws InputError "<source>: ..." when the bytes are not an ASCII DXF file or end
// before the EOF marker.
DxfScan scanDxf(const std::string& bytes, const std::string& source);

}  // namespace drape::detail
