#include "core/json_reader.h"

#include <cmath>
#include <fstream>
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

nlohmann::json parse(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source + ": invalid JSON: " + describeParseFailure(text, e));
  }
}

nlohmann::json parseFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file.string() + ": file not found");
  if (std::filesystem::is_directory(file, ec)) throw InputError(file.string() + ": is a directory, not a file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open file for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), file.string());
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
