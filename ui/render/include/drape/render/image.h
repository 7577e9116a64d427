#pragma once
// An 8-bit RGBA image, rows top to bottom, 4 bytes per pixel (straight alpha).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace drape::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4 bytes, row-major from the top-left corner

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 4, 0) {}

  bool empty() const { return width <= 0 || height <= 0; }
  std::uint8_t* at(int x, int y) { return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  const std::uint8_t* at(int x, int y) const { return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4; }
  void fill(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255);
  // Copies src with its top-left corner at (x, y), clipped to this image.
  void blit(const Image& src, int x, int y);
};

}  // namespace drape::render
