#include "drape/render/palette.h"

#include <algorithm>
#include <cmath>

namespace drape::render {

Eigen::Vector3f displayToLinear(const Eigen::Vector3f& display) {
  return display.array().max(0.0f).pow(2.2f).matrix();
}

Eigen::Vector3f defaultPanelColor(int panel) {
  static const Eigen::Vector3f kPalette[] = {
      {0.36f, 0.52f, 0.74f},  // steel blue
      {0.82f, 0.48f, 0.36f},  // terracotta
      {0.52f, 0.68f, 0.48f},  // sage
      {0.87f, 0.71f, 0.33f},  // mustard
      {0.60f, 0.45f, 0.68f},  // plum
      {0.32f, 0.64f, 0.66f},  // teal
      {0.86f, 0.56f, 0.64f},  // rose
      {0.55f, 0.58f, 0.64f},  // slate
  };
  const int n = static_cast<int>(std::size(kPalette));
  return displayToLinear(kPalette[((panel % n) + n) % n]);
}

Eigen::Vector3f domainColor(int domain) {
  const double hue = std::fmod(std::max(domain, 0) * 0.381966011250105 + 0.08, 1.0) * 6.0;  // golden angle
  const double s = 0.55, v = 0.90;
  const int sector = static_cast<int>(hue) % 6;
  const double f = hue - std::floor(hue);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  Eigen::Vector3f rgb;
  switch (sector) {
    case 0: rgb = {float(v), float(t), float(p)}; break;
    case 1: rgb = {float(q), float(v), float(p)}; break;
    case 2: rgb = {float(p), float(v), float(t)}; break;
    case 3: rgb = {float(p), float(q), float(v)}; break;
    case 4: rgb = {float(t), float(p), float(v)}; break;
    default: rgb = {float(v), float(p), float(q)}; break;
  }
  return displayToLinear(rgb);
}

const std::vector<Eigen::Vector3f>& strainRamp() {
  static const std::vector<Eigen::Vector3f> kRamp = {
      {0.19f, 0.29f, 0.69f},  // 0: deep blue
      {0.22f, 0.55f, 0.86f},  // light blue
      {0.36f, 0.78f, 0.72f},  // teal
      {0.64f, 0.86f, 0.40f},  // green-yellow
      {0.98f, 0.82f, 0.28f},  // amber
      {0.95f, 0.50f, 0.20f},  // orange
      {0.80f, 0.15f, 0.15f},  // max: red
  };
  return kRamp;
}

Eigen::Vector3f strainRampColor(double t) {
  const auto& ramp = strainRamp();
  const double x = std::clamp(t, 0.0, 1.0) * double(ramp.size() - 1);
  const int i = std::min(static_cast<int>(std::floor(x)), static_cast<int>(ramp.size()) - 2);
  const float f = static_cast<float>(x - i);
  return ramp[i] * (1.0f - f) + ramp[i + 1] * f;
}

double niceCeil(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * decade >= x * (1.0 - 1e-9)) return m * decade;
  return 10.0 * decade;
}

}  // namespace drape::render
