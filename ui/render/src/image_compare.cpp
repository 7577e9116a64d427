#include "drape/render/image_compare.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace drape::render {

std::string CompareResult::summary() const {
  std::ostringstream s;
  if (!sameSize) return "image sizes differ";
  s << mismatchedPixels << " of " << pixelCount << " pixels differ beyond tolerance (matching "
    << 100.0 * matchingFraction << "%, max channel difference " << maxChannelDifference << "/255)";
  return s.str();
}

CompareResult compareImages(const Image& expected, const Image& actual, const CompareTolerance& tolerance) {
  CompareResult r;
  r.sameSize = expected.width == actual.width && expected.height == actual.height && !expected.empty();
  if (!r.sameSize) return r;
  r.pixelCount = static_cast<long long>(expected.width) * expected.height;
  r.diff = Image(expected.width, expected.height);
  for (int y = 0; y < expected.height; ++y)
    for (int x = 0; x < expected.width; ++x) {
      const std::uint8_t* a = expected.at(x, y);
      const std::uint8_t* b = actual.at(x, y);
      int d = 0;
      for (int c = 0; c < 4; ++c) d = std::max(d, std::abs(int(a[c]) - int(b[c])));
      r.maxChannelDifference = std::max(r.maxChannelDifference, d);
      std::uint8_t* out = r.diff.at(x, y);
      if (d > tolerance.channelTolerance) {
        ++r.mismatchedPixels;
        out[0] = 255, out[1] = 0, out[2] = 0;
      } else {
        // faded grey copy of the expected image, so the mismatches can be located
        const int grey = (a[0] + a[1] + a[2]) / 3;
        out[0] = out[1] = out[2] = static_cast<std::uint8_t>(160 + grey * 95 / 255);
      }
      out[3] = 255;
    }
  r.matchingFraction = 1.0 - double(r.mismatchedPixels) / double(r.pixelCount);
  r.matches = r.matchingFraction >= tolerance.minMatchingFraction;
  return r;
}

}  // namespace drape::render
