// garmentTransfer: positions of one meshing of a pattern carried to another. The placed garment is an affine image
// of the pattern coordinates per panel, so carrying a coarse placed garment must give the fine placed garment
// (exactly where the outlines are straight); a smooth deformation is carried with an error of second order in the
// coarse edge length.
#include "drape/garment/garment_transfer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "drape/garment/garment_builder.h"
#include "drape/pattern/pattern_loader.h"
#include "shared_data.h"

namespace drape::test {
namespace {

// A trapezoid (the front) and a triangle (the back) with straight edges, in cm, placed apart and rotated, one seam.
Pattern straightPanels() {
  Pattern pattern;
  pattern.source = "test.json";
  pattern.unitsInMeter = 100.0;
  Panel front;
  front.name = "front";
  front.vertices = {{0, 0}, {60, 0}, {45, 50}, {10, 50}};
  for (int e = 0; e < 4; ++e) front.edges.push_back(PanelEdge{e, (e + 1) % 4, {}, ""});
  front.translation = {0, 0, 10};
  Panel back;
  back.name = "back";
  back.vertices = {{0, 0}, {50, 0}, {20, 40}};
  for (int e = 0; e < 3; ++e) back.edges.push_back(PanelEdge{e, (e + 1) % 3, {}, ""});
  back.translation = {60, 0, -10};
  back.rotationDeg = {10, 180, 5};
  pattern.panels = {front, back};
  pattern.stitches.push_back(Stitch{{0, 1}, {1, 2}, false});
  return pattern;
}

Garment meshed(const Pattern& pattern, double edge) {
  MeshingOptions options;
  options.targetEdgeLength = edge;
  return buildGarment(pattern, options);
}

// A smooth bend: the garment wrapped around the y axis (radius 0.3 m).
Eigen::MatrixX3d bent(const Eigen::MatrixX3d& x) {
  Eigen::MatrixX3d out(x.rows(), 3);
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const double r = 0.3 + x(v, 2), a = x(v, 0) / 0.3;
    out.row(v) << r * std::sin(a), x(v, 1) + 0.1 * x(v, 0) * x(v, 0), r * std::cos(a);
  }
  return out;
}

}  // namespace

TEST(GarmentTransfer, WeightsAreAPartitionOfUnity) {
  const Pattern pattern = straightPanels();
  const Garment coarse = meshed(pattern, 0.1), fine = meshed(pattern, 0.02);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> t = garmentTransfer(coarse, fine);
  ASSERT_EQ(t.rows(), fine.vertexCount());
  ASSERT_EQ(t.cols(), coarse.vertexCount());
  for (int v = 0; v < fine.vertexCount(); ++v) {
    double sum = 0.0;
    int count = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(t, v); it; ++it) {
      EXPECT_GE(it.value(), 0.0);
      EXPECT_EQ(coarse.vertexPanel[it.col()], fine.vertexPanel[v]) << "vertex " << v << " takes another panel";
      sum += it.value();
      ++count;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "vertex " << v;
    EXPECT_LE(count, 3);
  }
}

TEST(GarmentTransfer, CarriesThePlacedGarmentExactlyOnStraightPanels) {
  const Pattern pattern = straightPanels();
  const Garment coarse = meshed(pattern, 0.1), fine = meshed(pattern, 0.02);
  const Eigen::MatrixX3d carried = garmentTransfer(coarse, fine) * coarse.positions;
  EXPECT_LT((carried - fine.positions).rowwise().norm().maxCoeff(), 1e-12);
  // A garment carried to itself is unchanged.
  const Eigen::MatrixX3d same = garmentTransfer(fine, fine) * fine.positions;
  EXPECT_LT((same - fine.positions).rowwise().norm().maxCoeff(), 1e-12);
}

TEST(GarmentTransfer, SmoothDeformationErrorIsSecondOrderInTheCoarseEdge) {
  const Pattern pattern = straightPanels();
  const Garment fine = meshed(pattern, 0.01);
  const Eigen::MatrixX3d exact = bent(fine.positions);
  double previous = 0.0;
  for (const double edge : {0.16, 0.08, 0.04}) {
    const Garment coarse = meshed(pattern, edge);
    const double error =
        (garmentTransfer(coarse, fine) * bent(coarse.positions) - exact).rowwise().norm().maxCoeff();
    if (previous > 0.0) {
      // Halving the edge divides a linear interpolation's error by ~4 (unstructured meshes: at least 2.5).
      EXPECT_LT(error, previous / 2.5) << "edge " << edge;
    }
    previous = error;
  }
  EXPECT_LT(previous, 2e-3);
}

TEST(GarmentTransfer, LibraryShirtCarriedWithinTheChordOfItsCurves) {
  const Pattern pattern = loadPattern(assetsDir() / "patterns" / "tshirt.json");
  const Garment coarse = meshed(pattern, 0.02), fine = meshed(pattern, 0.01);
  const Eigen::VectorXd error =
      (garmentTransfer(coarse, fine) * coarse.positions - fine.positions).rowwise().norm();
  // Vertices inside the coarse outline land exactly; those on curved edges between coarse chords by their sag.
  int exact = 0;
  for (Eigen::Index v = 0; v < error.size(); ++v) exact += error[v] < 1e-9;
  EXPECT_GT(exact, 0.9 * fine.vertexCount());
  EXPECT_LT(error.maxCoeff(), 2e-3);
}

TEST(GarmentTransfer, RejectsAnotherPattern) {
  const Garment a = meshed(straightPanels(), 0.1);
  Pattern other = straightPanels();
  other.panels[1].name = "sleeve";
  const Garment b = meshed(other, 0.1);
  EXPECT_THROW(garmentTransfer(a, b), std::invalid_argument);
}

}  // namespace drape::test
