#pragma once
// Tolerant image comparison for screenshot regression tests.
#include <string>

#include "drape/render/image.h"

namespace drape::render {

struct CompareTolerance {
  int channelTolerance = 8;          // a pixel matches when every channel differs by at most this (0-255)
  double minMatchingFraction = 0.999;  // the images match when at least this fraction of pixels match
};

struct CompareResult {
  bool sameSize = false;
  long long pixelCount = 0;
  long long mismatchedPixels = 0;  // pixels with some channel beyond channelTolerance
  int maxChannelDifference = 0;    // 0-255
  double matchingFraction = 0.0;   // 1 - mismatched / count (0 when the sizes differ)
  bool matches = false;
  Image diff;  // same size as the inputs: mismatches in red over a faded copy of the expected image

  std::string summary() const;  // "12 of 65536 pixels differ by more than 8/255 (max 143/255)"
};

CompareResult compareImages(const Image& expected, const Image& actual, const CompareTolerance& tolerance = {});

}  // namespace drape::render
