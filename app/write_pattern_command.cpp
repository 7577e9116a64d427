// drape --write-pattern PATTERN -o OUT: a pattern (GarmentCode JSON, DXF-AAMA, or a scene's) written as GarmentCode
// JSON, as DXF-AAMA, or at full scale as PDF or SVG for printing, by OUT's extension.
#include <ostream>

#include "commands.h"
#include "drape/core/input_error.h"
#include "drape/pattern/dxf_aama.h"
#include "drape/pattern/pattern_writer.h"
#include "drape/scene/scene.h"
#ifdef DRAPE_WITH_GUI
#include "drape/qt/pattern_print.h"
#endif

namespace drape::app {

int runWritePattern(const CliOptions& options, std::ostream& out) {
  const Scene scene = loadScene(options.scene);
  const std::filesystem::path file = options.output;
#ifdef DRAPE_WITH_GUI
  qt::writePatternFile(scene.pattern, file);
#else
  if (isDxfFile(file))
    writeDxfAamaPattern(scene.pattern, file);
  else if (file.extension() == ".json")
    savePattern(scene.pattern, file);
  else
    throw InputError(file.string() + ": this build has no GUI (Qt): a pattern is written as .json or .dxf only");
#endif
  out << "wrote " << file.string() << ": " << scene.pattern.panels.size() << " panels, "
      << scene.pattern.stitches.size() << " seams\n";
  return 0;
}

}  // namespace drape::app
