// drape --make-avatar MEASUREMENTS -o AVATAR.(obj|glb): a mannequin from body measurements.
#include <ostream>

#include "commands.h"
#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/core/input_error.h"
#include "drape/geometry/triangle_mesh.h"
#include "drape/io/mesh_export.h"

namespace drape::app {

int runMakeAvatar(const CliOptions& options, std::ostream& out) {
  const std::filesystem::path output = options.output;
  const std::string ext = output.extension().string();
  if (ext != ".obj" && ext != ".glb" && ext != ".gltf" && ext != ".ply" && ext != ".stl")
    throw InputError(output.string() + ": the output of --make-avatar must be .obj, .glb, .gltf, .ply or .stl");
  const BodyMeasurements measurements = loadBodyMeasurements(options.scene.input);
  const TriangleMesh body = makeMannequin(measurements);
  exportMesh(body, output);
  const BoundingBox box = boundsOf(body.vertices);
  out << "wrote " << output.string() << " (" << body.vertexCount() << " vertices, " << body.triangleCount()
      << " triangles, height " << box.size().y() << " m)\n";
  return 0;
}

}  // namespace drape::app
