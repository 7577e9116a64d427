#include "drape/io/mesh_export.h"

#include <algorithm>
#include <cmath>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "io/export_data.h"

namespace drape {
namespace {

enum class Format { Obj, Glb, Gltf, Ply, Stl };

Format formatOf(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return Format::Obj;
  if (ext == ".glb") return Format::Glb;
  if (ext == ".gltf") return Format::Gltf;
  if (ext == ".ply") return Format::Ply;
  if (ext == ".stl") return Format::Stl;
  throw InputError(file.string() + ": unknown export format '" + ext + "' (valid: .obj, .glb, .gltf, .ply, .stl)");
}

// Positions must be finite and every index in range: exporting a diverged state would write garbage.
void validate(const detail::ExportData& data, const std::filesystem::path& file) {
  const Eigen::MatrixX3d& x = *data.positions;
  const Eigen::MatrixX3i& t = *data.triangles;
  if (t.rows() == 0) throw InputError(file.string() + ": nothing to export (no triangles)");
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (!x.row(i).allFinite()) {
      throw InputError(file.string() + ": cannot export: vertex " + std::to_string(i) + " has a non-finite position");
    }
  }
  if (t.minCoeff() < 0 || t.maxCoeff() >= x.rows()) {
    throw InputError(file.string() + ": cannot export: triangle index out of range (" + std::to_string(x.rows()) +
                     " vertices)");
  }
}

void write(const detail::ExportData& data, const std::filesystem::path& file) {
  const Format format = formatOf(file);
  validate(data, file);
  std::string bytes;
  try {
    switch (format) {
      case Format::Obj:
        bytes = detail::objText(data);
        break;
      case Format::Glb:
        bytes = detail::assimpExportBytes(data, "glb2", true);
        break;
      case Format::Gltf:
        bytes = detail::assimpExportBytes(data, "gltf2", true);
        break;
      case Format::Ply:
        bytes = detail::assimpExportBytes(data, "plyb", false);
        break;
      case Format::Stl:
        bytes = detail::assimpExportBytes(data, "stlb", false);
        break;
    }
  } catch (const std::exception& e) {
    throw InputError("cannot write " + file.string() + ": " + e.what());
  }
  writeFileAtomically(file, bytes);
}

}  // namespace

void exportGarment(const Garment& garment, const Eigen::MatrixX3d& positions, const std::filesystem::path& file) {
  if (positions.rows() != garment.vertexCount()) {
    throw InputError(file.string() + ": cannot export: " + std::to_string(positions.rows()) +
                     " positions for a garment of " + std::to_string(garment.vertexCount()) + " vertices");
  }
  detail::ExportData data;
  data.positions = &positions;
  data.triangles = &garment.triangles;
  data.uvs = garment.uvs.rows() == garment.vertexCount() && garment.vertexCount() > 0 ? &garment.uvs : nullptr;

  // One group per panel, in panel order; triangles without a valid panel index go to a last "unassigned" group.
  const int panelCount = static_cast<int>(garment.panelNames.size());
  data.groups.resize(static_cast<std::size_t>(panelCount));
  for (int p = 0; p < panelCount; ++p) data.groups[p].name = garment.panelNames[p];
  detail::ExportGroup unassigned{"unassigned", {}};
  const bool havePanels = garment.trianglePanel.size() == garment.triangleCount();
  for (int f = 0; f < garment.triangleCount(); ++f) {
    const int p = havePanels ? garment.trianglePanel[f] : -1;
    (p >= 0 && p < panelCount ? data.groups[p] : unassigned).triangles.push_back(f);
  }
  if (!unassigned.triangles.empty()) data.groups.push_back(std::move(unassigned));
  std::erase_if(data.groups, [](const detail::ExportGroup& g) { return g.triangles.empty(); });
  write(data, file);
}

void exportMesh(const TriangleMesh& mesh, const std::filesystem::path& file) {
  detail::ExportData data;
  data.positions = &mesh.vertices;
  data.triangles = &mesh.triangles;
  detail::ExportGroup all{file.stem().string(), {}};
  all.triangles.resize(static_cast<std::size_t>(mesh.triangleCount()));
  for (int f = 0; f < mesh.triangleCount(); ++f) all.triangles[f] = f;
  data.groups.push_back(std::move(all));
  write(data, file);
}

}  // namespace drape
