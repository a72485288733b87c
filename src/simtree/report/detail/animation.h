#pragma once
// The simulated motion as the page's 3D view replays it, sent compactly (docs/report.md):
//
//   rest     every node's frame-0 position (16-bit in the box) and radius (0.1 mm steps), once;
//   frames   per sent frame, the positions of the sent nodes only (16-bit in the box).
//
// The sent nodes are every k-th node of each branch and its tip; the page moves the nodes in
// between with the displacement interpolated from their two sent neighbours, on the full rest
// geometry, and rebuilds the tubes every frame. The plan keeps every node and lowers the frame
// rate first, down to a floor; below that it thins the nodes instead.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "simtree/dynamics/recorders.h"
#include "simtree/report/report.h"

namespace simtree::report {

struct AnimationPlan {
  int node_stride = 1;   // every k-th node of each branch, and its tip
  int frame_stride = 1;  // every s-th frame
  int sent_nodes = 0, sent_frames = 0;
  int64_t bytes = 0;  // base64 characters of every array
  bool fits = false;  // false: not even two frames of the fewest nodes fit the budget
};

// Node indices (into the frames' node order) sent at `stride`: per branch 0, k, 2k, ... and the
// last node, in branch order.
std::vector<int> SentNodeIndices(const std::vector<uint32_t>& branch_first_node,
                                 const std::vector<uint32_t>& branch_node_count, int stride);

// The finest plan within `budget_bytes` (base64 characters of all arrays): all nodes at the
// highest frame rate that fits, down to `min_fps`; then fewer nodes.
AnimationPlan PlanAnimation(const dynamics::NodeFrames& frames, int64_t budget_bytes,
                            double min_fps);

// What the page draws besides the motion. Everything is optional.
struct AnimationDecor {
  std::vector<float> radii;                // per node (m); empty: a constant radius
  std::vector<int> branch_level;           // per branch; empty: all 0
  std::vector<std::string> branch_source;  // per branch: measured, interpolated, default
  // The rope of a pull test: the node it is tied to, its anchor, and when it pulls.
  struct Rope {
    int node = 0;
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    double hold_s = 0.0, release_s = 0.0;
  };
  std::optional<Rope> rope;
};

// The JSON the page's viewer reads (arrays base64). Fills `report` (sizes, strides, step).
nlohmann::json AnimationPayload(const dynamics::NodeFrames& frames, const AnimationPlan& plan,
                                const AnimationDecor& decor, AnimationReport* report = nullptr);

}  // namespace simtree::report
