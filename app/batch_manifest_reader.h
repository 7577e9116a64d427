#pragma once
// The element checks of a batch manifest: each value is validated where it is read, and every error is one line
// "MANIFEST: <element>: <what is wrong>" (an InputError).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "batch_manifest.h"

namespace drape::app {

// "a, b, c"
std::string joinedList(const std::vector<std::string>& items, const char* separator = ", ");
bool listContains(const std::vector<std::string>& items, const std::string& item);

class ManifestReader {
 public:
  // Paths in the manifest are relative to its folder.
  explicit ManifestReader(const std::filesystem::path& manifest);

  [[noreturn]] void fail(const std::string& element, const std::string& what) const;
  // Every key of object must be one of valid; prefix names the object ("grid.", "jobs[2].").
  void checkKeys(const nlohmann::json& object, const std::string& prefix, const std::vector<std::string>& valid) const;
  // A non-empty string.
  std::string text(const nlohmann::json& value, const std::string& element) const;
  // A non-empty array.
  const nlohmann::json& list(const nlohmann::json& value, const std::string& element) const;
  // An existing regular file, resolved to an absolute path.
  BatchInput file(const nlohmann::json& value, const std::string& element) const;
  // An avatar mesh, or a body-measurement file (.yaml, .yml, .json) whose mannequin can be made: sets job.avatar,
  // job.avatarIsMeasurements and job.avatarMesh (the mesh itself; a mannequin's path is decided when the batch runs).
  void avatar(const nlohmann::json& value, const std::string& element, BatchJob& job) const;
  // Checks that the mannequin of the measurements file, every length times scale, can be made.
  void mannequinOf(const std::filesystem::path& measurements, double scale, const std::string& element) const;
  // The name of a fabric preset (drape --list-fabrics).
  std::string fabric(const nlohmann::json& value, const std::string& element) const;
  // A list of "KEY=VALUE" strings naming known settings. The values are checked by each job when it loads its
  // scene, so that a bad value fails only the jobs that use it.
  SettingOverrides overrides(const nlohmann::json& value, const std::string& element) const;

 private:
  std::string m_name;
  std::filesystem::path m_base;
};

}  // namespace drape::app
