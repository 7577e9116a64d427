#include "mesh_buffers.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "drape/render/palette.h"

namespace drape::render {
namespace {

void checkTriangles(const Eigen::MatrixX3i& triangles, Eigen::Index vertexCount, const char* what) {
  for (Eigen::Index f = 0; f < triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (triangles(f, k) < 0 || triangles(f, k) >= vertexCount)
        throw std::invalid_argument(std::string("snapshot: ") + what + " triangle " + std::to_string(f) +
                                    " refers to vertex " + std::to_string(triangles(f, k)) + " (there are " +
                                    std::to_string(vertexCount) + ")");
}

void checkLength(Eigen::Index length, Eigen::Index expected, const char* what, const char* per) {
  if (length != 0 && length != expected)
    throw std::invalid_argument(std::string("snapshot: ") + what + " has " + std::to_string(length) +
                                " entries, expected 0 or " + std::to_string(expected) + " (one per " + per + ")");
}

}  // namespace

Eigen::MatrixX3f vertexNormals(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles) {
  Eigen::MatrixX3d n = Eigen::MatrixX3d::Zero(positions.rows(), 3);
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const Eigen::Vector3d a = positions.row(triangles(f, 0)), b = positions.row(triangles(f, 1)),
                          c = positions.row(triangles(f, 2));
    const Eigen::Vector3d areaNormal = (b - a).cross(c - a);  // length = twice the area
    if (!areaNormal.allFinite()) continue;
    for (int k = 0; k < 3; ++k) n.row(triangles(f, k)) += areaNormal.transpose();
  }
  Eigen::MatrixX3f out(positions.rows(), 3);
  for (Eigen::Index v = 0; v < n.rows(); ++v) {
    const double length = n.row(v).norm();
    out.row(v) = length > 1e-20 ? (n.row(v) / length).cast<float>() : Eigen::RowVector3f(0.0f, 1.0f, 0.0f);
  }
  return out;
}

GarmentVertices buildGarmentVertices(const Snapshot& s) {
  const Eigen::Index nv = s.positions.rows(), nf = s.triangles.rows();
  checkTriangles(s.triangles, nv, "garment");
  checkLength(s.trianglePanel.size(), nf, "trianglePanel", "triangle");
  checkLength(s.triangleStrain.size(), nf, "triangleStrain", "triangle");
  checkLength(s.triangleDomain.size(), nf, "triangleDomain", "triangle");
  checkLength(s.vertexContact.size(), nv, "vertexContact", "vertex");

  GarmentVertices out;
  out.hasStrain = s.triangleStrain.size() == nf && nf > 0;
  const bool withUvs = s.uvs.rows() == nv && nv > 0;
  out.data.resize(static_cast<size_t>(nf) * 3 * kGarmentFloats);
  const Eigen::MatrixX3f normals = vertexNormals(s.positions, s.triangles);
  float* p = out.data.data();
  for (Eigen::Index f = 0; f < nf; ++f) {
    const int panel = s.trianglePanel.size() ? s.trianglePanel(f) : 0;
    const Eigen::Vector3f panelColor = panel >= 0 && panel < static_cast<int>(s.panelColors.size())
                                           ? s.panelColors[panel]
                                           : defaultPanelColor(panel);
    const Eigen::Vector3f domain = domainColor(s.triangleDomain.size() ? s.triangleDomain(f) : 0);
    float strain = kNoStrain;
    if (out.hasStrain && std::isfinite(s.triangleStrain(f))) {
      strain = static_cast<float>(s.triangleStrain(f));
      out.strainMaximum = std::max(out.strainMaximum, s.triangleStrain(f));
    }
    for (int k = 0; k < 3; ++k) {
      const int v = s.triangles(f, k);
      for (int i = 0; i < 3; ++i) *p++ = static_cast<float>(s.positions(v, i));
      for (int i = 0; i < 3; ++i) *p++ = normals(v, i);
      for (int i = 0; i < 3; ++i) *p++ = i == k ? 1.0f : 0.0f;
      for (int i = 0; i < 3; ++i) *p++ = panelColor(i);
      for (int i = 0; i < 3; ++i) *p++ = domain(i);
      *p++ = strain;
      *p++ = s.vertexContact.size() && s.vertexContact(v) ? 1.0f : 0.0f;
      *p++ = withUvs ? static_cast<float>(s.uvs(v, 0)) : 0.0f;
      *p++ = withUvs ? static_cast<float>(s.uvs(v, 1)) : 0.0f;
    }
  }
  return out;
}

AvatarVertices buildAvatarVertices(const TriangleMesh& avatar) {
  checkTriangles(avatar.triangles, avatar.vertices.rows(), "avatar");
  AvatarVertices out;
  const Eigen::MatrixX3f normals = vertexNormals(avatar.vertices, avatar.triangles);
  out.data.reserve(static_cast<size_t>(avatar.vertices.rows()) * 6);
  for (Eigen::Index v = 0; v < avatar.vertices.rows(); ++v) {
    for (int i = 0; i < 3; ++i) out.data.push_back(static_cast<float>(avatar.vertices(v, i)));
    for (int i = 0; i < 3; ++i) out.data.push_back(normals(v, i));
  }
  out.indices.reserve(static_cast<size_t>(avatar.triangles.rows()) * 3);
  for (Eigen::Index f = 0; f < avatar.triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.indices.push_back(static_cast<unsigned>(avatar.triangles(f, k)));
  return out;
}

}  // namespace drape::render
