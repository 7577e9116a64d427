// writeFileAtomically: content replaced in one step, old file kept on every failure, no temporary left over.
#include "drape/io/atomic_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "drape/core/input_error.h"
#include "shared_data.h"

namespace drape {
namespace {

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> fileNames(const std::filesystem::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

std::filesystem::path freshDir(const std::string& name) {
  const auto dir = test::testOutputDir() / name;
  std::error_code ignored;  // a previous failed run may have left it read-only
  std::filesystem::permissions(dir, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ignored);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AtomicFileTest, WritesAndReplacesContent) {
  const auto dir = freshDir("atomic_replace");
  const auto file = dir / "a.txt";
  writeFileAtomically(file, std::string("first"));
  EXPECT_EQ(readText(file), "first");
  writeFileAtomically(file, std::string("second, longer\0with a zero byte", 31));
  EXPECT_EQ(readText(file), std::string("second, longer\0with a zero byte", 31));
  writeFileAtomically(file, std::string());
  EXPECT_EQ(readText(file), "");
  EXPECT_EQ(fileNames(dir), std::vector<std::string>{"a.txt"});  // no temporary left behind
}

TEST(AtomicFileTest, CallbackWritesToATemporaryBesideTheTarget) {
  const auto dir = freshDir("atomic_callback");
  const auto file = dir / "b.bin";
  std::filesystem::path seen;
  writeFileAtomically(file, [&](const std::filesystem::path& temp) {
    seen = temp;
    EXPECT_EQ(temp.parent_path(), dir);
    EXPECT_NE(temp.filename(), file.filename());
    EXPECT_FALSE(std::filesystem::exists(file));  // the target appears only at the end
    std::ofstream(temp) << "payload";
  });
  EXPECT_EQ(readText(file), "payload");
  EXPECT_FALSE(std::filesystem::exists(seen));
  // Two writes get different temporary names.
  std::filesystem::path second;
  writeFileAtomically(file, [&](const std::filesystem::path& temp) {
    second = temp;
    std::ofstream(temp) << "again";
  });
  EXPECT_NE(second, seen);
  EXPECT_EQ(fileNames(dir), std::vector<std::string>{"b.bin"});
}

TEST(AtomicFileTest, FailingWriterKeepsOldFileAndRemovesTemporary) {
  const auto dir = freshDir("atomic_failing_writer");
  const auto file = dir / "c.obj";
  writeFileAtomically(file, std::string("old content"));
  const std::string message = errorOf([&] {
    writeFileAtomically(file, [](const std::filesystem::path& temp) {
      std::ofstream(temp) << "half of the new cont";
      throw std::runtime_error("disk on fire");
    });
  });
  EXPECT_EQ(message, "cannot write " + file.string() + ": disk on fire");
  EXPECT_EQ(readText(file), "old content");
  EXPECT_EQ(fileNames(dir), std::vector<std::string>{"c.obj"});
  // A writer that produces nothing is a failure too.
  EXPECT_EQ(errorOf([&] { writeFileAtomically(file, [](const std::filesystem::path&) {}); }),
            "cannot write " + file.string() + ": nothing was written");
  EXPECT_EQ(readText(file), "old content");
}

TEST(AtomicFileTest, UnwritableDirectoryKeepsOldFile) {
  const auto dir = freshDir("atomic_read_only");
  const auto file = dir / "d.txt";
  writeFileAtomically(file, std::string("old content"));
  namespace fs = std::filesystem;
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  const bool enforced = !std::ofstream(dir / "probe");  // root ignores permission bits
  if (!enforced) {
    fs::remove(dir / "probe");
    fs::permissions(dir, fs::perms::owner_all);
    GTEST_SKIP() << "running with privileges that ignore directory permissions";
  }
  const std::string message = errorOf([&] { writeFileAtomically(file, std::string("new content")); });
  fs::permissions(dir, fs::perms::owner_all);
  EXPECT_EQ(message.rfind("cannot write " + file.string() + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("ermission denied"), std::string::npos) << message;
  EXPECT_EQ(readText(file), "old content");
  EXPECT_EQ(fileNames(dir), std::vector<std::string>{"d.txt"});
}

TEST(AtomicFileTest, ImpossibleTargetsAreNamed) {
  const auto dir = freshDir("atomic_impossible");
  writeFileAtomically(dir / "plain", std::string("x"));
  // Parent is a regular file: fails whatever the privileges.
  const auto underFile = dir / "plain" / "e.txt";
  EXPECT_EQ(errorOf([&] { writeFileAtomically(underFile, std::string("y")); }),
            "cannot write " + underFile.string() + ": directory does not exist");
  // Target is a directory: it is left alone.
  std::filesystem::create_directory(dir / "sub");
  EXPECT_EQ(errorOf([&] { writeFileAtomically(dir / "sub", std::string("y")); }),
            "cannot write " + (dir / "sub").string() + ": is a directory");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "sub"));
  EXPECT_EQ(fileNames(dir), (std::vector<std::string>{"plain", "sub"}));
}

TEST(AtomicFileTest, RenameFailureRemovesTemporary) {
  // A target that becomes a non-empty directory after the checks: rename fails, temp must go.
  const auto dir = freshDir("atomic_rename_fails");
  const auto target = dir / "f";
  const std::string message = errorOf([&] {
    writeFileAtomically(target, [&](const std::filesystem::path& temp) {
      std::ofstream(temp) << "content";
      std::filesystem::create_directories(target / "inside");
    });
  });
  EXPECT_EQ(message.rfind("cannot write " + target.string() + ": ", 0), 0u) << message;
  EXPECT_TRUE(std::filesystem::is_directory(target / "inside"));
  EXPECT_EQ(fileNames(dir), std::vector<std::string>{"f"});
}

}  // namespace
}  // namespace drape
