// The table of every setting. Solver settings join here as the solvers land.
#include "drape/scene/settings.h"

namespace drape {

const std::vector<SettingSpec>& Settings::specs() {
  using T = SettingType;
  static const std::vector<SettingSpec> table = {
      {"pattern", T::Text, "", "", "sewing pattern file (GarmentCode JSON), relative to the scene file"},
      {"avatar.file", T::Text, "", "", "avatar or collider mesh (obj, glb, gltf, fbx, ply, stl); empty: none"},
      {"avatar.units", T::Choice, "m", "", "length unit of the avatar file", -1e300, 1e300, {"m", "cm", "mm"}},
      {"fabric.preset", T::Text, "cotton_shirting", "", "default fabric of every panel (a file in assets/fabrics)"},
      {"fabric.stretch_warp", T::Number, "", "N/m", "override: stretch stiffness along the warp", 0, 1e7},
      {"fabric.stretch_weft", T::Number, "", "N/m", "override: stretch stiffness along the weft", 0, 1e7},
      {"fabric.shear", T::Number, "", "N/m", "override: in-plane shear stiffness", 0, 1e7},
      {"fabric.bend_warp", T::Number, "", "N m", "override: bending stiffness about the weft axis", 0, 1},
      {"fabric.bend_weft", T::Number, "", "N m", "override: bending stiffness about the warp axis", 0, 1},
      {"fabric.density", T::Number, "", "kg/m^2", "override: areal density", 1e-4, 10},
      {"fabric.friction", T::Number, "", "", "override: Coulomb friction coefficient", 0, 5},
      {"fabric.thickness", T::Number, "", "m", "override: thickness (contact offset)", 0, 0.05},
      {"fabric.damping", T::Number, "", "", "override: stretch/bend dissipation factor", 0, 10},
      {"mesh.target_edge_length", T::Number, "0.01", "m", "target triangle edge length of the garment mesh", 1e-4,
       1.0},
      {"sim.gravity", T::Number, "-9.81", "m/s^2", "gravity along y", -1000, 1000},
      {"camera.view", T::Choice, "three-quarter", "", "default camera preset", -1e300, 1e300,
       {"front", "back", "left", "right", "three-quarter"}},
      {"camera.fov_deg", T::Number, "35", "deg", "vertical field of view", 5, 120},
  };
  return table;
}

}  // namespace drape
