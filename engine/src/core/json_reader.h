#pragma once
// Small helpers for reading validated JSON: parse errors with line and column, typed field access whose
// errors name the file and the element. Private to the engine (nlohmann stays out of public headers).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace drape::json {

// Why parsing text failed, located: nlohmann's "parse error at line L, column C: ..." for syntax errors; for a
// number too large for a double, its text plus " (non-finite number at line L, column C)". For messages.
std::string describeParseFailure(const std::string& text, const nlohmann::json::exception& e);

// A key that appears twice in one JSON object (nlohmann keeps only the last value, silently).
struct DuplicateKey {
  std::vector<std::string> path;  // keys and "[i]" array indices leading to the object, outermost first
  std::string key;
  std::string dotted() const;  // "sim.time_step", "colliders[0].radius"
};

// The first duplicate key of text (a separate SAX pass; text must be valid JSON), or nothing.
std::optional<DuplicateKey> findDuplicateKey(const std::string& text);

enum class DuplicateKeys { Refuse, Allow };

// Parses text; on failure throws InputError "<source>: invalid JSON: <describeParseFailure>", and with
// DuplicateKeys::Refuse "<source>: key '<dotted>' appears twice" for a repeated key.
nlohmann::json parse(const std::string& text, const std::string& source,
                     DuplicateKeys duplicates = DuplicateKeys::Refuse);

// Reads and parses a file; a missing or unreadable file throws InputError naming it. text, when given, receives
// the file's contents.
nlohmann::json parseFile(const std::filesystem::path& file, DuplicateKeys duplicates = DuplicateKeys::Refuse,
                         std::string* text = nullptr);

// Throws InputError "<source>: key '<dotted>' appears twice" when text has a duplicate key.
void refuseDuplicateKeys(const std::string& text, const std::string& source);

// Finite number at j[key]; where names the element for messages ("fabrics/denim.json: field").
double number(const nlohmann::json& j, const std::string& key, const std::string& where);
std::string text(const nlohmann::json& j, const std::string& key, const std::string& where);

// Textual form of a JSON scalar for the settings registry (numbers, bools and strings); throws otherwise.
std::string scalarText(const nlohmann::json& value, const std::string& where);

}  // namespace drape::json
