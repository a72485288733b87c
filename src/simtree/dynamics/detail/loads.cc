#include "simtree/dynamics/detail/loads.h"

#include <algorithm>

#include "simtree/core/units.h"
#include "simtree/dynamics/detail/pose.h"

namespace simtree::dynamics {
namespace {

void Accumulate(int id, const Load& delta, std::vector<Load>& loads, std::vector<int>* touched) {
  Load& l = loads[id];
  for (int i = 0; i < 3; ++i) l.q[i] += delta.q[i];
  l.force += delta.force;
  l.moment += delta.moment;
  if (touched) touched->push_back(id);
}

}  // namespace

void LoadTable::Clear(bool everything) {
  if (all_loaded || everything) {
    std::fill(load.begin(), load.end(), Load{});
    all_loaded = false;
  } else {
    for (int id : loaded) load[id] = Load{};
  }
  loaded.clear();
}

void AddPointLoad(const Eigen::Matrix3d& f, double phi, double slope, double psi,
                  const Eigen::Vector3d& r, const Eigen::Vector3d& force,
                  const Eigen::Vector3d& moment, Load& out) {
  const Eigen::Vector3d u = f.col(0), v = f.col(1), w = f.col(2);
  out.q[kModeU] += phi * force.dot(u) - slope * moment.dot(w);
  out.q[kModeW] += phi * force.dot(w) + slope * moment.dot(u);
  out.q[kModeT] += psi * (v.dot(r.cross(force)) + moment.dot(v));
  out.force += force;
  out.moment += moment + r.cross(force);
}

void AddChildReaction(const BranchLink& k, const Eigen::Matrix3d& parent_frame,
                      const Eigen::Vector3d& force, const Eigen::Vector3d& moment,
                      Load& parent_load) {
  const Eigen::Vector3d lever =
      parent_frame * Eigen::Vector3d(k.attach_au, k.attach_h, k.attach_aw);
  AddPointLoad(parent_frame, k.attach_phi, k.attach_slope, k.attach_psi, lever, force, moment,
               parent_load);
}

Load OwnDistributedLoad(const BranchMechanics& m, const BranchState& st, bool gravity,
                        const WindField& wind) {
  Load out;
  const Eigen::Vector3d u = st.frame.col(0), v = st.frame.col(1), w = st.frame.col(2);
  if (gravity) {
    const Eigen::Vector3d g(0, 0, -kGravity);
    out.q[kModeU] += m.lin_bend * g.dot(u);
    out.q[kModeW] += m.lin_bend * g.dot(w);
    out.q[kModeT] += (st.frame * m.lin_twist).dot(g);
    out.force += m.mass_total * g;
    out.moment += (st.frame * m.mass_moment).cross(g);
  }
  if (wind.options().enabled && m.area > 0.0) {
    const Eigen::Vector3d centroid = st.frame * m.centroid;
    const Eigen::Vector3d air = wind.Velocity(st.origin + centroid);
    // Drag of a cylinder: only the flow across the branch counts.
    const Eigen::Vector3d across = air - air.dot(v) * v;
    const Eigen::Vector3d pressure = 0.5 * wind.options().air_density_kg_m3 *
                                     wind.options().drag_coefficient * across.norm() * across;
    const Eigen::Vector3d drag = m.area * pressure;
    out.q[kModeU] += m.area_phi * pressure.dot(u);
    out.q[kModeW] += m.area_phi * pressure.dot(w);
    out.q[kModeT] += (st.frame * m.area_twist).dot(pressure);
    out.force += drag;
    out.moment += centroid.cross(drag);
  }
  return out;
}

void WalkPointLoad(const DynamicsModel& model, std::span<const BranchState> states,
                   bool transfer_loads, const PointForce& point, std::vector<Load>& loads,
                   std::vector<int>* touched) {
  const int id = point.branch;
  const PointOnBranch p = PointAt(model.tree.branches[id], model.models[id], point.arc_length);
  const Eigen::Vector3d r = states[id].frame * p.rest_offset;
  Load delta;
  AddPointLoad(states[id].frame, p.phi, p.slope, p.psi, r, point.force, Eigen::Vector3d::Zero(),
               delta);
  Accumulate(id, delta, loads, touched);
  if (!transfer_loads) return;
  Eigen::Vector3d moment = delta.moment;  // about the current branch's base
  for (int child = id; model.links[child].parent >= 0; child = model.links[child].parent) {
    const int parent = model.links[child].parent;
    Load up;
    AddChildReaction(model.links[child], states[parent].frame, point.force, moment, up);
    Accumulate(parent, up, loads, touched);
    moment = up.moment;
  }
}

}  // namespace simtree::dynamics
