#pragma once
// Private: typed access to fields of a parsed pattern file. Every failure throws InputError
// "<source>: <where>: <problem>", where `where` names the element ("panel 'front' edge 3", "stitch 2").
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

namespace drape::detail {

using Json = nlohmann::ordered_json;  // keeps the file's key order (panel order when panel_order is absent)

class JsonFields {
 public:
  explicit JsonFields(std::string source) : m_source(std::move(source)) {}

  const std::string& source() const { return m_source; }

  // Throws InputError("<source>: <where>: <problem>"), or "<source>: <problem>" when where is empty.
  [[noreturn]] void fail(const std::string& where, const std::string& problem) const;

  // The member `key` of object `object`; missing -> "missing field '<key>'".
  const Json& member(const Json& object, const char* key, const std::string& where) const;

  // Type checks; `what` names the value in the message ("'vertices'", "vertex 3").
  void expectObject(const Json& value, const std::string& where, const std::string& what) const;
  void expectArray(const Json& value, const std::string& where, const std::string& what) const;
  std::string readString(const Json& value, const std::string& where, const std::string& what) const;
  double readNumber(const Json& value, const std::string& where, const std::string& what) const;
  int readIndex(const Json& value, const std::string& where, const std::string& what) const;
  bool readFlag(const Json& value, const std::string& where, const std::string& what) const;
  Eigen::Vector2d readVec2(const Json& value, const std::string& where, const std::string& what) const;
  Eigen::Vector3d readVec3(const Json& value, const std::string& where, const std::string& what) const;

 private:
  std::string m_source;
};

// "an object", "a string", ... for messages.
std::string describeType(const Json& value);

}  // namespace drape::detail
