#include "simtree/core/validate.h"

#include <cmath>
#include <set>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "simtree/core/units.h"

namespace simtree {
namespace {

bool Finite(const Eigen::Vector3d& p) { return p.allFinite(); }

class ProblemList {
 public:
  void Add(std::string where, std::string message) {
    problems_.push_back({std::move(where), std::move(message)});
  }
  std::vector<ValidationProblem> Take() { return std::move(problems_); }

 private:
  std::vector<ValidationProblem> problems_;
};

void CheckMaterial(const Material& m, const std::string& at, const ValidationOptions& options,
                   ProblemList& problems) {
  for (int i = 0; i < 3; ++i) {
    const Mode& mode = m.modes[i];
    const std::string where = fmt::format("{}.modes[{}]", at, i);
    if (static_cast<int>(mode.kind) != i) {
      problems.Add(where + ".kind",
                   fmt::format("expected \"{}\", got \"{}\"", ToString(static_cast<ModeKind>(i)),
                               ToString(mode.kind)));
    }
    if (!std::isfinite(mode.frequency_hz) || mode.frequency_hz < options.min_frequency_hz ||
        mode.frequency_hz > options.max_frequency_hz) {
      problems.Add(
          where + ".frequency_hz",
          fmt::format("expected a frequency in [{}, {}] Hz, got {}", options.min_frequency_hz,
                      options.max_frequency_hz, mode.frequency_hz));
    }
    if (!std::isfinite(mode.damping_ratio) || mode.damping_ratio < 0.0 ||
        mode.damping_ratio > options.max_damping_ratio) {
      problems.Add(where + ".damping_ratio",
                   fmt::format("expected a damping ratio in [0, {}], got {}",
                               options.max_damping_ratio, mode.damping_ratio));
    }
  }
  if (!std::isfinite(m.mass_kg) || m.mass_kg <= 0.0) {
    problems.Add(at + ".mass_kg", fmt::format("expected a positive mass, got {}", m.mass_kg));
  }
  if (!std::isfinite(m.stiffness) || m.stiffness <= 0.0) {
    problems.Add(at + ".stiffness",
                 fmt::format("expected a positive stiffness, got {}", m.stiffness));
  } else if (std::isfinite(m.mass_kg) && m.mass_kg > 0.0 &&
             std::isfinite(m.modes[0].frequency_hz)) {
    const double expected = ModalStiffness(m.mass_kg, m.modes[0].frequency_hz);
    if (std::abs(expected - m.stiffness) > 1e-6 * expected) {
      problems.Add(at + ".stiffness",
                   fmt::format("expected 4 m pi^2 f^2 = {} N/m for mass {} kg and first-mode "
                               "frequency {} Hz, got {}",
                               expected, m.mass_kg, m.modes[0].frequency_hz, m.stiffness));
    }
  }
}

void CheckFrame(const Frame& f, const std::string& at, ProblemList& problems) {
  if (!Finite(f.u) || !Finite(f.v) || !Finite(f.w)) {
    problems.Add(at, "expected finite frame vectors");
    return;
  }
  const double tol = 1e-6;
  const bool unit = std::abs(f.u.norm() - 1) < tol && std::abs(f.v.norm() - 1) < tol &&
                    std::abs(f.w.norm() - 1) < tol;
  const bool orthogonal =
      std::abs(f.u.dot(f.v)) < tol && std::abs(f.v.dot(f.w)) < tol && std::abs(f.u.dot(f.w)) < tol;
  const bool right_handed = (f.u.cross(f.v) - f.w).norm() < 1e-5;
  if (!unit || !orthogonal || !right_handed) {
    problems.Add(at, "expected a right-handed orthonormal frame (u x v = w)");
  }
}

}  // namespace

std::vector<ValidationProblem> FindProblems(const Tree& tree, const ValidationOptions& options) {
  ProblemList problems;
  if (tree.branches.empty()) {
    problems.Add("branches", "expected at least one branch (the trunk)");
    return problems.Take();
  }
  for (int i = 0; i < tree.size(); ++i) {
    const Branch& b = tree.branches[i];
    const std::string at = fmt::format("branches[{}]", i);
    if (b.id != i) {
      problems.Add(at + ".id",
                   fmt::format("expected id {} (ids are the branch order), got {}", i, b.id));
    }
    if (i == 0 && b.parent != -1) {
      problems.Add(at + ".parent",
                   fmt::format("expected -1 (branch 0 is the trunk), got {}", b.parent));
    }
    if (i > 0 && (b.parent < 0 || b.parent >= i)) {
      problems.Add(at + ".parent",
                   fmt::format("expected a parent id in [0, {}] (parents come before children), "
                               "got {}",
                               i - 1, b.parent));
    }
    if (b.nodes.size() < 2) {
      problems.Add(at + ".nodes", fmt::format("expected at least 2 nodes, got {}", b.nodes.size()));
    }
    for (size_t n = 0; n < b.nodes.size(); ++n) {
      const Node& node = b.nodes[n];
      const std::string nat = fmt::format("{}.nodes[{}]", at, n);
      if (!Finite(node.position)) {
        problems.Add(nat + ".position", "expected finite coordinates, got NaN or infinity");
      }
      if (!std::isfinite(node.radius) || node.radius <= 0.0) {
        problems.Add(nat + ".radius",
                     fmt::format("expected a positive radius, got {}", node.radius));
      }
    }
    const bool parent_ok = i > 0 && b.parent >= 0 && b.parent < i;
    if (parent_ok) {
      const Branch& parent = tree.branches[b.parent];
      const int expected_level = parent.level + 1;
      if (b.level != expected_level) {
        problems.Add(at + ".level", fmt::format("expected {} (parent level + 1), got {}",
                                                expected_level, b.level));
      }
      if (b.parent_node < 0 || b.parent_node >= static_cast<int>(parent.nodes.size())) {
        problems.Add(
            at + ".parent_node",
            fmt::format("expected a node index in [0, {}] of parent branch {}, got {}",
                        static_cast<int>(parent.nodes.size()) - 1, b.parent, b.parent_node));
      } else if (!b.nodes.empty() && Finite(b.nodes.front().position)) {
        const double gap = (b.nodes.front().position - parent.nodes[b.parent_node].position).norm();
        if (!(gap <= options.attachment_tolerance_m)) {
          problems.Add(at + ".nodes[0]",
                       fmt::format("expected to start on node {} of parent branch {} (within {} "
                                   "m), but it is {:.6g} m away",
                                   b.parent_node, b.parent, options.attachment_tolerance_m, gap));
        }
      }
    } else if (i == 0 && b.level != 0) {
      problems.Add(at + ".level", fmt::format("expected 0 for the trunk, got {}", b.level));
    }
    CheckFrame(b.frame, at + ".frame", problems);
    if (b.material) {
      CheckMaterial(*b.material, at + ".material", options, problems);
    } else if (options.require_materials) {
      problems.Add(at + ".material", "expected a material (this tree must be simulation-ready)");
    }
  }
  // Ids are the tracker's: unique and >= 0, not necessarily 0..n-1 (a marker never seen is not
  // on the tree).
  std::set<int> ids;
  for (const Marker& marker : tree.markers) ids.insert(marker.id);
  std::set<int> seen;
  for (size_t m = 0; m < tree.markers.size(); ++m) {
    const Marker& marker = tree.markers[m];
    const std::string at = fmt::format("markers[{}]", m);
    if (marker.id < 0) {
      problems.Add(at + ".id", fmt::format("expected an id >= 0, got {}", marker.id));
    } else if (!seen.insert(marker.id).second) {
      problems.Add(at + ".id", fmt::format("marker id {} appears twice", marker.id));
    }
    if (marker.branch < 0 || marker.branch >= tree.size()) {
      problems.Add(at + ".branch", fmt::format("expected a branch id in [0, {}], got {}",
                                               tree.size() - 1, marker.branch));
    } else {
      const double length = tree.branches[marker.branch].Length();
      if (!std::isfinite(marker.arc_length) || marker.arc_length < 0.0 ||
          marker.arc_length > length + options.attachment_tolerance_m) {
        problems.Add(at + ".arc_length",
                     fmt::format("expected an arc length in [0, {:.6g}] m (the length of branch "
                                 "{}), got {}",
                                 length, marker.branch, marker.arc_length));
      }
    }
    if (marker.parent != -1 && (marker.parent == marker.id || !ids.count(marker.parent))) {
      problems.Add(at + ".parent",
                   fmt::format("expected -1 or the id of another marker, got {}", marker.parent));
    }
    if (!Finite(marker.position)) {
      problems.Add(at + ".position", "expected finite coordinates, got NaN or infinity");
    }
  }
  return problems.Take();
}

void Validate(const Tree& tree, const std::string& source, const ValidationOptions& options) {
  const std::vector<ValidationProblem> problems = FindProblems(tree, options);
  if (problems.empty()) return;
  std::string message = problems.front().message;
  if (problems.size() > 1) message += fmt::format(" (and {} more problems)", problems.size() - 1);
  throw InputError(source, problems.front().where, message);
}

}  // namespace simtree
