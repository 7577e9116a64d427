#include "core/json_reader.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "drape/core/input_error.h"

namespace drape::json {

std::string describeParseFailure(const std::string& text, const nlohmann::json::exception& e) {
  // "[json.exception.parse_error.101] parse error at line 1, column 2: ..." -> "parse error at line 1, column 2: ..."
  std::string what = e.what();
  if (const size_t close = what.find("] "); !what.empty() && what[0] == '[' && close != std::string::npos)
    what = what.substr(close + 2);
  if (dynamic_cast<const nlohmann::json::parse_error*>(&e)) return what;
  // Other failures (out_of_range 406, "number overflow parsing '1e999'") carry no position: find the token.
  const size_t open = what.find('\'');
  const size_t close = open == std::string::npos ? open : what.find('\'', open + 1);
  if (close == std::string::npos || close == open + 1) return what;
  const size_t at = text.find(what.substr(open + 1, close - open - 1));
  if (at == std::string::npos) return what;
  size_t line = 1, lineStart = 0;
  for (size_t i = 0; i < at; ++i)
    if (text[i] == '\n') {
      ++line;
      lineStart = i + 1;
    }
  return what + " (non-finite number at line " + std::to_string(line) + ", column " + std::to_string(at - lineStart + 1) +
         ")";
}

namespace {

// SAX handler that records the first key repeated within one object.
class DuplicateKeyFinder : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::optional<DuplicateKey> found;

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& key) override {
    Frame& top = m_frames.back();
    if (top.keys.insert(key).second) {
      top.current = key;
      return true;
    }
    DuplicateKey duplicate;
    for (size_t i = 0; i + 1 < m_frames.size(); ++i)
      duplicate.path.push_back(m_frames[i].object ? m_frames[i].current
                                                  : "[" + std::to_string(m_frames[i].items - 1) + "]");
    duplicate.key = key;
    found = std::move(duplicate);
    return false;  // stop parsing
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception&) override { return false; }

 private:
  struct Frame {
    bool object = false;
    std::set<std::string> keys;  // objects: keys so far
    std::string current;         // objects: the key whose value is being read
    size_t items = 0;            // arrays: values so far
  };
  std::vector<Frame> m_frames;

  bool value() {
    if (!m_frames.empty() && !m_frames.back().object) ++m_frames.back().items;
    return true;
  }
  bool open(bool object) {
    value();
    m_frames.push_back({object, {}, {}, 0});
    return true;
  }
  bool close() {
    m_frames.pop_back();
    return true;
  }
};

}  // namespace

std::string DuplicateKey::dotted() const {
  std::string out;
  for (const std::string& part : path) out += (out.empty() || part[0] == '[' ? "" : ".") + part;
  return out + (out.empty() ? "" : ".") + key;
}

std::optional<DuplicateKey> findDuplicateKey(const std::string& text) {
  DuplicateKeyFinder finder;
  nlohmann::json::sax_parse(text, &finder);
  return finder.found;
}

void refuseDuplicateKeys(const std::string& text, const std::string& source) {
  if (const auto duplicate = findDuplicateKey(text))
    throw InputError(source + ": key '" + duplicate->dotted() + "' appears twice");
}

nlohmann::json parse(const std::string& text, const std::string& source, DuplicateKeys duplicates) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source + ": invalid JSON: " + describeParseFailure(text, e));
  }
  if (duplicates == DuplicateKeys::Refuse) refuseDuplicateKeys(text, source);
  return j;
}

nlohmann::json parseFile(const std::filesystem::path& file, DuplicateKeys duplicates, std::string* text) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file.string() + ": file not found");
  if (std::filesystem::is_directory(file, ec)) throw InputError(file.string() + ": is a directory, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (text) *text = ss.str();
  return parse(ss.str(), file.string(), duplicates);
}

double number(const nlohmann::json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key)) throw InputError(where + ": missing field '" + key + "'");
  const auto& v = j.at(key);
  if (!v.is_number()) throw InputError(where + ": field '" + key + "' must be a number");
  const double d = v.get<double>();
  if (!std::isfinite(d)) throw InputError(where + ": field '" + key + "' is not finite");
  return d;
}

std::string text(const nlohmann::json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key)) throw InputError(where + ": missing field '" + key + "'");
  const auto& v = j.at(key);
  if (!v.is_string()) throw InputError(where + ": field '" + key + "' must be a string");
  return v.get<std::string>();
}

std::string scalarText(const nlohmann::json& value, const std::string& where) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  if (value.is_number()) {
    // Shortest text that reads back to the same double (0.1 stays "0.1").
    const double d = value.get<double>();
    for (int precision = 15; precision <= 17; ++precision) {
      std::ostringstream os;
      os.precision(precision);
      os << d;
      if (precision == 17 || std::stod(os.str()) == d) return os.str();
    }
  }
  if (value.is_null()) return "";
  throw InputError(where + ": expected a number, a string or true/false");
}

}  // namespace drape::json
