#include <Eigen/Geometry>
#include <cctype>
#include <cstdio>

#include "io/export_data.h"

namespace drape::detail {
namespace {

void appendFormatted(std::string& out, const char* format, double a, double b) {
  char buffer[96];
  const int n = std::snprintf(buffer, sizeof buffer, format, a, b);
  out.append(buffer, static_cast<std::size_t>(n));
}

void appendFormatted(std::string& out, const char* format, double a, double b, double c) {
  char buffer[128];
  const int n = std::snprintf(buffer, sizeof buffer, format, a, b, c);
  out.append(buffer, static_cast<std::size_t>(n));
}

// OBJ group names end at whitespace; replace it so that a panel name stays one group.
std::string groupName(const std::string& name, std::size_t index) {
  if (name.empty()) return "group_" + std::to_string(index);
  std::string result = name;
  for (char& c : result) {
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  }
  return result;
}

}  // namespace

Eigen::MatrixX3d vertexNormals(const ExportData& data) {
  const Eigen::MatrixX3d& x = *data.positions;
  const Eigen::MatrixX3i& t = *data.triangles;
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(x.rows(), 3);
  for (Eigen::Index f = 0; f < t.rows(); ++f) {
    const Eigen::Vector3d a = x.row(t(f, 0)).transpose();
    const Eigen::Vector3d areaNormal = (x.row(t(f, 1)).transpose() - a).cross(x.row(t(f, 2)).transpose() - a);
    for (int k = 0; k < 3; ++k) normals.row(t(f, k)) += areaNormal.transpose();
  }
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    const double length = normals.row(i).norm();
    if (length > 0.0) {
      normals.row(i) /= length;
    } else {
      normals.row(i) << 0.0, 0.0, 1.0;
    }
  }
  return normals;
}

std::string objText(const ExportData& data) {
  const Eigen::MatrixX3d& x = *data.positions;
  const Eigen::MatrixX3i& t = *data.triangles;
  const bool withUvs = data.uvs != nullptr;
  const Eigen::MatrixX3d normals = vertexNormals(data);

  std::string out;
  out.reserve(static_cast<std::size_t>(x.rows()) * (withUvs ? 110 : 80) + static_cast<std::size_t>(t.rows()) * 40);
  out += "# Drape export: " + std::to_string(x.rows()) + " vertices, " + std::to_string(t.rows()) + " triangles, " +
         std::to_string(data.groups.size()) + " groups; positions in metres\n";
  for (Eigen::Index i = 0; i < x.rows(); ++i) appendFormatted(out, "v %.9g %.9g %.9g\n", x(i, 0), x(i, 1), x(i, 2));
  if (withUvs) {
    const Eigen::MatrixX2d& uv = *data.uvs;
    for (Eigen::Index i = 0; i < uv.rows(); ++i) appendFormatted(out, "vt %.9g %.9g\n", uv(i, 0), uv(i, 1));
  }
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    appendFormatted(out, "vn %.6g %.6g %.6g\n", normals(i, 0), normals(i, 1), normals(i, 2));
  }
  for (std::size_t g = 0; g < data.groups.size(); ++g) {
    out += "g " + groupName(data.groups[g].name, g) + "\n";
    for (const int f : data.groups[g].triangles) {
      out += 'f';
      for (int k = 0; k < 3; ++k) {
        const std::string index = std::to_string(t(f, k) + 1);
        out += ' ';
        out += index;
        out += withUvs ? "/" + index + "/" : "//";
        out += index;
      }
      out += '\n';
    }
  }
  return out;
}

}  // namespace drape::detail
