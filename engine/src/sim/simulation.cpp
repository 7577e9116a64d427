#include "drape/sim/simulation.h"

#include <algorithm>
#include <chrono>

#include "drape/garment/garment_builder.h"
#include "drape/geometry/strain.h"
#include "drape/scene/pins.h"
#include "drape/sim/snapshot_builder.h"
#include "sim/cloth_model_builder.h"
#include "sim/contact_terms.h"

namespace drape {

const char* toString(StepStatus status) {
  switch (status) {
    case StepStatus::Converged: return "Converged";
    case StepStatus::MaxIterations: return "MaxIterations";
    case StepStatus::Diverged: return "Diverged";
    case StepStatus::Cancelled: return "Cancelled";
  }
  return "?";
}

struct Simulation::Solver {
  std::unique_ptr<newton::NewtonSolver> newton;
  ContactTerms contact;
};

namespace {

StepStatus fromNewton(newton::NewtonStatus s) {
  switch (s) {
    case newton::NewtonStatus::Converged: return StepStatus::Converged;
    case newton::NewtonStatus::MaxIterations: return StepStatus::MaxIterations;
    case newton::NewtonStatus::Diverged: return StepStatus::Diverged;
    case newton::NewtonStatus::Cancelled: return StepStatus::Cancelled;
  }
  return StepStatus::Diverged;
}

}  // namespace

Simulation::Simulation(Scene scene) : m_scene(std::move(scene)) {
  Diagnostics diagnostics;
  m_garment = buildGarment(m_scene.pattern, {m_scene.settings.number("mesh.target_edge_length")}, &diagnostics);
  m_scene.diagnostics.append(diagnostics);
  m_pinned = resolvePins(m_scene, m_garment);
  m_colliderMesh = mergedColliders(m_scene);
  m_solver = std::make_unique<Solver>();
  m_solver->contact = makeContactTerms(m_scene, m_garment, m_colliderMesh);
  m_solver->newton = std::make_unique<newton::NewtonSolver>(buildClothModel(m_scene, m_garment, m_pinned),
                                                            newtonSettingsFrom(m_scene.settings),
                                                            std::move(m_solver->contact.energies));
}

Simulation::~Simulation() = default;

std::vector<std::string> Simulation::terms() const { return m_solver->newton->energyNames(); }

double Simulation::time() const { return m_solver->newton->time(); }

Eigen::MatrixX3d Simulation::positions() const {
  const Eigen::VectorXd& x = m_solver->newton->positions();
  Eigen::MatrixX3d p(m_garment.vertexCount(), 3);
  for (int v = 0; v < m_garment.vertexCount(); ++v) p.row(v) = x.segment<3>(3 * v).transpose();
  return p;
}

void Simulation::requestCancel() { m_solver->newton->requestCancel(); }

bool Simulation::finished() const {
  return m_atRest || time() >= m_scene.settings.number("solver.max_sim_time") - 1e-12 ||
         m_steps >= m_scene.settings.integer("solver.max_steps");
}

StepReport Simulation::step() {
  const auto start = std::chrono::steady_clock::now();
  const newton::NewtonStepReport r = m_solver->newton->step();
  ++m_steps;
  m_atRest = r.atRest;
  StepReport report;
  report.status = fromNewton(r.status);
  report.stage = "drape";
  report.time = r.time;
  report.h = r.h;
  report.iterations = r.newtonIterations;
  report.cgIterations = r.cgIterations;
  report.splits = r.splits;
  report.residual = r.residual;
  report.kineticEnergy = r.kineticPercentile;
  report.atRest = r.atRest;
  report.contacts = countContacts(m_solver->contact, m_solver->newton->positions());
  const Eigen::VectorXd stretch = triangleStretch(m_garment.rest, positions(), m_garment.triangles);
  report.maxStrain = stretch.size() ? stretch.maxCoeff() : 0.0;
  report.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

Snapshot Simulation::snapshot() const {
  Snapshot s = makeSnapshot(m_scene, m_garment, positions());
  s.vertexContact = contactMask(m_solver->contact, m_solver->newton->positions());
  s.time = time();
  s.stage = m_atRest ? "done" : (m_steps == 0 ? "placed" : "drape");
  return s;
}

}  // namespace drape
