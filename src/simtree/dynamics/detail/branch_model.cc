#include "simtree/dynamics/detail/branch_model.h"

#include <algorithm>
#include <utility>

#include "simtree/core/units.h"
#include "simtree/dynamics/detail/mode_shapes.h"

namespace simtree::dynamics {

TreeOrder BuildTreeOrder(const Tree& tree) {
  const int n = tree.size();
  TreeOrder o;
  int max_level = 0;
  for (const Branch& b : tree.branches) max_level = std::max(max_level, b.level);
  std::vector<int> per_level(max_level + 2, 0);
  for (const Branch& b : tree.branches) ++per_level[b.level + 1];
  o.level_begin.assign(max_level + 2, 0);
  for (int l = 0; l <= max_level; ++l) o.level_begin[l + 1] = o.level_begin[l] + per_level[l + 1];
  o.level_order.assign(n, 0);
  std::vector<int> fill(o.level_begin.begin(), o.level_begin.end() - 1);
  for (const Branch& b : tree.branches) o.level_order[fill[b.level]++] = b.id;
  o.child_begin.assign(n + 1, 0);
  for (const Branch& b : tree.branches) {
    if (b.parent >= 0) ++o.child_begin[b.parent + 1];
  }
  for (int b = 0; b < n; ++b) o.child_begin[b + 1] += o.child_begin[b];
  o.child_list.assign(o.child_begin[n], 0);
  std::vector<int> next(o.child_begin.begin(), o.child_begin.end() - 1);
  for (const Branch& b : tree.branches) {
    if (b.parent >= 0) o.child_list[next[b.parent]++] = b.id;
  }
  return o;
}

namespace {

// The branch's nodes in its rest frame, with their mode-shape values.
void FillNodeTables(const Branch& b, const BranchLink& k, const BranchModel& m, NodeTables& node) {
  const std::vector<double> s = b.ArcLengths();
  for (int j = 0; j < k.nodes; ++j) {
    const Eigen::Vector3d r = m.frame.transpose() * (b.nodes[j].position - m.rest_base);
    const double x = m.length > 0.0 ? s[j] / m.length : 0.0;
    const size_t i = k.first_node + j;
    node.a_u[i] = static_cast<float>(r.x());
    node.h[i] = static_cast<float>(r.y());
    node.a_w[i] = static_cast<float>(r.z());
    node.phi[i] = m.length > 0.0 ? static_cast<float>(BendingModeShape(x)) : 0.f;
    node.psi[i] = m.length > 0.0 ? static_cast<float>(TwistModeShape(x)) : 0.f;
    node.arc_fraction[i] = static_cast<float>(x);
  }
}

// Where branch b hangs on its parent p: the attachment node's rest offset and mode shapes, and
// b's rest frame in p's.
void Attach(const Branch& b, const Branch& p, const BranchModel& pm, const BranchModel& m,
            BranchLink& k) {
  const double lp = pm.length;
  const double xp = lp > 0.0 ? p.ArcLengths()[b.parent_node] / lp : 0.0;
  k.attach_phi = lp > 0.0 ? BendingModeShape(xp) : 0.0;
  k.attach_slope = lp > 0.0 ? BendingModeSlope(xp) / lp : 0.0;
  k.attach_psi = lp > 0.0 ? TwistModeShape(xp) : 0.0;
  const Eigen::Vector3d offset =
      pm.frame.transpose() * (p.nodes[b.parent_node].position - p.base().position);
  k.attach_au = offset.x();
  k.attach_h = offset.y();
  k.attach_aw = offset.z();
  k.relative_frame = pm.frame.transpose() * m.frame;
}

}  // namespace

DynamicsModel BuildDynamicsModel(Tree input) {
  DynamicsModel out;
  out.tree = std::move(input);
  const Tree& tree = out.tree;
  out.order = BuildTreeOrder(tree);
  out.links.resize(tree.size());
  out.models.resize(tree.size());
  const int total = tree.NodeCount();
  NodeTables& node = out.nodes;
  for (auto* v : {&node.h, &node.a_u, &node.a_w, &node.phi, &node.psi, &node.arc_fraction}) {
    v->assign(total, 0.f);
  }
  int first = 0;
  for (const Branch& b : tree.branches) {
    BranchLink& k = out.links[b.id];
    BranchModel& m = out.models[b.id];
    k.parent = b.parent;
    k.first_node = first;
    k.nodes = static_cast<int>(b.nodes.size());
    m.parent_node = b.parent_node;
    m.level = b.level;
    m.length = b.Length();
    m.frame.col(0) = b.frame.u;
    m.frame.col(1) = b.frame.v;
    m.frame.col(2) = b.frame.w;
    m.rest_base = b.base().position;
    FillNodeTables(b, k, m, node);
    if (b.parent >= 0) {
      Attach(b, tree.branches[b.parent], out.models[b.parent], m, k);
      out.links[b.parent].has_children = true;
    }
    first += k.nodes;
  }
  return out;
}

void SetBranchMechanics(const BranchMechanics& mechanics, BranchModel& model, BranchLink& link) {
  model.mechanics = mechanics;
  link.lin_bend = mechanics.lin_bend;
  link.twist_rotation = mechanics.twist_rotation;
  link.rot_u = mechanics.rot_u;
  link.rot_w = mechanics.rot_w;
  link.inverse_mass = mechanics.inverse_mass;
  for (int i = 0; i < 3; ++i) {
    const double w = kTwoPi * mechanics.frequency[i];
    link.half_mass[i] = 0.5 * mechanics.modal_mass[i];
    link.half_stiffness[i] = 0.5 * mechanics.modal_mass[i] * w * w;
  }
}

}  // namespace simtree::dynamics
