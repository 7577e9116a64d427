#include "drape/io/garment_state.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>
#include <tuple>

#include "drape/core/input_error.h"

namespace drape {
namespace {

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw InputError(file.string() + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + what);
}

// The next whitespace-separated token of rest (empty at the end); rest is advanced past it.
std::string_view nextToken(std::string_view& rest) {
  const auto begin = rest.find_first_not_of(" \t\r");
  if (begin == std::string_view::npos) {
    rest = {};
    return {};
  }
  rest.remove_prefix(begin);
  const auto end = std::min(rest.find_first_of(" \t\r"), rest.size());
  const std::string_view token = rest.substr(0, end);
  rest.remove_prefix(end);
  return token;
}

bool parseNumber(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

// The vertex index of a face corner "a", "a/b", "a//c" or "a/b/c" (1-based, or negative from the end), 0-based.
bool parseCorner(std::string_view token, int vertexCount, int& index) {
  token = token.substr(0, token.find('/'));
  int value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || value == 0) return false;
  index = value > 0 ? value - 1 : vertexCount + value;
  return index >= 0 && index < vertexCount;
}

// The triangle rotated to start at its smallest index (orientation kept), for comparing face lists.
std::array<int, 3> canonical(int a, int b, int c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

}  // namespace

GarmentState readGarmentState(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (extension != ".obj")
    fail(file, 0,
         "a garment state must be an OBJ written by drape (.glb, .gltf, .ply and .stl do not keep the "
         "garment's vertex order)");
  std::ifstream in(file);
  if (!in) fail(file, 0, "cannot open the garment state");
  std::vector<double> coordinates;
  std::vector<std::array<int, 3>> faces;
  GarmentState state;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    std::string_view rest = text;
    const std::string_view keyword = nextToken(rest);
    if (keyword == "v") {
      std::array<double, 3> xyz{};
      for (double& c : xyz)
        if (!parseNumber(nextToken(rest), c)) fail(file, line, "vertex needs three finite coordinates: " + text);
      coordinates.insert(coordinates.end(), xyz.begin(), xyz.end());
    } else if (keyword == "f") {
      const int vertexCount = static_cast<int>(coordinates.size() / 3);
      std::array<int, 3> face{};
      int corners = 0;
      for (std::string_view token = nextToken(rest); !token.empty(); token = nextToken(rest), ++corners) {
        if (corners == 3) fail(file, line, "face is not a triangle (drape writes triangles only): " + text);
        if (!parseCorner(token, vertexCount, face[corners]))
          fail(file, line,
               "face corner '" + std::string(token) + "' names no vertex defined before it (" +
                   std::to_string(vertexCount) + " so far)");
      }
      if (corners != 3) fail(file, line, "face is not a triangle (drape writes triangles only): " + text);
      faces.push_back(face);
      state.faceLines.push_back(line);
    }
  }
  if (in.bad()) fail(file, 0, "read error");
  if (coordinates.empty()) fail(file, 0, "no vertices (\"v\" lines)");
  state.positions = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      coordinates.data(), static_cast<Eigen::Index>(coordinates.size() / 3), 3);
  state.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    state.faces.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  return state;
}

void checkGarmentState(const GarmentState& state, const Garment& garment, const std::filesystem::path& file) {
  const Eigen::Index vertices = state.positions.rows();
  if (vertices != garment.positions.rows())
    fail(file, 0,
         std::to_string(vertices) + " vertices, the scene's garment has " + std::to_string(garment.positions.rows()) +
             " (written from another scene or mesh setting?)");
  if (state.faces.rows() == 0) return;  // positions only: the count is all there is to check
  if (state.faces.rows() != garment.triangles.rows())
    fail(file, 0,
         std::to_string(state.faces.rows()) + " faces, the scene's garment has " +
             std::to_string(garment.triangles.rows()) + " triangles");
  std::vector<std::array<int, 3>> expected(static_cast<std::size_t>(garment.triangles.rows()));
  for (Eigen::Index f = 0; f < garment.triangles.rows(); ++f)
    expected[static_cast<std::size_t>(f)] =
        canonical(garment.triangles(f, 0), garment.triangles(f, 1), garment.triangles(f, 2));
  std::sort(expected.begin(), expected.end());
  std::vector<char> used(expected.size(), 0);
  for (Eigen::Index f = 0; f < state.faces.rows(); ++f) {
    const std::array<int, 3> face = canonical(state.faces(f, 0), state.faces(f, 1), state.faces(f, 2));
    const auto it = std::lower_bound(expected.begin(), expected.end(), face);
    const std::size_t k = static_cast<std::size_t>(it - expected.begin());
    if (it == expected.end() || *it != face || used[k]) {
      fail(file, state.faceLines[static_cast<std::size_t>(f)],
           "face " + std::to_string(state.faces(f, 0) + 1) + " " + std::to_string(state.faces(f, 1) + 1) + " " +
               std::to_string(state.faces(f, 2) + 1) +
               (it != expected.end() && *it == face ? " appears twice" : " is not a triangle of the scene's garment") +
               " (the file was written from another garment, or its vertices were reordered)");
    }
    used[k] = 1;
  }
}

Eigen::MatrixX3d readGarmentPositions(const std::filesystem::path& file, const Garment& garment) {
  const GarmentState state = readGarmentState(file);
  checkGarmentState(state, garment, file);
  return state.positions;
}

}  // namespace drape
