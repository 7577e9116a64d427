#pragma once
// Colours of the renderer: default panel palette, domain colours, the strain ramp and its legend scale.
#include <Eigen/Core>
#include <vector>

namespace drape::render {

// Display (sRGB-encoded) <-> linear RGB, gamma 2.2 as in the shaders.
Eigen::Vector3f displayToLinear(const Eigen::Vector3f& display);

// Linear RGB of panel i when the snapshot gives no colours: 8 muted fabric colours, repeating.
Eigen::Vector3f defaultPanelColor(int panel);
// Linear RGB of preview-solver domain d: hues spaced by the golden angle, so neighbours differ.
Eigen::Vector3f domainColor(int domain);

// Strain ramp stops in display RGB, evenly spaced from the scale minimum to its maximum (blue -> red).
const std::vector<Eigen::Vector3f>& strainRamp();
// Display RGB of the ramp at t in [0, 1] (the shader interpolates the same stops the same way).
Eigen::Vector3f strainRampColor(double t);

// Smallest value of the form {1, 2, 2.5, 5} x 10^k that is >= x (x > 0); for legend scales.
double niceCeil(double x);

}  // namespace drape::render
