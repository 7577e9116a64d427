// The membrane's and the hinge bending's gradient passes run several stencils at a time (every quantity an array
// over the lanes, stvk_membrane.cpp and hinge_bending.cpp). Here they are checked against the per-stencil
// functions they replace, summed stencil by stencil: the gradients with the folded dissipations, and the records the
// passes leave for the next step (the deformation gradients, the zero-sum angle gradients with their offsets, the
// elastic step-start gradient). Stencil counts that are not multiples of the lane count, wings inside the fade band
// and a collapsed wing are included.
#include <gtest/gtest.h>

#include <vector>

#include "drape/newton/hinge_bending.h"
#include "drape/newton/strain_rate_damping.h"
#include "drape/newton/stvk_membrane.h"
#include "newton_test_cloths.h"

using namespace drape::newton;

namespace {

// A perturbed 11 x 11 grid (200 triangles, 280 hinges: neither a multiple of 8 when one triangle row is cut) with
// the start positions xn and the end positions x of a step.
struct Step {
  drape::model::ClothModel model;
  Eigen::VectorXd xn, x, v;
};

Step perturbedStep(unsigned seed) {
  Step s;
  s.model = gridCloth(11, 0.02, 0.3, seed);
  s.model.triangles.conservativeResize(s.model.triangles.rows() - 3, 3);  // 197 triangles
  s.xn = s.model.positions;
  s.x = gridCloth(11, 0.02, 0.3, seed + 1).positions;
  s.v = Eigen::VectorXd::Zero(s.x.size());
  return s;
}

double relativeError(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / b.norm();
}

}  // namespace

TEST(NewtonBatchedGradients, MembranePassEqualsTheSumOfItsTriangles) {
  for (bool parallel : {false, true}) {
    Step s = perturbedStep(3);
    StvkMembrane membrane(s.model);
    MembraneDissipation stretch(membrane.elements(), 1e-2);
    membrane.foldDissipation(&stretch);
    stretch.setFolded(true);
    membrane.setRecordDeformationGradients(true);
    membrane.setRecordStepStartGradient(true);
    AssemblyOptions options;
    options.parallel = parallel;
    const StepContext ctx{&s.xn, &s.v, 2e-3, 0.0, 0.7, options};  // stiffness ramp at 0.7
    membrane.beginStep(ctx);
    stretch.beginStep(ctx);

    Eigen::VectorXd elastic = Eigen::VectorXd::Zero(s.x.size()), both = elastic;
    const std::vector<MembraneElement>& elements = membrane.elements();
    ASSERT_EQ(elements.size() % 8, 5u);
    for (size_t t = 0; t < elements.size(); ++t) {
      Eigen::Matrix<double, 9, 1> ge;
      membrane.elementDerivatives(elements[t], s.x, &ge);
      const Eigen::Matrix<double, 9, 1> gd = stretch.stencilGradient(static_cast<int>(t), s.x);
      for (int k = 0; k < 3; ++k) {
        elastic.segment<3>(3 * elements[t].v[k]) += ge.segment<3>(3 * k);
        both.segment<3>(3 * elements[t].v[k]) += ge.segment<3>(3 * k) + gd.segment<3>(3 * k);
      }
    }
    ASSERT_GT(relativeError(elastic, both), 1e-3);  // the dissipation is not negligible here

    Eigen::VectorXd g = Eigen::VectorXd::Zero(s.x.size());
    membrane.addGuessGradient(s.x, g);
    EXPECT_LT(relativeError(g, both), 1e-13) << "parallel " << parallel;
    g.setZero();
    membrane.addGradient(s.x, g);
    EXPECT_LT(relativeError(g, both), 1e-13) << "parallel " << parallel;

    // What the recording pass left: the elastic share (the step-start gradient) and every triangle's F.
    Eigen::VectorXd recorded = Eigen::VectorXd::Zero(s.x.size());
    ASSERT_TRUE(membrane.addRecordedStepStartGradient(s.x, recorded));
    EXPECT_LT(relativeError(recorded, elastic), 1e-13);
    std::vector<Eigen::Matrix<double, 3, 2>> f;
    ASSERT_TRUE(membrane.takeRecordedDeformationGradients(s.x, f));
    ASSERT_EQ(f.size(), elements.size());
    for (size_t t = 0; t < elements.size(); ++t)
      EXPECT_LT((f[t] - deformationGradient(elements[t], s.x)).norm(), 1e-14) << "triangle " << t;
  }
}

TEST(NewtonBatchedGradients, BendingPassEqualsTheSumOfItsHinges) {
  for (bool parallel : {false, true}) {
    Step s = perturbedStep(5);
    HingeBending bending(s.model);
    const std::vector<Hinge>& hinges = bending.hinges();
    ASSERT_NE(hinges.size() % 8, 0u);
    // Hinge 7's wing B collapses onto the edge's midpoint: its edge ends rounded to multiples of 2^-10 m, so that the
    // wing's normal is exactly 0 and so is its fade. Hinge 40's wing B keeps 5 % of its rest height, inside the fade
    // band. The same vertices are wings and edge ends of their neighbours' hinges.
    auto point = [&](int v) { return s.x.segment<3>(3 * v); };
    for (int k = 0; k < 2; ++k) point(hinges[7].v[k]) = (point(hinges[7].v[k]) * 1024.0).array().round() / 1024.0;
    point(hinges[7].v[3]) = point(hinges[7].v[0]) + 0.5 * (point(hinges[7].v[1]) - point(hinges[7].v[0]));
    const Eigen::Vector3d foot = point(hinges[40].v[0]) + 0.4 * (point(hinges[40].v[1]) - point(hinges[40].v[0]));
    point(hinges[40].v[3]) = foot + 0.05 * (point(hinges[40].v[3]) - foot);
    BendingDissipation damping(hinges, 1e-1);
    bending.foldDissipation(&damping);
    damping.setFolded(true);
    damping.setGradientSource(&bending);
    bending.setRecordAngleGradients(true);
    bending.setRecordStepStartGradient(true);
    AssemblyOptions options;
    options.parallel = parallel;
    const StepContext ctx{&s.xn, &s.v, 2e-3, 0.0, 0.7, options};
    bending.beginStep(ctx);
    damping.beginStep(ctx);

    Eigen::VectorXd elastic = Eigen::VectorXd::Zero(s.x.size()), both = elastic;
    std::vector<Eigen::Matrix<double, 12, 1>> zeroSum(hinges.size());
    std::vector<double> offsets(hinges.size());
    int faded = 0, collapsed = 0;
    for (size_t i = 0; i < hinges.size(); ++i) {
      double phi = 0.0;
      const Eigen::Matrix<double, 12, 1> grad = hingeBendGradient(hinges[i], s.x, true, phi);
      double theta = hingeAngle(hinges[i], s.x);
      collapsed += grad.isZero(0.0);
      faded += phi != 0.0 && std::abs(phi - theta) > 1e-12 * std::abs(theta);
      const Eigen::Matrix<double, 12, 1> ge = (0.7 * hinges[i].stiffness * phi) * grad;
      const Eigen::Matrix<double, 12, 1> gd = damping.stencilGradient(static_cast<int>(i), s.x);
      for (int k = 0; k < 4; ++k) {
        elastic.segment<3>(3 * hinges[i].v[k]) += ge.segment<3>(3 * k);
        both.segment<3>(3 * hinges[i].v[k]) += ge.segment<3>(3 * k) + gd.segment<3>(3 * k);
      }
      zeroSum[i] = grad;
      offsets[i] = zeroSumOffset(hinges[i], s.x, zeroSum[i]);
    }
    ASSERT_GE(collapsed, 1);
    ASSERT_GE(faded, 2);
    ASSERT_GT(relativeError(elastic, both), 1e-3);

    Eigen::VectorXd g = Eigen::VectorXd::Zero(s.x.size());
    bending.addGuessGradient(s.x, g);
    ASSERT_TRUE(g.allFinite());
    EXPECT_LT(relativeError(g, both), 1e-12) << "parallel " << parallel;
    g.setZero();
    bending.addGradient(s.x, g);
    EXPECT_LT(relativeError(g, both), 1e-12) << "parallel " << parallel;

    Eigen::VectorXd recorded = Eigen::VectorXd::Zero(s.x.size());
    ASSERT_TRUE(bending.addRecordedStepStartGradient(s.x, recorded));
    EXPECT_LT(relativeError(recorded, elastic), 1e-12);
    std::vector<Eigen::Matrix<double, 12, 1>> gradients;
    std::vector<double> recordedOffsets;
    ASSERT_TRUE(bending.takeRecordedGradients(s.x, true, gradients, recordedOffsets));
    ASSERT_EQ(gradients.size(), hinges.size());
    for (size_t i = 0; i < hinges.size(); ++i) {
      const double scale = zeroSum[i].norm() + 1e-30;
      EXPECT_LT((gradients[i] - zeroSum[i]).norm(), 1e-12 * scale) << "hinge " << i;
      EXPECT_NEAR(recordedOffsets[i], offsets[i], 1e-12 * (std::abs(offsets[i]) + scale * 0.02)) << "hinge " << i;
    }
  }
}
