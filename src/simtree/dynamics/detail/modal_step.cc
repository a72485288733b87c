#include "simtree/dynamics/detail/modal_step.h"

#include "simtree/core/units.h"
#include "simtree/dynamics/detail/pose.h"

namespace simtree::dynamics {

std::array<OscillatorStep, 3> MakeBranchSteps(const BranchMechanics& mechanics, double dt,
                                              Integrator integrator) {
  std::array<OscillatorStep, 3> steps;
  for (int i = 0; i < 3; ++i) {
    steps[i] = MakeOscillatorStep(mechanics.frequency[i], mechanics.damping[i], dt, integrator);
  }
  return steps;
}

std::array<double, 3> StaticDeflection(const BranchMechanics& m,
                                       const std::array<double, 3>& force) {
  std::array<double, 3> q = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const double w = kTwoPi * m.frequency[i];
    q[i] = force[i] * m.inverse_mass[i] / (w * w);
  }
  return q;
}

void AdvanceBranch(const BranchLink& k, const BranchState* parent,
                   const std::array<double, 3>& force, double dt, bool base_excitation,
                   BranchState& st) {
  const double inv_dt = 1.0 / dt;
  for (int i = 0; i < 3; ++i) {
    const double v0 = st.primary.v[i];
    k.step[i].Apply(force[i] * k.inverse_mass[i], st.primary.q[i], st.primary.v[i]);
    st.acceleration[i] = (st.primary.v[i] - v0) * inv_dt;
  }
  if (base_excitation && parent != nullptr) {
    const BranchState& ps = *parent;
    const std::array<double, 3>& qdd = ps.acceleration;
    // The attachment node's acceleration relative to the parent's base, parent coordinates.
    const Eigen::Vector3d lin(
        k.attach_phi * qdd[kModeU] + k.attach_psi * qdd[kModeT] * k.attach_aw, 0.0,
        k.attach_phi * qdd[kModeW] - k.attach_psi * qdd[kModeT] * k.attach_au);
    st.base_acceleration = ps.base_acceleration +
                           ps.base_angular_acceleration.cross(st.origin - ps.origin) +
                           ps.frame * lin;
    st.base_angular_acceleration =
        ps.base_angular_acceleration + ps.frame * LocalRotation(k.attach_slope, k.attach_psi, qdd);
    // The pseudo-forces -w_j (a + alpha x r_j) on the branch's masses. Twist feels only the
    // turn of the base about the branch axis: its inertia is a material constant, not the
    // lumped masses, so a linear push on mass just off a nearly straight axis would fling it.
    const Eigen::Vector3d a = st.frame.transpose() * st.base_acceleration;
    const Eigen::Vector3d alpha = st.frame.transpose() * st.base_angular_acceleration;
    const std::array<double, 3> g = {-(k.lin_bend * a.x() + alpha.dot(k.rot_u)),
                                     -(k.lin_bend * a.z() + alpha.dot(k.rot_w)),
                                     -k.twist_rotation * alpha.y()};
    for (int i = 0; i < 3; ++i) {
      k.step[i].Apply(g[i] * k.inverse_mass[i], st.swing.q[i], st.swing.v[i]);
    }
  }
  for (int i = 0; i < 3; ++i) {
    st.modal.q[i] = st.primary.q[i] + st.swing.q[i];
    st.modal.v[i] = st.primary.v[i] + st.swing.v[i];
  }
}

}  // namespace simtree::dynamics
