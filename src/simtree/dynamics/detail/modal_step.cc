#include "simtree/dynamics/detail/modal_step.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "simtree/core/units.h"
#include "simtree/dynamics/detail/pose.h"

namespace simtree::dynamics {
namespace {

constexpr std::array<double, 3> kNoForce = {0, 0, 0};

// The energy of a state about `rest` (J).
double EnergyAbout(const BranchLink& k, const ModalState& s, const std::array<double, 3>& rest) {
  double e = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double q = s.q[i] - rest[i];
    e += k.half_mass[i] * s.v[i] * s.v[i] + k.half_stiffness[i] * q * q;
  }
  return e;
}

// The equilibrium of a branch under generalised forces `force`: q = F / (m w^2).
std::array<double, 3> Equilibrium(const BranchLink& k, const std::array<double, 3>& force) {
  return {0.5 * force[0] / k.half_stiffness[0], 0.5 * force[1] / k.half_stiffness[1],
          0.5 * force[2] / k.half_stiffness[2]};
}

// What damping takes out of a branch's motion over a step (J, >= 0 with the exact integrator):
// the energy of its state `s` about its equilibrium `rest` under the step's load, less that of
// the same state after the step without a drive.
double DampingLoss(const BranchLink& k, const ModalState& s, const std::array<double, 3>& rest) {
  ModalState after = s;
  for (int i = 0; i < 3; ++i) {
    after.q[i] -= rest[i];
    k.step[i].Apply(0.0, after.q[i], after.v[i]);
    after.q[i] += rest[i];
  }
  return std::max(0.0, EnergyAbout(k, s, rest) - EnergyAbout(k, after, rest));
}

// The primary motion over the step, and its acceleration (what drives the children's swings).
void AdvancePrimary(const BranchLink& k, const std::array<double, 3>& force, double dt,
                    BranchState& st) {
  const double inv_dt = 1.0 / dt;
  for (int i = 0; i < 3; ++i) {
    const double v0 = st.primary.v[i];
    k.step[i].Apply(force[i] * k.inverse_mass[i], st.primary.q[i], st.primary.v[i]);
    st.acceleration[i] = (st.primary.v[i] - v0) * inv_dt;
  }
}

// The generalised forces (N, N, N m) of the acceleration of the base of branch `st` (link `k`)
// on its parent `ps`, which has been advanced and posed for this step. Stores the base's linear
// and angular acceleration in `st`.
std::array<double, 3> BaseExcitation(const BranchLink& k, const BranchState& ps, BranchState& st) {
  const std::array<double, 3>& qdd = ps.acceleration;
  // The attachment node's acceleration relative to the parent's base, parent coordinates.
  const Eigen::Vector3d lin(k.attach_phi * qdd[kModeU] + k.attach_psi * qdd[kModeT] * k.attach_aw,
                            0.0,
                            k.attach_phi * qdd[kModeW] - k.attach_psi * qdd[kModeT] * k.attach_au);
  st.base_acceleration = ps.base_acceleration +
                         ps.base_angular_acceleration.cross(st.origin - ps.origin) + ps.frame * lin;
  st.base_angular_acceleration =
      ps.base_angular_acceleration + ps.frame * LocalRotation(k.attach_slope, k.attach_psi, qdd);
  // The pseudo-forces -w_j (a + alpha x r_j) on the branch's masses. Twist feels only the turn
  // of the base about the branch axis: its inertia is a material constant, not the lumped
  // masses, so a linear push on mass just off a nearly straight axis would fling it.
  const Eigen::Vector3d a = st.frame.transpose() * st.base_acceleration;
  const Eigen::Vector3d alpha = st.frame.transpose() * st.base_angular_acceleration;
  return {-(k.lin_bend * a.x() + alpha.dot(k.rot_u)), -(k.lin_bend * a.z() + alpha.dot(k.rot_w)),
          -k.twist_rotation * alpha.y()};
}

// A child's swing over the step without the drive, and what the drive adds to it.
struct SwingStep {
  ModalState free;
  std::array<double, 3> dq = {0, 0, 0}, dv = {0, 0, 0};
};

// The largest share lambda in [0, 1] of the drive whose work lambda lin + lambda^2 quad
// (quad >= 0) fits in `budget` (>= 0).
double AffordableShare(double lin, double quad, double budget) {
  if (lin + quad <= budget) return 1.0;
  if (quad <= 0.0) return lin > 0.0 ? std::clamp(budget / lin, 0.0, 1.0) : 1.0;
  const double root = (-lin + std::sqrt(std::max(0.0, lin * lin + 4.0 * quad * budget))) / quad;
  return std::clamp(0.5 * root, 0.0, 1.0);
}

}  // namespace

std::array<OscillatorStep, 3> MakeBranchSteps(const BranchMechanics& mechanics, double dt,
                                              Integrator integrator) {
  std::array<OscillatorStep, 3> steps;
  for (int i = 0; i < 3; ++i) {
    steps[i] = MakeOscillatorStep(mechanics.frequency[i], mechanics.damping[i], dt, integrator);
  }
  return steps;
}

double SwingBankKeep(const BranchMechanics& m, double dt) {
  double slowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) slowest = std::min(slowest, m.damping[i] * kTwoPi * m.frequency[i]);
  return std::exp(-2.0 * slowest * dt);
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

double ModalEnergy(const BranchMechanics& m, const ModalState& s) {
  double e = 0.0;
  for (int i = 0; i < 3; ++i)
    e += OscillatorEnergy(m.modal_mass[i], m.frequency[i], s.q[i], s.v[i]);
  return e;
}

void AdvanceRoot(const BranchLink& k, const std::array<double, 3>& force, double dt,
                 BranchState& st) {
  if (k.has_children)
    st.swing_budget = DampingLoss(k, st.modal, Equilibrium(k, force)) + st.swing_bank;
  AdvancePrimary(k, force, dt, st);
  for (int i = 0; i < 3; ++i) {
    st.modal.q[i] = st.primary.q[i] + st.swing.q[i];
    st.modal.v[i] = st.primary.v[i] + st.swing.v[i];
  }
}

void AdvanceChildren(int parent, std::span<const int> children, std::span<const BranchLink> links,
                     std::span<const Load> loads, double dt, bool base_excitation,
                     std::span<BranchState> states) {
  BranchState& ps = states[parent];
  thread_local std::vector<SwingStep> swings;
  swings.assign(children.size(), SwingStep{});
  // The drive's work on the family is lambda lin + lambda^2 quad for a share lambda of it: the
  // energy of (primary + free swing + lambda delta) less that of (primary + free swing), each
  // about the child's equilibrium under its load (what a held rope stores is not the drive's).
  double lin = 0.0, quad = 0.0;
  for (size_t j = 0; j < children.size(); ++j) {
    const int c = children[j];
    const BranchLink& k = links[c];
    BranchState& st = states[c];
    const std::array<double, 3>& force = loads.empty() ? kNoForce : loads[c].q;
    const std::array<double, 3> rest = loads.empty() ? kNoForce : Equilibrium(k, force);
    if (k.has_children) st.swing_budget = DampingLoss(k, st.modal, rest) + st.swing_bank;
    AdvancePrimary(k, force, dt, st);
    SwingStep& s = swings[j];
    s.free = st.swing;
    for (int i = 0; i < 3; ++i) k.step[i].Apply(0.0, s.free.q[i], s.free.v[i]);
    if (!base_excitation) continue;
    const std::array<double, 3> g = BaseExcitation(k, ps, st);
    for (int i = 0; i < 3; ++i) {
      const double accel = g[i] * k.inverse_mass[i];
      s.dq[i] = k.step[i].b1 * accel;
      s.dv[i] = k.step[i].b2 * accel;
      const double q = st.primary.q[i] + s.free.q[i] - rest[i];
      const double v = st.primary.v[i] + s.free.v[i];
      lin += 2.0 * (k.half_mass[i] * v * s.dv[i] + k.half_stiffness[i] * q * s.dq[i]);
      quad += k.half_mass[i] * s.dv[i] * s.dv[i] + k.half_stiffness[i] * s.dq[i] * s.dq[i];
    }
  }
  const double share = AffordableShare(lin, quad, ps.swing_budget);
  for (size_t j = 0; j < children.size(); ++j) {
    BranchState& st = states[children[j]];
    const SwingStep& s = swings[j];
    for (int i = 0; i < 3; ++i) {
      // At a full share, the same operations in the same order as one driven step.
      st.swing.q[i] = s.free.q[i] + (share < 1.0 ? share * s.dq[i] : s.dq[i]);
      st.swing.v[i] = s.free.v[i] + (share < 1.0 ? share * s.dv[i] : s.dv[i]);
      st.modal.q[i] = st.primary.q[i] + st.swing.q[i];
      st.modal.v[i] = st.primary.v[i] + st.swing.v[i];
    }
  }
  const double spent = share * lin + share * share * quad;
  ps.swing_bank = links[parent].bank_keep * std::max(0.0, ps.swing_budget - spent);
}

}  // namespace simtree::dynamics
