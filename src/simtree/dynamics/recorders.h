#pragma once
// What a simulation run writes, one recorder per output (docs/formats.md describes each file):
//   NodeFrameWriter     every node of every frame, compact binary (simtree.node_frames v1)
//   MarkerTrackWriter   marker positions per frame, the trajectory CSV of docs/formats.md
//                       in the world frame, and the markers.json that lists them
//   AnimationRecorder   a skinned glTF 2.0 animation of the tube mesh (Blender, three.js)

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simtree/core/atomic_file.h"
#include "simtree/core/tree.h"
#include "simtree/core/tube_mesh.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/io/gltf_animation.h"
#include "simtree/io/trajectories.h"

namespace simtree::dynamics {

inline constexpr char kNodeFramesMagic[9] = "SIMTNODE";
inline constexpr uint32_t kNodeFramesVersion = 1;

// Streams frames to `path` (written atomically: the file appears complete at End()).
class NodeFrameWriter : public FrameRecorder {
 public:
  explicit NodeFrameWriter(std::filesystem::path path);
  void Begin(const TreeDynamics& sim, int frame_count, double fps) override;
  void Record(int frame, double time_s, const TreeDynamics& sim) override;
  void End() override;

 private:
  std::filesystem::path path_;
  std::unique_ptr<AtomicFile> file_;
  int frames_expected_ = 0, frames_written_ = 0;
};

// The frames of a node-frames file, read back whole (for tests and tools).
struct NodeFrames {
  double fps = 0, start_time_s = 0;
  std::vector<uint32_t> branch_first_node, branch_node_count;
  int node_count = 0, frame_count = 0;
  std::vector<float> xyz;  // frame-major: frame f, node n at 3 (f * node_count + n)
};
// Throws InputError naming the file for a wrong magic, version or size.
NodeFrames ReadNodeFrames(const std::filesystem::path& path);

// Markers to record when a tree has none: the tip of every branch up to `max_level`, plus the
// pulled point (label "pull") when there is a pull. Parents follow the branch hierarchy (a
// marker's parent is the marker on the nearest ancestor branch).
std::vector<Marker> AutoMarkers(const Tree& tree, int max_level,
                                const std::optional<Rope>& pull = std::nullopt);

// The first line of a world-frame trajectory file (the layout of io/trajectories.h, whose files
// are in the pull camera's frame).
inline constexpr const char* kWorldTrajectoriesFirstLine =
    "# simtree.trajectories v1 frame=world units=m";

// Collects marker positions every frame; at End() writes `csv_path` (io/trajectories.h's layout
// with kWorldTrajectoriesFirstLine) and `markers_json_path` (io/capture.h's markers.json).
class MarkerTrackWriter : public FrameRecorder {
 public:
  MarkerTrackWriter(std::vector<Marker> markers, std::filesystem::path csv_path,
                    std::filesystem::path markers_json_path);
  void Begin(const TreeDynamics& sim, int frame_count, double fps) override;
  void Record(int frame, double time_s, const TreeDynamics& sim) override;
  void End() override;
  const std::vector<Marker>& markers() const { return markers_; }
  const Trajectories& trajectories() const { return tracks_; }

 private:
  std::vector<Marker> markers_;
  std::filesystem::path csv_path_, json_path_;
  Trajectories tracks_;
};

struct AnimationOptions {
  // The tube mesh the joints skin (sides >= 3, min_radius >= 0 m).
  TubeMeshOptions mesh = {.sides = 8, .caps = true, .min_radius = 1e-4};
  // Joints (1 to kMaxGltfJoints): one per node while the tree has at most this many nodes, else
  // every k-th node of each branch (and its tip), vertices in between blending the two nearest.
  int max_joints = 16384;
  // Joint keys kept in memory (joints x frames, >= 1); fewer joints when a run is long.
  int64_t max_keys = 8'000'000;
  bool markers = true;  // animate the markers as empty nodes too

  // Throws InputError ("animation options", the field) for a value out of range.
  void Validate() const;
};

// Collects joint transforms every frame; End() writes the glTF file.
class AnimationRecorder : public FrameRecorder {
 public:
  // Throws InputError for options out of range (options.Validate()).
  AnimationRecorder(std::filesystem::path path, std::vector<Marker> markers,
                    AnimationOptions options = {});
  void Begin(const TreeDynamics& sim, int frame_count, double fps) override;
  void Record(int frame, double time_s, const TreeDynamics& sim) override;
  void End() override;
  int joint_count() const { return static_cast<int>(joint_branch_.size()); }

 private:
  std::filesystem::path path_;
  std::vector<Marker> markers_;
  AnimationOptions options_;
  SkinnedAnimation animation_;
  std::vector<int> joint_branch_, joint_node_;
};

}  // namespace simtree::dynamics
