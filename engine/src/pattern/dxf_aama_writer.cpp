// Writing a Pattern as DXF-AAMA (R12, millimetres) with libdxflib. Format: docs/FORMATS.md "DXF-AAMA pattern files".
#include <dl_dxf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <memory>
#include <set>
#include <stdexcept>

#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "drape/pattern/dxf_aama.h"
#include "drape/pattern/edge_curve.h"

namespace drape {
namespace {

constexpr double kMaxSegmentMm = 5.0;   // curved edges are sampled into segments at most this long
constexpr double kNotchLengthMm = 5.0;  // a notch is a slit this long (at most 5% of the piece) into the piece
constexpr double kTextHeightMm = 5.0;
constexpr double kGapMm = 20.0;           // between pieces laid side by side
constexpr double kMaxCoordinateMm = 1e9;  // beyond, the panel is broken (and libdxflib's number buffer too small)

using Points = std::vector<Eigen::Vector2d>;

// One panel, millimetres.
struct Piece {
  std::string name;
  std::string blockName;
  Points outline;  // closed: the last point is not repeated
  std::array<Eigen::Vector2d, 2> grain;
  std::vector<std::array<Eigen::Vector2d, 2>> notches;  // from the notch into the piece
  std::vector<Points> internalLines;
  Eigen::Vector2d centroid;
  Eigen::AlignedBox2d box;
};

double signedArea(const Points& p) {
  double twice = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % p.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

Eigen::Vector2d areaCentroid(const Points& p, const Eigen::AlignedBox2d& box) {
  const double area = signedArea(p);
  if (!(std::abs(area) > 0.0)) return box.center();
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < p.size(); ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % p.size()];
    sum += (a + b) * (a.x() * b.y() - b.x() * a.y());
  }
  return sum / (6.0 * area);
}

// A slit from notch into the piece, perpendicular to the nearest outline segment.
std::array<Eigen::Vector2d, 2> notchSlit(const Eigen::Vector2d& notch, const Points& outline, double length) {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d direction(1.0, 0.0);
  for (size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d d = outline[(i + 1) % outline.size()] - a;
    if (!(d.squaredNorm() > 0.0)) continue;
    const double t = std::clamp((notch - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double distance = (a + t * d - notch).norm();
    if (distance < best) {
      best = distance;
      direction = Eigen::Vector2d(-d.y(), d.x()).normalized();  // left of the outline's direction
    }
  }
  if (signedArea(outline) < 0.0) direction = -direction;  // inside is left of a counter-clockwise outline
  return {notch, notch + length * direction};
}

// Block names: letters, digits, '_' and '-' (R12), unique without regard to case.
std::string blockNameFor(const std::string& name, std::set<std::string>& used) {
  std::string base;
  for (unsigned char c : name) base += (std::isalnum(c) || c == '_' || c == '-') ? char(c) : '_';
  if (base.empty()) base = "PIECE";
  base = base.substr(0, 24);
  std::string candidate = base;
  auto key = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
    return s;
  };
  for (int k = 2; used.count(key(candidate)); ++k) candidate = base + "_" + std::to_string(k);
  used.insert(key(candidate));
  return candidate;
}

// DXF text is one line: control characters become spaces.
std::string textLine(std::string s) {
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return s;
}

Piece pieceOf(const Panel& panel, double mmPerUnit, const std::string& target, std::set<std::string>& blockNames) {
  const std::string where = target + ": panel '" + panel.name + "'";
  const int nv = int(panel.vertices.size());
  if (panel.edges.size() < 2) throw InputError(where + ": no outline to write (fewer than 2 edges)");
  Piece piece;
  piece.name = panel.name;
  piece.blockName = blockNameFor(panel.name, blockNames);
  for (int e = 0; e < int(panel.edges.size()); ++e) {
    const PanelEdge& edge = panel.edges[e];
    if (edge.start < 0 || edge.start >= nv || edge.end < 0 || edge.end >= nv)
      throw InputError(where + " edge " + std::to_string(e) + ": endpoint out of range");
    if (edge.curve.type == CurveType::Straight) {
      piece.outline.push_back(mmPerUnit * panel.vertices[edge.start]);
      continue;
    }
    const double length = mmPerUnit * edgeLength(panel, e);
    const int segments = std::clamp(int(std::ceil(length / kMaxSegmentMm)), 8, 1000);
    const Points samples = sampleEdge(panel, e, segments);
    for (int k = 0; k < segments; ++k) piece.outline.push_back(mmPerUnit * samples[k]);
  }
  for (const auto& p : piece.outline) piece.box.extend(p);
  piece.centroid = areaCentroid(piece.outline, piece.box);
  if (panel.grainLine) {
    piece.grain = {mmPerUnit * (*panel.grainLine)[0], mmPerUnit * (*panel.grainLine)[1]};
  } else {  // the warp: the panel's x axis, through its centroid
    const Eigen::Vector2d half(0.25 * piece.box.sizes().x(), 0.0);
    piece.grain = {piece.centroid - half, piece.centroid + half};
  }
  const double slit = std::min(kNotchLengthMm, 0.05 * piece.box.diagonal().norm());
  for (const auto& notch : panel.notches) piece.notches.push_back(notchSlit(mmPerUnit * notch, piece.outline, slit));
  for (const auto& line : panel.internalLines) {
    if (line.size() < 2) continue;
    piece.internalLines.emplace_back();
    for (const auto& p : line) piece.internalLines.back().push_back(mmPerUnit * p);
  }
  auto check = [&](const Eigen::Vector2d& p, const char* what) {
    if (!(p.cwiseAbs().maxCoeff() <= kMaxCoordinateMm))
      throw InputError(where + ": " + what + " has a coordinate that is not finite or beyond 1e9 mm");
  };
  for (const auto& p : piece.outline) check(p, "the outline");
  for (const auto& p : piece.grain) check(p, "the grain line");
  for (const auto& n : piece.notches) check(n[1], "a notch");
  for (const auto& line : piece.internalLines)
    for (const auto& p : line) check(p, "an internal line");
  for (const auto& n : piece.notches) piece.box.extend(n[1]);
  for (const auto& line : piece.internalLines)
    for (const auto& p : line) piece.box.extend(p);
  for (const auto& p : piece.grain) piece.box.extend(p);
  return piece;
}

void writePolyline(DL_Dxf& dxf, DL_WriterA& dw, const Points& points, bool closed, const DL_Attributes& attributes) {
  dxf.writePolyline(dw, DL_PolylineData(int(points.size()), 0, 0, closed ? 1 : 0), attributes);
  for (const auto& p : points) dxf.writeVertex(dw, DL_VertexData(p.x(), p.y(), 0.0, 0.0));
  dxf.writePolylineEnd(dw);
}

void writeLine(DL_Dxf& dxf, DL_WriterA& dw, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
               const DL_Attributes& attributes) {
  dxf.writeLine(dw, DL_LineData(a.x(), a.y(), 0.0, b.x(), b.y(), 0.0), attributes);
}

void writeText(DL_Dxf& dxf, DL_WriterA& dw, const Eigen::Vector2d& at, const std::string& text,
               const DL_Attributes& attributes) {
  dxf.writeText(dw,
                DL_TextData(at.x(), at.y(), 0.0, at.x(), at.y(), 0.0, kTextHeightMm, 1.0, 0, 0, 0, textLine(text),
                            "STANDARD", 0.0),
                attributes);
}

void writeTables(DL_Dxf& dxf, DL_WriterA& dw) {
  dw.sectionTables();
  dxf.writeVPort(dw);
  dw.tableLinetypes(3);
  dxf.writeLinetype(dw, DL_LinetypeData("BYBLOCK", "BYBLOCK", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("BYLAYER", "BYLAYER", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("CONTINUOUS", "Continuous", 0, 0, 0.0));
  dw.tableEnd();
  const std::array<const char*, 5> layers = {"0", "1", "4", "7", "8"};
  dw.tableLayers(int(layers.size()));
  for (const char* layer : layers)
    dxf.writeLayer(dw, DL_LayerData(layer, 0), DL_Attributes("", 7, 100, "CONTINUOUS", 1.0));
  dw.tableEnd();
  dw.tableStyle(1);
  dxf.writeStyle(dw, DL_StyleData("STANDARD", 0, 0.0, 1.0, 0.0, 0, kTextHeightMm, "txt", ""));
  dw.tableEnd();
  dxf.writeView(dw);
  dxf.writeUcs(dw);
  dw.tableAppid(1);
  dxf.writeAppid(dw, "ACAD");
  dw.tableEnd();
  dxf.writeDimStyle(dw, 1, 1, 1, 1, 1);
  dw.sectionEnd();
}

void writeFile(const std::vector<Piece>& pieces, const std::filesystem::path& path) {
  DL_Dxf dxf;
  std::unique_ptr<DL_WriterA> dw(dxf.out(path.c_str(), DL_Codes::AC1009));
  if (!dw) throw std::runtime_error("libdxflib cannot open the file");
  auto on = [](const char* layer) { return DL_Attributes(layer, 256, -1, "BYLAYER", 1.0); };

  dxf.writeHeader(*dw);
  dw->dxfString(9, "$INSUNITS");
  dw->dxfInt(70, 4);  // millimetres
  dw->dxfString(9, "$MEASUREMENT");
  dw->dxfInt(70, 1);  // metric
  dw->sectionEnd();
  writeTables(dxf, *dw);

  dw->sectionBlocks();
  for (const char* space : {"*Model_Space", "*Paper_Space"}) {
    dxf.writeBlock(*dw, DL_BlockData(space, 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(*dw, space);
  }
  for (const Piece& piece : pieces) {
    dxf.writeBlock(*dw, DL_BlockData(piece.blockName, 0, 0.0, 0.0, 0.0));
    writePolyline(dxf, *dw, piece.outline, true, on("1"));
    writeLine(dxf, *dw, piece.grain[0], piece.grain[1], on("7"));
    for (const auto& slit : piece.notches) writeLine(dxf, *dw, slit[0], slit[1], on("4"));
    for (const Points& line : piece.internalLines) {
      if (line.size() == 2)
        writeLine(dxf, *dw, line[0], line[1], on("8"));
      else
        writePolyline(dxf, *dw, line, false, on("8"));
    }
    writeText(dxf, *dw, piece.centroid, "Piece Name: " + piece.name, on("1"));
    dxf.writeEndBlock(*dw, piece.blockName);
  }
  dw->sectionEnd();

  dw->sectionEntities();
  writeText(dxf, *dw, Eigen::Vector2d(0.0, -2.0 * kTextHeightMm), "UNITS: METRIC", on("1"));
  double cursor = 0.0;  // pieces side by side along x, bottoms on y = 0
  for (const Piece& piece : pieces) {
    const Eigen::Vector2d at(cursor - piece.box.min().x(), -piece.box.min().y());
    dxf.writeInsert(*dw, DL_InsertData(piece.blockName, at.x(), at.y(), 0.0, 1.0, 1.0, 1.0, 0.0, 1, 1, 0.0, 0.0),
                    on("1"));
    cursor += piece.box.sizes().x() + kGapMm;
  }
  dw->sectionEnd();
  dw->dxfEOF();
  dw->close();

  std::ifstream check(path, std::ios::binary | std::ios::ate);  // libdxflib does not report write errors
  const auto size = static_cast<std::streamoff>(check.tellg());
  std::string tail(4, '\0');
  if (check && size >= 4) check.seekg(size - 4).read(tail.data(), 4);
  if (!check || tail != "EOF\n") throw std::runtime_error("the DXF file is incomplete (disk full?)");
}

}  // namespace

void writeDxfAamaPattern(const Pattern& pattern, const std::filesystem::path& file) {
  const std::string target = file.string();
  if (pattern.panels.empty()) throw InputError(target + ": the pattern has no panels to write");
  if (!(pattern.unitsInMeter > 0.0) || !std::isfinite(pattern.unitsInMeter))
    throw InputError(target + ": the pattern's units_in_meter is not a positive number");
  const double mmPerUnit = 1000.0 / pattern.unitsInMeter;
  std::vector<Piece> pieces;
  std::set<std::string> blockNames;
  for (const Panel& panel : pattern.panels) pieces.push_back(pieceOf(panel, mmPerUnit, target, blockNames));
  writeFileAtomically(file, [&](const std::filesystem::path& temp) { writeFile(pieces, temp); });
}

}  // namespace drape
