// drape --render SCENE -o OUT.png: headless rendering through EGL (OSMesa fallback); no QApplication.
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <ostream>

#include "commands.h"
#include "drape/avatar/avatar_loader.h"
#include "drape/core/diagnostics.h"
#include "drape/core/input_error.h"
#include "drape/render/headless.h"
#include "drape/render/png_io.h"
#include "drape/scene/pins.h"
#include "drape/sim/scene_garment.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"
#include "quality_output.h"
#include "scene_request.h"
#include "start_state.h"

namespace drape::app {
namespace {

// Runs the scene's stage (none: the placed garment) and returns what to draw; exitStatus: the run's
// (simulatedExitStatus: its quality verdict, or diverged), 0 for the placed garment.
Snapshot stageSnapshot(Scene scene, const std::string& from, std::ostream& out, int& exitStatus) {
  exitStatus = 0;
  if (scene.settings.stagePlan() == StagePlan::None) {
    Diagnostics diagnostics;
    const Garment garment = buildSceneGarment(scene, &diagnostics);
    resolvePins(scene, garment);  // validates the pins
    printWarnings(scene.diagnostics.warnings(), out);
    printWarnings(diagnostics.warnings(), out);
    return makeSnapshot(scene, garment, placedOrFrom(garment, from));
  }
  const std::unique_ptr<Simulation> started = startSimulation(std::move(scene), from);
  Simulation& simulation = *started;
  printWarnings(simulation.scene().diagnostics.warnings(), out);  // the scene's and the garment mesher's
  StepReport last;
  while (!simulation.finished()) {
    last = simulation.step();
    if (last.status == StepStatus::Diverged || last.status == StepStatus::Cancelled) break;
  }
  out << "render: simulated " << simulation.time() << " s in " << simulation.steps() << " steps ("
      << toString(last.status) << (last.atRest ? ", at rest" : "") << ")\n";
  const bool stopped = last.status == StepStatus::Diverged || last.status == StepStatus::Cancelled;
  const std::string status = stopped ? std::string(toString(last.status)) : simulation.endReason();
  const QualityReport quality = checkDrapeQuality(simulation, status);
  printQualityWarnings(quality, out);
  exitStatus = simulatedExitStatus(status, quality);
  return simulation.snapshot();
}

}  // namespace

void checkWritableDirectory(const std::filesystem::path& file) {
  const std::filesystem::path dir = file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError("cannot write " + file.string() + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError("cannot write " + file.string() + ": directory " + dir.string() + " is not writable");
}

void checkPngPath(const std::filesystem::path& output, const std::string& option) {
  if (output.extension() != ".png") throw InputError(output.string() + ": the output of " + option + " must be a .png file");
}

namespace {

// Body meshes render on their own (mannequin previews); everything else is a scene or a pattern.
bool isMeshFile(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".obj" || ext == ".glb" || ext == ".gltf" || ext == ".fbx" || ext == ".ply" || ext == ".stl";
}

}  // namespace

int runRender(const CliOptions& options, std::ostream& out) {
  checkPngPath(options.output, "--render");
  checkWritableDirectory(options.output);
  if (isMeshFile(options.scene.input)) {
    if (!options.simulateStage.empty() && options.simulateStage != "none")
      throw InputError(options.scene.input.string() + ": a body mesh has nothing to simulate (--simulate " +
                       options.simulateStage + " needs a scene or a pattern)");
    const std::string units = options.scene.avatarUnits.empty() ? "m" : options.scene.avatarUnits;
    Snapshot body;
    Diagnostics diagnostics;
    body.avatar = loadAvatar(options.scene.input, unitsInMeterFromName(units), &diagnostics);
    printWarnings(diagnostics.warnings(), out);
    renderToPng(body, options, SceneCamera{}, options.output, out);
    return 0;
  }
  Scene scene = loadScene(requestWithStage(options));
  const SceneCamera camera = sceneCamera(scene.settings);
  int exitStatus = 0;
  const Snapshot snapshot = stageSnapshot(std::move(scene), options.from, out, exitStatus);
  renderToPng(snapshot, options, camera, options.output, out);
  return exitStatus;
}

SceneCamera sceneCamera(const Settings& settings) {
  SceneCamera c;
  c.view = settings.text("camera.view");
  c.fovDegrees = settings.number("camera.fov_deg");
  c.explicitEye = settings.has("camera.eye");
  c.explicitTarget = settings.has("camera.target");
  if (c.explicitEye) c.eye = settings.vector3("camera.eye");
  if (c.explicitTarget) c.target = settings.vector3("camera.target");
  c.up = settings.vector3("camera.up");
  return c;
}

void renderToPng(const Snapshot& snapshot, const CliOptions& options, const SceneCamera& sceneCam,
                 const std::filesystem::path& output, std::ostream& out) {

  render::RenderOptions ro;
  ro.mode = *render::parseDisplayMode(options.renderMode);
  ro.width = options.width;
  ro.height = options.height;
  render::Image image;
  try {
    render::OffscreenRenderer renderer;
    if (options.view == "all") {
      image = renderer.contactSheet(snapshot, ro);
    } else {
      // --view given on the command line wins; then the scene's explicit camera; then its camera.view.
      render::Camera camera;
      if (!options.viewGiven && sceneCam.explicitEye) {
        camera.eye = sceneCam.eye;
        camera.target = sceneCam.explicitTarget ? sceneCam.target : snapshot.bounds().center();
        camera.up = sceneCam.up;
        camera.fovYDegrees = sceneCam.fovDegrees;
        if ((camera.eye - camera.target).norm() < 1e-9 || camera.up.cross(camera.eye - camera.target).norm() < 1e-9)
          throw InputError("camera.eye, camera.target and camera.up do not define a view (eye on the target, or "
                           "looking along up)");
      } else {
        const std::string view = options.viewGiven ? options.view : sceneCam.view;
        camera = render::presetCamera(*render::parseViewPreset(view), snapshot.bounds(),
                                      double(ro.width) / ro.height, sceneCam.fovDegrees);
      }
      image = renderer.render(snapshot, camera, ro);
    }
    out << "render: " << renderer.backendName() << " (" << renderer.glRendererName() << ")\n";
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("--render: ") + e.what());
  }
  render::writePng(output, image);
  out << "wrote " << output.string() << " (" << image.width << "x" << image.height << ")\n";
}

}  // namespace drape::app
