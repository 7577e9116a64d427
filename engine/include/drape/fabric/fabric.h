#pragma once
// Material parameters of one fabric (DESIGN.md section 4): an anisotropic membrane in the pattern's material
// frame (warp = pattern x, weft = pattern y), hinge bending, mass, friction and damping.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace drape {

struct Fabric {
  std::string name;
  double stretchWarp = 2000.0;  // N/m, membrane stiffness along the warp (pattern x)
  double stretchWeft = 1500.0;  // N/m, along the weft (pattern y)
  double shear = 60.0;          // N/m, in-plane shear
  double bendWarp = 5e-6;       // N m, bending stiffness for folds across the warp
  double bendWeft = 4e-6;       // N m, for folds across the weft
  double density = 0.12;        // kg/m^2, areal density
  double friction = 0.4;        // Coulomb coefficient against bodies and itself
  double thickness = 3e-4;      // m, used as the contact offset
  double damping = 1e-2;        // s, the drape's stretch dissipation beta_s
  Eigen::Vector3f color = Eigen::Vector3f(0.8f, 0.8f, 0.8f);  // linear RGB for rendering
};

// Directory holding the fabric presets: $DRAPE_ASSETS/fabrics if set, else the source tree's assets/fabrics.
std::filesystem::path fabricPresetDir();

// Names (file stems) of the presets in dir, sorted.
std::vector<std::string> fabricPresetNames(const std::filesystem::path& dir = fabricPresetDir());

// Loads preset name from dir; an unknown name raises InputError listing the available presets.
Fabric loadFabricPreset(const std::string& name, const std::filesystem::path& dir = fabricPresetDir());

// Reads a fabric from a JSON file (preset format, see docs/FORMATS.md); every field is validated.
Fabric loadFabricFile(const std::filesystem::path& file);

}  // namespace drape
