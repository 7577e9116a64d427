#pragma once
// A collision-aware global solve problem for the PD contact tests: a horizontal square cloth (1 m, grid x grid
// vertices, no pins) whose collision-free solve sinks `sink` metres, with every vertex over a disc of radius `patch`
// held on a sphere cap of radius 0.3 m (w_k = 1e6 N/m), as a garment lying on the body; and the independent
// reference solution of (K + Delta K) x = b + Delta b by a sparse LDL^T.
#include <Eigen/SparseCholesky>

#include <cmath>
#include <memory>

#include "drape/pd/contact_solve.h"
#include "drape/pd/global_solver.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/pd_system.h"

namespace drape::pd::test {

struct ContactProblem {
  drape::model::ClothModel model;
  std::unique_ptr<PdSystem> system;
  std::unique_ptr<MonolithicSolver> solver;
  Eigen::MatrixX3d b;  // right-hand side of eq. 3
  ContactSet contacts;
};

inline ContactProblem makeContactProblem(int grid, double sink, double patch) {
  ContactProblem p;
  GridClothOptions o;
  o.nx = o.ny = grid;
  o.horizontal = true;
  o.pinTopCorners = false;
  p.model = makeGridCloth(o);
  p.system = std::make_unique<PdSystem>(p.model, PreviewSettings{});
  p.solver = std::make_unique<MonolithicSolver>(p.system->matrix());
  Eigen::MatrixX3d x0(p.system->freeCount(), 3);
  for (int d = 0; d < x0.rows(); ++d) x0.row(d) = p.model.positions.segment<3>(3 * d).transpose();
  x0.col(1).array() -= sink;
  p.b = p.system->matrix() * x0;
  const double radius = 0.3;
  for (int d = 0; d < x0.rows(); ++d) {
    const double r2 = x0(d, 0) * x0(d, 0) + x0(d, 2) * x0(d, 2);
    if (r2 > patch * patch) continue;
    p.contacts.dofs.push_back(d);
    p.contacts.weights.push_back(1e6);
  }
  p.contacts.targets.resize(p.contacts.size(), 3);
  for (int k = 0; k < p.contacts.size(); ++k) {
    const Eigen::Vector3d q = x0.row(p.contacts.dofs[k]).transpose();
    p.contacts.targets.row(k) << q.x(), std::sqrt(radius * radius - q.x() * q.x() - q.z() * q.z()) - radius, q.z();
  }
  return p;
}

inline Eigen::MatrixX3d directContactSolution(const ContactProblem& p) {
  Eigen::SparseMatrix<double> a = p.system->matrix();
  Eigen::MatrixX3d rhs = p.b;
  for (int k = 0; k < p.contacts.size(); ++k) {
    a.coeffRef(p.contacts.dofs[k], p.contacts.dofs[k]) += p.contacts.weights[k];
    rhs.row(p.contacts.dofs[k]) += p.contacts.weights[k] * p.contacts.targets.row(k);
  }
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  return ldlt.solve(rhs);
}

}  // namespace drape::pd::test
