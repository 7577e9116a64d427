// PNG round trip, atomic write, and errors naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "drape/core/input_error.h"
#include "drape/render/png_io.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(PngIoTest, RoundTripKeepsEveryPixel) {
  render::Image image(37, 19);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t* p = image.at(x, y);
      p[0] = std::uint8_t(x * 7), p[1] = std::uint8_t(y * 13), p[2] = std::uint8_t(x * y), p[3] = std::uint8_t(255 - x);
    }
  const auto path = testOutputDir() / "png_roundtrip.png";
  render::writePng(path, image);
  const render::Image back = render::readPng(path);
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 19);
  EXPECT_EQ(back.pixels, image.pixels);
  // no temporary file left behind
  for (const auto& entry : std::filesystem::directory_iterator(testOutputDir()))
    EXPECT_EQ(entry.path().filename().string().find("png_roundtrip.png."), std::string::npos) << entry.path();
}

TEST(PngIoTest, ReadingAMissingOrBrokenFileNamesIt) {
  const auto missing = testOutputDir() / "does_not_exist.png";
  try {
    render::readPng(missing);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.png"), std::string::npos) << e.what();
  }
  const auto broken = testOutputDir() / "broken.png";
  std::ofstream(broken) << "not a png";
  try {
    render::readPng(broken);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.png"), std::string::npos) << e.what();
  }
}

TEST(PngIoTest, WritingIntoAMissingDirectoryFailsClearly) {
  const auto target = testOutputDir() / "no_such_dir" / "out.png";
  EXPECT_THROW(render::writePng(target, render::Image(4, 4)), InputError);
  EXPECT_FALSE(std::filesystem::exists(target));
}

}  // namespace
}  // namespace drape::test
