#pragma once
// The flat pattern at full scale for printing: every panel as the pattern view draws it (outline, name, grain line,
// notches, internal lines, seams in colour), with a 10 cm check square, on one page as large as the layout.
// PDF (QPdfWriter) or SVG (QSvgGenerator, sized in millimetres) by the file's extension.
#include <filesystem>

#include "drape/pattern/pattern.h"

namespace drape::qt {

// Writes file atomically; throws InputError for another extension or when it cannot be written.
void printPattern(const Pattern& pattern, const std::filesystem::path& file);

// True for the extensions printPattern writes (.pdf, .svg; any case).
bool isPrintFile(const std::filesystem::path& file);

// Writes the pattern in the format of the file's extension: .json GarmentCode JSON, .dxf DXF-AAMA, .pdf and .svg
// printed at full scale. Atomic; throws InputError for any other extension or when it cannot be written.
void writePatternFile(const Pattern& pattern, const std::filesystem::path& file);

}  // namespace drape::qt
