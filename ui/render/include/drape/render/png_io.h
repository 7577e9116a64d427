#pragma once
// PNG files through libpng. Errors throw drape::InputError naming the file.
#include <filesystem>

#include "drape/render/image.h"

namespace drape::render {

// Writes an 8-bit RGBA PNG atomically (temporary file + rename): a reader never sees half a file.
void writePng(const std::filesystem::path& path, const Image& image);

// Reads any PNG (grey, palette, 16-bit, with or without alpha) converted to 8-bit RGBA.
Image readPng(const std::filesystem::path& path);

}  // namespace drape::render
