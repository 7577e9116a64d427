// Reading DXF-AAMA pattern files: dxf_scan.cpp checks and filters the text, libdxflib parses it into the blocks
// collected here, dxf_aama_piece.cpp turns each piece block into a Panel. Format: docs/FORMATS.md
// "DXF-AAMA pattern files".
#include <dl_creationadapter.h>
#include <dl_dxf.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "drape/core/input_error.h"
#include "drape/pattern/dxf_aama.h"
#include "drape/pattern/edge_curve.h"
#include "pattern/dxf_aama_piece.h"
#include "pattern/dxf_scan.h"

namespace drape {
namespace {

using detail::DxfBlock;
using detail::DxfPolyline;

constexpr double kMetresPerInch = 0.0254;

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return s;
}

std::string trimmed(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The value after "<key>:" in a text such as "Piece Name: FRONT" (key matched without case), or "" if absent.
std::string textField(const DxfBlock& block, const std::string& key) {
  for (const std::string& text : block.texts) {
    const size_t colon = text.find(':');
    if (colon != std::string::npos && upper(trimmed(text.substr(0, colon))) == upper(key))
      return trimmed(text.substr(colon + 1));
  }
  return "";
}

// A piece block holds something on layer 1 or a piece name.
bool isAamaPiece(const DxfBlock& block) {
  for (const auto& p : block.polylines)
    if (p.layer == "1") return true;
  return !textField(block, "Piece Name").empty();
}

// Collects the entities libdxflib reports, per block; entities outside any block are the model space (ENTITIES).
class AamaCollector final : public DL_CreationAdapter {
 public:
  using DL_CreationAdapter::addMTextChunk;
  using DL_CreationAdapter::setVariableInt;

  std::vector<DxfBlock> blocks;  // file order
  DxfBlock modelSpace;
  std::vector<DL_InsertData> inserts;  // INSERTs in the model space
  int insUnits = -1;                   // $INSUNITS, -1 when absent

  void addBlock(const DL_BlockData& data) override {
    flush();
    blocks.push_back(DxfBlock{data.name, {}, {}, {}, {}});
    m_current = int(blocks.size()) - 1;
  }
  void endBlock() override {
    flush();
    m_current = -1;
  }
  void addPoint(const DL_PointData& data) override {
    flush();
    block().polylines.push_back(DxfPolyline{layer(), {Eigen::Vector2d(data.x, data.y)}, {0.0}, false});
  }
  void addLine(const DL_LineData& data) override {
    flush();
    block().polylines.push_back(DxfPolyline{
        layer(), {Eigen::Vector2d(data.x1, data.y1), Eigen::Vector2d(data.x2, data.y2)}, {0.0, 0.0}, false});
  }
  void addPolyline(const DL_PolylineData& data) override {
    flush();
    if (data.flags & (16 | 64)) {  // polygon mesh or polyface mesh: not an outline
      block().skipped.push_back("mesh POLYLINE on layer " + layer());
      return;
    }
    m_polyline = DxfPolyline{layer(), {}, {}, (data.flags & 1) != 0};
    // Object coordinates with extrusion (0, 0, -1) are mirrored in x (a piece drawn from below).
    m_mirrored = getExtrusion()->getDirection()[2] < 0.0;
    m_open = true;
  }
  void addVertex(const DL_VertexData& data) override {
    if (!m_open) return;
    m_polyline.points.emplace_back(m_mirrored ? -data.x : data.x, data.y);
    m_polyline.bulges.push_back(m_mirrored ? -data.bulge : data.bulge);
  }
  void endEntity() override { flush(); }
  void endSequence() override { flush(); }
  void addText(const DL_TextData& data) override {
    flush();
    block().texts.push_back(data.text);
  }
  void addMTextChunk(const std::string& text) override { m_mtext += text; }
  void addMText(const DL_MTextData& data) override {
    flush();
    const std::string text = m_mtext + data.text;
    m_mtext.clear();
    for (size_t start = 0;;) {  // paragraphs are separated by "\P"
      const size_t end = text.find("\\P", start);
      block().texts.push_back(text.substr(start, end == std::string::npos ? end : end - start));
      if (end == std::string::npos) break;
      start = end + 2;
    }
  }
  void addInsert(const DL_InsertData& data) override {
    flush();
    if (m_current < 0)
      inserts.push_back(data);
    else
      block().skipped.push_back("INSERT of block '" + data.name + "' (nested)");
  }
  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") insUnits = value;
  }

  void finish() { flush(); }

 private:
  DxfBlock& block() { return m_current < 0 ? modelSpace : blocks[m_current]; }
  std::string layer() { return trimmed(getAttributes().getLayer()); }
  void flush() {
    if (m_open && !m_polyline.points.empty()) block().polylines.push_back(std::move(m_polyline));
    m_open = false;
  }

  int m_current = -1;  // index into blocks, -1 = model space
  DxfPolyline m_polyline;
  bool m_open = false;
  bool m_mirrored = false;
  std::string m_mtext;
};

// File units per metre: the AAMA text "UNITS: METRIC / ENGLISH" first, then $INSUNITS, else millimetres.
double readUnits(const AamaCollector& c, const std::string& source, Diagnostics& diag) {
  double fromText = 0.0;
  std::vector<const DxfBlock*> all{&c.modelSpace};
  for (const DxfBlock& b : c.blocks) all.push_back(&b);
  for (const DxfBlock* b : all) {
    const std::string value = upper(textField(*b, "UNITS"));
    if (value.empty()) continue;
    if (value == "METRIC")
      fromText = 1000.0;
    else if (value == "ENGLISH")
      fromText = 1.0 / kMetresPerInch;
    else
      diag.warn(source + ": unknown 'UNITS: " + value + "' (METRIC or ENGLISH expected); ignored");
    if (fromText > 0.0) break;
  }
  const std::map<int, double> insUnits = {
      {1, 1.0 / kMetresPerInch}, {2, 1.0 / (12 * kMetresPerInch)}, {4, 1000.0}, {5, 100.0}, {6, 1.0}};
  double fromHeader = 0.0;
  if (const auto it = insUnits.find(c.insUnits); it != insUnits.end())
    fromHeader = it->second;
  else if (c.insUnits > 0)
    diag.warn(source + ": $INSUNITS " + std::to_string(c.insUnits) + " is not a length unit Drape reads; ignored");
  if (fromText > 0.0 && fromHeader > 0.0 && fromText != fromHeader)
    diag.warn(source + ": the UNITS text and $INSUNITS " + std::to_string(c.insUnits) + " disagree; the text is used");
  if (fromText > 0.0) return fromText;
  if (fromHeader > 0.0) return fromHeader;
  diag.warn(source + ": no units (no 'UNITS:' text, no $INSUNITS); assuming millimetres");
  return 1000.0;
}

// The piece blocks: those inserted in the model space (or, in a file without INSERTs, all named blocks) that
// hold something on layer 1 or a piece name.
std::vector<const DxfBlock*> pieceBlocks(const AamaCollector& c, const std::string& source, Diagnostics& diag) {
  std::vector<const DxfBlock*> candidates;
  auto find = [&c](const std::string& name) -> const DxfBlock* {
    for (const DxfBlock& b : c.blocks)
      if (b.name == name) return &b;
    return nullptr;
  };
  for (const DL_InsertData& insert : c.inserts) {
    if (insert.name.empty() || insert.name[0] == '*') continue;
    const DxfBlock* block = find(insert.name);
    if (!block) throw InputError(source + ": an INSERT places block '" + insert.name + "', which is not defined");
    if (std::find(candidates.begin(), candidates.end(), block) != candidates.end()) continue;
    candidates.push_back(block);
    if (insert.sx != 1.0 || insert.sy != 1.0)
      diag.warn(source + ": the INSERT of block '" + insert.name + "' scales it; the piece is read unscaled");
  }
  const bool inserted = !candidates.empty();
  if (!inserted)
    for (const DxfBlock& b : c.blocks)
      if (!b.name.empty() && b.name[0] != '*') candidates.push_back(&b);
  std::vector<const DxfBlock*> pieces;
  for (const DxfBlock* b : candidates) {
    if (isAamaPiece(*b))
      pieces.push_back(b);
    else if (inserted)
      diag.warn(source + ": block '" + b->name + "' holds nothing on layer 1 and no piece name; not a piece");
  }
  if (pieces.empty()) {
    bool loose = false;
    for (const auto& p : c.modelSpace.polylines) loose = loose || p.layer == "1";
    throw InputError(source + ": no pieces: no block holds a boundary on layer 1 or a 'Piece Name' text" +
                     (loose ? " (entities outside blocks are not pieces in DXF-AAMA)" : ""));
  }
  return pieces;
}

// DXF-AAMA places its pieces on a flat marker, not around a body: they are hung side by side, facing +z, in a plane
// 35 cm in front of a body standing at the origin (as Drape's avatars do), in rows at most 2 m wide with their middle
// at 1.1 m, so that the 3D view shows them apart before they are sewn. The pieces keep their own coordinates.
void layOutInFront(Pattern& pattern) {
  const double u = pattern.unitsInMeter, gap = 0.05 * u, rowWidth = 2.0 * u;
  struct Box {
    Eigen::Vector2d min, max;
  };
  std::vector<Box> boxes;
  for (const Panel& p : pattern.panels) {
    Box b{p.vertices.front(), p.vertices.front()};
    for (const Eigen::Vector2d& q : panelOutline(p, 0.01 * u)) b.min = b.min.cwiseMin(q), b.max = b.max.cwiseMax(q);
    boxes.push_back(b);
  }
  // Rows: left to right, each below the one before.
  std::vector<std::vector<size_t>> rows(1);
  double x = 0.0;
  for (size_t i = 0; i < boxes.size(); ++i) {
    const double w = boxes[i].max.x() - boxes[i].min.x();
    if (!rows.back().empty() && x + w > rowWidth) rows.emplace_back(), x = 0.0;
    rows.back().push_back(i);
    x += w + gap;
  }
  std::vector<double> heights;
  double total = 0.0;
  for (const auto& row : rows) {
    double h = 0.0;
    for (size_t i : row) h = std::max(h, boxes[i].max.y() - boxes[i].min.y());
    heights.push_back(h);
    total += h + (heights.size() > 1 ? gap : 0.0);
  }
  double top = 1.1 * u + 0.5 * total;
  for (size_t r = 0; r < rows.size(); ++r) {
    double width = -gap;
    for (size_t i : rows[r]) width += boxes[i].max.x() - boxes[i].min.x() + gap;
    double left = -0.5 * width;
    for (size_t i : rows[r]) {
      pattern.panels[i].translation =
          Eigen::Vector3d(left - boxes[i].min.x(), top - heights[r] - boxes[i].min.y(), 0.35 * u);
      left += boxes[i].max.x() - boxes[i].min.x() + gap;
    }
    top -= heights[r] + gap;
  }
}

}  // namespace

Pattern readDxfAamaPattern(const std::filesystem::path& file, Diagnostics* diagnostics) {
  Diagnostics localDiagnostics;
  Diagnostics& diag = diagnostics ? *diagnostics : localDiagnostics;
  const std::string source = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(source + ": cannot open the DXF file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(source + ": cannot open the DXF file");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError(source + ": cannot read the DXF file");

  const detail::DxfScan scan = detail::scanDxf(bytes.str(), source);
  AamaCollector collector;
  std::istringstream text(scan.text);
  DL_Dxf dxf;
  if (!dxf.in(text, &collector)) throw InputError(source + ": libdxflib cannot read the DXF file");
  collector.finish();
  for (DxfBlock& b : collector.blocks) {
    if (const auto it = scan.badNumbers.find(b.name); it != scan.badNumbers.end()) b.badNumber = it->second;
    if (const auto it = scan.skipped.find(b.name); it != scan.skipped.end())
      b.skipped.insert(b.skipped.end(), it->second.begin(), it->second.end());
  }

  Pattern pattern;
  pattern.source = source;
  pattern.unitsInMeter = readUnits(collector, source, diag);
  const std::vector<const DxfBlock*> pieces = pieceBlocks(collector, source, diag);
  std::set<std::string> names;  // every name a piece gives itself; renamed duplicates avoid them too
  for (const DxfBlock* b : pieces) {
    const std::string name = textField(*b, "Piece Name");
    names.insert(name.empty() ? b->name : name);
  }
  std::set<std::string> taken;
  for (const DxfBlock* b : pieces) {
    std::string name = textField(*b, "Piece Name");
    if (name.empty()) name = b->name;
    pattern.panels.push_back(detail::buildAamaPanel(*b, name, pattern.unitsInMeter, source, diag));
    if (taken.insert(name).second) continue;
    std::string unique;
    for (int k = 2; unique.empty() || names.count(unique) || taken.count(unique); ++k)
      unique = name + "_" + std::to_string(k);
    diag.warn(source + ": piece name '" + name + "' is used more than once (block '" + b->name + "'); renamed '" +
              unique + "'");
    pattern.panels.back().name = unique;
    taken.insert(unique);
  }
  layOutInFront(pattern);
  return pattern;
}

bool isDxfFile(const std::filesystem::path& file) {
  return upper(file.extension().string()) == ".DXF";
}

}  // namespace drape
