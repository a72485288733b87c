#include "simtree/dynamics/detail/branch_mechanics.h"

#include <algorithm>
#include <vector>

#include "simtree/core/units.h"

namespace simtree::dynamics {

BranchMechanics ComputeBranchMechanics(const Branch& b, const BranchModel& m, const BranchLink& k,
                                       const NodeTables& node, double twist_stiffness_ratio) {
  const Material& mat = *b.material;
  const std::vector<double> s = b.ArcLengths();
  const int n = k.nodes;
  // Each node stands for half of each segment next to it.
  std::vector<double> ds(n, 0.0);
  for (int j = 1; j < n; ++j) {
    const double seg = s[j] - s[j - 1];
    ds[j - 1] += 0.5 * seg;
    ds[j] += 0.5 * seg;
  }
  double sum_area_phi2 = 0;
  for (int j = 0; j < n; ++j) {
    const double phi = node.phi[k.first_node + j];
    sum_area_phi2 += b.nodes[j].radius * b.nodes[j].radius * ds[j] * phi * phi;
  }
  // Scale cross-section volumes to masses so that sum w phi^2 is the modal mass.
  const double scale = sum_area_phi2 > 0.0 ? mat.mass_kg / sum_area_phi2 : 0.0;
  const Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = Eigen::Vector3d::UnitY(),
                        w = Eigen::Vector3d::UnitZ();  // frame coordinates
  BranchMechanics out;
  double polar_psi = 0, polar_psi2 = 0, offaxis_inertia = 0;
  for (int j = 0; j < n; ++j) {
    const double r2 = b.nodes[j].radius * b.nodes[j].radius;
    const double wj = scale * r2 * ds[j];
    const double phi = node.phi[k.first_node + j];
    const double psi = node.psi[k.first_node + j];
    const Eigen::Vector3d r = m.frame.transpose() * (b.nodes[j].position - m.rest_base);
    out.mass_total += wj;
    out.mass_moment += wj * r;
    out.lin_bend += wj * phi;
    out.rot_u += wj * phi * r.cross(u);
    out.rot_w += wj * phi * r.cross(w);
    out.lin_twist += wj * psi * v.cross(r);
    // Rotary inertia about the axis: the cross-section's own (w r^2 / 2) and, on a curved
    // branch, that of the mass off the chord.
    const double axis_inertia = wj * (0.5 * r2 + r.x() * r.x() + r.z() * r.z());
    polar_psi += axis_inertia * psi;
    polar_psi2 += axis_inertia * psi * psi;
    offaxis_inertia += wj * psi * psi * (r.x() * r.x() + r.z() * r.z());
    const double aj = 2.0 * b.nodes[j].radius * ds[j];
    out.area += aj;
    out.area_phi += aj * phi;
    out.area_twist += aj * psi * v.cross(r);
    out.centroid += aj * r;
  }
  if (out.area > 0.0) out.centroid /= out.area;
  for (int i = 0; i < 3; ++i) {
    out.frequency[i] = mat.modes[i].frequency_hz;
    out.damping[i] = mat.modes[i].damping_ratio;
  }
  out.modal_mass[kModeU] = out.modal_mass[kModeW] = mat.mass_kg;
  // Twist: stiffness ratio L^2 k over the twist frequency squared gives the inertia, but never
  // less than that of the mass off the chord (which base accelerations drive), so a curved
  // branch cannot be flung round by its own weight. A branch of no length uses 1 m^2.
  const double lever2 = std::max(m.length * m.length, 1e-6);
  const double w_twist = kTwoPi * out.frequency[kModeT];
  out.modal_mass[kModeT] = std::max(
      twist_stiffness_ratio * lever2 * mat.stiffness / (w_twist * w_twist), offaxis_inertia);
  const double participation = polar_psi2 > 0.0 ? polar_psi / polar_psi2 : 0.0;
  out.twist_rotation = participation * out.modal_mass[kModeT];
  for (int i = 0; i < 3; ++i) out.inverse_mass[i] = 1.0 / out.modal_mass[i];
  return out;
}

}  // namespace simtree::dynamics
