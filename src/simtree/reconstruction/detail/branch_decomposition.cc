#include "simtree/reconstruction/detail/branch_decomposition.h"

#include <algorithm>
#include <cmath>

#include "simtree/core/frames.h"
#include "simtree/core/option_checks.h"

namespace simtree::reconstruction {
namespace {

// Direction from `from` towards the node `steps` down the heaviest path of `child`.
Eigen::Vector3d PathDirection(const Skeleton& skeleton,
                              const std::vector<std::vector<int>>& children,
                              const std::vector<double>& subtree, int from, int child, int steps) {
  int at = child;
  for (int k = 1; k < steps && !children[at].empty(); ++k) {
    at = *std::max_element(children[at].begin(), children[at].end(),
                           [&](int a, int b) { return subtree[a] < subtree[b]; });
  }
  const Eigen::Vector3d d = skeleton.nodes[at].position - skeleton.nodes[from].position;
  return d.norm() > 0 ? d.normalized() : Eigen::Vector3d::UnitZ();
}

}  // namespace

void BranchDecompositionOptions::Validate() const {
  CheckNonNegative("comparable_share", comparable_share);
  CheckAtLeast("straightness_nodes", straightness_nodes, 1);
}

Tree DecomposeIntoBranches(const Skeleton& skeleton, const BranchDecompositionOptions& options,
                           const std::string& source) {
  options.Validate();
  Tree tree;
  tree.metadata.source = source;
  if (skeleton.size() < 2) return tree;
  const auto children = skeleton.Children();
  std::vector<double> carried = skeleton.SubtreeLengths();
  // A child's weight includes its own edge to the fork.
  for (int i = 1; i < skeleton.size(); ++i) {
    carried[i] +=
        (skeleton.nodes[i].position - skeleton.nodes[skeleton.nodes[i].parent].position).norm();
  }

  struct Start {
    int parent_branch;
    int parent_node;  // index on the parent branch
    int fork;         // skeleton node the branch starts at
    int first;        // first skeleton node after the fork (-1 for the trunk)
  };
  std::vector<Start> stack = {{-1, 0, 0, -1}};
  while (!stack.empty()) {
    const Start start = stack.back();
    stack.pop_back();
    Branch branch;
    branch.id = tree.size();
    branch.parent = start.parent_branch;
    branch.parent_node = start.parent_node;
    const SkeletonNode& fork = skeleton.nodes[start.fork];
    // A child starts on its parent's node, with its own radius.
    const double first_radius = start.first >= 0 ? skeleton.nodes[start.first].radius : fork.radius;
    branch.nodes.push_back({fork.position, first_radius});
    std::vector<Start> side;
    int previous = start.fork;
    int at = start.first >= 0 ? start.first : start.fork;
    if (start.first >= 0)
      branch.nodes.push_back({skeleton.nodes[at].position, skeleton.nodes[at].radius});
    for (;;) {
      const auto& kids = children[at];
      if (kids.empty()) break;
      int next = kids[0];
      if (kids.size() > 1) {
        const double heaviest = carried[*std::max_element(
            kids.begin(), kids.end(), [&](int a, int b) { return carried[a] < carried[b]; })];
        const Eigen::Vector3d incoming =
            at == previous
                ? Eigen::Vector3d::UnitZ()
                : (skeleton.nodes[at].position - skeleton.nodes[previous].position).normalized();
        double best_score = -1e9;
        for (const int c : kids) {
          // Among comparable children the straightest wins; otherwise the heaviest.
          const bool comparable = carried[c] >= options.comparable_share * heaviest;
          const double straightness = incoming.dot(
              PathDirection(skeleton, children, carried, at, c, options.straightness_nodes));
          const double score = comparable ? 10.0 + straightness : carried[c] / heaviest;
          if (score > best_score) {
            best_score = score;
            next = c;
          }
        }
      }
      const int here = static_cast<int>(branch.nodes.size()) - 1;
      for (const int c : kids) {
        if (c != next) side.push_back({branch.id, here, at, c});
      }
      previous = at;
      at = next;
      branch.nodes.push_back({skeleton.nodes[at].position, skeleton.nodes[at].radius});
    }
    if (branch.nodes.size() < 2) {
      // A trunk with no growth: give it a second node straight up so it is a valid branch.
      branch.nodes.push_back({fork.position + Eigen::Vector3d(0, 0, 1e-3), fork.radius});
    }
    tree.branches.push_back(std::move(branch));
    // Depth-first, nearest fork to the base first (pushed last, popped first).
    std::reverse(side.begin(), side.end());
    for (const Start& s : side) stack.push_back(s);
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

}  // namespace simtree::reconstruction
