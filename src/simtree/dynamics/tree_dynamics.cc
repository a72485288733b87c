#include "simtree/dynamics/tree_dynamics.h"

#include <algorithm>
#include <cmath>
#include <map>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/core/validate.h"
#include "simtree/dynamics/detail/mode_shapes.h"

namespace simtree::dynamics {
namespace {

constexpr int kU = 0;  // bend_u
constexpr int kW = 1;  // bend_w
constexpr int kT = 2;  // twist_v

// Levels with fewer branches than this run on the calling thread: splitting them costs more than
// it saves.
constexpr int kParallelMinBranches = 512;
constexpr int kParallelGrain = 64;

// sin x / x and (1 - cos x) / x^2 from x^2, by their Taylor series for |x| <= 0.5 (error below
// 1e-12), libm beyond: Rodrigues' formula without a division by zero and, for the small angles of
// modal rotations, without a libm call.
[[gnu::always_inline]] inline void RotationCoefficients(double angle2, double* sinc, double* cosc) {
  const double a2 = angle2;
  if (a2 < 0.25) {
    // Multiplications by reciprocals: a division costs as much as this whole polynomial.
    constexpr double k6 = 1.0 / 6, k20 = 1.0 / 20, k42 = 1.0 / 42, k72 = 1.0 / 72;
    constexpr double k12 = 1.0 / 12, k30 = 1.0 / 30, k56 = 1.0 / 56, k90 = 1.0 / 90;
    *sinc = 1.0 - a2 * k6 * (1.0 - a2 * k20 * (1.0 - a2 * k42 * (1.0 - a2 * k72)));
    *cosc = 0.5 * (1.0 - a2 * k12 * (1.0 - a2 * k30 * (1.0 - a2 * k56 * (1.0 - a2 * k90))));
  } else {
    const double angle = std::sqrt(a2);
    *sinc = std::sin(angle) / angle;
    *cosc = (1.0 - std::cos(angle)) / a2;
  }
}

// sin and cos of an angle, by series for |x| <= 0.5.
[[gnu::always_inline]] inline void SinCos(double x, double* s, double* c) {
  double sinc = 0, cosc = 0;
  RotationCoefficients(x * x, &sinc, &cosc);
  *s = x * sinc;
  *c = 1.0 - x * x * cosc;
}

// The rotation by the rotation vector w (axis w / |w|, angle |w|): I + sinc K + cosc K^2 with
// K = [w]x and K^2 = w w^T - |w|^2 I, written out.
[[gnu::always_inline]] inline Eigen::Matrix3d RotationFromVector(const Eigen::Vector3d& w) {
  const double x = w.x(), y = w.y(), z = w.z();
  const double a2 = x * x + y * y + z * z;
  double s = 0, c = 0;
  RotationCoefficients(a2, &s, &c);
  Eigen::Matrix3d r;
  r << 1 + c * (x * x - a2), -s * z + c * x * y, s * y + c * x * z,  //
      s * z + c * x * y, 1 + c * (y * y - a2), -s * x + c * y * z,   //
      -s * y + c * x * z, s * x + c * y * z, 1 + c * (z * z - a2);
  return r;
}

// The per-node work of a step. Each node stores, relative to its branch's base in the branch's
// rest frame (u, v, w): h, its offset along the chord axis v; (a_u, a_w), its offset across it;
// and the mode-shape values phi (bending) and psi (twist) at its arc length. Twisting by
// t = psi q_t turns (a_u, a_w) by t about v, bending adds phi (q_u, q_w), and the branch's pose
// (o, R) places the result:
//   x = o + h Rv + (cos t a_u + sin t a_w + phi q_u) Ru + (cos t a_w - sin t a_u + phi q_w) Rw
// with Ru, Rv, Rw the branch's deformed frame at its base. Five floats in, three out, ~30 flops.
struct NodePass {
  float o[3];
  float ru[3], rv[3], rw[3];
  float q_u, q_w, q_t;
};

struct NodeArrays {
  std::vector<float> h, a_u, a_w, phi, psi;
  std::vector<float> arc_fraction;  // s / L, for rotations (not used by the step)
};

// Small twists (|q_t| <= 1 rad, every realistic case): sin and cos by series, so there is no
// branch and no libm call. Error below 3e-8, under float resolution.
inline void TwistSinCos(float t, float* s, float* c) {
  const float t2 = t * t;
  *s = t * (1.f + t2 * (-1.f / 6 + t2 * (1.f / 120 + t2 * (-1.f / 5040 + t2 * (1.f / 362880)))));
  *c = 1.f + t2 * (-0.5f + t2 * (1.f / 24 +
                                 t2 * (-1.f / 720 + t2 * (1.f / 40320 + t2 * (-1.f / 3628800)))));
}

void DeformNodesSmallTwist(const NodePass& p, const float* __restrict__ hh,
                           const float* __restrict__ au, const float* __restrict__ aw,
                           const float* __restrict__ phi, const float* __restrict__ psi, int count,
                           float* __restrict__ out) {
  int i = 0;
#if defined(__SSE2__)
  // Four nodes at a time in SSE registers (x86-64 always has SSE2): the compiler does not
  // vectorise the interleaved xyz stores by itself.
  {
    const __m128 ox = _mm_set1_ps(p.o[0]), oy = _mm_set1_ps(p.o[1]), oz = _mm_set1_ps(p.o[2]);
    const __m128 ux = _mm_set1_ps(p.ru[0]), uy = _mm_set1_ps(p.ru[1]), uz = _mm_set1_ps(p.ru[2]);
    const __m128 vx = _mm_set1_ps(p.rv[0]), vy = _mm_set1_ps(p.rv[1]), vz = _mm_set1_ps(p.rv[2]);
    const __m128 wx = _mm_set1_ps(p.rw[0]), wy = _mm_set1_ps(p.rw[1]), wz = _mm_set1_ps(p.rw[2]);
    const __m128 qu = _mm_set1_ps(p.q_u), qw = _mm_set1_ps(p.q_w), qt = _mm_set1_ps(p.q_t);
    const auto k = [](float x) { return _mm_set1_ps(x); };
    for (; i + 4 <= count; i += 4) {
      const __m128 t = _mm_mul_ps(_mm_loadu_ps(psi + i), qt);
      const __m128 t2 = _mm_mul_ps(t, t);
      __m128 sn = _mm_add_ps(k(-1.f / 5040), _mm_mul_ps(t2, k(1.f / 362880)));
      sn = _mm_add_ps(k(1.f / 120), _mm_mul_ps(t2, sn));
      sn = _mm_add_ps(k(-1.f / 6), _mm_mul_ps(t2, sn));
      sn = _mm_mul_ps(t, _mm_add_ps(k(1.f), _mm_mul_ps(t2, sn)));
      __m128 cs = _mm_add_ps(k(1.f / 40320), _mm_mul_ps(t2, k(-1.f / 3628800)));
      cs = _mm_add_ps(k(-1.f / 720), _mm_mul_ps(t2, cs));
      cs = _mm_add_ps(k(1.f / 24), _mm_mul_ps(t2, cs));
      cs = _mm_add_ps(k(-0.5f), _mm_mul_ps(t2, cs));
      cs = _mm_add_ps(k(1.f), _mm_mul_ps(t2, cs));
      const __m128 a_u = _mm_loadu_ps(au + i), a_w = _mm_loadu_ps(aw + i);
      const __m128 f = _mm_loadu_ps(phi + i), h = _mm_loadu_ps(hh + i);
      const __m128 alpha =
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(cs, a_u), _mm_mul_ps(sn, a_w)), _mm_mul_ps(f, qu));
      const __m128 beta =
          _mm_add_ps(_mm_sub_ps(_mm_mul_ps(cs, a_w), _mm_mul_ps(sn, a_u)), _mm_mul_ps(f, qw));
      const auto axis = [&](__m128 o, __m128 v, __m128 u, __m128 w) {
        return _mm_add_ps(_mm_add_ps(o, _mm_mul_ps(h, v)),
                          _mm_add_ps(_mm_mul_ps(alpha, u), _mm_mul_ps(beta, w)));
      };
      const __m128 x = axis(ox, vx, ux, wx), y = axis(oy, vy, uy, wy), z = axis(oz, vz, uz, wz);
      // (x0..3, y0..3, z0..3) -> x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3
      const __m128 xy01 = _mm_unpacklo_ps(x, y);                            // x0 y0 x1 y1
      const __m128 xy23 = _mm_unpackhi_ps(x, y);                            // x2 y2 x3 y3
      const __m128 zx = _mm_shuffle_ps(z, xy01, _MM_SHUFFLE(2, 2, 0, 0));   // z0 z0 x1 x1
      const __m128 yz = _mm_shuffle_ps(xy01, z, _MM_SHUFFLE(1, 1, 3, 3));   // y1 y1 z1 z1
      const __m128 zx3 = _mm_shuffle_ps(z, xy23, _MM_SHUFFLE(2, 2, 2, 2));  // z2 z2 x3 x3
      const __m128 yz3 = _mm_shuffle_ps(xy23, z, _MM_SHUFFLE(3, 3, 3, 3));  // y3 y3 z3 z3
      _mm_storeu_ps(out + 3 * i + 0, _mm_shuffle_ps(xy01, zx, _MM_SHUFFLE(2, 0, 1, 0)));
      _mm_storeu_ps(out + 3 * i + 4, _mm_shuffle_ps(yz, xy23, _MM_SHUFFLE(1, 0, 2, 0)));
      _mm_storeu_ps(out + 3 * i + 8, _mm_shuffle_ps(zx3, yz3, _MM_SHUFFLE(2, 0, 2, 0)));
    }
  }
#endif
  for (; i < count; ++i) {
    float s = 0, c = 1;
    TwistSinCos(psi[i] * p.q_t, &s, &c);
    // The same operations in the same order as the SSE lanes: bit-identical results.
    const float alpha = (c * au[i] + s * aw[i]) + phi[i] * p.q_u;
    const float beta = (c * aw[i] - s * au[i]) + phi[i] * p.q_w;
    for (int a = 0; a < 3; ++a) {
      out[3 * i + a] = (p.o[a] + hh[i] * p.rv[a]) + (alpha * p.ru[a] + beta * p.rw[a]);
    }
  }
}

// Any twist: libm sin and cos per node.
void DeformNodesLargeTwist(const NodePass& p, const float* hh, const float* au, const float* aw,
                           const float* phi, const float* psi, int count, float* out) {
  for (int i = 0; i < count; ++i) {
    const float t = psi[i] * p.q_t;
    const float s = std::sin(t), c = std::cos(t);
    const float alpha = c * au[i] + s * aw[i] + phi[i] * p.q_u;
    const float beta = c * aw[i] - s * au[i] + phi[i] * p.q_w;
    for (int a = 0; a < 3; ++a) {
      out[3 * i + a] = p.o[a] + hh[i] * p.rv[a] + alpha * p.ru[a] + beta * p.rw[a];
    }
  }
}

void CheckMaterialForSimulation(const Material& m, const std::string& source,
                                const std::string& at) {
  for (int i = 0; i < 3; ++i) {
    const Mode& mode = m.modes[i];
    const std::string where = fmt::format("{}.modes[{}]", at, i);
    if (!std::isfinite(mode.frequency_hz) || mode.frequency_hz <= 0.0) {
      throw InputError(source, where + ".frequency_hz",
                       fmt::format("expected a positive finite natural frequency (Hz), got {}",
                                   mode.frequency_hz));
    }
    if (!std::isfinite(mode.damping_ratio) || mode.damping_ratio < 0.0) {
      throw InputError(
          source, where + ".damping_ratio",
          fmt::format("expected a finite damping ratio >= 0, got {}", mode.damping_ratio));
    }
  }
  if (!std::isfinite(m.mass_kg) || m.mass_kg <= 0.0) {
    throw InputError(source, at + ".mass_kg",
                     fmt::format("expected a positive finite modal mass (kg), got {}", m.mass_kg));
  }
  if (!std::isfinite(m.stiffness) || m.stiffness <= 0.0) {
    throw InputError(
        source, at + ".stiffness",
        fmt::format("expected a positive finite stiffness (N/m), got {}", m.stiffness));
  }
}

}  // namespace

void ValidateForSimulation(const Tree& tree, const std::string& source) {
  if (tree.empty()) throw InputError(source, "branches", "expected at least one branch");
  for (const Branch& b : tree.branches) {
    const std::string at = fmt::format("branches[{}].material", b.id);
    if (!b.material) {
      throw InputError(source, at,
                       "expected a material (frequency, damping, stiffness) on every branch: give "
                       "the tree materials (simtree build) or a parameter file (--material-file)");
    }
    CheckMaterialForSimulation(*b.material, source, at);
  }
  ValidationOptions options;
  options.require_materials = true;
  Validate(tree, source, options);
}

// ------------------------------------------------------------------------------------------------

struct TreeDynamics::Impl {
  // What a step reads of a branch, kept together and small. "Frame coordinates" are components
  // along the branch's own rest frame (u, v, w); "parent coordinates" along its parent's.
  struct Link {
    int parent = -1, first_node = 0, nodes = 0;
    // The attachment node on the parent: rest offset from the parent's base (parent
    // coordinates: a_u, h, a_w), the parent's mode shapes there, and this branch's rest frame in
    // parent coordinates.
    double attach_au = 0, attach_h = 0, attach_aw = 0;
    double attach_phi = 0, attach_slope = 0, attach_psi = 0;  // slope per metre
    Eigen::Matrix3d relative_frame = Eigen::Matrix3d::Identity();
    // What a base acceleration a and angular acceleration alpha (frame coordinates) do to the
    // modes: Q_u = -(lin_bend a_u + rot_u . alpha), Q_w likewise, Q_t = -(lin_twist . a +
    // twist_rotation alpha_v). From the lumped node masses w_j (cross-sections scaled so that
    // sum w phi^2 is the modal mass): lin_bend = sum w phi, rot_u = sum w phi (r x u),
    // lin_twist = sum w psi (v x r), twist_rotation = participation x twist inertia.
    double lin_bend = 0, twist_rotation = 0;
    Eigen::Vector3d rot_u = Eigen::Vector3d::Zero(), rot_w = Eigen::Vector3d::Zero();
    Eigen::Vector3d lin_twist = Eigen::Vector3d::Zero();
    std::array<double, 3> inverse_mass = {1, 1, 1};
    std::array<OscillatorStep, 3> step;
  };
  // The rest of a branch's constants.
  struct Model {
    int parent_node = 0, level = 0;
    double length = 0;
    Eigen::Matrix3d frame;  // columns: rest u, v, w (world)
    Eigen::Vector3d rest_base;
    // Weight: total mass and first moment sum w r (frame coordinates).
    double mass_total = 0;
    Eigen::Vector3d mass_moment = Eigen::Vector3d::Zero();
    // Wind: projected area (diameter x length), its mode-shape weighted sums and centroid
    // (frame coordinates).
    double area = 0, area_phi = 0;
    Eigen::Vector3d area_twist = Eigen::Vector3d::Zero();
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::array<double, 3> modal_mass = {1, 1, 1};  // kg, kg, kg m^2
    std::array<double, 3> frequency = {1, 1, 1};
    std::array<double, 3> damping = {0, 0, 0};
  };
  // Changing every step.
  struct State {
    ModalState modal;                                // primary + swing: what the geometry shows
    ModalState primary;                              // response to external loads
    ModalState swing;                                // response to the base's acceleration
    std::array<double, 3> acceleration = {0, 0, 0};  // primary, over the last step
    // The deformed frame at the base: columns are the world directions of u, v, w now.
    Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Vector3d base_acceleration = Eigen::Vector3d::Zero();  // world, linear
    Eigen::Vector3d base_angular_acceleration = Eigen::Vector3d::Zero();
  };
  // External load of the current step: generalised forces on the branch's modes, and the force
  // and moment (about its base, world) it passes to its parent.
  struct Load {
    std::array<double, 3> q = {0, 0, 0};
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  };
  struct RopeSlot {
    Rope rope;
    double arc_length = 0;
    double tension = 0;
  };

  Tree tree;
  DynamicsOptions options;
  std::vector<Link> link;
  std::vector<Model> model;
  std::vector<State> state;
  std::vector<Load> load;
  NodeArrays node;
  std::vector<Eigen::Vector3f> positions;
  std::vector<int> level_order;  // branch ids by level, then id
  std::vector<int> level_begin;  // level L is level_order[level_begin[L], level_begin[L + 1])
  std::vector<int> child_begin, child_list;  // children of b: child_list[child_begin[b], [b + 1])
  std::map<int, RopeSlot> ropes;
  int next_rope_id = 0;
  WindField wind;
  Eigen::Vector3d bounds_min, bounds_max;
  double step_dt = 0;  // dt the step coefficients are for (0 = none yet)
  double time = 0;
  int64_t steps = 0;
  // Which branches carry a load now (to clear only those).
  bool all_loaded = false;
  std::vector<int> loaded;
  std::unique_ptr<tbb::task_arena> arena;

  Impl(const Tree& input, const DynamicsOptions& opts) : tree(input), options(opts) {
    ValidateForSimulation(tree, "tree");
    if (!std::isfinite(options.twist_stiffness_ratio) || options.twist_stiffness_ratio <= 0.0) {
      throw InputError(
          "dynamics options", "twist_stiffness_ratio",
          fmt::format("expected a positive ratio, got {}", options.twist_stiffness_ratio));
    }
    if (options.max_threads < 0) {
      throw InputError("dynamics options", "max_threads",
                       fmt::format("expected 0 (all cores) or more, got {}", options.max_threads));
    }
    arena = options.max_threads > 0 ? std::make_unique<tbb::task_arena>(options.max_threads)
                                    : std::make_unique<tbb::task_arena>();
    if (options.demo_mode_spread) {
      for (Branch& b : tree.branches) {
        Material& m = *b.material;
        const double f = m.modes[kT].frequency_hz, z = m.modes[kT].damping_ratio;
        m.modes[kW].frequency_hz = 1.05 * f;
        m.modes[kW].damping_ratio = 0.8 * z;
        m.modes[kU].damping_ratio = 1.2 * z;
        m.SetFrequency(ModeKind::kBendU, 0.95 * f);
      }
    }
    BuildTopology();
    BuildNodes();
    for (int b = 0; b < tree.size(); ++b) BuildMaterial(b);
    tree.Bounds(&bounds_min, &bounds_max);
    wind = WindField(options.wind, bounds_min, bounds_max);
    ResetState();
  }

  int size() const { return tree.size(); }

  void BuildTopology() {
    const int n = size();
    link.resize(n);
    model.resize(n);
    state.resize(n);
    load.resize(n);
    int max_level = 0;
    for (const Branch& b : tree.branches) max_level = std::max(max_level, b.level);
    std::vector<int> per_level(max_level + 2, 0);
    for (const Branch& b : tree.branches) ++per_level[b.level + 1];
    level_begin.assign(max_level + 2, 0);
    for (int l = 0; l <= max_level; ++l) level_begin[l + 1] = level_begin[l] + per_level[l + 1];
    level_order.assign(n, 0);
    std::vector<int> fill(level_begin.begin(), level_begin.end() - 1);
    for (const Branch& b : tree.branches) level_order[fill[b.level]++] = b.id;
    child_begin.assign(n + 1, 0);
    for (const Branch& b : tree.branches) {
      if (b.parent >= 0) ++child_begin[b.parent + 1];
    }
    for (int b = 0; b < n; ++b) child_begin[b + 1] += child_begin[b];
    child_list.assign(child_begin[n], 0);
    std::vector<int> next(child_begin.begin(), child_begin.end() - 1);
    for (const Branch& b : tree.branches) {
      if (b.parent >= 0) child_list[next[b.parent]++] = b.id;
    }
  }

  void BuildNodes() {
    const int total = tree.NodeCount();
    for (auto* v : {&node.h, &node.a_u, &node.a_w, &node.phi, &node.psi, &node.arc_fraction}) {
      v->assign(total, 0.f);
    }
    positions.assign(total, Eigen::Vector3f::Zero());
    int first = 0;
    for (const Branch& b : tree.branches) {
      Link& k = link[b.id];
      Model& m = model[b.id];
      k.parent = b.parent;
      k.first_node = first;
      k.nodes = static_cast<int>(b.nodes.size());
      m.parent_node = b.parent_node;
      m.level = b.level;
      m.length = b.Length();
      m.frame.col(0) = b.frame.u;
      m.frame.col(1) = b.frame.v;
      m.frame.col(2) = b.frame.w;
      m.rest_base = b.base().position;
      const std::vector<double> s = b.ArcLengths();
      for (int j = 0; j < k.nodes; ++j) {
        const Eigen::Vector3d r = m.frame.transpose() * (b.nodes[j].position - m.rest_base);
        const double x = m.length > 0.0 ? s[j] / m.length : 0.0;
        const size_t i = first + j;
        node.a_u[i] = static_cast<float>(r.x());
        node.h[i] = static_cast<float>(r.y());
        node.a_w[i] = static_cast<float>(r.z());
        node.phi[i] = m.length > 0.0 ? static_cast<float>(BendingModeShape(x)) : 0.f;
        node.psi[i] = m.length > 0.0 ? static_cast<float>(TwistModeShape(x)) : 0.f;
        node.arc_fraction[i] = static_cast<float>(x);
        positions[i] = b.nodes[j].position.cast<float>();
      }
      if (b.parent >= 0) {
        const Branch& p = tree.branches[b.parent];
        const Model& pm = model[b.parent];
        const double lp = pm.length;
        const double xp = lp > 0.0 ? p.ArcLengths()[b.parent_node] / lp : 0.0;
        k.attach_phi = lp > 0.0 ? BendingModeShape(xp) : 0.0;
        k.attach_slope = lp > 0.0 ? BendingModeSlope(xp) / lp : 0.0;
        k.attach_psi = lp > 0.0 ? TwistModeShape(xp) : 0.0;
        const Eigen::Vector3d offset =
            pm.frame.transpose() * (p.nodes[b.parent_node].position - p.base().position);
        k.attach_au = offset.x();
        k.attach_h = offset.y();
        k.attach_aw = offset.z();
        k.relative_frame = pm.frame.transpose() * m.frame;
      }
      first += k.nodes;
    }
  }

  // Mass distribution, participations, wind areas and modal constants of one branch.
  void BuildMaterial(int id) {
    const Branch& b = tree.branches[id];
    Link& k = link[id];
    Model& m = model[id];
    const Material& mat = *b.material;
    const std::vector<double> s = b.ArcLengths();
    const int n = k.nodes;
    // Each node stands for half of each segment next to it.
    std::vector<double> ds(n, 0.0);
    for (int j = 1; j < n; ++j) {
      const double seg = s[j] - s[j - 1];
      ds[j - 1] += 0.5 * seg;
      ds[j] += 0.5 * seg;
    }
    double sum_area_phi2 = 0;
    for (int j = 0; j < n; ++j) {
      const double phi = node.phi[k.first_node + j];
      sum_area_phi2 += b.nodes[j].radius * b.nodes[j].radius * ds[j] * phi * phi;
    }
    // Scale cross-section volumes to masses so that sum w phi^2 is the modal mass.
    const double scale = sum_area_phi2 > 0.0 ? mat.mass_kg / sum_area_phi2 : 0.0;
    const Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = Eigen::Vector3d::UnitY(),
                          w = Eigen::Vector3d::UnitZ();  // frame coordinates
    m.mass_total = 0;
    m.mass_moment.setZero();
    k.lin_bend = 0;
    k.rot_u.setZero();
    k.rot_w.setZero();
    k.lin_twist.setZero();
    m.area = m.area_phi = 0;
    m.area_twist.setZero();
    m.centroid.setZero();
    double polar_psi = 0, polar_psi2 = 0, offaxis_inertia = 0;
    for (int j = 0; j < n; ++j) {
      const double r2 = b.nodes[j].radius * b.nodes[j].radius;
      const double wj = scale * r2 * ds[j];
      const double phi = node.phi[k.first_node + j];
      const double psi = node.psi[k.first_node + j];
      const Eigen::Vector3d r = m.frame.transpose() * (b.nodes[j].position - m.rest_base);
      m.mass_total += wj;
      m.mass_moment += wj * r;
      k.lin_bend += wj * phi;
      k.rot_u += wj * phi * r.cross(u);
      k.rot_w += wj * phi * r.cross(w);
      k.lin_twist += wj * psi * v.cross(r);
      // Rotary inertia about the axis: the cross-section's own (w r^2 / 2) and, on a curved
      // branch, that of the mass off the chord.
      const double axis_inertia = wj * (0.5 * r2 + r.x() * r.x() + r.z() * r.z());
      polar_psi += axis_inertia * psi;
      polar_psi2 += axis_inertia * psi * psi;
      offaxis_inertia += wj * psi * psi * (r.x() * r.x() + r.z() * r.z());
      const double aj = 2.0 * b.nodes[j].radius * ds[j];
      m.area += aj;
      m.area_phi += aj * phi;
      m.area_twist += aj * psi * v.cross(r);
      m.centroid += aj * r;
    }
    if (m.area > 0.0) m.centroid /= m.area;
    for (int i = 0; i < 3; ++i) {
      m.frequency[i] = mat.modes[i].frequency_hz;
      m.damping[i] = mat.modes[i].damping_ratio;
    }
    m.modal_mass[kU] = m.modal_mass[kW] = mat.mass_kg;
    // Twist: stiffness ratio L^2 k over the twist frequency squared gives the inertia, but never
    // less than that of the mass off the chord (which base accelerations drive), so a curved
    // branch cannot be flung round by its own weight. A branch of no length uses 1 m^2.
    const double lever2 = std::max(m.length * m.length, 1e-6);
    const double w_twist = kTwoPi * m.frequency[kT];
    m.modal_mass[kT] =
        std::max(options.twist_stiffness_ratio * lever2 * mat.stiffness / (w_twist * w_twist),
                 offaxis_inertia);
    const double participation = polar_psi2 > 0.0 ? polar_psi / polar_psi2 : 0.0;
    k.twist_rotation = participation * m.modal_mass[kT];
    for (int i = 0; i < 3; ++i) k.inverse_mass[i] = 1.0 / m.modal_mass[i];
    if (step_dt > 0.0) BuildSteps(id, step_dt);
  }

  void BuildSteps(int id, double dt) {
    for (int i = 0; i < 3; ++i) {
      link[id].step[i] =
          MakeOscillatorStep(model[id].frequency[i], model[id].damping[i], dt, options.integrator);
    }
  }

  template <typename Fn>
  void ForRange(int begin, int end, const Fn& fn) {
    if (end - begin < kParallelMinBranches || options.max_threads == 1) {
      for (int i = begin; i < end; ++i) fn(i);
      return;
    }
    arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(begin, end, kParallelGrain),
                        [&](const tbb::blocked_range<int>& r) {
                          for (int i = r.begin(); i < r.end(); ++i) fn(i);
                        });
    });
  }

  // Calls fn(branch) for every branch, parents before children.
  template <typename Fn>
  void TopDown(const Fn& fn) {
    for (size_t l = 0; l + 1 < level_begin.size(); ++l) {
      ForRange(level_begin[l], level_begin[l + 1], [&](int i) { fn(level_order[i]); });
    }
  }

  // Rotation from rest to now at a branch's base.
  Eigen::Matrix3d Rotation(int id) const { return state[id].frame * model[id].frame.transpose(); }

  // The rotation, in frame coordinates, of the cross-section at a point whose bending slope (per
  // metre) is `slope` and twist shape `psi`, for modal coordinates q.
  static Eigen::Vector3d LocalRotation(double slope, double psi, const std::array<double, 3>& q) {
    return {slope * q[kW], psi * q[kT], -slope * q[kU]};
  }

  // Offset from the base, in frame coordinates, of a point whose rest offset is (a_u, h, a_w)
  // and whose mode shapes are phi, psi: twisted about v, then bent (the node formula).
  [[gnu::always_inline]] static Eigen::Vector3d LocalOffset(double a_u, double h, double a_w,
                                                            double phi, double psi,
                                                            const std::array<double, 3>& q) {
    double s = 0, c = 1;
    SinCos(psi * q[kT], &s, &c);
    return {c * a_u + s * a_w + phi * q[kU], h, c * a_w - s * a_u + phi * q[kW]};
  }

  // Places a branch: its base on its parent's deformed attachment node, its frame turned by the
  // parent's cross-section there.
  void PoseBranch(int id) {
    const Link& k = link[id];
    State& st = state[id];
    if (k.parent < 0) {
      st.origin = model[id].rest_base;
      st.frame = model[id].frame;
      return;
    }
    const State& ps = state[k.parent];
    const std::array<double, 3>& q = ps.modal.q;
    st.origin = ps.origin + ps.frame * LocalOffset(k.attach_au, k.attach_h, k.attach_aw,
                                                   k.attach_phi, k.attach_psi, q);
    st.frame = ps.frame * (RotationFromVector(LocalRotation(k.attach_slope, k.attach_psi, q)) *
                           k.relative_frame);
  }

  void DeformNodes(int id) {
    const Link& k = link[id];
    const State& st = state[id];
    NodePass p;
    for (int a = 0; a < 3; ++a) {
      p.o[a] = static_cast<float>(st.origin[a]);
      p.ru[a] = static_cast<float>(st.frame(a, 0));
      p.rv[a] = static_cast<float>(st.frame(a, 1));
      p.rw[a] = static_cast<float>(st.frame(a, 2));
    }
    p.q_u = static_cast<float>(st.modal.q[kU]);
    p.q_w = static_cast<float>(st.modal.q[kW]);
    p.q_t = static_cast<float>(st.modal.q[kT]);
    const size_t f = k.first_node;
    float* out = positions[f].data();
    if (std::abs(st.modal.q[kT]) <= 1.0) {
      DeformNodesSmallTwist(p, &node.h[f], &node.a_u[f], &node.a_w[f], &node.phi[f], &node.psi[f],
                            k.nodes, out);
    } else {
      DeformNodesLargeTwist(p, &node.h[f], &node.a_u[f], &node.a_w[f], &node.phi[f], &node.psi[f],
                            k.nodes, out);
    }
  }

  void UpdateGeometry() {
    TopDown([&](int id) {
      PoseBranch(id);
      DeformNodes(id);
    });
  }

  // Advances one branch by dt. Its motion is the sum of two responses of the same three
  // oscillators: the primary one to its external load, and its swing under the inertial load of
  // its base's acceleration. Only the ancestors' primary motion drives a swing: swings do not
  // drive further swings. A one-way cascade has no physical limit (through six levels of equal
  // frequency it amplified a pull 250,000-fold); in a real tree the children's reactions on their
  // parents stop it, and this keeps every branch within one level of resonance of a load.
  void AdvanceBranch(int id, double dt, bool loaded_step) {
    const Link& k = link[id];
    State& st = state[id];
    const double inv_dt = 1.0 / dt;
    for (int i = 0; i < 3; ++i) {
      const double f = loaded_step ? load[id].q[i] : 0.0;
      const double v0 = st.primary.v[i];
      k.step[i].Apply(f * k.inverse_mass[i], st.primary.q[i], st.primary.v[i]);
      st.acceleration[i] = (st.primary.v[i] - v0) * inv_dt;
    }
    if (options.base_excitation && k.parent >= 0) {
      const State& ps = state[k.parent];
      const std::array<double, 3>& qdd = ps.acceleration;
      // The attachment node's acceleration relative to the parent's base, parent coordinates.
      const Eigen::Vector3d lin(k.attach_phi * qdd[kU] + k.attach_psi * qdd[kT] * k.attach_aw, 0.0,
                                k.attach_phi * qdd[kW] - k.attach_psi * qdd[kT] * k.attach_au);
      st.base_acceleration = ps.base_acceleration +
                             ps.base_angular_acceleration.cross(st.origin - ps.origin) +
                             ps.frame * lin;
      st.base_angular_acceleration = ps.base_angular_acceleration +
                                     ps.frame * LocalRotation(k.attach_slope, k.attach_psi, qdd);
      // The pseudo-forces -w_j (a + alpha x r_j) on the branch's masses. Twist feels only the
      // turn of the base about the branch axis: its inertia is a material constant, not the
      // lumped masses, so a linear push on mass just off a nearly straight axis would fling it.
      const Eigen::Vector3d a = st.frame.transpose() * st.base_acceleration;
      const Eigen::Vector3d alpha = st.frame.transpose() * st.base_angular_acceleration;
      const std::array<double, 3> g = {-(k.lin_bend * a.x() + alpha.dot(k.rot_u)),
                                       -(k.lin_bend * a.z() + alpha.dot(k.rot_w)),
                                       -k.twist_rotation * alpha.y()};
      for (int i = 0; i < 3; ++i) {
        k.step[i].Apply(g[i] * k.inverse_mass[i], st.swing.q[i], st.swing.v[i]);
      }
    }
    for (int i = 0; i < 3; ++i) {
      st.modal.q[i] = st.primary.q[i] + st.swing.q[i];
      st.modal.v[i] = st.primary.v[i] + st.swing.v[i];
    }
  }

  // ---- Loads

  // Adds the generalised forces of a force F and a moment M acting at a point of branch `id`,
  // given the point's mode-shape values (phi, bending slope per metre, psi) and its lever arm r
  // from the branch base (world). Lever arms are rest offsets turned with the branch's base
  // (co-rotational): a branch's own deflection does not change how a load acts on it, which keeps
  // the model linear in its own modal coordinates. Also adds F and M + r x F to the reaction the
  // branch passes to its parent.
  void AddPointLoad(int id, double phi, double slope, double psi, const Eigen::Vector3d& r,
                    const Eigen::Vector3d& force, const Eigen::Vector3d& moment, Load& out) const {
    const Eigen::Matrix3d& f = state[id].frame;
    const Eigen::Vector3d u = f.col(0), v = f.col(1), w = f.col(2);
    out.q[kU] += phi * force.dot(u) - slope * moment.dot(w);
    out.q[kW] += phi * force.dot(w) + slope * moment.dot(u);
    out.q[kT] += psi * (v.dot(r.cross(force)) + moment.dot(v));
    out.force += force;
    out.moment += moment + r.cross(force);
  }

  // Passes a child's base reaction (force, moment about its base) to its parent.
  void AddChildReaction(int child, const Eigen::Vector3d& force, const Eigen::Vector3d& moment,
                        Load& parent_load) const {
    const Link& k = link[child];
    const Eigen::Vector3d lever =
        state[k.parent].frame * Eigen::Vector3d(k.attach_au, k.attach_h, k.attach_aw);
    AddPointLoad(k.parent, k.attach_phi, k.attach_slope, k.attach_psi, lever, force, moment,
                 parent_load);
  }

  // The branch's own distributed loads: weight and wind drag.
  Load OwnDistributedLoad(int id) const {
    const Link& k = link[id];
    const Model& m = model[id];
    const State& st = state[id];
    Load out;
    const Eigen::Vector3d u = st.frame.col(0), v = st.frame.col(1), w = st.frame.col(2);
    if (options.gravity) {
      const Eigen::Vector3d g(0, 0, -kGravity);
      out.q[kU] += k.lin_bend * g.dot(u);
      out.q[kW] += k.lin_bend * g.dot(w);
      out.q[kT] += (st.frame * k.lin_twist).dot(g);
      out.force += m.mass_total * g;
      out.moment += (st.frame * m.mass_moment).cross(g);
    }
    if (wind.options().enabled && m.area > 0.0) {
      const Eigen::Vector3d centroid = st.frame * m.centroid;
      const Eigen::Vector3d air = wind.Velocity(st.origin + centroid);
      // Drag of a cylinder: only the flow across the branch counts.
      const Eigen::Vector3d across = air - air.dot(v) * v;
      const Eigen::Vector3d pressure = 0.5 * wind.options().air_density_kg_m3 *
                                       wind.options().drag_coefficient * across.norm() * across;
      const Eigen::Vector3d drag = m.area * pressure;
      out.q[kU] += m.area_phi * pressure.dot(u);
      out.q[kW] += m.area_phi * pressure.dot(w);
      out.q[kT] += (st.frame * m.area_twist).dot(pressure);
      out.force += drag;
      out.moment += centroid.cross(drag);
    }
    return out;
  }

  // A point of a branch at an arc length: mode-shape values, slope and rest offset (frame
  // coordinates).
  struct PointOnBranch {
    double phi = 0, slope = 0, psi = 0;
    Eigen::Vector3d rest_offset = Eigen::Vector3d::Zero();
  };
  PointOnBranch PointAt(int id, double arc_length) const {
    const Model& m = model[id];
    PointOnBranch p;
    if (m.length > 0.0) {
      const double x = std::clamp(arc_length / m.length, 0.0, 1.0);
      p.phi = BendingModeShape(x);
      p.slope = BendingModeSlope(x) / m.length;
      p.psi = TwistModeShape(x);
    }
    p.rest_offset = m.frame.transpose() * (tree.branches[id].PointAt(arc_length) - m.rest_base);
    return p;
  }

  Eigen::Vector3d PointLocal(const PointOnBranch& p, const std::array<double, 3>& q) const {
    return LocalOffset(p.rest_offset.x(), p.rest_offset.y(), p.rest_offset.z(), p.phi, p.psi, q);
  }

  Eigen::Vector3d PointNow(int id, double arc_length) const {
    const State& st = state[id];
    return st.origin + st.frame * PointLocal(PointAt(id, arc_length), st.modal.q);
  }

  // A point's position for the modal states `q_of(branch)` of its branch and ancestors.
  template <typename StateOf>
  Eigen::Vector3d PointWith(int id, double arc_length, const StateOf& q_of) const {
    std::vector<int> chain;
    for (int b = id; b >= 0; b = link[b].parent) chain.push_back(b);
    Eigen::Vector3d origin = model[chain.back()].rest_base;
    Eigen::Matrix3d frame = model[chain.back()].frame;
    for (size_t i = chain.size(); i-- > 1;) {
      const Link& k = link[chain[i - 1]];
      const std::array<double, 3> q = q_of(chain[i]);
      origin +=
          frame * LocalOffset(k.attach_au, k.attach_h, k.attach_aw, k.attach_phi, k.attach_psi, q);
      frame = frame * (RotationFromVector(LocalRotation(k.attach_slope, k.attach_psi, q)) *
                       k.relative_frame);
    }
    return origin + frame * PointLocal(PointAt(id, arc_length), q_of(id));
  }

  // Applies a point force at a point of a branch: to the branch and (when loads are transferred)
  // to every ancestor, touching only that chain. `touched` records loaded branches.
  void WalkPointLoad(int id, double arc_length, const Eigen::Vector3d& force,
                     std::vector<Load>& loads, std::vector<int>* touched) const {
    const PointOnBranch p = PointAt(id, arc_length);
    const Eigen::Vector3d r = state[id].frame * p.rest_offset;
    Load delta;
    AddPointLoad(id, p.phi, p.slope, p.psi, r, force, Eigen::Vector3d::Zero(), delta);
    Accumulate(id, delta, loads, touched);
    if (!options.transfer_loads) return;
    Eigen::Vector3d moment = delta.moment;  // about the current branch's base
    for (int child = id; link[child].parent >= 0; child = link[child].parent) {
      Load up;
      AddChildReaction(child, force, moment, up);
      Accumulate(link[child].parent, up, loads, touched);
      moment = up.moment;
    }
  }

  static void Accumulate(int id, const Load& delta, std::vector<Load>& loads,
                         std::vector<int>* touched) {
    Load& l = loads[id];
    for (int i = 0; i < 3; ++i) l.q[i] += delta.q[i];
    l.force += delta.force;
    l.moment += delta.moment;
    if (touched) touched->push_back(id);
  }

  Eigen::Vector3d RopeForce(const RopeSlot& slot) const {
    const Eigen::Vector3d point = PointNow(slot.rope.branch, slot.arc_length);
    const Eigen::Vector3d to_anchor = slot.rope.anchor - point;
    const double distance = to_anchor.norm();
    if (distance < 1e-9 || slot.tension == 0.0) return Eigen::Vector3d::Zero();
    return slot.tension / distance * to_anchor;
  }

  bool DistributedLoads() const { return options.gravity || wind.options().enabled; }
  bool AnyLoad() const { return DistributedLoads() || !ropes.empty(); }

  void ClearLoads(bool everything = false) {
    if (all_loaded || everything) {
      std::fill(load.begin(), load.end(), Load{});
      all_loaded = false;
    } else {
      for (int id : loaded) load[id] = Load{};
    }
    loaded.clear();
  }

  // Fills `load` for the configuration now.
  void ComputeLoads() {
    ClearLoads();
    if (DistributedLoads()) {
      if (wind.options().enabled) wind.SampleGrid(time);
      ForRange(0, size(), [&](int id) { load[id] = OwnDistributedLoad(id); });
      all_loaded = true;
      for (const auto& [rope_id, slot] : ropes) {
        const int b = slot.rope.branch;
        const PointOnBranch p = PointAt(b, slot.arc_length);
        AddPointLoad(b, p.phi, p.slope, p.psi, state[b].frame * p.rest_offset, RopeForce(slot),
                     Eigen::Vector3d::Zero(), load[b]);
      }
      if (!options.transfer_loads) return;
      // Children before parents: each parent gathers its children's reactions.
      for (size_t l = level_begin.size() - 1; l-- > 1;) {
        ForRange(level_begin[l - 1], level_begin[l], [&](int i) {
          const int parent = level_order[i];
          for (int c = child_begin[parent]; c < child_begin[parent + 1]; ++c) {
            const int child = child_list[c];
            AddChildReaction(child, load[child].force, load[child].moment, load[parent]);
          }
        });
      }
      return;
    }
    for (const auto& [rope_id, slot] : ropes) {
      WalkPointLoad(slot.rope.branch, slot.arc_length, RopeForce(slot), load, &loaded);
    }
  }

  void Step(double dt) {
    if (!(dt > 0.0) || !std::isfinite(dt)) {
      throw InputError("TreeDynamics::Step", "dt",
                       fmt::format("expected a positive finite time step (s), got {}", dt));
    }
    if (dt != step_dt) {
      step_dt = dt;
      ForRange(0, size(), [&](int id) { BuildSteps(id, dt); });
    }
    const bool loaded_step = AnyLoad();
    if (loaded_step) {
      ComputeLoads();
    } else if (all_loaded || !loaded.empty()) {
      ClearLoads();
    }
    TopDown([&](int id) {
      AdvanceBranch(id, dt, loaded_step);
      PoseBranch(id);
      DeformNodes(id);
    });
    time += dt;
    ++steps;
  }

  void SettleStatic() {
    // Loads depend on the configuration (rope direction, frames), so iterate a few times.
    for (int iteration = 0; iteration < 4; ++iteration) {
      ComputeLoads();
      ForRange(0, size(), [&](int id) {
        State& st = state[id];
        for (int i = 0; i < 3; ++i) {
          const double w = kTwoPi * model[id].frequency[i];
          st.modal.q[i] = load[id].q[i] * link[id].inverse_mass[i] / (w * w);
          st.modal.v[i] = 0.0;
          st.acceleration[i] = 0.0;
        }
        st.primary = st.modal;
        st.swing = ModalState{};
        st.base_acceleration.setZero();
        st.base_angular_acceleration.setZero();
      });
      UpdateGeometry();
    }
  }

  void ResetState() {
    for (State& st : state) st = State{};
    ropes.clear();
    ClearLoads(/*everything=*/true);
    time = 0.0;
    steps = 0;
    UpdateGeometry();
    if (options.gravity) {
      // Pre-sag: the equilibrium under self-weight alone, whatever the wind does.
      const WindOptions saved = wind.options();
      if (saved.enabled) {
        WindOptions off = saved;
        off.enabled = false;
        wind = WindField(off, bounds_min, bounds_max);
      }
      SettleStatic();
      if (saved.enabled) wind = WindField(saved, bounds_min, bounds_max);
    }
  }

  // Tension that displaces the rope's point statically by its displacement towards the anchor:
  // the compliance along the rope comes from the static response to a probe force.
  double TensionForDisplacement(const RopeSlot& slot) const {
    const int id = slot.rope.branch;
    const Eigen::Vector3d point = PointNow(id, slot.arc_length);
    const Eigen::Vector3d to_anchor = slot.rope.anchor - point;
    if (to_anchor.norm() < 1e-9 || slot.rope.displacement_m == 0.0) return 0.0;
    const Eigen::Vector3d direction = to_anchor.normalized();
    std::vector<Load> probe(size());
    std::vector<int> touched;
    WalkPointLoad(id, slot.arc_length, direction, probe, &touched);
    std::map<int, std::array<double, 3>> dq;
    double largest = 0.0;
    for (int b : touched) {
      std::array<double, 3> q = {0, 0, 0};
      for (int i = 0; i < 3; ++i) {
        const double w = kTwoPi * model[b].frequency[i];
        q[i] = probe[b].q[i] * link[b].inverse_mass[i] / (w * w);
        largest = std::max(largest, std::abs(q[i]));
      }
      dq[b] = q;
    }
    if (largest == 0.0) {
      throw InputError("rope", "displacement_m",
                       fmt::format("the point at {:.4g} m on branch {} cannot move towards the "
                                   "anchor, so no tension displaces it",
                                   slot.arc_length, id));
    }
    // Linearise around the state now with a probe small enough to stay linear.
    const double epsilon = 1e-6 / largest;
    const auto moved = [&](int b) {
      std::array<double, 3> q = state[b].modal.q;
      if (auto it = dq.find(b); it != dq.end()) {
        for (int i = 0; i < 3; ++i) q[i] += epsilon * it->second[i];
      }
      return q;
    };
    const auto now = [&](int b) { return state[b].modal.q; };
    const Eigen::Vector3d displaced = PointWith(id, slot.arc_length, moved);
    const Eigen::Vector3d here = PointWith(id, slot.arc_length, now);
    const double compliance = (displaced - here).dot(direction) / epsilon;  // m per N
    if (!(compliance > 0.0)) {
      throw InputError("rope", "displacement_m",
                       fmt::format("the point at {:.4g} m on branch {} does not move towards the "
                                   "anchor when pulled",
                                   slot.arc_length, id));
    }
    return slot.rope.displacement_m / compliance;
  }

  void SetTension(RopeSlot& slot) const {
    slot.tension =
        slot.rope.mode == Rope::Mode::kForce ? slot.rope.force_n : TensionForDisplacement(slot);
  }

  Eigen::Matrix3d NodeRotation(int id, int j) const {
    const Link& k = link[id];
    const Model& m = model[id];
    const State& st = state[id];
    const double x = node.arc_fraction[k.first_node + j];
    const double slope = m.length > 0.0 ? BendingModeSlope(x) / m.length : 0.0;
    const double psi = node.psi[k.first_node + j];
    return st.frame * RotationFromVector(LocalRotation(slope, psi, st.modal.q)) *
           m.frame.transpose();
  }
};

// ------------------------------------------------------------------------------------------------

TreeDynamics::TreeDynamics(const Tree& tree, const DynamicsOptions& options)
    : impl_(std::make_unique<Impl>(tree, options)) {}
TreeDynamics::~TreeDynamics() = default;
TreeDynamics::TreeDynamics(TreeDynamics&&) noexcept = default;
TreeDynamics& TreeDynamics::operator=(TreeDynamics&&) noexcept = default;

const Tree& TreeDynamics::tree() const { return impl_->tree; }
const DynamicsOptions& TreeDynamics::options() const { return impl_->options; }

void TreeDynamics::Step(double dt) { impl_->Step(dt); }

void TreeDynamics::Advance(double duration, double max_dt) {
  if (!(duration >= 0.0) || !std::isfinite(duration) || !(max_dt > 0.0)) {
    throw InputError(
        "TreeDynamics::Advance", "duration",
        fmt::format("expected a duration >= 0 and a step > 0, got {} and {}", duration, max_dt));
  }
  if (duration == 0.0) return;
  const int64_t n = static_cast<int64_t>(std::ceil(duration / max_dt - 1e-9));
  const double dt = duration / static_cast<double>(n);
  for (int64_t i = 0; i < n; ++i) impl_->Step(dt);
}

double TreeDynamics::time() const { return impl_->time; }
int64_t TreeDynamics::steps() const { return impl_->steps; }
void TreeDynamics::Reset() { impl_->ResetState(); }
void TreeDynamics::SettleStatic() { impl_->SettleStatic(); }

int TreeDynamics::AttachRope(const Rope& rope) {
  Impl::RopeSlot slot;
  slot.rope = rope;
  slot.arc_length = ValidateRope(impl_->tree, rope);
  impl_->SetTension(slot);
  const int id = impl_->next_rope_id++;
  impl_->ropes[id] = slot;
  return id;
}

void TreeDynamics::UpdateRope(int id, const Rope& rope) {
  auto it = impl_->ropes.find(id);
  if (it == impl_->ropes.end()) {
    throw InputError("rope", "id", fmt::format("expected an attached rope, got id {}", id));
  }
  Impl::RopeSlot slot;
  slot.rope = rope;
  slot.arc_length = ValidateRope(impl_->tree, rope);
  impl_->SetTension(slot);
  it->second = slot;
}

void TreeDynamics::ReleaseRope(int id) { impl_->ropes.erase(id); }
void TreeDynamics::ReleaseAllRopes() { impl_->ropes.clear(); }
bool TreeDynamics::HasRope(int id) const { return impl_->ropes.count(id) > 0; }

const Rope& TreeDynamics::rope(int id) const {
  auto it = impl_->ropes.find(id);
  if (it == impl_->ropes.end()) {
    throw InputError("rope", "id", fmt::format("expected an attached rope, got id {}", id));
  }
  return it->second.rope;
}

double TreeDynamics::RopeTension(int id) const {
  auto it = impl_->ropes.find(id);
  return it == impl_->ropes.end() ? 0.0 : it->second.tension;
}

Eigen::Vector3d TreeDynamics::RopePoint(int id) const {
  auto it = impl_->ropes.find(id);
  if (it == impl_->ropes.end()) {
    throw InputError("rope", "id", fmt::format("expected an attached rope, got id {}", id));
  }
  return impl_->PointNow(it->second.rope.branch, it->second.arc_length);
}

void TreeDynamics::SetWind(const WindOptions& wind) {
  impl_->wind = WindField(wind, impl_->bounds_min, impl_->bounds_max);
  impl_->options.wind = wind;
}

void TreeDynamics::SetWindEnabled(bool enabled) {
  WindOptions w = impl_->options.wind;
  w.enabled = enabled;
  SetWind(w);
}

void TreeDynamics::SetWindSpeed(double mean_speed_mps) {
  WindOptions w = impl_->options.wind;
  w.mean_speed_mps = mean_speed_mps;
  SetWind(w);
}

const WindOptions& TreeDynamics::wind() const { return impl_->options.wind; }

Eigen::Vector3d TreeDynamics::WindVelocity(const Eigen::Vector3d& point) const {
  return impl_->wind.VelocityExact(point, impl_->time);
}

const Material& TreeDynamics::material(int branch) const {
  return *impl_->tree.branches.at(branch).material;
}

void TreeDynamics::SetMaterial(int branch, const Material& material) {
  if (branch < 0 || branch >= impl_->size()) {
    throw InputError(
        "material", "branch",
        fmt::format("expected a branch id in [0, {}], got {}", impl_->size() - 1, branch));
  }
  CheckMaterialForSimulation(material, "material", fmt::format("branches[{}]", branch));
  impl_->tree.branches[branch].material = material;
  impl_->BuildMaterial(branch);
  // Ropes pulling by displacement need the new compliance.
  for (auto& [id, slot] : impl_->ropes) impl_->SetTension(slot);
}

const ModalState& TreeDynamics::modal_state(int branch) const {
  return impl_->state.at(branch).modal;
}

void TreeDynamics::SetModalState(int branch, const ModalState& s) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(s.q[i]) || !std::isfinite(s.v[i])) {
      throw InputError("modal state", fmt::format("branch {}", branch),
                       "expected finite coordinates and rates");
    }
  }
  Impl::State& st = impl_->state.at(branch);
  st.modal = st.primary = s;
  st.swing = ModalState{};
  impl_->UpdateGeometry();
}

double TreeDynamics::BranchEnergy(int branch) const {
  const Impl::Model& m = impl_->model.at(branch);
  const ModalState& s = impl_->state[branch].modal;
  double e = 0.0;
  for (int i = 0; i < 3; ++i)
    e += OscillatorEnergy(m.modal_mass[i], m.frequency[i], s.q[i], s.v[i]);
  return e;
}

double TreeDynamics::Energy() const {
  double e = 0.0;
  for (int b = 0; b < impl_->size(); ++b) e += BranchEnergy(b);
  return e;
}

std::span<const Eigen::Vector3f> TreeDynamics::node_positions() const { return impl_->positions; }
int TreeDynamics::node_offset(int branch) const { return impl_->link.at(branch).first_node; }
int TreeDynamics::node_count() const { return static_cast<int>(impl_->positions.size()); }
int TreeDynamics::branch_count() const { return impl_->size(); }

BranchPose TreeDynamics::pose(int branch) const {
  const Impl::State& st = impl_->state.at(branch);
  BranchPose p;
  p.origin = st.origin;
  p.rotation = impl_->Rotation(branch);
  p.frame.u = st.frame.col(0);
  p.frame.v = st.frame.col(1);
  p.frame.w = st.frame.col(2);
  return p;
}

Eigen::Vector3d TreeDynamics::PointPosition(int branch, double arc_length) const {
  if (branch < 0 || branch >= impl_->size()) {
    throw InputError(
        "point", "branch",
        fmt::format("expected a branch id in [0, {}], got {}", impl_->size() - 1, branch));
  }
  return impl_->PointNow(branch, arc_length);
}

Eigen::Matrix3d TreeDynamics::NodeRotation(int branch, int node) const {
  const Impl::Link& k = impl_->link.at(branch);
  if (node < 0 || node >= k.nodes) {
    throw InputError("node rotation", fmt::format("branch {}", branch),
                     fmt::format("expected a node index in [0, {}], got {}", k.nodes - 1, node));
  }
  return impl_->NodeRotation(branch, node);
}

void TreeDynamics::NodeRotations(std::span<Eigen::Quaternionf> out) const {
  if (static_cast<int>(out.size()) != node_count()) {
    throw InputError(
        "node rotations", "out",
        fmt::format("expected room for {} rotations, got {}", node_count(), out.size()));
  }
  impl_->ForRange(0, impl_->size(), [&](int b) {
    const Impl::Link& k = impl_->link[b];
    for (int j = 0; j < k.nodes; ++j) {
      out[k.first_node + j] = Eigen::Quaternionf(impl_->NodeRotation(b, j).cast<float>());
    }
  });
}

}  // namespace simtree::dynamics
