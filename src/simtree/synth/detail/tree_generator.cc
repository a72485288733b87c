#include "simtree/synth/detail/tree_generator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "simtree/core/frames.h"
#include "simtree/core/units.h"
#include "simtree/core/validate.h"
#include "simtree/synth/detail/segment_grid.h"

namespace simtree::synth {
namespace {

using Vec3 = Eigen::Vector3d;

class Random {
 public:
  explicit Random(uint64_t seed) : engine_(seed) {}
  double Uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(engine_);
  }
  double Symmetric() { return Uniform(-1.0, 1.0); }  // uniform in [-1, 1)

 private:
  std::mt19937_64 engine_;
};

// Uniform draws in [0, 1) taken in blocks of kBlock: one in each 1/kBlock of the interval, in
// random order. Any one draw is uniform; a block's draws are spread evenly.
class StratifiedDraws {
 public:
  double Next(Random& rng) {
    if (next_ == kBlock) {
      for (int i = 0; i < kBlock; ++i) block_[i] = (i + rng.Uniform(0.0, 1.0)) / kBlock;
      for (int i = kBlock - 1; i > 0; --i) {
        std::swap(block_[i], block_[std::min(i, static_cast<int>(rng.Uniform(0.0, i + 1.0)))]);
      }
      next_ = 0;
    }
    return block_[next_++];
  }

 private:
  static constexpr int kBlock = 4;
  std::array<double, kBlock> block_ = {};
  int next_ = kBlock;
};

// The low-frequency waviness of one axis: per bending plane a curvature amplitude (rad/m), a
// wavenumber (rad/m) and a phase.
struct Waves {
  std::array<double, 2> amplitude = {0, 0};
  std::array<double, 2> wavenumber = {0, 0};
  std::array<double, 2> phase = {0, 0};
};

Waves DrawWaves(const AxisShape& shape, Random& rng) {
  Waves waves;
  for (int i = 0; i < 2; ++i) {
    const double wavelength = shape.bend_wavelength_m * rng.Uniform(0.75, 1.25);
    // A half-wave of curvature A sin(k s) turns the axis by A * wavelength / pi.
    waves.amplitude[i] = DegToRad(shape.bend_angle_deg) * kPi / wavelength * rng.Uniform(0.6, 1.0);
    waves.wavenumber[i] = kTwoPi / wavelength;
    waves.phase[i] = rng.Uniform(0.0, kTwoPi);
  }
  return waves;
}

int SegmentCount(double length, double node_spacing) {
  return std::max(2, static_cast<int>(std::lround(length / node_spacing)));
}

// The polyline of an axis of arc length `length` in `segments` equal segments, integrated in
// small steps from `base` along `direction`: curvature from the two waves (in a frame transported
// along the axis, so the waves do not twist) and tropism towards +Z.
std::vector<Vec3> IntegrateAxis(const Vec3& base, const Vec3& direction, double length,
                                int segments, const AxisShape& shape, const Waves& waves) {
  constexpr int kSubsteps = 8;
  const int steps = segments * kSubsteps;
  const double ds = length / steps;
  const Vec3 up = Vec3::UnitZ();
  Vec3 d = direction.normalized();
  Vec3 e = d.unitOrthogonal();
  Vec3 p = base;
  std::vector<Vec3> points;
  points.reserve(segments + 1);
  points.push_back(base);
  for (int i = 0; i < steps; ++i) {
    const double s = (i + 0.5) * ds;
    const double tropism = shape.tropism_base_per_m +
                           (shape.tropism_tip_per_m - shape.tropism_base_per_m) * s / length;
    const Vec3 f = d.cross(e);
    const Vec3 turn = waves.amplitude[0] * std::sin(waves.wavenumber[0] * s + waves.phase[0]) * e +
                      waves.amplitude[1] * std::sin(waves.wavenumber[1] * s + waves.phase[1]) * f +
                      tropism * (up - up.dot(d) * d);
    const Vec3 next = (d + ds * turn).normalized();
    p += ds * (d + next).normalized();
    e = (e - e.dot(next) * next).normalized();
    d = next;
    if ((i + 1) % kSubsteps == 0) points.push_back(p);
  }
  return points;
}

// Unit tangent at node i: the bisector of the adjacent segments.
Vec3 TangentAt(const std::vector<Vec3>& points, size_t i) {
  Vec3 t = Vec3::Zero();
  if (i > 0) t += (points[i] - points[i - 1]).normalized();
  if (i + 1 < points.size()) t += (points[i + 1] - points[i]).normalized();
  return t.norm() > 1e-12 ? Vec3(t.normalized()) : Vec3::UnitZ();
}

// Normals transported along the polyline without twist: the zero of every bud azimuth.
std::vector<Vec3> TransportedNormals(const std::vector<Vec3>& points) {
  std::vector<Vec3> normals(points.size());
  Vec3 n = TangentAt(points, 0).unitOrthogonal();
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 t = TangentAt(points, i);
    Vec3 projected = n - n.dot(t) * t;
    n = projected.norm() > 1e-9 ? Vec3(projected.normalized()) : t.unitOrthogonal();
    normals[i] = n;
  }
  return normals;
}

// An axis grown so far.
struct Axis {
  int parent = -1;
  int parent_node = 0;
  int level = 0;
  double length = 0.0;
  double estimated_radius = 0.0;  // for the clearance check only
  std::vector<Vec3> points;
};

// A bud about to grow into an axis.
struct Candidate {
  int parent = 0;
  int parent_node = 0;
  int level = 1;
  Vec3 tangent = Vec3::UnitZ();  // parent's tangent at the node
  Vec3 normal = Vec3::UnitX();   // zero azimuth around it
  double azimuth = 0.0;          // radians, before jitter
  double angle_deg = 45.0;
  double angle_spread_deg = 10.0;
  double length = 0.0;
};

Vec3 DirectionFrom(const Candidate& c, double angle, double azimuth) {
  const Vec3 binormal = c.tangent.cross(c.normal);
  const Vec3 out = std::cos(azimuth) * c.normal + std::sin(azimuth) * binormal;
  return std::cos(angle) * c.tangent + std::sin(angle) * out;
}

// Length share of a level-1 lateral at crown position t in [0, 1] (species.h, crown profile).
double CrownProfile(const SpeciesParams& p, double t) {
  const double peak = p.crown_peak_position, k = p.crown_sharpness;
  const double rise = peak > 0.0 ? std::pow(std::clamp(t / peak, 0.0, 1.0e9), k * peak) : 1.0;
  const double fall =
      peak < 1.0 ? std::pow(std::clamp((1.0 - t) / (1.0 - peak), 0.0, 1.0e9), k * (1.0 - peak))
                 : 1.0;
  return p.crown_floor + (1.0 - p.crown_floor) * std::min(1.0, rise * fall);
}

class Grower {
 public:
  Grower(const SpeciesParams& species, uint64_t seed, const GeneratorOptions& options)
      : species_(species), options_(options), seed_(seed), rng_(seed) {}

  TreeGenerationResult Grow() {
    TreeGenerationResult result;
    height_ = species_.height_m * (1.0 + species_.height_spread * rng_.Symmetric());
    const double radius_spread = 1.0 + species_.trunk_radius_spread * rng_.Symmetric();
    // While growing, the clearance check guesses radii from a trunk of a typical tree of this
    // height; the final trunk radius follows the finished tree's longest path (header, step 9).
    estimated_trunk_radius_ =
        species_.trunk_base_radius_m * std::pow(height_ / species_.height_m, 1.5) * radius_spread;
    GrowTrunk();
    for (int level = 1; level <= species_.branching_levels(); ++level) {
      std::vector<Candidate> candidates;
      for (int parent = 0; parent < static_cast<int>(axes_.size()); ++parent) {
        if (axes_[parent].level != level - 1) continue;
        AddLateralBuds(parent, level, candidates);
        if (parent == 0 && species_.trunk.fork_count >= 2) AddForkStems(candidates);
      }
      KeepWithinBudget(candidates);
      for (const Candidate& c : candidates) TryToGrow(c);
    }
    result.scale = ScaleToHeight();
    result.longest_path_m = LongestPathToTip();
    trunk_radius_ =
        species_.trunk_base_radius_m *
        std::pow(result.longest_path_m / (species_.longest_path_ratio * species_.height_m), 1.5) *
        radius_spread;
    result.tree = BuildTree(&result.tip_radius_m);
    result.height_m = height_;
    result.trunk_base_radius_m = trunk_radius_;
    result.redrawn_directions = redrawn_;
    result.dropped_crowded = dropped_crowded_;
    result.dropped_budget = dropped_budget_;
    result.stopped_at_ground = stopped_at_ground_;
    result.branches_per_level.assign(species_.branching_levels() + 1, 0);
    for (const Axis& a : axes_) ++result.branches_per_level[a.level];
    return result;
  }

 private:
  // Base radius of an axis of `length`, before the pipe model knows it.
  double EstimatedRadius(double length) const {
    const double r = estimated_trunk_radius_ * std::pow(length / height_, 1.3);
    return std::clamp(r, species_.min_twig_radius_m, estimated_trunk_radius_);
  }
  // Estimated radius at arc length s of an axis with base radius r0: tapering to a quarter.
  double EstimatedRadiusAt(double r0, double s, double length) const {
    return std::max(species_.min_twig_radius_m, r0 * (1.0 - 0.75 * s / length));
  }

  double Clearance(double r1, double r2) const {
    return std::max(options_.min_clearance_m, options_.clearance_radii * (r1 + r2));
  }

  void AddAxis(Axis axis) {
    const int id = static_cast<int>(axes_.size());
    const double segment = axis.length / (axis.points.size() - 1);
    for (size_t i = 1; i < axis.points.size(); ++i) {
      const double r = EstimatedRadiusAt(axis.estimated_radius, (i - 1) * segment, axis.length);
      grid_.Add({axis.points[i - 1], axis.points[i], r, id, static_cast<int>(i - 1)});
    }
    nodes_ += static_cast<int>(axis.points.size());
    axes_.push_back(std::move(axis));
  }

  void GrowTrunk() {
    const TrunkParams& trunk = species_.trunk;
    const double length = trunk.length_fraction * height_;
    const double lean = DegToRad(trunk.lean_deg) * rng_.Uniform(0.0, 1.0);
    const double lean_azimuth = rng_.Uniform(0.0, kTwoPi);
    const Vec3 direction(std::sin(lean) * std::cos(lean_azimuth),
                         std::sin(lean) * std::sin(lean_azimuth), std::cos(lean));
    const Waves waves = DrawWaves(trunk.shape, rng_);
    Axis axis;
    axis.length = length;
    axis.estimated_radius = estimated_trunk_radius_;
    axis.points =
        IntegrateAxis(Vec3::Zero(), direction, length,
                      SegmentCount(length, trunk.shape.node_spacing_m), trunk.shape, waves);
    AddAxis(std::move(axis));
  }

  // Buds along `parent` at botanical nodes; those that break become candidates of `level`.
  void AddLateralBuds(int parent, int level, std::vector<Candidate>& out) {
    const Axis& axis = axes_[parent];
    const bool from_trunk = parent == 0;
    const BudPattern& buds = from_trunk ? species_.trunk.buds : species_.levels[level - 2].buds;
    const LevelParams& child = species_.levels[level - 1];
    const int n = static_cast<int>(axis.points.size());
    const double segment = axis.length / (n - 1);
    const double start_fraction = from_trunk ? species_.trunk.clear_bole_fraction
                                             : species_.levels[level - 2].branching_start_fraction;
    const double start = start_fraction * axis.length;
    // Laterals stop short of the tip (a forked trunk's tip carries the stems).
    const bool forked = from_trunk && species_.trunk.fork_count >= 2;
    const double end = axis.length - (forked ? 0.5 * buds.spacing_m : 0.5 * segment);
    const std::vector<Vec3> normals = TransportedNormals(axis.points);
    const int buds_per_node = species_.phyllotaxis == Phyllotaxis::kOpposite ? 2 : 1;
    const double divergence = DegToRad(species_.divergence_angle_deg);
    const double jitter = DegToRad(species_.phyllotaxis_jitter_deg);
    double phase = rng_.Uniform(0.0, kTwoPi);
    int last_node = -1;
    int k = 0;
    // The buds of one node share their vigour, so an opposite pair breaks together (each bud
    // still breaks with its own probability). Vigour is drawn stratified in blocks of nodes, so
    // an axis grows close to its expected number of children (few long branches without any)
    // and trees of one species have similar branch counts.
    StratifiedDraws vigour_draws;
    for (double s = start + buds.spacing_m * rng_.Uniform(0.0, 1.0); s < end;
         s += buds.spacing_m * rng_.Uniform(0.85, 1.15), ++k) {
      // The axis twists a little from node to node: without it, decussate pairs would stack
      // in four exact directions.
      phase += jitter * rng_.Symmetric();
      const int node = std::clamp(static_cast<int>(std::lround(s / segment)), 1, n - 2);
      if (node == last_node) continue;
      last_node = node;
      const double arc = node * segment;
      const double vigour = vigour_draws.Next(rng_);
      for (int b = 0; b < buds_per_node; ++b) {
        Candidate c;
        c.parent = parent;
        c.parent_node = node;
        c.level = level;
        c.tangent = TangentAt(axis.points, node);
        c.normal = normals[node];
        c.azimuth = phase + k * divergence + b * kPi;
        c.angle_deg = child.branching_angle_deg;
        c.angle_spread_deg = child.branching_angle_spread_deg;
        const Vec3 bud_out = DirectionFrom(c, kPi / 2, c.azimuth);
        const double p =
            buds.break_probability * (1.0 - buds.lateral_preference * std::abs(bud_out.z()));
        // Draw the length even for buds that do not break, so the draws that follow do not
        // depend on which buds broke.
        const double spread = 1.0 + child.length_spread * rng_.Symmetric();
        const bool breaks = vigour < p;
        if (from_trunk) {
          const double crown = axis.length - start;
          const double t = crown > 0 ? std::clamp((arc - start) / crown, 0.0, 1.0) : 0.0;
          c.length = child.length_ratio * height_ * CrownProfile(species_, t) * spread;
        } else {
          c.length =
              child.length_ratio * spread * (axis.length - child.remaining_length_weight * arc);
        }
        if (breaks && c.length >= species_.min_branch_length_m) out.push_back(c);
      }
    }
  }

  // The co-dominant stems at the tip of a forked trunk.
  void AddForkStems(std::vector<Candidate>& out) {
    const TrunkParams& trunk = species_.trunk;
    const Axis& axis = axes_[0];
    const int tip = static_cast<int>(axis.points.size()) - 1;
    const double above = std::max(0.2 * height_, height_ - axis.points.back().z());
    const double phase = rng_.Uniform(0.0, kTwoPi);
    for (int j = 0; j < trunk.fork_count; ++j) {
      Candidate c;
      c.parent = 0;
      c.parent_node = tip;
      c.level = 1;
      c.tangent = TangentAt(axis.points, tip);
      c.normal = TransportedNormals(axis.points).back();
      c.azimuth = phase + j * kTwoPi / trunk.fork_count;
      c.angle_deg = trunk.fork_angle_deg;
      c.angle_spread_deg = trunk.fork_angle_spread_deg;
      c.length = trunk.fork_length_ratio * above *
                 (1.0 + 0.5 * species_.levels[0].length_spread * rng_.Symmetric());
      out.push_back(c);
    }
  }

  // Drops the shortest candidates when the level would pass the branch or node budget.
  void KeepWithinBudget(std::vector<Candidate>& candidates) {
    std::vector<int> order(candidates.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return candidates[a].length > candidates[b].length; });
    std::vector<bool> keep(candidates.size(), false);
    int branches = static_cast<int>(axes_.size()), nodes = nodes_;
    for (const int i : order) {
      const LevelParams& level = species_.levels[candidates[i].level - 1];
      const int n = SegmentCount(candidates[i].length, level.shape.node_spacing_m) + 1;
      if (branches + 1 > options_.max_branches || nodes + n > options_.max_nodes) continue;
      keep[i] = true;
      ++branches;
      nodes += n;
    }
    std::vector<Candidate> kept;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (keep[i]) {
        kept.push_back(candidates[i]);
      } else {
        ++dropped_budget_;
      }
    }
    candidates = std::move(kept);
  }

  // Grows a candidate, drawing its direction again while it crowds an existing axis.
  void TryToGrow(const Candidate& c) {
    const LevelParams& level = species_.levels[c.level - 1];
    const int segments = SegmentCount(c.length, level.shape.node_spacing_m);
    const Waves waves = DrawWaves(level.shape, rng_);
    const double radius = EstimatedRadius(c.length);
    const Vec3 base = axes_[c.parent].points[c.parent_node];
    for (int attempt = 0; attempt < std::max(1, options_.max_direction_tries); ++attempt) {
      if (attempt > 0) ++redrawn_;
      const double angle = DegToRad(c.angle_deg + c.angle_spread_deg * rng_.Symmetric());
      const double azimuth =
          c.azimuth + DegToRad(species_.phyllotaxis_jitter_deg) * rng_.Symmetric();
      std::vector<Vec3> points = IntegrateAxis(base, DirectionFrom(c, angle, azimuth), c.length,
                                               segments, level.shape, waves);
      const size_t whole = points.size();
      StopAboveGround(points);
      if (points.size() < 3) continue;  // into the ground at once: drawn again (step 6)
      if (!Crowds(c, points, radius, angle)) {
        Axis axis;
        axis.parent = c.parent;
        axis.parent_node = c.parent_node;
        axis.level = c.level;
        axis.length = c.length * (points.size() - 1) / (whole - 1);
        if (points.size() < whole) ++stopped_at_ground_;
        axis.estimated_radius = radius;
        axis.points = std::move(points);
        AddAxis(std::move(axis));
        return;
      }
    }
    ++dropped_crowded_;
  }

  // Cuts a drooping axis at its last node at least min_ground_clearance_m above the ground (the
  // header, step 6): a shoot does not grow into the ground.
  void StopAboveGround(std::vector<Vec3>& points) const {
    const auto below = std::find_if(points.begin() + 1, points.end(), [&](const Vec3& p) {
      return p.z() < options_.min_ground_clearance_m;
    });
    points.erase(below, points.end());
  }

  // True when the new axis comes too close to an axis grown before (see the header, step 5).
  bool Crowds(const Candidate& c, const std::vector<Vec3>& points, double radius,
              double angle) const {
    const Axis& parent = axes_[c.parent];
    const double parent_segment = parent.length / (parent.points.size() - 1);
    const double parent_radius =
        EstimatedRadiusAt(parent.estimated_radius, c.parent_node * parent_segment, parent.length);
    const Vec3& base = points.front();
    // Arc length after which the child has left its parent and same-node siblings (with room
    // to spare: the parent curves, the child bends).
    const double leave = 1.5 * Clearance(parent_radius, radius) / std::max(std::sin(angle), 0.2);
    const double near_base = Clearance(parent_radius, radius);
    const double margin = Clearance(radius, grid_.max_radius());
    const double segment = c.length / (points.size() - 1);
    for (size_t i = 1; i < points.size(); ++i) {
      const Vec3& b = points[i];
      const double b_out = (b - base).norm();
      if (b_out < near_base) continue;
      // Only the part of the segment outside the ball around the base is checked.
      Vec3 a = points[i - 1];
      const double a_out = (a - base).norm();
      if (a_out < near_base) a += (b - a) * ((near_base - a_out) / (b_out - a_out));
      const bool leaving = (i - 1) * segment < leave;
      const double r = EstimatedRadiusAt(radius, i * segment, c.length);
      const bool hit = grid_.AnyNear(a, b, margin, [&](const GridSegment& s) {
        const Axis& other = axes_[s.branch];
        const bool at_attachment =
            s.branch == c.parent && (s.index == c.parent_node || s.index + 1 == c.parent_node);
        if (at_attachment ||
            (leaving && (s.branch == c.parent ||
                         (other.parent == c.parent && other.parent_node == c.parent_node)))) {
          return false;
        }
        return SegmentDistance(a, b, s.a, s.b) < Clearance(r, s.radius);
      });
      if (hit) return true;
    }
    return false;
  }

  // Scales every axis about the origin so the highest node is at the drawn height.
  double ScaleToHeight() {
    double top = 0.0;
    for (const Axis& a : axes_) {
      for (const Vec3& p : a.points) top = std::max(top, p.z());
    }
    const double scale = top > 0 ? height_ / top : 1.0;
    for (Axis& a : axes_) {
      for (Vec3& p : a.points) p *= scale;
      a.length *= scale;
    }
    return scale;
  }

  // The longest path along the axes from the trunk base to a tip (after scaling).
  double LongestPathToTip() const {
    std::vector<double> base_path(axes_.size(), 0.0);  // path from the trunk base to each axis
    double longest = 0.0;
    for (size_t id = 0; id < axes_.size(); ++id) {  // parents before children
      const Axis& a = axes_[id];
      if (a.parent >= 0) {
        const std::vector<Vec3>& up = axes_[a.parent].points;
        base_path[id] = base_path[a.parent];
        for (int i = 1; i <= a.parent_node; ++i) base_path[id] += (up[i] - up[i - 1]).norm();
      }
      double path = base_path[id];
      for (size_t i = 1; i < a.points.size(); ++i) path += (a.points[i] - a.points[i - 1]).norm();
      longest = std::max(longest, path);
    }
    return longest;
  }

  // The finished Tree with pipe-model radii (header, step 9).
  Tree BuildTree(double* tip_radius) const {
    const int count = static_cast<int>(axes_.size());
    const double n = species_.pipe_exponent;
    // Pipe quantity P per node, children before parents (they have larger ids).
    std::vector<std::vector<double>> pipe(count);
    std::vector<std::vector<double>> carried(count);  // sum of children's base P per node
    for (int id = 0; id < count; ++id) carried[id].assign(axes_[id].points.size(), 0.0);
    for (int id = count - 1; id >= 0; --id) {
      const Axis& a = axes_[id];
      const int nodes = static_cast<int>(a.points.size());
      std::vector<double>& p = pipe[id];
      p.assign(nodes, 0.0);
      p[nodes - 1] = 1.0 + carried[id][nodes - 1];
      for (int i = nodes - 2; i >= 0; --i) {
        const double segment = (a.points[i + 1] - a.points[i]).norm();
        p[i] = p[i + 1] + species_.shed_shoots_per_m * segment + carried[id][i];
      }
      if (a.parent >= 0) carried[a.parent][a.parent_node] += p[0];
    }
    const double c = trunk_radius_ / std::pow(pipe[0][0], 1.0 / n);
    *tip_radius = c;

    Tree tree;
    tree.metadata.species = species_.name;
    tree.metadata.source = fmt::format("synth {} seed {}", species_.name, seed_);
    tree.branches.resize(count);
    for (int id = 0; id < count; ++id) {
      const Axis& a = axes_[id];
      Branch& b = tree.branches[id];
      b.id = id;
      b.parent = a.parent;
      b.parent_node = a.parent_node;
      b.nodes.resize(a.points.size());
      for (size_t i = 0; i < a.points.size(); ++i) {
        b.nodes[i].position = a.points[i];
        b.nodes[i].radius =
            std::max(species_.min_twig_radius_m, c * std::pow(pipe[id][i], 1.0 / n));
      }
    }
    AssignLevels(tree);
    ComputeFrames(tree);
    Validate(tree, tree.metadata.source);
    return tree;
  }

  const SpeciesParams& species_;
  const GeneratorOptions& options_;
  uint64_t seed_;
  Random rng_;
  double height_ = 0.0;
  double estimated_trunk_radius_ = 0.0;  // for the clearance check while growing
  double trunk_radius_ = 0.0;            // the finished tree's, from its longest path
  std::vector<Axis> axes_;
  SegmentGrid grid_{0.1};
  int nodes_ = 0;
  int redrawn_ = 0;
  int dropped_crowded_ = 0;
  int dropped_budget_ = 0;
  int stopped_at_ground_ = 0;
};

}  // namespace

TreeGenerationResult GrowTree(const SpeciesParams& species, uint64_t seed,
                              const GeneratorOptions& options) {
  ValidateSpecies(species, species.name.empty() ? "species" : "species " + species.name);
  if (options.max_branches < 1 || options.max_nodes < 3 || !(options.clearance_radii >= 0) ||
      !(options.min_clearance_m >= 0) || !(options.min_ground_clearance_m >= 0)) {
    throw InputError("GeneratorOptions", "",
                     "expected max_branches >= 1, max_nodes >= 3 and non-negative clearances");
  }
  Grower grower(species, seed, options);
  return grower.Grow();
}

Tree GenerateTree(const SpeciesParams& species, uint64_t seed, const GeneratorOptions& options) {
  return GrowTree(species, seed, options).tree;
}

}  // namespace simtree::synth
