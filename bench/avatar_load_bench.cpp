// Times loadAvatar on the given files: `drape_avatar_load_bench body.obj [more files...]`.
// Prints vertices, triangles, bounds, closedness and wall time per file. Not built by default; add
//   add_executable(drape_avatar_load_bench avatar_load_bench.cpp)
//   target_link_libraries(drape_avatar_load_bench PRIVATE drape::engine drape_warnings)
// to bench/CMakeLists.txt to build it.
#include <chrono>
#include <cstdio>
#include <exception>

#include "drape/avatar/avatar_loader.h"
#include "drape/core/input_error.h"
#include "drape/geometry/primitives.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s mesh-file...\n", argv[0]);
    return 2;
  }
  int status = 0;
  for (int i = 1; i < argc; ++i) {
    try {
      const auto start = std::chrono::steady_clock::now();
      drape::Diagnostics diagnostics;
      const drape::TriangleMesh mesh = drape::loadAvatar(argv[i], 1.0, &diagnostics);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const drape::BoundingBox b = drape::boundsOf(mesh.vertices);
      std::printf("%s: %d vertices, %d triangles, size %.3f x %.3f x %.3f m, %s, load %.3f s\n", argv[i],
                  mesh.vertexCount(), mesh.triangleCount(), b.size().x(), b.size().y(), b.size().z(),
                  drape::isClosedManifold(mesh) ? "closed" : "open", seconds);
      for (const std::string& w : diagnostics.warnings()) std::printf("  warning: %s\n", w.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      status = 1;
    }
  }
  return status;
}
