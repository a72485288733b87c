#include "simtree/report/detail/animation.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "simtree/report/detail/base64.h"
#include "simtree/report/detail/quantize.h"

namespace simtree::report {
namespace {

constexpr double kRadiusStepM = 1e-4;  // radii in 0.1 mm steps (up to 6.5 m)

// Characters of everything sent once: rest positions and radii (8 bytes a node) and the branch
// table (about 24 characters a branch in JSON).
int64_t FixedBytes(const dynamics::NodeFrames& frames) {
  return static_cast<int64_t>(Base64Size(static_cast<size_t>(frames.node_count) * 6) +
                              Base64Size(static_cast<size_t>(frames.node_count) * 2)) +
         24 * static_cast<int64_t>(frames.branch_first_node.size()) + 512;
}

int64_t FrameBytes(int sent_nodes, int sent_frames) {
  return static_cast<int64_t>(
      Base64Size(static_cast<size_t>(sent_nodes) * static_cast<size_t>(sent_frames) * 6));
}

int SentFrameCount(int frames, int stride) { return (frames + stride - 1) / stride; }

std::span<const float> FrameSpan(const dynamics::NodeFrames& frames, int f) {
  return {frames.xyz.data() + static_cast<size_t>(f) * frames.node_count * 3,
          static_cast<size_t>(frames.node_count) * 3};
}

}  // namespace

std::vector<int> SentNodeIndices(const std::vector<uint32_t>& branch_first_node,
                                 const std::vector<uint32_t>& branch_node_count, int stride) {
  std::vector<int> sent;
  for (size_t b = 0; b < branch_first_node.size(); ++b) {
    const int first = static_cast<int>(branch_first_node[b]);
    const int count = static_cast<int>(branch_node_count[b]);
    for (int j = 0; j < count; j += stride) sent.push_back(first + j);
    if (count > 0 && (count - 1) % stride != 0) sent.push_back(first + count - 1);
  }
  return sent;
}

AnimationPlan PlanAnimation(const dynamics::NodeFrames& frames, int64_t budget_bytes,
                            double min_fps) {
  AnimationPlan plan;
  if (frames.frame_count < 1 || frames.node_count < 1) return plan;
  const int64_t available = budget_bytes - FixedBytes(frames);
  uint32_t longest = 1;
  for (uint32_t c : frames.branch_node_count) longest = std::max(longest, c);
  const int min_frames = std::min(frames.frame_count, 2);
  for (int k = 1; k <= static_cast<int>(longest); ++k) {
    const int sent_nodes = static_cast<int>(
        SentNodeIndices(frames.branch_first_node, frames.branch_node_count, k).size());
    if (k > 1 && sent_nodes == plan.sent_nodes) continue;  // thinning no longer helps
    int stride = 1;
    if (available > 0) {
      const int64_t per_frame = static_cast<int64_t>(sent_nodes) * 8;  // base64 of 6 bytes
      const int64_t max_frames = std::max<int64_t>(1, available / std::max<int64_t>(per_frame, 1));
      stride = static_cast<int>(
          std::max<int64_t>(1, (frames.frame_count + max_frames - 1) / max_frames));
    } else {
      stride = frames.frame_count;
    }
    stride = std::min(stride, frames.frame_count);
    while (stride < frames.frame_count &&
           FrameBytes(sent_nodes, SentFrameCount(frames.frame_count, stride)) > available) {
      ++stride;
    }
    int sent_frames = SentFrameCount(frames.frame_count, stride);
    const bool fits = FrameBytes(sent_nodes, sent_frames) <= available && sent_frames >= min_frames;
    plan = {k,
            stride,
            sent_nodes,
            sent_frames,
            FixedBytes(frames) + FrameBytes(sent_nodes, sent_frames),
            fits};
    if (fits && frames.fps / stride >= min_fps - 1e-9) return plan;
    if (fits && frames.frame_count == 1) return plan;
  }
  // The fewest nodes: accept whatever frame rate fits (plan.fits says whether anything does).
  return plan;
}

nlohmann::json AnimationPayload(const dynamics::NodeFrames& frames, const AnimationPlan& plan,
                                const AnimationDecor& decor, AnimationReport* report) {
  const std::vector<int> sent =
      SentNodeIndices(frames.branch_first_node, frames.branch_node_count, plan.node_stride);
  // One box over the rest pose and every sent frame.
  QuantisationBox box = QuantisationBox::Of(FrameSpan(frames, 0));
  std::vector<float> picked(sent.size() * 3);
  std::string frame_bytes;
  frame_bytes.reserve(static_cast<size_t>(plan.sent_frames) * sent.size() * 6);
  std::vector<int> frame_indices;
  for (int f = 0; f < frames.frame_count; f += plan.frame_stride) frame_indices.push_back(f);
  for (int f : frame_indices) box.Include(FrameSpan(frames, f));
  for (int f : frame_indices) {
    const std::span<const float> all = FrameSpan(frames, f);
    for (size_t i = 0; i < sent.size(); ++i) {
      for (int a = 0; a < 3; ++a) picked[3 * i + a] = all[3 * static_cast<size_t>(sent[i]) + a];
    }
    AppendQuantised(picked, box, frame_bytes);
  }
  std::string rest;
  AppendQuantised(FrameSpan(frames, 0), box, rest);
  std::string radii;
  for (int n = 0; n < frames.node_count; ++n) {
    const double r =
        decor.radii.size() == static_cast<size_t>(frames.node_count) ? decor.radii[n] : 0.0;
    const auto q = static_cast<uint16_t>(std::clamp(std::round(r / kRadiusStepM), 0.0, 65535.0));
    radii += static_cast<char>(q & 0xff);
    radii += static_cast<char>(q >> 8);
  }
  nlohmann::json branches = nlohmann::json::array();
  for (size_t b = 0; b < frames.branch_first_node.size(); ++b) {
    branches.push_back({frames.branch_first_node[b], frames.branch_node_count[b],
                        b < decor.branch_level.size() ? decor.branch_level[b] : 0,
                        b < decor.branch_source.size() ? decor.branch_source[b] : ""});
  }
  nlohmann::json doc = {
      {"nodes", frames.node_count},
      {"node_stride", plan.node_stride},
      {"sent_nodes", sent.size()},
      {"frames", frame_indices.size()},
      {"frame_dt", plan.frame_stride / frames.fps},
      {"duration_s", (frames.frame_count - 1) / frames.fps},
      {"box",
       {{"min", {box.min.x(), box.min.y(), box.min.z()}},
        {"step", {box.step.x(), box.step.y(), box.step.z()}}}},
      {"radius_step", decor.radii.empty() ? 0.0 : kRadiusStepM},
      {"branches", branches},
      {"rest", Base64Encode(rest)},
      {"radii", Base64Encode(radii)},
      {"positions", Base64Encode(frame_bytes)},
  };
  if (decor.rope) {
    doc["rope"] = {
        {"node", decor.rope->node},
        {"anchor", {decor.rope->anchor.x(), decor.rope->anchor.y(), decor.rope->anchor.z()}},
        {"hold_s", decor.rope->hold_s},
        {"release_s", decor.rope->release_s}};
  }
  if (report) {
    report->present = true;
    report->nodes = frames.node_count;
    report->frames = frames.frame_count;
    report->sent_nodes = static_cast<int>(sent.size());
    report->sent_frames = static_cast<int>(frame_indices.size());
    report->node_stride = plan.node_stride;
    report->frame_stride = plan.frame_stride;
    report->fps = frames.fps;
    report->sent_fps = frames.fps / plan.frame_stride;
    report->quantisation_step_m = box.max_step();
    report->bytes = static_cast<int64_t>(doc["rest"].get_ref<const std::string&>().size() +
                                         doc["radii"].get_ref<const std::string&>().size() +
                                         doc["positions"].get_ref<const std::string&>().size());
  }
  return doc;
}

}  // namespace simtree::report
