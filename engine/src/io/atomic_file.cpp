#include "drape/io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <random>
#include <system_error>

#include "drape/core/input_error.h"

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <unistd.h>
#define DRAPE_HAVE_FSYNC 1
#endif

namespace drape {
namespace {

// ".<name>.tmp-<pid>-<counter>-<random>" beside the target: hidden, and unique across threads and processes.
std::filesystem::path temporaryPathFor(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  static thread_local std::mt19937_64 random(
      std::random_device{}() ^ static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()));
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "." + string.
  std::string name = ".";
  name += target.filename().string();
  name += ".tmp-";
#ifdef DRAPE_HAVE_FSYNC
  name += std::to_string(::getpid()) + "-";
#endif
  name += std::to_string(counter++) + "-" + std::to_string(random() % 1000000007ULL);
  return target.parent_path() / name;
}

// Flushes the file's content to disk so that the rename never publishes a file whose data is not yet stored.
void syncToDisk(const std::filesystem::path& path) {
#ifdef DRAPE_HAVE_FSYNC
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
#else
  (void)path;
#endif
}

[[noreturn]] void failWrite(const std::filesystem::path& target, const std::string& reason) {
  throw InputError("cannot write " + target.string() + ": " + reason);
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path& tempPath)>& write) {
  if (target.filename().empty()) failWrite(target, "not a file name");
  std::error_code ec;
  const std::filesystem::path directory = target.parent_path().empty() ? "." : target.parent_path();
  if (!std::filesystem::is_directory(directory, ec)) failWrite(target, "directory does not exist");
  if (std::filesystem::is_directory(target, ec)) failWrite(target, "is a directory");

  const std::filesystem::path temp = temporaryPathFor(target);
  auto removeTemp = [&] {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
  };
  try {
    write(temp);
  } catch (const std::exception& e) {
    removeTemp();
    failWrite(target, e.what());
  }
  if (!std::filesystem::is_regular_file(temp, ec)) {
    removeTemp();
    failWrite(target, "nothing was written");
  }
  syncToDisk(temp);
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    removeTemp();
    failWrite(target, ec.message());
  }
}

void writeFileAtomically(const std::filesystem::path& target, const std::string& bytes) {
  writeFileAtomically(target, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(std::strerror(errno));
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error("write failed (disk full?)");
  });
}

}  // namespace drape
