#pragma once
// Body measurements in GarmentCode's layout (a `body:` map of centimetre values, as GarmentCode's
// assets/bodies/mean_all.yaml), read from YAML or JSON and held here in metres.
#include <filesystem>
#include <optional>

namespace drape {

// Lengths in metres, angles in degrees. Names follow GarmentCode's keys (in brackets).
struct BodyMeasurements {
  // Required.
  double height = 0.0;         // [height] floor to the top of the head
  double bust = 0.0;           // [bust] girth over the bust points
  double underbust = 0.0;      // [underbust] girth just below the breasts
  double waist = 0.0;          // [waist] girth at the natural waist
  double hips = 0.0;           // [hips] girth at the fullest part of the buttocks
  double shoulderWidth = 0.0;  // [shoulder_w] distance between the two shoulder points
  double neckWidth = 0.0;      // [neck_w] width of the neck at its base (side neck point to side neck point)
  double armLength = 0.0;      // [arm_length] shoulder point to wrist
  double wrist = 0.0;          // [wrist] wrist girth
  double thigh = 0.0;          // [leg_circ] girth of one thigh just below the crotch
  double armPoseAngle = 0.0;   // [arm_pose_angle] degrees below the horizontal: 0 = T-pose, ~45 = A-pose
  // Optional vertical landmarks (GarmentCode: waist level = height - head_l - waist_line); when absent the
  // mannequin takes them as fixed fractions of this body's height (docs/MANNEQUIN.md).
  std::optional<double> headLength;     // [head_l] top of the head to the base of the neck
  std::optional<double> waistLine;      // [waist_line] base of the neck down to the waist
  std::optional<double> hipsLine;       // [hips_line] waist down to the hip line
  std::optional<double> crotchHipDiff;  // [crotch_hip_diff] hip line down to the crotch
  std::optional<double> vertBustLine;   // [vert_bust_line] base of the neck down to the bust line
};

// Reads a GarmentCode body-measurement file (.yaml/.yml or .json; values in cm under a top-level `body` map,
// or at the top level). Missing required keys, non-numeric or non-positive values (arm_pose_angle: outside
// [0, 90)) raise InputError naming the file and the key.
BodyMeasurements loadBodyMeasurements(const std::filesystem::path& file);

// The body of a uniformly graded size: every length times scale, the arm pose angle kept.
BodyMeasurements scaledBodyMeasurements(const BodyMeasurements& body, double scale);

}  // namespace drape
