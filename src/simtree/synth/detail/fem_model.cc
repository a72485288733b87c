#include "simtree/synth/detail/fem_model.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "simtree/core/error.h"
#include "simtree/core/validate.h"

namespace simtree::synth {
namespace {

// Global index of the 12 element degrees of freedom (-1 where held).
std::array<int, 12> ElementDofs(const std::array<int, 6>& a, const std::array<int, 6>& b) {
  std::array<int, 12> dofs;
  std::copy(a.begin(), a.end(), dofs.begin());
  std::copy(b.begin(), b.end(), dofs.begin() + 6);
  return dofs;
}

}  // namespace

PointMotion PointMap::Apply(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Vector12d local = Vector12d::Zero();
  for (int k = 0; k < 12; ++k) {
    if (dofs[k] >= 0) local[k] = x[dofs[k]];
  }
  const Eigen::Matrix<double, 6, 1> m = rows * local;
  return {m.head<3>(), m.tail<3>()};
}

Eigen::Matrix<double, 6, Eigen::Dynamic> PointMap::ApplyToColumns(
    const Eigen::MatrixXd& shapes) const {
  Eigen::Matrix<double, 12, Eigen::Dynamic> local =
      Eigen::Matrix<double, 12, Eigen::Dynamic>::Zero(12, shapes.cols());
  for (int k = 0; k < 12; ++k) {
    if (dofs[k] >= 0) local.row(k) = shapes.row(dofs[k]);
  }
  return rows * local;
}

FemModel::FemModel(const Tree& tree, const WoodProperties& wood, const FemOptions& options)
    : tree_(tree), wood_(wood), options_(options) {
  Validate(tree_, "tree");
  ValidateWood(wood_, "wood");
  if (!std::isfinite(options_.max_element_length_m) || options_.max_element_length_m <= 0) {
    throw InputError(
        "fem options", "max_element_length_m",
        fmt::format("expected a positive length, got {}", options_.max_element_length_m));
  }
  if (!std::isfinite(options_.merge_distance_m) || options_.merge_distance_m < 0) {
    throw InputError("fem options", "merge_distance_m",
                     fmt::format("expected a length >= 0, got {}", options_.merge_distance_m));
  }
  if (!std::isfinite(options_.root_plate_stiffness_ratio) ||
      options_.root_plate_stiffness_ratio < 0) {
    throw InputError("fem options", "root_plate_stiffness_ratio",
                     fmt::format("expected a ratio >= 0 (0 clamps the base), got {}",
                                 options_.root_plate_stiffness_ratio));
  }
  BuildMesh();
  if (elements_.empty()) {
    throw InputError("tree", "branches", "expected at least one segment of non-zero length");
  }
  Assemble();
}

void FemModel::BuildMesh() {
  const int branches = tree_.size();
  tree_nodes_.assign(branches, {});
  stations_.assign(branches, {});
  first_element_.assign(branches, 0);
  node_positions_.push_back(tree_.trunk().base().position);  // node 0: the base
  for (const Branch& b : tree_.branches) {
    const int n = static_cast<int>(b.nodes.size());
    std::vector<int>& fem_nodes = tree_nodes_[b.id];
    fem_nodes.resize(n);
    // A child starts *on* its parent's node: the rigid joint.
    int previous = b.is_trunk() ? 0 : tree_nodes_[b.parent][b.parent_node];
    fem_nodes[0] = previous;
    stations_[b.id].push_back({previous, 0.0});
    first_element_[b.id] = element_count();
    const std::vector<double> arc = b.ArcLengths();
    double previous_radius = b.nodes[0].radius;
    for (int i = 1; i < n; ++i) {
      const Eigen::Vector3d start = node_positions_[previous];
      const Eigen::Vector3d target = b.nodes[i].position;
      const double length = (target - start).norm();
      if (length <= options_.merge_distance_m) {
        fem_nodes[i] = previous;
        continue;
      }
      const int pieces =
          std::max(1, static_cast<int>(std::ceil(length / options_.max_element_length_m - 1e-9)));
      const double s0 = stations_[b.id].back().arc_length;
      for (int k = 1; k <= pieces; ++k) {
        const double t = static_cast<double>(k) / pieces;
        const int node = node_count();
        node_positions_.push_back(k == pieces ? target
                                              : Eigen::Vector3d(start + t * (target - start)));
        BeamElement e;
        e.a = node_positions_[previous];
        e.b = node_positions_[node];
        // Radii: linear from the previous station's radius to this tree node's.
        const double r_end = b.nodes[i].radius;
        e.radius_a = previous_radius + (r_end - previous_radius) * (k - 1) / pieces;
        e.radius_b = previous_radius + (r_end - previous_radius) * t;
        elements_.push_back(e);
        element_nodes_.push_back({previous, node});
        stations_[b.id].push_back({node, s0 + t * (std::max(arc[i], s0) - s0)});
        previous = node;
      }
      previous_radius = b.nodes[i].radius;
      fem_nodes[i] = previous;
    }
  }
}

void FemModel::Assemble() {
  const int elements = element_count();
  using Triplet = Eigen::Triplet<double>;
  std::vector<Triplet> k_entries(static_cast<size_t>(elements) * 144);
  std::vector<Triplet> m_entries(static_cast<size_t>(elements) * 144);
  std::vector<double> element_mass(elements);
  tbb::parallel_for(tbb::blocked_range<int>(0, elements), [&](const tbb::blocked_range<int>& r) {
    for (int e = r.begin(); e < r.end(); ++e) {
      const BeamElement& element = elements_[e];
      const Matrix12d k = element.Stiffness(wood_);
      const Matrix12d m = element.Mass(wood_);
      const auto dofs =
          ElementDofs(node_dofs(element_nodes_[e][0]), node_dofs(element_nodes_[e][1]));
      size_t slot = static_cast<size_t>(e) * 144;
      for (int i = 0; i < 12; ++i) {
        for (int j = 0; j < 12; ++j, ++slot) {
          // Held rows and columns become zero entries at (0, 0): summed away harmlessly.
          const bool free = dofs[i] >= 0 && dofs[j] >= 0;
          k_entries[slot] = Triplet(free ? dofs[i] : 0, free ? dofs[j] : 0, free ? k(i, j) : 0.0);
          m_entries[slot] = Triplet(free ? dofs[i] : 0, free ? dofs[j] : 0, free ? m(i, j) : 0.0);
        }
      }
      // Translational mass of a rigid unit translation: the element's rho * integral of A.
      element_mass[e] = m(0, 0) + m(0, 6) + m(6, 0) + m(6, 6);
    }
  });
  if (has_root_plate()) {
    // k = ratio E I / H of the trunk's base section, on the base's two tilts.
    const double r = tree_.trunk().base().radius;
    const double e_base = wood_.youngs_modulus_pa * wood_.StiffnessFactorAt(r);
    const double second_moment = 0.25 * kPi * r * r * r * r;
    double height = 0.0;  // of the highest node (the tree's bounds would add the radii)
    for (const Eigen::Vector3d& p : node_positions_) {
      height = std::max(height, p.z() - node_positions_[0].z());
    }
    if (!(height > 0)) {
      throw InputError("tree", "trunk",
                       "expected the tree to rise above its base (a root plate's stiffness "
                       "scales with the height)");
    }
    root_plate_stiffness_ = options_.root_plate_stiffness_ratio * e_base * second_moment / height;
    const std::array<int, 6> base = node_dofs(0);
    for (int k : {3, 4}) k_entries.emplace_back(base[k], base[k], root_plate_stiffness_);
  }
  const int n = dof_count();
  stiffness_.resize(n, n);
  mass_.resize(n, n);
  stiffness_.setFromTriplets(k_entries.begin(), k_entries.end());
  mass_.setFromTriplets(m_entries.begin(), m_entries.end());
  damping_ = wood_.rayleigh_alpha * mass_ + wood_.rayleigh_beta * stiffness_;
  total_mass_kg_ = 0.0;
  for (double m : element_mass) total_mass_kg_ += m;
}

std::pair<int, double> FemModel::Locate(int branch, double arc_length) const {
  const std::vector<Station>& st = stations_[branch];
  if (st.size() < 2) return {-1, 0.0};
  const auto it = std::upper_bound(st.begin(), st.end(), arc_length,
                                   [](double s, const Station& x) { return s < x.arc_length; });
  const int k =
      std::clamp(static_cast<int>(it - st.begin()) - 1, 0, static_cast<int>(st.size()) - 2);
  const double span = st[k + 1].arc_length - st[k].arc_length;
  const double xi = span > 0 ? std::clamp((arc_length - st[k].arc_length) / span, 0.0, 1.0) : 0.0;
  return {first_element_[branch] + k, xi};
}

void FemModel::CheckPoint(int branch, double arc_length, const char* what) const {
  if (branch < 0 || branch >= tree_.size()) {
    throw InputError(
        what, "branch",
        fmt::format("expected a branch id in [0, {}], got {}", tree_.size() - 1, branch));
  }
  const double length = tree_.branches[branch].Length();
  if (!std::isfinite(arc_length) || arc_length < 0 || arc_length > length + 1e-3) {
    throw InputError(what, "arc_length",
                     fmt::format("expected an arc length in [0, {:.6g}] m (the length of branch "
                                 "{}), got {}",
                                 length, branch, arc_length));
  }
}

std::array<int, 6> FemModel::node_dofs(int node) const {
  std::array<int, 6> dofs;
  dofs.fill(-1);
  if (node > 0) {
    for (int k = 0; k < 6; ++k) dofs[k] = 6 * (node - 1) + k;
  } else if (has_root_plate()) {
    dofs[3] = 6 * (node_count() - 1);
    dofs[4] = dofs[3] + 1;
  }
  return dofs;
}

PointMap FemModel::NodeMap(int node) const {
  PointMap map;
  map.dofs.fill(-1);
  const std::array<int, 6> own = node_dofs(node);
  std::copy(own.begin(), own.end(), map.dofs.begin());
  map.rows.setZero();
  map.rows.leftCols<6>().setIdentity();
  return map;
}

PointMap FemModel::PointMapAt(int branch, double arc_length) const {
  CheckPoint(branch, arc_length, "point");
  const auto [e, xi] = Locate(branch, arc_length);
  if (e < 0) return NodeMap(stations_[branch].front().node);
  PointMap map;
  map.dofs = ElementDofs(node_dofs(element_nodes_[e][0]), node_dofs(element_nodes_[e][1]));
  map.rows = elements_[e].PointOperator(xi);
  return map;
}

void FemModel::Scatter(const PointMap& map, const Eigen::Matrix<double, 6, 1>& load,
                       Eigen::VectorXd& f) const {
  const Vector12d nodal = map.rows.transpose() * load;
  for (int k = 0; k < 12; ++k) {
    if (map.dofs[k] >= 0) f[map.dofs[k]] += nodal[k];
  }
}

Eigen::VectorXd FemModel::PointLoad(int branch, double arc_length, const Eigen::Vector3d& force,
                                    const Eigen::Vector3d& moment) const {
  CheckPoint(branch, arc_length, "load");
  if (!force.allFinite() || !moment.allFinite()) {
    throw InputError("load", "force", "expected a finite force and moment");
  }
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dof_count());
  Eigen::Matrix<double, 6, 1> load;
  load << force, moment;
  Scatter(PointMapAt(branch, arc_length), load, f);
  return f;
}

Eigen::VectorXd FemModel::GravityLoad(const Eigen::Vector3d& gravity) const {
  if (!gravity.allFinite()) throw InputError("load", "gravity", "expected a finite vector");
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dof_count());
  for (int e = 0; e < element_count(); ++e) {
    const Vector12d w = elements_[e].Weight(wood_, gravity);
    const auto dofs = ElementDofs(node_dofs(element_nodes_[e][0]), node_dofs(element_nodes_[e][1]));
    for (int k = 0; k < 12; ++k) {
      if (dofs[k] >= 0) f[dofs[k]] += w[k];
    }
  }
  return f;
}

TreePose FemModel::Pose(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != dof_count()) {
    throw InputError("displacement", "size",
                     fmt::format("expected {} values, got {}", dof_count(), x.size()));
  }
  TreePose pose(tree_);
  for (const Branch& b : tree_.branches) {
    for (int i = 0; i < static_cast<int>(b.nodes.size()); ++i) {
      const int dof = node_dof(tree_nodes_[b.id][i]);
      if (dof >= 0) pose.node(b.id, i) += x.segment<3>(dof);
    }
  }
  return pose;
}

PointMotion FemModel::MotionAt(const Eigen::Ref<const Eigen::VectorXd>& x, int branch,
                               double arc_length) const {
  if (x.size() != dof_count()) {
    throw InputError("displacement", "size",
                     fmt::format("expected {} values, got {}", dof_count(), x.size()));
  }
  return PointMapAt(branch, arc_length).Apply(x);
}

}  // namespace simtree::synth
