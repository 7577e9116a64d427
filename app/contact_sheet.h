#pragma once
// The contact sheet of a batch: the jobs' PNG thumbnails in a grid, each with a few label lines under it, drawn with
// QImage/QPainter on Qt's offscreen platform (no display server). Builds without the GUI have no Qt: no sheet.
#include <filesystem>
#include <string>
#include <vector>

namespace drape::app {

struct ContactSheetEntry {
  std::filesystem::path image;     // the job's PNG; a grey tile when it does not exist
  std::vector<std::string> label;  // lines under the tile (garment and avatar, fabric and set, status)
  bool failed = false;             // the status line and the tile's frame in red
};

// Writes the sheet as a PNG atomically, with title above the grid. Returns false and says why in note when this build
// cannot draw one (no Qt); throws InputError when the file cannot be written.
bool writeContactSheet(const std::vector<ContactSheetEntry>& entries, const std::string& title,
                       const std::filesystem::path& file, std::string& note);

}  // namespace drape::app
