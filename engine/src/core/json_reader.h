#pragma once
// Small helpers for reading validated JSON: parse errors with line and column, typed field access whose
// errors name the file and the element. Private to the engine (nlohmann stays out of public headers).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace drape::json {

// Why parsing text failed, located: nlohmann's "parse error at line L, column C: ..." for syntax errors; for a
// number too large for a double, its text plus " (non-finite number at line L, column C)". For messages.
std::string describeParseFailure(const std::string& text, const nlohmann::json::exception& e);

// Parses text; on failure throws InputError "<source>: invalid JSON: <describeParseFailure>".
nlohmann::json parse(const std::string& text, const std::string& source);

// Reads and parses a file; a missing or unreadable file throws InputError naming it.
nlohmann::json parseFile(const std::filesystem::path& file);

// Finite number at j[key]; where names the element for messages ("fabrics/denim.json: field").
double number(const nlohmann::json& j, const std::string& key, const std::string& where);
std::string text(const nlohmann::json& j, const std::string& key, const std::string& where);

// Textual form of a JSON scalar for the settings registry (numbers, bools and strings); throws otherwise.
std::string scalarText(const nlohmann::json& value, const std::string& where);

}  // namespace drape::json
