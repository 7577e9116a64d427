#pragma once
// One offscreen renderer shared by the tests of a suite (creating an EGL context costs ~0.1 s).
#include <gtest/gtest.h>

#include <memory>

#include "drape/render/headless.h"

namespace drape::test {

class RenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!s_renderer) s_renderer = std::make_unique<render::OffscreenRenderer>();
  }
  static void TearDownTestSuite() { s_renderer.reset(); }
  static render::OffscreenRenderer& renderer() { return *s_renderer; }

  static render::RenderOptions smallOptions(render::DisplayMode mode = render::DisplayMode::Shaded) {
    render::RenderOptions options;
    options.width = options.height = 256;
    options.mode = mode;
    return options;
  }

 private:
  static inline std::unique_ptr<render::OffscreenRenderer> s_renderer;
};

}  // namespace drape::test
