#include "drape/avatar/avatar_loader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "avatar/obj_scan.h"
#include "avatar/ply_header.h"
#include "drape/core/input_error.h"
#include "drape/geometry/mesh_orientation.h"

namespace drape {
namespace {

// Most corners of one polygon (docs/FORMATS.md "Limits"); real scans and modelled bodies use triangles and quads.
constexpr unsigned kMaxFaceCorners = 1000;

std::string lowerExtension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw InputError(file.string() + ": " + what);
}

std::string formatPoint(const aiVector3D& p) {
  std::ostringstream out;
  out << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return out.str();
}

// Throws InputError for a face with more than kMaxFaceCorners corners, naming its line for OBJ files, and for a face
// without corners or with a corner past the mesh's vertices (assimp's triangulation aborts the process on those; a
// malformed PLY read past its garbage gave one, found by fuzz/fuzz_avatar.cpp).
void refuseBadFaces(const aiScene& scene, const std::filesystem::path& file) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      const unsigned corners = face.mNumIndices;
      bool outOfRange = corners == 0 || face.mIndices == nullptr;
      for (unsigned k = 0; k < corners && !outOfRange; ++k) outOfRange = face.mIndices[k] >= mesh->mNumVertices;
      if (outOfRange)
        fail(file, "mesh " + std::to_string(m) + " face " + std::to_string(f) +
                       (corners == 0 ? " has no vertices" : " refers to a vertex out of range"));
      if (corners <= kMaxFaceCorners) continue;
      const std::string limit = " (at most " + std::to_string(kMaxFaceCorners) + ")";
      if (lowerExtension(file) == ".obj") {
        const detail::ObjProblem big = detail::findLargeObjFace(file, kMaxFaceCorners);
        if (big.found) fail(file, "line " + std::to_string(big.line) + ": " + big.message + limit);
      }
      const std::string name = mesh->mName.length > 0 ? std::string(" '") + mesh->mName.C_Str() + "'" : "";
      fail(file, "mesh " + std::to_string(m) + name + " face " + std::to_string(f) + " has " + std::to_string(corners) +
                     " vertices" + limit);
    }
  }
}

// assimp's reading of the file: triangulated, node transforms applied, normals/UVs/materials stripped, points
// and lines removed. No aiProcess_JoinIdenticalVertices: loadAvatar welds equal positions itself with a hash
// map, which also welds across meshes and is faster (1M-triangle OBJ: everything after parsing takes 0.4 s CPU;
// assimp's step alone took 1.2 s CPU, 6.4 s wall on a busy machine).
const aiScene* readScene(Assimp::Importer& importer, const std::filesystem::path& file) {
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                          aiComponent_COLORS | aiComponent_TEXCOORDS |
                                                          aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                                          aiComponent_TEXTURES | aiComponent_LIGHTS |
                                                          aiComponent_CAMERAS | aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read without post-processing first: a polygon with very many corners is refused before triangulation, whose
  // ear clipping takes time quadratic or worse in the corner count (a 100k-corner face ran for minutes).
  const std::string plyProblem = detail::plyHeaderProblem(file, lowerExtension(file) == ".ply");
  if (!plyProblem.empty()) fail(file, plyProblem);
  const aiScene* scene = importer.ReadFile(file.string(), 0);
  if (scene) {
    refuseBadFaces(*scene, file);
    const unsigned flags =
        aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType;
    scene = importer.ApplyPostProcessing(flags);
    if (scene) return scene;
  }

  const std::string reason = importer.GetErrorString();
  if (lowerExtension(file) == ".obj") {
    // assimp says "OBJ: vertex index out of range" without saying where; find the face ourselves.
    const detail::ObjProblem bad = detail::findBadObjFaceIndex(file);
    if (bad.found) fail(file, "line " + std::to_string(bad.line) + ": " + bad.message);
  }
  fail(file, "cannot read mesh: " + reason);
}

// Key for welding corners at bitwise-equal positions (+0 and -0 count as equal).
struct PositionKey {
  std::uint32_t x, y, z;
  bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = (static_cast<std::uint64_t>(k.x) << 32 | k.y) * 0x9E3779B97F4A7C15ULL;
    h ^= (h >> 29) + k.z * 0xBF58476D1CE4E5B9ULL;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};
PositionKey keyOf(const aiVector3D& p) {
  static_assert(sizeof(ai_real) == sizeof(std::uint32_t), "assimp built with single-precision ai_real");
  auto bits = [](ai_real v) {
    std::uint32_t b;
    v = v == 0 ? 0 : v;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  return {bits(p.x), bits(p.y), bits(p.z)};
}

// True when the triangle repeats an index or its area is zero relative to its longest edge
// (|cross| <= 1e-12 * longest^2, i.e. a sliver far thinner than any real surface has).
bool isDegenerate(const std::vector<aiVector3D>& v, int a, int b, int c) {
  if (a == b || b == c || c == a) return true;
  auto point = [&](int i) { return Eigen::Vector3d(v[i].x, v[i].y, v[i].z); };
  const Eigen::Vector3d pa = point(a);
  const Eigen::Vector3d ab = point(b) - pa;
  const Eigen::Vector3d ac = point(c) - pa;
  const double longest = std::max({ab.squaredNorm(), ac.squaredNorm(), (ac - ab).squaredNorm()});
  return ab.cross(ac).norm() <= 1e-12 * longest;
}

// The length unit the file declares: FBX's UnitScaleFactor (centimetres per file unit), which assimp passes on in
// the scene's metadata without applying it (AI_CONFIG_FBX_CONVERT_TO_M is off).
DeclaredUnit declaredUnit(const aiScene& scene) {
  const aiMetadata* meta = scene.mMetaData;
  if (!meta) return {};
  for (unsigned i = 0; i < meta->mNumProperties; ++i) {
    if (std::strcmp(meta->mKeys[i].C_Str(), "UnitScaleFactor") != 0) continue;
    const aiMetadataEntry& entry = meta->mValues[i];
    double cmPerUnit = 0.0;
    if (entry.mType == AI_FLOAT)
      cmPerUnit = *static_cast<const float*>(entry.mData);
    else if (entry.mType == AI_DOUBLE)
      cmPerUnit = *static_cast<const double*>(entry.mData);
    else if (entry.mType == AI_INT32)
      cmPerUnit = *static_cast<const std::int32_t*>(entry.mData);
    if (!(cmPerUnit > 0.0) || !std::isfinite(cmPerUnit)) return {};
    std::ostringstream source;
    source << "FBX UnitScaleFactor " << cmPerUnit;
    return {100.0 / cmPerUnit, source.str()};
  }
  return {};
}

}  // namespace

TriangleMesh loadAvatar(const std::filesystem::path& file, double unitsInMeter, Diagnostics* diagnostics) {
  if (!(unitsInMeter > 0.0) || !std::isfinite(unitsInMeter)) {
    fail(file, "units per metre must be a positive number (got " + std::to_string(unitsInMeter) + ")");
  }
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) fail(file, "file not found");
  if (!std::filesystem::is_regular_file(file, ec)) fail(file, "not a regular file");

  Assimp::Importer importer;
  const aiScene* scene = readScene(importer, file);
  const DeclaredUnit declared = declaredUnit(*scene);

  // Merge all triangle meshes, welding corners at equal positions (OBJ and STL readers give one vertex per
  // face corner; a body split by material into head and hands must stay one closed surface).
  std::size_t vertexTotal = 0;
  std::size_t faceTotal = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    vertexTotal += mesh->mNumVertices;
    faceTotal += mesh->mNumFaces;
  }
  if (faceTotal == 0) fail(file, "contains no triangles");

  std::unordered_map<PositionKey, int, PositionKeyHash> welded;
  welded.reserve(vertexTotal);
  std::vector<aiVector3D> positions;
  positions.reserve(vertexTotal);
  std::vector<Eigen::Vector3i> triangles;
  triangles.reserve(faceTotal);
  std::size_t degenerate = 0;

  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    std::vector<int> target(mesh->mNumVertices);
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& p = mesh->mVertices[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        if (lowerExtension(file) == ".obj") {
          const detail::ObjProblem bad = detail::findNonFiniteObjVertex(file);
          if (bad.found) fail(file, "line " + std::to_string(bad.line) + ": " + bad.message);
        }
        fail(file, "mesh " + std::to_string(m) + " '" + mesh->mName.C_Str() + "' vertex " + std::to_string(i) +
                       ": non-finite coordinate " + formatPoint(p));
      }
      const auto [it, inserted] = welded.try_emplace(keyOf(p), static_cast<int>(positions.size()));
      if (inserted) positions.push_back(p);
      target[i] = it->second;
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // SortByPType removed points and lines; be safe anyway
      Eigen::Vector3i t;
      for (int k = 0; k < 3; ++k) {
        const unsigned index = face.mIndices[k];
        if (index >= mesh->mNumVertices) {
          fail(file, "mesh " + std::to_string(m) + " '" + mesh->mName.C_Str() + "' face " + std::to_string(f) +
                         ": vertex index " + std::to_string(index) + " out of range (mesh has " +
                         std::to_string(mesh->mNumVertices) + " vertices)");
        }
        t[k] = target[index];
      }
      if (isDegenerate(positions, t[0], t[1], t[2])) {
        ++degenerate;
        continue;
      }
      triangles.push_back(t);
    }
  }
  if (triangles.empty()) fail(file, "contains no triangles with a non-zero area");

  // Keep only the vertices that some triangle uses (dropped faces can leave unused ones), in first-seen order;
  // scale to metres.
  std::vector<int> newIndex(positions.size(), -1);
  for (const Eigen::Vector3i& t : triangles) {
    for (int k = 0; k < 3; ++k) newIndex[t[k]] = 0;
  }
  int used = 0;
  for (int& index : newIndex) {
    if (index == 0) index = used++;
  }
  const double scale = 1.0 / unitsInMeter;
  TriangleMesh result;
  result.vertices.resize(used, 3);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (newIndex[i] < 0) continue;
    result.vertices.row(newIndex[i]) << scale * positions[i].x, scale * positions[i].y, scale * positions[i].z;
  }
  result.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Eigen::Vector3i& t = triangles[f];
    result.triangles.row(static_cast<Eigen::Index>(f)) << newIndex[t[0]], newIndex[t[1]], newIndex[t[2]];
  }

  const OrientationRepair turned = orientOutward(result);
  if (turned.facesTurned > 0 && diagnostics) {
    diagnostics->warn(file.string() + ": " + std::to_string(turned.facesTurned) + " of " +
                      std::to_string(result.triangleCount()) + " faces were wound inward and are turned outward" +
                      (turned.partsInsideOut > 0 ? " (" + std::to_string(turned.partsInsideOut) + " part" +
                                                       (turned.partsInsideOut == 1 ? " was" : "s were") +
                                                       " inside out)"
                                                 : std::string()));
  }
  if (degenerate > 0 && diagnostics) {
    diagnostics->warn(file.string() + ": dropped " + std::to_string(degenerate) + " degenerate face" +
                      (degenerate == 1 ? "" : "s") + " (zero area or repeated vertex) of " + std::to_string(faceTotal));
  }
  const double height = result.vertices.col(1).maxCoeff() - result.vertices.col(1).minCoeff();
  const std::string unitWarning = avatarHeightWarning(file.string(), height, unitsInMeter, declared);
  if (!unitWarning.empty() && diagnostics) diagnostics->warn(unitWarning);
  return result;
}

}  // namespace drape
