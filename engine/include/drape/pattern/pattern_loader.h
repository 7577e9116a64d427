#pragma once
// Reads and validates a GarmentCode JSON sewing pattern. Every problem in the file raises an InputError whose
// message names the file, the panel, the edge or stitch and what is wrong; usable oddities (stitched edges
// whose lengths differ by more than 5%) become warnings in diagnostics.
#include <filesystem>
#include <string>

#include "drape/core/diagnostics.h"
#include "drape/pattern/pattern.h"

namespace drape {

// A .dxf file is read as DXF-AAMA (pattern/dxf_aama.h).
Pattern loadPattern(const std::filesystem::path& file, Diagnostics* diagnostics = nullptr);

// Same, from JSON text already in memory; source names the file in messages.
Pattern parsePattern(const std::string& jsonText, const std::string& source, Diagnostics* diagnostics = nullptr);

}  // namespace drape
