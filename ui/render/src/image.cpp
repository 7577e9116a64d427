#include "drape/render/image.h"

#include <algorithm>
#include <cstring>

namespace drape::render {

void Image::fill(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
  for (size_t i = 0; i + 3 < pixels.size(); i += 4) {
    pixels[i] = r, pixels[i + 1] = g, pixels[i + 2] = b, pixels[i + 3] = a;
  }
}

void Image::blit(const Image& src, int x, int y) {
  const int x0 = std::max(0, x), x1 = std::min(width, x + src.width);
  if (x1 <= x0) return;
  for (int row = std::max(0, y); row < std::min(height, y + src.height); ++row)
    std::memcpy(at(x0, row), src.at(x0 - x, row - y), static_cast<size_t>(x1 - x0) * 4);
}

}  // namespace drape::render
