#include "simtree/core/tree.h"

#include <algorithm>
#include <limits>

#include "simtree/core/units.h"

namespace simtree {

Material Material::FromFrequencyDampingStiffness(double frequency_hz, double damping_ratio,
                                                 double stiffness, MaterialSource source) {
  Material m;
  for (Mode& mode : m.modes) {
    mode.frequency_hz = frequency_hz;
    mode.damping_ratio = damping_ratio;
  }
  m.stiffness = stiffness;
  m.mass_kg = ModalMass(stiffness, frequency_hz);
  m.source = source;
  return m;
}

void Material::SetStiffness(double k) {
  stiffness = k;
  mass_kg = ModalMass(k, modes[0].frequency_hz);
}

void Material::SetFrequency(ModeKind kind, double frequency_hz) {
  mode(kind).frequency_hz = frequency_hz;
  stiffness = ModalStiffness(mass_kg, modes[0].frequency_hz);
}

double Branch::Length() const {
  double length = 0.0;
  for (size_t i = 1; i < nodes.size(); ++i) {
    length += (nodes[i].position - nodes[i - 1].position).norm();
  }
  return length;
}

std::vector<double> Branch::ArcLengths() const {
  std::vector<double> s(nodes.size(), 0.0);
  for (size_t i = 1; i < nodes.size(); ++i) {
    s[i] = s[i - 1] + (nodes[i].position - nodes[i - 1].position).norm();
  }
  return s;
}

Eigen::Vector3d Branch::PointAt(double arc_length) const {
  if (nodes.empty()) return Eigen::Vector3d::Zero();
  double remaining = std::max(0.0, arc_length);
  for (size_t i = 1; i < nodes.size(); ++i) {
    const Eigen::Vector3d d = nodes[i].position - nodes[i - 1].position;
    const double len = d.norm();
    if (remaining <= len) {
      return len > 0.0 ? Eigen::Vector3d(nodes[i - 1].position + d * (remaining / len))
                       : nodes[i - 1].position;
    }
    remaining -= len;
  }
  return nodes.back().position;
}

double Branch::Volume() const {
  double volume = 0.0;
  for (size_t i = 1; i < nodes.size(); ++i) {
    const double h = (nodes[i].position - nodes[i - 1].position).norm();
    const double r0 = nodes[i - 1].radius;
    const double r1 = nodes[i].radius;
    volume += kPi * h * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
  }
  return volume;
}

bool Tree::IsSimulationReady() const {
  return !branches.empty() && std::all_of(branches.begin(), branches.end(),
                                          [](const Branch& b) { return b.material.has_value(); });
}

std::vector<std::vector<int>> Tree::Children() const {
  std::vector<std::vector<int>> children(branches.size());
  for (const Branch& b : branches) {
    if (b.parent >= 0 && b.parent < size()) children[b.parent].push_back(b.id);
  }
  return children;
}

std::vector<int> Tree::DepthFirstOrder() const {
  std::vector<int> order;
  if (branches.empty()) return order;
  const std::vector<std::vector<int>> children = Children();
  order.reserve(branches.size());
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    order.push_back(id);
    // Push in reverse so children are visited in id order.
    for (auto it = children[id].rbegin(); it != children[id].rend(); ++it) stack.push_back(*it);
  }
  return order;
}

int Tree::MaxLevel() const {
  int level = 0;
  for (const Branch& b : branches) level = std::max(level, b.level);
  return level;
}

int Tree::NodeCount() const {
  int count = 0;
  for (const Branch& b : branches) count += static_cast<int>(b.nodes.size());
  return count;
}

void Tree::Bounds(Eigen::Vector3d* min_corner, Eigen::Vector3d* max_corner) const {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Branch& b : branches) {
    for (const Node& n : b.nodes) {
      lo = lo.cwiseMin(n.position - Eigen::Vector3d::Constant(n.radius));
      hi = hi.cwiseMax(n.position + Eigen::Vector3d::Constant(n.radius));
    }
  }
  if (min_corner) *min_corner = lo;
  if (max_corner) *max_corner = hi;
}

const char* ToString(ModeKind kind) {
  switch (kind) {
    case ModeKind::kBendU:
      return "bend_u";
    case ModeKind::kBendW:
      return "bend_w";
    case ModeKind::kTwistV:
      return "twist_v";
  }
  return "?";
}

const char* ToString(MaterialSource source) {
  switch (source) {
    case MaterialSource::kMeasured:
      return "measured";
    case MaterialSource::kInterpolated:
      return "interpolated";
    case MaterialSource::kDefault:
      return "default";
    case MaterialSource::kAssumed:
      return "assumed";
  }
  return "?";
}

}  // namespace simtree
