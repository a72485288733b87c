#pragma once
// The simulation-ready tree: the one data model every stage shares (DESIGN.md).
//
// A Tree is a list of branches whose index is their id. Branch 0 is the trunk (parent -1); every
// other branch starts on a node of its parent (`parent_node`), and parents come before children.
// Geometry is a polyline of nodes (position in the world frame at rest, radius) from base to tip,
// i.e. a generalized cylinder. A branch carries a local frame (u, v, w) with v along the branch
// (paper Fig. 9) and, once materials are known, three modes: bending along u, bending along w and
// twist about v, each with a natural frequency and a damping ratio (paper Eq. 5-6).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace simtree {

struct Node {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // metres, world frame, rest pose
  double radius = 0.0;                                 // metres
};

// Right-handed orthonormal frame of a branch: v along the branch (base to tip), u and w across it;
// u x v = w.
struct Frame {
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d v = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d w = -Eigen::Vector3d::UnitY();
};

enum class ModeKind { kBendU = 0, kBendW = 1, kTwistV = 2 };

struct Mode {
  ModeKind kind = ModeKind::kBendU;
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
};

// Where a material value came from: measured on this branch, interpolated from measured branches,
// a default (imported from a parameter file, or the viewer's demo values), or assumed for a tree
// without a pull test (typical values of its kind of tree, `simtree build --species`).
enum class MaterialSource { kMeasured, kInterpolated, kDefault, kAssumed };

// Modal material of one branch. `mass_kg` is the modal mass m of paper Eq. 6 (modes normalised to
// a unit tip deflection), so a static tip force F bends the branch by F / k with
// k = 4 m pi^2 f^2. `stiffness` is k of the first mode, kept because the paper's parameter files
// give it; it always equals ModalStiffness(mass_kg, modes[0].frequency_hz).
struct Material {
  std::array<Mode, 3> modes = {Mode{ModeKind::kBendU, 0, 0}, Mode{ModeKind::kBendW, 0, 0},
                               Mode{ModeKind::kTwistV, 0, 0}};
  double mass_kg = 0.0;
  double stiffness = 0.0;  // N/m
  MaterialSource source = MaterialSource::kDefault;
  // Why a measured value was flagged uncertain by `simtree build` (its standard deviation, or how
  // far it lies from the other branches); empty when it was not. The branch keeps `measured` when
  // the value was kept, `interpolated` when the interpolation replaced it.
  std::string uncertain;

  // One frequency and damping for all three modes, with the stiffness k (the paper's parameter
  // line "f zeta k"); the mass follows from k and f.
  static Material FromFrequencyDampingStiffness(double frequency_hz, double damping_ratio,
                                                double stiffness, MaterialSource source);
  const Mode& mode(ModeKind kind) const { return modes[static_cast<int>(kind)]; }
  Mode& mode(ModeKind kind) { return modes[static_cast<int>(kind)]; }
  // Sets k and keeps the frequencies: the mass changes.
  void SetStiffness(double k);
  // Sets a mode's frequency and keeps the mass; k follows when it is the first mode.
  void SetFrequency(ModeKind kind, double frequency_hz);
};

struct Branch {
  int id = 0;
  int parent = -1;      // -1 for the trunk
  int parent_node = 0;  // index of the node on the parent where this branch starts
  int level = 0;        // trunk 0, its children 1, ...
  std::vector<Node> nodes;
  Frame frame;
  std::optional<Material> material;

  bool is_trunk() const { return parent < 0; }
  const Node& base() const { return nodes.front(); }
  const Node& tip() const { return nodes.back(); }
  double Length() const;
  // Cumulative arc length at every node: 0 at the base, Length() at the tip.
  std::vector<double> ArcLengths() const;
  // Position at arc length s (clamped to [0, Length()]), linearly interpolated between nodes.
  Eigen::Vector3d PointAt(double arc_length) const;
  // Volume of the frustums between consecutive nodes (m^3).
  double Volume() const;
};

// A visual marker (red tape) on a branch, at an arc length from the branch base. `parent` links
// markers into the simplified tree of paper Fig. 8 (-1 for the root marker).
struct Marker {
  int id = 0;
  std::string label;
  int branch = 0;
  double arc_length = 0.0;  // metres from the branch base
  int parent = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // rest position, world frame
};

struct TreeMetadata {
  std::string species;      // e.g. "acer_rubrum", or empty when unknown
  std::string source;       // where the tree came from, e.g. "synth seed 7", "legacy tree01.txt"
  std::string units = "m";  // always metres inside simtree; kept so files say so
};

struct Tree {
  TreeMetadata metadata;
  std::vector<Branch> branches;
  std::vector<Marker> markers;

  bool empty() const { return branches.empty(); }
  int size() const { return static_cast<int>(branches.size()); }
  const Branch& trunk() const { return branches.front(); }
  // True when every branch has a material (the tree can be simulated).
  bool IsSimulationReady() const;
  // Child ids of every branch, in id order.
  std::vector<std::vector<int>> Children() const;
  // Branch ids in depth-first pre-order from the trunk (children in id order).
  std::vector<int> DepthFirstOrder() const;
  int MaxLevel() const;
  int NodeCount() const;
  // Axis-aligned bounds of all nodes, each grown by its radius.
  void Bounds(Eigen::Vector3d* min_corner, Eigen::Vector3d* max_corner) const;
};

const char* ToString(ModeKind kind);
const char* ToString(MaterialSource source);

}  // namespace simtree
