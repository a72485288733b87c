#include "simtree/synth/detail/fem_truth.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/validate.h"
#include "simtree/synth/detail/fem_effective_mass.h"

namespace simtree::synth {
namespace {

// A signal's value per unit of each modal coordinate: 3 x mode count.
using ModalSignal = Eigen::Matrix<double, 3, Eigen::Dynamic>;

Eigen::Matrix3d Skew(const Eigen::Vector3d& e) {
  Eigen::Matrix3d s;
  s << 0, -e.z(), e.y(), e.z(), 0, -e.x(), -e.y(), e.x(), 0;
  return s;
}

class SignalBuilder {
 public:
  SignalBuilder(const FemModel& model, const ModalBasis& modes, const Tree& tree)
      : model_(model), modes_(modes), tree_(tree) {}

  Eigen::Vector3d RestPoint(int branch, double s) const {
    return tree_.branches[branch].PointAt(s);
  }
  ModalSignal Displacement(int branch, double s) const {
    return model_.PointMapAt(branch, s).ApplyToColumns(modes_.shapes).topRows<3>();
  }
  // The shortest rotation of a segment of rest direction `e` and length `length` whose ends move
  // by `d_start` and `d_end`: e x (d_end - d_start) / length.
  static ModalSignal Swing(const Eigen::Vector3d& e, double length, const ModalSignal& d_start,
                           const ModalSignal& d_end) {
    return Skew(e) * (d_end - d_start) / length;
  }
  // The deflection of a direction `e` (length `length`, ends moving by d_start, d_end) with a
  // reference swing `reference` (rotation vectors) taken out: the change of the de-rotated
  // direction, (I - e e^T)(d_end - d_start) / length - reference x e.
  static ModalSignal Deflection(const Eigen::Vector3d& e, double length, const ModalSignal& d_start,
                                const ModalSignal& d_end, const ModalSignal& reference) {
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - e * e.transpose();
    return across * (d_end - d_start) / length + Skew(e) * reference;
  }
  // The rotation (3 x modes) of a FEM node, less its component about `tangent`.
  ModalSignal TangentSwing(int node, const Eigen::Vector3d& tangent) const {
    const ModalSignal rotation = model_.NodeMap(node).ApplyToColumns(modes_.shapes).bottomRows<3>();
    return (Eigen::Matrix3d::Identity() - tangent * tangent.transpose()) * rotation;
  }
  ModalSignal Zero() const { return ModalSignal::Zero(3, modes_.count()); }

 private:
  const FemModel& model_;
  const ModalBasis& modes_;
  const Tree& tree_;
};

// The unit tangent of a branch's rest polyline at node `index`: the mean of its two segments.
Eigen::Vector3d TangentAtNode(const Branch& b, int index) {
  const int n = static_cast<int>(b.nodes.size());
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  if (index + 1 < n) t += (b.nodes[index + 1].position - b.nodes[index].position).normalized();
  if (index > 0) t += (b.nodes[index].position - b.nodes[index - 1].position).normalized();
  return t.norm() > 1e-12 ? Eigen::Vector3d(t.normalized()) : Eigen::Vector3d::UnitZ();
}

// A mode's damped angular frequency w_d = w sqrt(1 - zeta^2), kept above zero for the decay's
// B = (q'(0) + zeta w A) / w_d (an overdamped mode, none of a tree's lowest, is nearly still).
double DampedOmega(double omega, double zeta) {
  return omega * std::sqrt(std::max(1e-12, 1.0 - zeta * zeta));
}

// Each mode's free decay after release, q(t) = e^(-zeta w t) (A cos w_d t + B sin w_d t).
struct Decay {
  Eigen::VectorXd cos_part, sin_part;  // A, B per mode
};
Decay FreeDecay(const ModalBasis& modes, const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0) {
  Decay out{q0, Eigen::VectorXd(modes.count())};
  for (int i = 0; i < modes.count(); ++i) {
    const double w = modes.omega[i], zeta = modes.damping_ratio[i];
    out.sin_part[i] = (qd0[i] + zeta * w * q0[i]) / DampedOmega(w, zeta);
  }
  return out;
}

// Modes of one frequency (a round branch bends alike in two planes) make one spectral peak, and
// how an eigensolver splits such a pair is arbitrary: they are one group, reported as its first.
constexpr double kSameFrequency = 1e-6;  // relative

// The first mode of each group of modes of one frequency, and the end of the last group.
std::vector<int> FrequencyGroups(const ModalBasis& modes) {
  std::vector<int> first;
  for (int i = 0; i < modes.count(); ++i) {
    if (first.empty() ||
        modes.frequency_hz[i] > modes.frequency_hz[first.back()] * (1 + kSameFrequency)) {
      first.push_back(i);
    }
  }
  first.push_back(modes.count());
  return first;
}

// spectra(i, g): the Fourier integral over the record of mode i's free decay at group g's damped
// frequency (DecayFourierIntegral).
Eigen::MatrixXcd DecaySpectra(const ModalBasis& modes, const Decay& decay,
                              const std::vector<int>& groups, double record) {
  const int group_count = static_cast<int>(groups.size()) - 1;
  Eigen::MatrixXcd spectra(modes.count(), group_count);
  for (int g = 0; g < group_count; ++g) {
    const int j = groups[g];
    const double at = DampedOmega(modes.omega[j], modes.damping_ratio[j]);
    for (int i = 0; i < modes.count(); ++i) {
      spectra(i, g) = DecayFourierIntegral(modes.omega[i], modes.damping_ratio[i],
                                           decay.cos_part[i], decay.sin_part[i], at, record);
    }
  }
  return spectra;
}

std::vector<ModalTruth::ModePeak> StrongestModes(const ModalSignal& signal, const ModalBasis& modes,
                                                 const Decay& decay, const std::vector<int>& groups,
                                                 const Eigen::MatrixXcd& spectra,
                                                 const ModalTruthOptions& options) {
  // The signal's spectrum at every group's frequency: every mode adds with its phase.
  const Eigen::MatrixXcd spectrum = signal.cast<std::complex<double>>() * spectra;  // 3 x groups
  std::vector<ModalTruth::ModePeak> all;
  for (int g = 0; g + 1 < static_cast<int>(groups.size()); ++g) {
    // The group's own signal: Re and Im parts of its complex amplitude vector.
    Eigen::Vector3d re = Eigen::Vector3d::Zero(), im = Eigen::Vector3d::Zero();
    for (int i = groups[g]; i < groups[g + 1]; ++i) {
      re += signal.col(i) * decay.cos_part[i];
      im += signal.col(i) * decay.sin_part[i];
    }
    ModalTruth::ModePeak p;
    p.mode = groups[g];
    p.frequency_hz = modes.frequency_hz[p.mode];
    p.damping_ratio = modes.damping_ratio[p.mode];
    p.amplitude = std::sqrt(re.squaredNorm() + im.squaredNorm());
    // Twice the one-sided integral: a lone mode's peak, a (1 - e^(-zeta w T)) / (zeta w).
    p.strength = 2.0 * spectrum.col(g).norm();
    all.push_back(p);
  }
  // Strongest first; ties (a signal at rest) go to the lower mode.
  std::stable_sort(all.begin(), all.end(),
                   [](const auto& a, const auto& b) { return a.strength > b.strength; });
  all.resize(std::min(static_cast<int>(all.size()), options.peaks));
  return all;
}

}  // namespace

std::complex<double> DecayFourierIntegral(double omega, double zeta, double cos_part,
                                          double sin_part, double at, double record) {
  // q(t) = (A - iB)/2 e^((-s + i w_d) t) + (A + iB)/2 e^((-s - i w_d) t), s = zeta w, and
  // integral_0^T e^(l t) dt = (e^(l T) - 1) / l (T as l -> 0).
  const auto integral = [record](std::complex<double> l) {
    return std::abs(l) * record < 1e-9 ? std::complex<double>(record)
                                       : (std::exp(l * record) - 1.0) / l;
  };
  const double decay_rate = zeta * omega;
  const double wd = DampedOmega(omega, zeta);
  const std::complex<double> a(cos_part, -sin_part);
  return 0.5 * a * integral({-decay_rate, wd - at}) +
         0.5 * std::conj(a) * integral({-decay_rate, -wd - at});
}

ModalTruth ComputeModalTruth(const FemModel& model, const ModalBasis& modes, const Tree& tree,
                             const FemState& release_state, const ModalTruthOptions& options) {
  if (!std::isfinite(options.record_after_release_s) || options.record_after_release_s <= 0 ||
      options.peaks < 1) {
    throw InputError("modal truth options", "",
                     "expected record_after_release_s > 0 and peaks >= 1");
  }
  Validate(tree, "tree");
  bool same = tree.size() == model.tree().size();
  for (int b = 0; same && b < tree.size(); ++b) {
    same = tree.branches[b].nodes.size() == model.tree().branches[b].nodes.size();
  }
  if (!same) throw InputError("tree", "branches", "expected the tree the FEM model was built from");
  if (modes.count() == 0 || modes.shapes.rows() != model.dof_count()) {
    throw InputError("modes", "", "expected the modes of this FEM model");
  }
  const int n = model.dof_count();
  const auto check = [&](const Eigen::VectorXd& v, const char* what) {
    if (v.size() != n || !v.allFinite()) {
      throw InputError("release state", what,
                       fmt::format("expected {} finite values, got {}", n, v.size()));
    }
  };
  check(release_state.x, "x");
  check(release_state.v, "v");

  const Decay decay = FreeDecay(modes, modes.Project(model.mass(), release_state.x),
                                modes.Project(model.mass(), release_state.v));
  const SignalBuilder signals(model, modes, tree);
  const std::vector<int> groups = FrequencyGroups(modes);
  const Eigen::MatrixXcd spectra =
      DecaySpectra(modes, decay, groups, options.record_after_release_s);

  ModalTruth truth;
  truth.source = "fem";
  const EffectiveMasses masses = ComputeEffectiveMasses(model, modes);
  for (int i = 0; i < modes.count(); ++i) {
    truth.modes.push_back(
        {modes.frequency_hz[i], modes.damping_ratio[i], masses.horizontal[i], masses.torsion[i]});
  }
  if (const int sway = LowestSwayMode(masses); sway >= 0) truth.lowest_sway_mode = sway;
  const auto fill = [&](const ModalSignal& signal, auto& out) {
    out.peaks = StrongestModes(signal, modes, decay, groups, spectra, options);
    out.frequency_hz = out.peaks.front().frequency_hz;
    out.damping_ratio = out.peaks.front().damping_ratio;
  };

  // Marker links, the root marker's displacement first (as identification lists them).
  const std::vector<Marker>& markers = tree.markers;
  std::vector<int> order(markers.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_partition(order.begin(), order.end(), [&](int m) { return markers[m].parent < 0; });
  for (int m : order) {
    const Marker& child = markers[m];
    ModalTruth::Link link;
    link.parent = child.parent;
    link.child = child.id;
    const ModalSignal d_child = signals.Displacement(child.branch, child.arc_length);
    if (child.parent < 0) {
      fill(d_child, link);
      truth.links.push_back(std::move(link));
      continue;
    }
    const Marker& parent = markers[child.parent];
    const Eigen::Vector3d p_child = signals.RestPoint(child.branch, child.arc_length);
    const Eigen::Vector3d p_parent = signals.RestPoint(parent.branch, parent.arc_length);
    const double length = (p_child - p_parent).norm();
    if (length < 1e-6) {
      throw InputError("tree", fmt::format("markers[{}]", child.id),
                       fmt::format("markers {} and {} coincide at rest: their link has no "
                                   "direction",
                                   parent.id, child.id));
    }
    const ModalSignal d_parent = signals.Displacement(parent.branch, parent.arc_length);
    ModalSignal reference = signals.Zero();
    if (parent.parent >= 0) {
      const Marker& grand = markers[parent.parent];
      const Eigen::Vector3d p_grand = signals.RestPoint(grand.branch, grand.arc_length);
      const double parent_length = (p_parent - p_grand).norm();
      if (parent_length >= 1e-6) {
        reference =
            SignalBuilder::Swing((p_parent - p_grand) / parent_length, parent_length,
                                 signals.Displacement(grand.branch, grand.arc_length), d_parent);
      }
    }
    fill(SignalBuilder::Deflection((p_child - p_parent) / length, length, d_parent, d_child,
                                   reference),
         link);
    truth.links.push_back(std::move(link));
  }

  // Branches: the chord against the parent's tangent at the attachment.
  for (const Branch& b : tree.branches) {
    const double arc = b.Length();
    const Eigen::Vector3d chord = signals.RestPoint(b.id, arc) - signals.RestPoint(b.id, 0.0);
    const double length = chord.norm();
    if (length < 1e-9) continue;
    ModalSignal reference = signals.Zero();
    if (!b.is_trunk()) {
      const Branch& parent = tree.branches[b.parent];
      reference =
          signals.TangentSwing(model.tree_node(b.id, 0), TangentAtNode(parent, b.parent_node));
    }
    ModalTruth::BranchTruth out;
    out.branch = b.id;
    fill(SignalBuilder::Deflection(chord / length, length, signals.Displacement(b.id, 0.0),
                                   signals.Displacement(b.id, arc), reference),
         out);
    truth.branches.push_back(std::move(out));
  }
  return truth;
}

}  // namespace simtree::synth
