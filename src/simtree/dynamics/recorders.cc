#include "simtree/dynamics/recorders.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/capture.h"

namespace simtree::dynamics {
namespace {

template <typename T>
void Put(std::ostream& out, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // x86 and ARM are little-endian, as the format is
  out.write(bytes, sizeof(T));
}

template <typename T>
T Get(const std::string& data, size_t& at, const std::string& source) {
  if (at + sizeof(T) > data.size()) {
    throw InputError(source, fmt::format("byte {}", at), "expected more data: file truncated");
  }
  T value;
  std::memcpy(&value, data.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

constexpr size_t kNodeFramesFixedHeader = 48;

}  // namespace

// ---- Node frames

NodeFrameWriter::NodeFrameWriter(std::filesystem::path path) : path_(std::move(path)) {}

void NodeFrameWriter::Begin(const TreeDynamics& sim, int frame_count, double fps) {
  file_ = std::make_unique<AtomicFile>(path_, /*binary=*/true);
  std::ostream& out = file_->stream();
  const uint32_t branches = static_cast<uint32_t>(sim.branch_count());
  out.write(kNodeFramesMagic, 8);
  Put<uint32_t>(out, kNodeFramesVersion);
  Put<uint32_t>(out, static_cast<uint32_t>(kNodeFramesFixedHeader + 8 * branches));
  Put<uint32_t>(out, branches);
  Put<uint32_t>(out, static_cast<uint32_t>(sim.node_count()));
  Put<uint32_t>(out, static_cast<uint32_t>(frame_count));
  Put<uint32_t>(out, 0);  // flags
  Put<double>(out, fps);
  Put<double>(out, 0.0);  // time of frame 0
  for (int b = 0; b < sim.branch_count(); ++b) {
    Put<uint32_t>(out, static_cast<uint32_t>(sim.node_offset(b)));
    Put<uint32_t>(out, static_cast<uint32_t>(sim.tree().branches[b].nodes.size()));
  }
  frames_expected_ = frame_count;
  frames_written_ = 0;
}

void NodeFrameWriter::Record(int frame, double time_s, const TreeDynamics& sim) {
  const auto positions = sim.node_positions();
  static_assert(sizeof(Eigen::Vector3f) == 12);
  file_->stream().write(reinterpret_cast<const char*>(positions.data()),
                        static_cast<std::streamsize>(positions.size() * 12));
  ++frames_written_;
}

void NodeFrameWriter::End() {
  if (frames_written_ != frames_expected_) {
    throw Error(fmt::format("{}: wrote {} frames, expected {}", path_.string(), frames_written_,
                            frames_expected_));
  }
  file_->Commit();
  file_.reset();
}

NodeFrames ReadNodeFrames(const std::filesystem::path& path) {
  const std::string data = ReadFile(path);
  const std::string source = path.string();
  size_t at = 0;
  if (data.size() < 8 || std::memcmp(data.data(), kNodeFramesMagic, 8) != 0) {
    throw InputError(source, "byte 0", "expected the magic \"SIMTNODE\" of a node-frames file");
  }
  at = 8;
  NodeFrames f;
  const auto version = Get<uint32_t>(data, at, source);
  if (version != kNodeFramesVersion) {
    throw InputError(source, "version",
                     fmt::format("expected version {}, got {}", kNodeFramesVersion, version));
  }
  const auto header = Get<uint32_t>(data, at, source);
  const auto branches = Get<uint32_t>(data, at, source);
  f.node_count = static_cast<int>(Get<uint32_t>(data, at, source));
  f.frame_count = static_cast<int>(Get<uint32_t>(data, at, source));
  Get<uint32_t>(data, at, source);  // flags
  f.fps = Get<double>(data, at, source);
  f.start_time_s = Get<double>(data, at, source);
  if (header != kNodeFramesFixedHeader + 8ull * branches) {
    throw InputError(source, "header_bytes",
                     fmt::format("expected {} for {} branches, got {}",
                                 kNodeFramesFixedHeader + 8ull * branches, branches, header));
  }
  for (uint32_t b = 0; b < branches; ++b) {
    f.branch_first_node.push_back(Get<uint32_t>(data, at, source));
    f.branch_node_count.push_back(Get<uint32_t>(data, at, source));
  }
  const size_t payload = 12ull * f.node_count * f.frame_count;
  if (data.size() != header + payload) {
    throw InputError(source, "size",
                     fmt::format("expected {} bytes for {} frames of {} nodes, got {}",
                                 header + payload, f.frame_count, f.node_count, data.size()));
  }
  f.xyz.resize(payload / 4);
  std::memcpy(f.xyz.data(), data.data() + header, payload);
  return f;
}

// ---- Markers

std::vector<Marker> AutoMarkers(const Tree& tree, int max_level, const std::optional<Rope>& pull) {
  std::vector<Marker> markers;
  std::vector<int> tip_marker(tree.size(), -1);
  for (const Branch& b : tree.branches) {
    if (b.level > max_level) continue;
    Marker m;
    m.id = static_cast<int>(markers.size());
    m.label = fmt::format("B{}_tip", b.id);
    m.branch = b.id;
    m.arc_length = b.Length();
    m.position = b.tip().position;
    for (int a = b.parent; a >= 0; a = tree.branches[a].parent) {
      if (tip_marker[a] >= 0) {
        m.parent = tip_marker[a];
        break;
      }
    }
    tip_marker[b.id] = m.id;
    markers.push_back(m);
  }
  if (pull) {
    const Branch& b = tree.branches.at(pull->branch);
    const double s = pull->arc_length < 0.0 ? b.Length() : std::min(pull->arc_length, b.Length());
    Marker m;
    m.id = static_cast<int>(markers.size());
    m.label = "pull";
    m.branch = b.id;
    m.arc_length = s;
    m.position = b.PointAt(s);
    for (int a = b.id; a >= 0; a = tree.branches[a].parent) {
      if (tip_marker[a] >= 0 && a != b.id) {
        m.parent = tip_marker[a];
        break;
      }
    }
    markers.push_back(m);
  }
  return markers;
}

MarkerTrackWriter::MarkerTrackWriter(std::vector<Marker> markers, std::filesystem::path csv_path,
                                     std::filesystem::path markers_json_path)
    : markers_(std::move(markers)),
      csv_path_(std::move(csv_path)),
      json_path_(std::move(markers_json_path)) {}

void MarkerTrackWriter::Begin(const TreeDynamics& sim, int frame_count, double fps) {
  tracks_ = Trajectories{};
  for (const Marker& m : markers_) {
    if (m.branch < 0 || m.branch >= sim.branch_count()) {
      throw InputError(
          "markers", fmt::format("marker {}", m.id),
          fmt::format("expected a branch id in [0, {}], got {}", sim.branch_count() - 1, m.branch));
    }
    MarkerTrack track;
    track.marker = m.id;
    track.positions.reserve(frame_count);
    track.valid.reserve(frame_count);
    tracks_.tracks.push_back(std::move(track));
  }
}

void MarkerTrackWriter::Record(int frame, double time_s, const TreeDynamics& sim) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(markers_.size());
  for (const Marker& m : markers_) positions.push_back(sim.PointPosition(m.branch, m.arc_length));
  tracks_.AddFrame(frame, time_s, positions, std::vector<bool>(markers_.size(), true));
}

void MarkerTrackWriter::End() {
  std::vector<MarkerLink> links;
  for (const Marker& m : markers_) links.push_back({m.id, m.label, m.parent, m.branch});
  WriteMarkersJson(links, json_path_);
  // io's formatter, with the first line saying these are world coordinates.
  std::string csv = TrajectoriesToCsv(tracks_);
  csv.replace(0, csv.find('\n'), kWorldTrajectoriesFirstLine);
  WriteFileAtomically(csv_path_, csv);
}

// ---- glTF animation

void AnimationOptions::Validate() const {
  const std::string source = "animation options";
  CheckOption(mesh.sides >= 3, source, "mesh.sides",
              fmt::format("expected 3 or more sides, got {}", mesh.sides));
  CheckOption(std::isfinite(mesh.min_radius) && mesh.min_radius >= 0.0, source, "mesh.min_radius",
              fmt::format("expected a radius >= 0 m, got {}", mesh.min_radius));
  CheckOption(max_joints >= 1 && max_joints <= kMaxGltfJoints, source, "max_joints",
              fmt::format("expected 1 to {} joints, got {}", kMaxGltfJoints, max_joints));
  CheckOption(max_keys >= 1, source, "max_keys", fmt::format("expected >= 1, got {}", max_keys));
}

AnimationRecorder::AnimationRecorder(std::filesystem::path path, std::vector<Marker> markers,
                                     AnimationOptions options)
    : path_(std::move(path)), markers_(std::move(markers)), options_(options) {
  options_.Validate();
}

void AnimationRecorder::Begin(const TreeDynamics& sim, int frame_count, double fps) {
  const Tree& tree = sim.tree();
  const int64_t budget = std::max<int64_t>(1, options_.max_keys / std::max(1, frame_count));
  const int64_t max_joints =
      std::clamp<int64_t>(std::min<int64_t>(options_.max_joints, budget), 1, kMaxGltfJoints);
  // Every k-th node of a branch (and its tip) carries a joint.
  int stride = 1;
  auto count_joints = [&](int k) {
    int64_t n = 0;
    for (const Branch& b : tree.branches) {
      const int nodes = static_cast<int>(b.nodes.size());
      n += (nodes - 1 + k - 1) / k + 1;
    }
    return n;
  };
  while (count_joints(stride) > max_joints) ++stride;
  if (count_joints(stride) > max_joints) {
    throw InputError("glTF animation", "joints",
                     fmt::format("the tree has {} branches, more than the {} joints allowed; "
                                 "raise the joint limit or leave the glTF out",
                                 tree.size(), max_joints));
  }
  animation_ = SkinnedAnimation{};
  animation_.name = tree.metadata.species.empty() ? "tree" : tree.metadata.species;
  joint_branch_.clear();
  joint_node_.clear();
  std::vector<std::vector<int>> node_joint(tree.size());  // joint of each joint node, else -1
  for (const Branch& b : tree.branches) {
    const int nodes = static_cast<int>(b.nodes.size());
    node_joint[b.id].assign(nodes, -1);
    for (int j = 0; j < nodes; ++j) {
      if (j % stride == 0 || j == nodes - 1) {
        node_joint[b.id][j] = joint_count();
        joint_branch_.push_back(b.id);
        joint_node_.push_back(j);
        animation_.joint_rest.push_back(b.nodes[j].position.cast<float>());
        animation_.joint_names.push_back(fmt::format("branch {} node {}", b.id, j));
      }
    }
  }
  // The tube mesh, branch by branch; a ring's arc length (its v texture coordinate) names its node.
  TriangleMesh& mesh = animation_.mesh;
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> radii;
  for (const Branch& b : tree.branches) {
    centers.clear();
    radii.clear();
    for (const Node& n : b.nodes) {
      centers.push_back(n.position);
      radii.push_back(n.radius);
    }
    const size_t first = mesh.vertices.size();
    AppendTube(centers, radii, b.frame.u, b.id, options_.mesh, mesh);
    const std::vector<double> s = b.ArcLengths();
    const std::vector<int>& joints = node_joint[b.id];
    for (size_t v = first; v < mesh.vertices.size(); ++v) {
      const double arc = mesh.uvs[v].y();
      const auto it = std::lower_bound(s.begin(), s.end(), arc - 1e-5);
      const int node =
          std::clamp(static_cast<int>(it - s.begin()), 0, static_cast<int>(s.size()) - 1);
      // The joint nodes around `node`.
      int below = node, above = node;
      while (joints[below] < 0) --below;
      while (joints[above] < 0) ++above;
      float w_above = 0.f;
      if (above != below)
        w_above = static_cast<float>((s[node] - s[below]) / (s[above] - s[below]));
      animation_.vertex_joints.push_back(
          {static_cast<uint16_t>(joints[below]), static_cast<uint16_t>(joints[above])});
      animation_.vertex_weights.push_back({1.f - w_above, w_above});
    }
  }
  if (options_.markers) {
    for (const Marker& m : markers_) animation_.point_names.push_back("marker " + m.label);
  }
  animation_.times.reserve(frame_count);
  animation_.translations.reserve(static_cast<size_t>(frame_count) * joint_count());
  animation_.rotations.reserve(static_cast<size_t>(frame_count) * joint_count());
}

void AnimationRecorder::Record(int frame, double time_s, const TreeDynamics& sim) {
  animation_.times.push_back(static_cast<float>(time_s));
  const auto positions = sim.node_positions();
  for (int j = 0; j < joint_count(); ++j) {
    const int b = joint_branch_[j], n = joint_node_[j];
    animation_.translations.push_back(positions[sim.node_offset(b) + n]);
    animation_.rotations.emplace_back(Eigen::Quaterniond(sim.NodeRotation(b, n)).cast<float>());
  }
  if (options_.markers) {
    for (const Marker& m : markers_) {
      animation_.point_positions.push_back(sim.PointPosition(m.branch, m.arc_length).cast<float>());
    }
  }
}

void AnimationRecorder::End() { WriteGltfAnimation(animation_, path_); }

}  // namespace simtree::dynamics
