#include "pattern/json_fields.h"

#include <cmath>
#include <limits>

#include "drape/core/input_error.h"

namespace drape::detail {

std::string describeType(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::object:
      return "an object";
    case Json::value_t::array:
      return "an array of " + std::to_string(value.size());
    case Json::value_t::string:
      return "the string \"" + value.get<std::string>() + "\"";
    case Json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return "the number " + value.dump();
    default:
      return "an unsupported value";
  }
}

void JsonFields::fail(const std::string& where, const std::string& problem) const {
  throw InputError(where.empty() ? m_source + ": " + problem : m_source + ": " + where + ": " + problem);
}

const Json& JsonFields::member(const Json& object, const char* key, const std::string& where) const {
  const auto it = object.find(key);
  if (it == object.end()) fail(where, std::string("missing field '") + key + "'");
  return *it;
}

void JsonFields::expectObject(const Json& value, const std::string& where, const std::string& what) const {
  if (!value.is_object()) fail(where, what + " must be an object, got " + describeType(value));
}

void JsonFields::expectArray(const Json& value, const std::string& where, const std::string& what) const {
  if (!value.is_array()) fail(where, what + " must be an array, got " + describeType(value));
}

std::string JsonFields::readString(const Json& value, const std::string& where, const std::string& what) const {
  if (!value.is_string()) fail(where, what + " must be a string, got " + describeType(value));
  return value.get<std::string>();
}

double JsonFields::readNumber(const Json& value, const std::string& where, const std::string& what) const {
  if (!value.is_number()) fail(where, what + " must be a number, got " + describeType(value));
  const double x = value.get<double>();
  if (!std::isfinite(x)) fail(where, what + " is not a finite number (" + value.dump() + ")");
  return x;
}

int JsonFields::readIndex(const Json& value, const std::string& where, const std::string& what) const {
  if (value.is_number_unsigned() || value.is_number_integer()) {
    const auto i = value.get<long long>();
    if (i < 0 || i > std::numeric_limits<int>::max()) fail(where, what + " " + value.dump() + " is out of range");
    return int(i);
  }
  if (value.is_number_float()) {
    const double x = value.get<double>();
    if (std::isfinite(x) && x == std::floor(x) && x >= 0.0 && x <= std::numeric_limits<int>::max()) return int(x);
  }
  fail(where, what + " must be a non-negative integer, got " + describeType(value));
}

bool JsonFields::readFlag(const Json& value, const std::string& where, const std::string& what) const {
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_number()) {
    const double x = value.get<double>();
    if (x == 0.0 || x == 1.0) return x == 1.0;
  }
  fail(where, what + " must be true/false (or 1/0), got " + describeType(value));
}

Eigen::Vector2d JsonFields::readVec2(const Json& value, const std::string& where, const std::string& what) const {
  if (!value.is_array() || value.size() != 2)
    fail(where, what + " must be an array of 2 numbers, got " + describeType(value));
  return {readNumber(value[0], where, what + " x"), readNumber(value[1], where, what + " y")};
}

Eigen::Vector3d JsonFields::readVec3(const Json& value, const std::string& where, const std::string& what) const {
  if (!value.is_array() || value.size() != 3)
    fail(where, what + " must be an array of 3 numbers, got " + describeType(value));
  return {readNumber(value[0], where, what + " x"), readNumber(value[1], where, what + " y"),
          readNumber(value[2], where, what + " z")};
}

}  // namespace drape::detail
