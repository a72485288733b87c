#include "simtree/synth/detail/fem_effective_mass.h"

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::synth {

EffectiveMasses ComputeEffectiveMasses(const FemModel& model, const ModalBasis& modes) {
  const int n = model.dof_count();
  if (modes.shapes.rows() != n) {
    throw InputError("modes", "shapes",
                     fmt::format("expected the modes of this FEM model ({} degrees of freedom), "
                                 "got {} rows",
                                 n, modes.shapes.rows()));
  }
  // The three rigid-body base motions over the free degrees of freedom.
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(n, 3);
  const Eigen::Vector3d base = model.node_position(0);
  for (int node = 1; node < model.node_count(); ++node) {
    const int dof = model.node_dof(node);
    r(dof + 0, 0) = 1.0;
    r(dof + 1, 1) = 1.0;
    const Eigen::Vector3d arm = model.node_position(node) - base;
    r(dof + 0, 2) = -arm.y();  // e_z x arm
    r(dof + 1, 2) = arm.x();
    r(dof + 5, 2) = 1.0;
  }
  const Eigen::MatrixXd mr = model.mass() * r;
  const Eigen::Vector3d total = (r.transpose() * mr).diagonal();
  // phi^T M r and phi^T M phi per mode (1 for mass-normalised shapes, computed all the same).
  const Eigen::MatrixXd participation = modes.shapes.transpose() * mr;  // count x 3
  const Eigen::VectorXd modal_mass =
      (modes.shapes.transpose() * (model.mass() * modes.shapes)).diagonal();

  EffectiveMasses out;
  out.translating_mass_kg = total[0];
  out.polar_moment_kg_m2 = total[2];
  const int count = modes.count();
  out.x.resize(count);
  out.y.resize(count);
  out.torsion.resize(count);
  for (int i = 0; i < count; ++i) {
    // Effective mass (phi^T M r)^2 / phi^T M phi, as a share of r^T M r.
    const auto share = [&](int k) {
      return total[k] > 0 ? participation(i, k) * participation(i, k) / modal_mass[i] / total[k]
                          : 0.0;
    };
    out.x[i] = share(0);
    out.y[i] = share(1);
    out.torsion[i] = share(2);
  }
  out.horizontal = out.x + out.y;
  return out;
}

int LowestSwayMode(const EffectiveMasses& masses, double min_horizontal_fraction) {
  for (int i = 0; i < masses.count(); ++i) {
    if (masses.horizontal[i] >= min_horizontal_fraction) return i;
  }
  return -1;
}

}  // namespace simtree::synth
