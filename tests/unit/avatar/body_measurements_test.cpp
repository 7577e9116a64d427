#include "drape/avatar/body_measurements.h"

#include <gtest/gtest.h>

#include <fstream>

#include "drape/core/input_error.h"
#include "shared_data.h"

namespace drape {
namespace {

std::filesystem::path writeFile(const std::string& name, const std::string& text) {
  const auto dir = test::testOutputDir() / "body_measurements";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

const char* kComplete =
    "height: 170\nbust: 90\nunderbust: 75\nwaist: 70\nhips: 95\nshoulder_w: 36\nneck_w: 18\narm_length: 55\n"
    "wrist: 16\nleg_circ: 55\narm_pose_angle: 30\n";

std::string errorOf(const std::filesystem::path& file) {
  try {
    loadBodyMeasurements(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(BodyMeasurements, ReadsGarmentCodeMeanBody) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.yaml");
  const BodyMeasurements m = loadBodyMeasurements(file);
  EXPECT_NEAR(m.height, 1.7199, 1e-6);
  EXPECT_NEAR(m.bust, 0.998407, 1e-9);
  EXPECT_NEAR(m.underbust, 0.862455, 1e-9);
  EXPECT_NEAR(m.waist, 0.843338, 1e-9);
  EXPECT_NEAR(m.hips, 1.03478, 1e-9);
  EXPECT_NEAR(m.shoulderWidth, 0.364568, 1e-9);
  EXPECT_NEAR(m.neckWidth, 0.189328, 1e-9);
  EXPECT_NEAR(m.armLength, 0.539697, 1e-9);
  EXPECT_NEAR(m.wrist, 0.165945, 1e-9);
  EXPECT_NEAR(m.thigh, 0.602039, 1e-9);
  EXPECT_NEAR(m.armPoseAngle, 45.483, 1e-9);
  ASSERT_TRUE(m.headLength && m.waistLine && m.hipsLine && m.crotchHipDiff && m.vertBustLine);
  EXPECT_NEAR(*m.headLength, 0.263262, 1e-9);
  EXPECT_NEAR(*m.crotchHipDiff, 0.0881363, 1e-9);
}

TEST(BodyMeasurements, YamlWithoutBodyMapAndJsonAgree) {
  const BodyMeasurements flat = loadBodyMeasurements(writeFile("flat.yaml", kComplete));
  const BodyMeasurements json = loadBodyMeasurements(
      writeFile("body.json",
                R"({"body": {"height": 170, "bust": 90, "underbust": 75, "waist": 70, "hips": 95, "shoulder_w": 36,
          "neck_w": 18, "arm_length": 55, "wrist": 16, "leg_circ": 55, "arm_pose_angle": 30}})"));
  EXPECT_DOUBLE_EQ(flat.height, 1.70);
  EXPECT_DOUBLE_EQ(json.height, 1.70);
  EXPECT_DOUBLE_EQ(flat.thigh, json.thigh);
  EXPECT_DOUBLE_EQ(json.armPoseAngle, 30.0);
  EXPECT_FALSE(json.headLength.has_value());
}

TEST(BodyMeasurements, MissingKeyNamesFileAndKey) {
  std::string text = kComplete;
  text.erase(text.find("waist: 70\n"), 10);
  const std::string message = errorOf(writeFile("no_waist.yaml", text));
  EXPECT_NE(message.find("no_waist.yaml"), std::string::npos) << message;
  EXPECT_NE(message.find("'waist'"), std::string::npos) << message;
}

TEST(BodyMeasurements, NonPositiveOrBadValuesAreErrors) {
  std::string negative = kComplete;
  negative.replace(negative.find("hips: 95"), 8, "hips: -5");
  const std::string m1 = errorOf(writeFile("negative.yaml", negative));
  EXPECT_NE(m1.find("negative.yaml: key 'hips'"), std::string::npos) << m1;

  std::string word = kComplete;
  word.replace(word.find("wrist: 16"), 9, "wrist: thin");
  const std::string m2 = errorOf(writeFile("word.yaml", word));
  EXPECT_NE(m2.find("'wrist'"), std::string::npos) << m2;

  std::string angle = kComplete;
  angle.replace(angle.find("arm_pose_angle: 30"), 18, "arm_pose_angle: 120");
  const std::string m3 = errorOf(writeFile("angle.yaml", angle));
  EXPECT_NE(m3.find("'arm_pose_angle'"), std::string::npos) << m3;

  EXPECT_NE(errorOf(writeFile("broken.json", "{\"body\": {")).find("broken.json"), std::string::npos);
  EXPECT_NE(errorOf(test::testOutputDir() / "does_not_exist.yaml").find("does_not_exist.yaml"), std::string::npos);
}

TEST(BodyMeasurements, ShippedAvatarsAreComplete) {
  for (const char* name : {"female.yaml", "male.yaml"}) {
    const BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / name);
    EXPECT_GT(m.height, 1.5) << name;
    EXPECT_LT(m.height, 2.0) << name;
    EXPECT_TRUE(m.headLength && m.waistLine && m.hipsLine && m.crotchHipDiff && m.vertBustLine) << name;
  }
}

}  // namespace
}  // namespace drape
