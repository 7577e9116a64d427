#include <assimp/material.h>
#include <assimp/scene.h>

#include <assimp/Exporter.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <unordered_map>

#include "io/export_data.h"

namespace drape::detail {
namespace {

std::string base64(const unsigned char* data, std::size_t size) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (std::size_t i = 0; i < size; i += 3) {
    const unsigned a = data[i];
    const unsigned b = i + 1 < size ? data[i + 1] : 0u;
    const unsigned c = i + 2 < size ? data[i + 2] : 0u;
    const unsigned triple = (a << 16) | (b << 8) | c;
    out += alphabet[(triple >> 18) & 63];
    out += alphabet[(triple >> 12) & 63];
    out += i + 1 < size ? alphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < size ? alphabet[triple & 63] : '=';
  }
  return out;
}

// One assimp mesh holding the given triangles, its vertices renumbered in order of first use.
aiMesh* buildMesh(const ExportData& data, const Eigen::MatrixX3d& normals, const std::vector<int>& triangles,
                  const std::string& name) {
  const Eigen::MatrixX3d& x = *data.positions;
  const Eigen::MatrixX3i& t = *data.triangles;
  std::unordered_map<int, unsigned> local;
  std::vector<int> global;
  for (const int f : triangles) {
    for (int k = 0; k < 3; ++k) {
      if (local.try_emplace(t(f, k), static_cast<unsigned>(global.size())).second) global.push_back(t(f, k));
    }
  }
  auto mesh = std::make_unique<aiMesh>();
  mesh->mName = name;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mMaterialIndex = 0;
  mesh->mNumVertices = static_cast<unsigned>(global.size());
  mesh->mVertices = new aiVector3D[global.size()];
  mesh->mNormals = new aiVector3D[global.size()];
  if (data.uvs) {
    mesh->mTextureCoords[0] = new aiVector3D[global.size()];
    mesh->mNumUVComponents[0] = 2;
  }
  for (std::size_t i = 0; i < global.size(); ++i) {
    const int v = global[i];
    mesh->mVertices[i] =
        aiVector3D(static_cast<ai_real>(x(v, 0)), static_cast<ai_real>(x(v, 1)), static_cast<ai_real>(x(v, 2)));
    mesh->mNormals[i] = aiVector3D(static_cast<ai_real>(normals(v, 0)), static_cast<ai_real>(normals(v, 1)),
                                   static_cast<ai_real>(normals(v, 2)));
    if (data.uvs) {
      mesh->mTextureCoords[0][i] =
          aiVector3D(static_cast<ai_real>((*data.uvs)(v, 0)), static_cast<ai_real>((*data.uvs)(v, 1)), 0);
    }
  }
  mesh->mNumFaces = static_cast<unsigned>(triangles.size());
  mesh->mFaces = new aiFace[triangles.size()];
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    aiFace& face = mesh->mFaces[i];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) face.mIndices[k] = local.at(t(triangles[i], k));
  }
  return mesh.release();
}

// A scene owning its meshes: one node per mesh under the root, one plain grey material.
std::unique_ptr<aiScene> buildScene(const ExportData& data, bool meshPerGroup) {
  const Eigen::MatrixX3d normals = vertexNormals(data);
  std::vector<std::pair<std::string, std::vector<int>>> parts;
  if (meshPerGroup) {
    for (const ExportGroup& g : data.groups) {
      if (!g.triangles.empty()) parts.emplace_back(g.name, g.triangles);
    }
  } else {
    std::vector<int> all;
    for (const ExportGroup& g : data.groups) all.insert(all.end(), g.triangles.begin(), g.triangles.end());
    parts.emplace_back(data.groups.size() == 1 ? data.groups[0].name : "mesh", std::move(all));
  }

  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("root");
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1];
  scene->mMaterials[0] = new aiMaterial();
  const aiString materialName("drape_default");
  scene->mMaterials[0]->AddProperty(&materialName, AI_MATKEY_NAME);
  const aiColor4D grey(0.8f, 0.8f, 0.8f, 1.0f);
  scene->mMaterials[0]->AddProperty(&grey, 1, AI_MATKEY_COLOR_DIFFUSE);
  const int twoSided = 1;
  scene->mMaterials[0]->AddProperty(&twoSided, 1, AI_MATKEY_TWOSIDED);

  scene->mNumMeshes = static_cast<unsigned>(parts.size());
  scene->mMeshes = new aiMesh*[parts.size()]();
  scene->mRootNode->mNumChildren = static_cast<unsigned>(parts.size());
  scene->mRootNode->mChildren = new aiNode*[parts.size()]();
  for (std::size_t i = 0; i < parts.size(); ++i) {
    scene->mMeshes[i] = buildMesh(data, normals, parts[i].second, parts[i].first);
    aiNode* node = new aiNode(parts[i].first);
    node->mParent = scene->mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{static_cast<unsigned>(i)};
    scene->mRootNode->mChildren[i] = node;
  }
  return scene;
}

}  // namespace

std::string assimpExportBytes(const ExportData& data, const std::string& formatId, bool meshPerGroup) {
  const std::unique_ptr<aiScene> scene = buildScene(data, meshPerGroup);
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(scene.get(), formatId);
  if (!blob) throw std::runtime_error(std::string("assimp export failed: ") + exporter.GetErrorString());
  std::string bytes(static_cast<const char*>(blob->data), blob->size);
  if (formatId != "gltf2") return bytes;

  // glTF text: assimp puts the binary buffer in a second blob ("$blobfile.bin"); embed it as a data URI.
  const aiExportDataBlob* bin = blob->next;
  if (!bin) throw std::runtime_error("assimp export failed: glTF binary buffer missing");
  nlohmann::json gltf = nlohmann::json::parse(bytes);
  if (!gltf.contains("buffers") || gltf["buffers"].size() != 1) {
    throw std::runtime_error("assimp export failed: expected one glTF buffer");
  }
  gltf["buffers"][0]["uri"] =
      "data:application/octet-stream;base64," + base64(static_cast<const unsigned char*>(bin->data), bin->size);
  return gltf.dump(1) + "\n";
}

}  // namespace drape::detail
