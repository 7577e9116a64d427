#include "pattern/dxf_scan.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>
#include <string_view>

#include "drape/core/input_error.h"

namespace drape::detail {
namespace {

// libdxflib reads a line into a 1024-byte buffer and stops making progress on a longer one; a longer value
// (only text can be one) is cut to this length.
constexpr size_t kMaxValueLength = 1000;
constexpr int kMaxGroupCode = 1071;

const std::set<std::string, std::less<>> kPassedEntities = {
    "BLOCK", "ENDBLK", "POINT", "LINE", "POLYLINE", "VERTEX", "LWPOLYLINE", "TEXT", "MTEXT", "INSERT", "SEQEND"};
// The layers the AAMA reader reads: an entity skipped on one of them is reported.
const std::set<std::string, std::less<>> kReadLayers = {"1", "4", "7", "8"};

std::string_view trim(std::string_view s) {
  const size_t b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// Up to 40 bytes of a value for a message, control characters shown as '?' (the message stays one line).
std::string quoted(std::string_view s) {
  std::string text(trim(s).substr(0, 40));
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  return "'" + text + "'";
}

bool parseInt(std::string_view s, int& out) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

// A DXF real that is finite and is the whole value (',' is taken for the decimal point, as libdxflib does).
// from_chars, unlike strtod, ignores the C locale a GUI may have set.
bool isFiniteReal(std::string_view s) {
  std::string t(trim(s));
  std::replace(t.begin(), t.end(), ',', '.');
  const char* first = t.data() + (!t.empty() && t.front() == '+' ? 1 : 0);
  const char* last = t.data() + t.size();
  double x = 0.0;
  const auto [end, ec] = std::from_chars(first, last, x);
  return first != last && ec == std::errc() && end == last && std::isfinite(x);
}

struct Pair {
  int code = 0;
  std::string_view value;
  size_t valueLine = 0;  // 1-based line number of the value
};

class Scanner {
 public:
  Scanner(const std::string& source, DxfScan& out) : m_source(source), m_out(out) {}

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(m_source + ": " + problem); }

  // Called with each entity: its pairs from one group code 0 to the next.
  void entity(const std::vector<Pair>& pairs) {
    const std::string_view type = trim(pairs.front().value);
    if (type == "SECTION") {
      m_section = std::string(trim(valueOf(pairs, 2)));
      if (m_section == "HEADER") return emit(pairs);
      emitPair(0, "SECTION");
      return emitPair(2, m_section);
    }
    if (type == "ENDSEC" || type == "EOF") {
      m_section.clear();
      m_block.clear();
      return emitPair(0, type);
    }
    if (m_section != "BLOCKS" && m_section != "ENTITIES") return;
    if (type == "BLOCK") m_block = std::string(trim(valueOf(pairs, 2)));
    const std::string layer(trim(valueOf(pairs, 8, "0")));
    if (!kPassedEntities.count(type)) {
      if (kReadLayers.count(layer)) m_out.skipped[m_block].push_back(std::string(type) + " on layer " + layer);
      return;
    }
    checkNumbers(pairs, type, layer);
    if (type == "LWPOLYLINE")
      emitLwPolyline(pairs);
    else
      emit(pairs);
    if (type == "ENDBLK") m_block.clear();
  }

 private:
  static std::string_view valueOf(const std::vector<Pair>& pairs, int code, std::string_view fallback = {}) {
    for (const Pair& p : pairs)
      if (p.code == code) return p.value;
    return fallback;
  }

  void checkNumbers(const std::vector<Pair>& pairs, std::string_view type, const std::string& layer) {
    if (m_out.badNumbers.count(m_block)) return;
    for (const Pair& p : pairs) {
      if (p.code < 10 || p.code > 59 || isFiniteReal(p.value)) continue;
      m_out.badNumbers[m_block] = std::string(type) + " on layer " + layer + " (line " + std::to_string(p.valueLine) +
                                  "): " + quoted(p.value) + " is not a finite number";
      return;
    }
  }

  void emitPair(int code, std::string_view value) {
    if (code != 1 && code != 3) value = trim(value);  // text keeps its spaces
    m_out.text += std::to_string(code);
    m_out.text += '\n';
    m_out.text.append(value.substr(0, kMaxValueLength));
    m_out.text += '\n';
  }

  void emit(const std::vector<Pair>& pairs) {
    for (const Pair& p : pairs) emitPair(p.code, p.value);
  }

  // libdxflib sizes its vertex buffer from group 90 and writes a bulge (42) given before the first vertex (10)
  // in front of it: the count is replaced by the true one and such groups are dropped.
  void emitLwPolyline(const std::vector<Pair>& pairs) {
    const auto vertices = std::count_if(pairs.begin(), pairs.end(), [](const Pair& p) { return p.code == 10; });
    emitPair(0, "LWPOLYLINE");
    emitPair(90, std::to_string(vertices));
    bool seenVertex = false;
    for (size_t i = 1; i < pairs.size(); ++i) {
      const int code = pairs[i].code;
      if (code == 90) continue;
      seenVertex = seenVertex || code == 10;
      if (!seenVertex && (code == 20 || code == 30 || code == 42)) continue;
      emitPair(code, pairs[i].value);
    }
  }

  const std::string& m_source;
  DxfScan& m_out;
  std::string m_section;
  std::string m_block;
};

std::vector<std::string_view> splitLines(const std::string& bytes) {
  std::vector<std::string_view> lines;
  size_t start = 0;
  while (start < bytes.size()) {
    size_t end = bytes.find('\n', start);
    if (end == std::string::npos) end = bytes.size();
    std::string_view line(bytes.data() + start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

}  // namespace

DxfScan scanDxf(const std::string& bytes, const std::string& source) {
  if (bytes.rfind("AutoCAD Binary DXF", 0) == 0)
    throw InputError(source + ": binary DXF is not supported (save the file as ASCII DXF)");
  const std::vector<std::string_view> lines = splitLines(bytes);
  DxfScan out;
  Scanner scanner(source, out);
  std::vector<Pair> current;
  bool started = false;
  for (size_t i = 0; i < lines.size(); i += 2) {
    Pair pair;
    if (!parseInt(lines[i], pair.code) || pair.code < 0 || pair.code > kMaxGroupCode) {
      if (!started) scanner.fail("not a DXF file (line " + std::to_string(i + 1) + " is not a group code)");
      scanner.fail("line " + std::to_string(i + 1) + ": " + quoted(lines[i]) + " is not a DXF group code");
    }
    if (i + 1 >= lines.size()) break;  // a group code without its value: the file is cut short
    pair.value = lines[i + 1];
    pair.valueLine = i + 2;
    if (pair.code == 999) continue;  // comment
    if (!started) {
      if (pair.code != 0 || trim(pair.value) != "SECTION")
        scanner.fail("not a DXF file (it does not start with a SECTION)");
      started = true;
    }
    if (pair.code == 0 && !current.empty()) {
      scanner.entity(current);
      current.clear();
    }
    current.push_back(pair);
    if (pair.code == 0 && trim(pair.value) == "EOF") {  // what follows the marker is not read
      scanner.entity(current);
      return out;
    }
  }
  if (!started) scanner.fail("not a DXF file (no SECTION)");
  scanner.fail("truncated DXF file: it ends at line " + std::to_string(lines.size()) + " before the EOF marker");
}

}  // namespace drape::detail
