// The avatar's length unit: a body whose height along y is not a human body's gets one warning naming the unit that
// would make it one (avatarHeightWarning), through loadAvatar's diagnostics; an FBX file's UnitScaleFactor is named.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "drape/avatar/avatar_loader.h"
#include "drape/core/input_error.h"
#include "drape/geometry/primitives.h"
#include "scaled_obj.h"
#include "shared_data.h"

namespace drape {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The box [0, 0.4] x [0, 1.7] x [0, 0.3] m (a body's height and girth) as OBJ text in file units of `unitsInMeter`
// per metre, 12 triangles wound outward.
std::string bodyBoxObj(double unitsInMeter) {
  std::ostringstream out;
  for (int i = 0; i < 8; ++i)
    out << "v " << (i & 1 ? 0.4 : 0.0) * unitsInMeter << " " << (i & 2 ? 1.7 : 0.0) * unitsInMeter << " "
        << (i & 4 ? 0.3 : 0.0) * unitsInMeter << "\n";
  out << "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  return out.str();
}

// The same box as an ASCII FBX 7.4 file of six quads whose GlobalSettings declare `unitScaleFactor` (centimetres per
// file unit).
std::string bodyBoxFbx(double unitsInMeter, double unitScaleFactor) {
  std::ostringstream v;
  for (int i = 0; i < 8; ++i)
    v << (i ? "," : "") << (i & 1 ? 0.4 : 0.0) * unitsInMeter << "," << (i & 2 ? 1.7 : 0.0) * unitsInMeter << ","
      << (i & 4 ? 0.3 : 0.0) * unitsInMeter;
  std::ostringstream out;
  out << "; FBX 7.4.0 project file\n"
      << "FBXHeaderExtension:  {\n  FBXHeaderVersion: 1003\n  FBXVersion: 7400\n}\n"
      << "GlobalSettings:  {\n  Version: 1000\n  Properties70:  {\n"
      << "    P: \"UpAxis\", \"int\", \"Integer\", \"\",1\n"
      << "    P: \"UnitScaleFactor\", \"double\", \"Number\", \"\"," << unitScaleFactor << "\n  }\n}\n"
      << "Objects:  {\n  Geometry: 1000, \"Geometry::box\", \"Mesh\" {\n"
      << "    Vertices: *24 {\n      a: " << v.str()
      << "\n    }\n"
      // Quads (0 2 3 1), (4 5 7 6), (0 1 5 4), (2 6 7 3), (0 4 6 2), (1 3 7 5); a polygon's last index is -(i + 1).
      << "    PolygonVertexIndex: *24 {\n      a: 0,2,3,-2,4,5,7,-7,0,1,5,-5,2,6,7,-4,0,4,6,-3,1,3,7,-6\n    }\n"
      << "    GeometryVersion: 124\n  }\n"
      << "  Model: 2000, \"Model::box\", \"Mesh\" {\n    Version: 232\n  }\n}\n"
      << "Connections:  {\n  C: \"OO\",1000,2000\n  C: \"OO\",2000,0\n}\n";
  return out.str();
}

std::filesystem::path writeFile(const std::string& name, const std::string& text) {
  const auto file = test::testOutputDir() / name;
  std::ofstream(file) << text;
  return file;
}

// An OBJ file with every vertex line's coordinates multiplied by `factor`, written next to the test's other files.
std::filesystem::path scaledObj(const std::filesystem::path& original, double factor, const std::string& name) {
  const std::filesystem::path file = writeFile(name, "");
  test::writeScaledObj(original, factor, file);
  return file;
}

std::string unitOption(const char* unit) {
  return std::string("load it with --avatar-units ") + unit + " (scene: \"avatar\": {\"units\": \"" + unit + "\"})";
}

TEST(AvatarUnits, UnitNames) {
  EXPECT_EQ(unitsInMeterFromName("m"), 1.0);
  EXPECT_EQ(unitsInMeterFromName("cm"), 100.0);
  EXPECT_EQ(unitsInMeterFromName("mm"), 1000.0);
  EXPECT_DOUBLE_EQ(unitsInMeterFromName("in") * 0.0254, 1.0);
  try {
    unitsInMeterFromName("inch");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "unknown length unit 'inch' (valid: m, cm, mm, in)");
  }
}

TEST(AvatarUnits, HeightsOfAHumanBodyAreNotWarnedAbout) {
  for (double height : {0.3, 0.9, 1.72, 2.5}) EXPECT_EQ(avatarHeightWarning("b.obj", height, 1.0), "") << height;
  EXPECT_EQ(avatarHeightWarning("b.obj", 1.72, 100.0), "");
}

TEST(AvatarUnits, TheUnitThatGivesAHumanHeightIsNamed) {
  // A 1.72 m body written in centimetres, millimetres and inches, read as metres; and in metres read as millimetres.
  EXPECT_EQ(avatarHeightWarning("b.obj", 172.0, 1.0),
            "b.obj: the avatar is 172.00 m tall; it looks like centimetres: " + unitOption("cm"));
  EXPECT_EQ(avatarHeightWarning("b.obj", 1720.0, 1.0),
            "b.obj: the avatar is 1720.00 m tall; it looks like millimetres: " + unitOption("mm"));
  // 67.7 in: as centimetres 0.68 m would fit too, but 1.72 m is nearer an adult's height.
  EXPECT_TRUE(contains(avatarHeightWarning("b.obj", 1.72 / 0.0254, 1.0), "it looks like inches: " + unitOption("in")));
  EXPECT_EQ(avatarHeightWarning("b.obj", 0.00172, 1000.0),
            "b.obj: the avatar is 0.00172 m tall; it looks like metres: " + unitOption("m"));
  // Read as centimetres, a body in millimetres is 10 times too tall.
  EXPECT_TRUE(contains(avatarHeightWarning("b.obj", 17.2, 100.0), "it looks like millimetres"));
}

TEST(AvatarUnits, NoUnitFitsSaysTheHeightIsOutsideTheRange) {
  // 10 m: 0.1 m as centimetres, 0.254 m as inches, both too short for a body.
  const std::string said = avatarHeightWarning("b.obj", 10.0, 1.0);
  EXPECT_EQ(said,
            "b.obj: the avatar is 10.00 m tall, outside the range of a human body (0.3-2.5 m); if it is a body, give "
            "its file's length unit with --avatar-units m|cm|mm|in (scene: \"avatar\": {\"units\": ...})");
  EXPECT_TRUE(contains(avatarHeightWarning("b.obj", 0.0, 1.0), "0 m tall, outside the range"));
}

TEST(AvatarUnits, TheDeclaredUnitIsNamedAndWinsWhenItFits) {
  const DeclaredUnit cm{100.0, "FBX UnitScaleFactor 1"};
  EXPECT_EQ(avatarHeightWarning("b.fbx", 172.0, 1.0, cm),
            "b.fbx: the avatar is 172.00 m tall (the file declares centimetres: FBX UnitScaleFactor 1); it looks like "
            "centimetres: " +
                unitOption("cm"));
  // 67.7 units: inches fit best, but the file says centimetres (0.68 m), which fits too.
  EXPECT_TRUE(contains(avatarHeightWarning("b.fbx", 1.72 / 0.0254, 1.0, cm), "it looks like centimetres"));
  // A declared unit that does not fit is named, and the guess goes on.
  EXPECT_TRUE(contains(avatarHeightWarning("b.fbx", 1720.0, 1.0, cm),
                       "(the file declares centimetres: FBX UnitScaleFactor 1); it looks like millimetres"));
  const DeclaredUnit feet{100.0 / 30.48, "FBX UnitScaleFactor 30.48"};
  EXPECT_TRUE(contains(avatarHeightWarning("b.fbx", 172.0, 1.0, feet),
                       "(the file declares 1 unit = 30.48 cm: FBX UnitScaleFactor 30.48)"));
}

TEST(AvatarUnits, LoadAvatarWarnsAboutABodyInCentimetresReadAsMetres) {
  const auto cm = writeFile("avatar_body_box_cm.obj", bodyBoxObj(100.0));
  Diagnostics diagnostics;
  const TriangleMesh mesh = loadAvatar(cm, 1.0, &diagnostics);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_EQ(diagnostics.warnings()[0],
            cm.string() + ": the avatar is 170.00 m tall; it looks like centimetres: " + unitOption("cm"));
  EXPECT_NEAR(boundsOf(mesh.vertices).size().y(), 170.0, 1e-9);  // the warning does not change what is loaded

  // Loaded as centimetres, or the same box written in metres: 1.7 m, nothing to say.
  Diagnostics asCentimetres;
  EXPECT_NEAR(boundsOf(loadAvatar(cm, unitsInMeterFromName("cm"), &asCentimetres).vertices).size().y(), 1.7, 1e-9);
  EXPECT_TRUE(asCentimetres.warnings().empty()) << asCentimetres.warnings()[0];
  Diagnostics metres;
  loadAvatar(writeFile("avatar_body_box_m.obj", bodyBoxObj(1.0)), 1.0, &metres);
  EXPECT_TRUE(metres.warnings().empty()) << metres.warnings()[0];
}

// assimp passes an FBX file's UnitScaleFactor on without applying it: the warning names what the file declares.
TEST(AvatarUnits, FbxUnitScaleFactorIsNamed) {
  // Centimetres, declared as such (UnitScaleFactor 1).
  const auto declaredCm = writeFile("avatar_body_box_cm.fbx", bodyBoxFbx(100.0, 1.0));
  Diagnostics diagnostics;
  const TriangleMesh mesh = loadAvatar(declaredCm, 1.0, &diagnostics);
  EXPECT_NEAR(boundsOf(mesh.vertices).size().y(), 170.0, 1e-4);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_EQ(diagnostics.warnings()[0], declaredCm.string() +
                                           ": the avatar is 170.00 m tall (the file declares centimetres: FBX "
                                           "UnitScaleFactor 1); it looks like centimetres: " +
                                           unitOption("cm"));
  Diagnostics asCentimetres;
  loadAvatar(declaredCm, 100.0, &asCentimetres);
  EXPECT_TRUE(asCentimetres.warnings().empty()) << asCentimetres.warnings()[0];

  // Centimetres declared as metres (UnitScaleFactor 100): the declaration is named, the guess still centimetres.
  const auto declaredM = writeFile("avatar_body_box_declared_m.fbx", bodyBoxFbx(100.0, 100.0));
  Diagnostics wrong;
  loadAvatar(declaredM, 1.0, &wrong);
  ASSERT_EQ(wrong.warnings().size(), 1u);
  EXPECT_TRUE(
      contains(wrong.warnings()[0], "(the file declares metres: FBX UnitScaleFactor 100); it looks like centimetres"))
      << wrong.warnings()[0];
}

// GarmentCode's mean body is in metres (1.72 m tall): no warning; the same file with its coordinates times 100 is
// taken for centimetres.
TEST(AvatarUnits, GarmentCodeMeanBodyInMetresAndInCentimetres) {
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  Diagnostics metres;
  loadAvatar(body, 1.0, &metres);
  EXPECT_TRUE(metres.warnings().empty()) << metres.warnings()[0];

  const auto cm = scaledObj(body, 100.0, "mean_all_cm.obj");
  Diagnostics read;
  const TriangleMesh mesh = loadAvatar(cm, 1.0, &read);
  ASSERT_EQ(read.warnings().size(), 1u);
  EXPECT_TRUE(contains(read.warnings()[0], "it looks like centimetres: " + unitOption("cm"))) << read.warnings()[0];
  char tall[64];
  std::snprintf(tall, sizeof tall, "the avatar is %.2f m tall", boundsOf(mesh.vertices).size().y());
  EXPECT_TRUE(contains(read.warnings()[0], tall)) << read.warnings()[0];
  Diagnostics asCentimetres;
  loadAvatar(cm, 100.0, &asCentimetres);
  EXPECT_TRUE(asCentimetres.warnings().empty()) << asCentimetres.warnings()[0];
}

}  // namespace
}  // namespace drape
