#pragma once
// Warnings collected while reading or building something: input that is usable but suspicious
// (stitched edges of different lengths, dropped degenerate faces). Errors are InputError, not warnings.
#include <string>
#include <vector>

namespace drape {

class Diagnostics {
 public:
  void warn(std::string message) { m_warnings.push_back(std::move(message)); }
  const std::vector<std::string>& warnings() const { return m_warnings; }
  void append(const Diagnostics& other) {
    m_warnings.insert(m_warnings.end(), other.m_warnings.begin(), other.m_warnings.end());
  }

 private:
  std::vector<std::string> m_warnings;
};

}  // namespace drape
