#pragma once
// Runs a command line and captures its exit status, stdout and stderr (for tests of the drape executable).
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace drape::test {

struct ProcessResult {
  int exitCode = -1;
  std::string out;
  std::string err;
};

inline std::string readWhole(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// command is passed to /bin/sh; stderr goes to a temporary file next to the test output.
inline ProcessResult runProcess(const std::string& command, const std::filesystem::path& scratchDir) {
  std::filesystem::create_directories(scratchDir);
  static int counter = 0;
  const auto errFile = scratchDir / ("stderr_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".txt");
  ProcessResult r;
  FILE* pipe = ::popen((command + " 2>" + errFile.string()).c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = readWhole(errFile);
  std::filesystem::remove(errFile);
  return r;
}

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

}  // namespace drape::test
