#include "simtree/simready/build.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/frames.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/core/units.h"
#include "simtree/core/validate.h"

namespace simtree::simready {

double CantileverModeShape(double xi) {
  // beta L of the first mode: the smallest root of 1 + cos(x) cosh(x) = 0.
  constexpr double kBeta = 1.8751040687119611;
  static const double sigma =
      (std::cosh(kBeta) + std::cos(kBeta)) / (std::sinh(kBeta) + std::sin(kBeta));
  auto raw = [](double x) {
    const double b = kBeta * x;
    return std::cosh(b) - std::cos(b) - sigma * (std::sinh(b) - std::sin(b));
  };
  static const double tip = raw(1.0);
  return raw(std::clamp(xi, 0.0, 1.0)) / tip;
}

std::vector<double> SubtreeMasses(const Tree& tree, double density_kg_m3) {
  std::vector<double> mass(tree.size(), 0.0);
  // Parents come before children, so one backward pass adds every sub-tree into its parent.
  for (int b = tree.size() - 1; b >= 0; --b) {
    mass[b] += density_kg_m3 * tree.branches[b].Volume();
    if (tree.branches[b].parent >= 0) mass[tree.branches[b].parent] += mass[b];
  }
  return mass;
}

double BranchModalMass(const Tree& tree, int id, double density_kg_m3,
                       const std::vector<double>& subtree_mass) {
  const Branch& branch = tree.branches[id];
  const std::vector<double> s = branch.ArcLengths();
  const double length = s.back();
  if (!(length > 0)) return 0.0;
  // 3-point Gauss-Legendre on each frustum: r is linear along it, so mu phi^2 is smooth.
  static const double kNodes[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  static const double kWeights[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  double mass = 0.0;
  for (size_t i = 0; i + 1 < branch.nodes.size(); ++i) {
    const double half = 0.5 * (s[i + 1] - s[i]);
    for (int q = 0; q < 3; ++q) {
      const double a = 0.5 * (1 + kNodes[q]);
      const double r = (1 - a) * branch.nodes[i].radius + a * branch.nodes[i + 1].radius;
      const double phi = CantileverModeShape((s[i] + a * (s[i + 1] - s[i])) / length);
      mass += kWeights[q] * half * density_kg_m3 * kPi * r * r * phi * phi;
    }
  }
  if (!subtree_mass.empty()) {
    for (const Branch& child : tree.branches) {
      if (child.parent != id) continue;
      const double phi = CantileverModeShape(s[child.parent_node] / length);
      mass += subtree_mass[child.id] * phi * phi;
    }
  }
  return mass;
}

Tree RenumberDepthFirst(const Tree& tree, std::vector<int>* new_id_out) {
  const std::vector<int> order = tree.DepthFirstOrder();
  std::vector<int> new_id(tree.size(), -1);
  for (size_t i = 0; i < order.size(); ++i) new_id[order[i]] = static_cast<int>(i);
  Tree out;
  out.metadata = tree.metadata;
  for (int old : order) {
    Branch b = tree.branches[old];
    b.id = new_id[old];
    b.parent = b.parent < 0 ? -1 : new_id[b.parent];
    out.branches.push_back(std::move(b));
  }
  out.markers = tree.markers;
  for (Marker& m : out.markers) m.branch = new_id[m.branch];
  if (new_id_out) *new_id_out = std::move(new_id);
  return out;
}

void BuildOptions::Validate() const {
  CheckPositive("wood_density_kg_m3", wood_density_kg_m3);
  CheckNested("interpolation", interpolation);
  CheckNested("uncertainty", uncertainty);
}

void AssumedMaterial::Validate() const {
  CheckInRange("frequency_hz", frequency_hz, 0.01, 100.0);
  CheckThat(damping_ratio > 0 && damping_ratio < 1, "damping_ratio", "a value in (0, 1)",
            damping_ratio);
}

AssumedMaterial AssumedMaterialOf(const std::string& species) {
  const TypicalMaterial& row = FindTypicalMaterial(species);
  return {row.frequency_hz(), row.damping_ratio(),
          fmt::format("{}, the middle of the paper's Table IV ranges ({:.2f}-{:.2f} Hz, damping "
                      "{:.3f}-{:.3f})",
                      row.species, row.min_frequency_hz, row.max_frequency_hz,
                      row.min_damping_ratio, row.max_damping_ratio)};
}

namespace {

// The materials with every measured link's branch found: its own branch id, or the static
// tree's marker of the same id.
identification::MaterialsFile MaterialsOnTree(const Tree& tree,
                                              const identification::MaterialsFile& materials) {
  identification::MaterialsFile m = materials;
  if (m.links.empty()) return m;
  std::vector<int> marker_branch;
  for (const Marker& marker : tree.markers) {
    if (marker.id < 0) continue;
    if (marker.id >= static_cast<int>(marker_branch.size()))
      marker_branch.resize(marker.id + 1, -1);
    marker_branch[marker.id] = marker.branch;
  }
  identification::AssignBranchMaterials(m, marker_branch);
  return m;
}

// Why nothing can be built: no link measured, or none on a branch of the tree.
[[noreturn]] void ThrowNothingMeasured(const identification::MaterialsFile& m) {
  int with_value = 0;
  for (const identification::LinkMaterial& l : m.links) {
    with_value += l.value.status == identification::EstimateStatus::kOk;
  }
  throw InputError(
      "materials", "",
      with_value == 0
          ? "no link has a measured value: nothing to build from (see the links' status)"
          : fmt::format("{} links are measured but none is on a known branch: give markers a "
                        "\"branch\" in markers.json, or use a static tree whose markers have "
                        "the same ids",
                        with_value));
}

// The measured branches: their dominant values (what the interpolation fits) and the median
// ratio of each mode's frequency and damping to the dominant one's (how an interpolated branch
// spreads its value over three modes).
struct Measured {
  std::vector<bool> branch;  // per branch of the tree
  std::vector<BranchSample> samples;
  double mode_f[3] = {0, 0, 0}, mode_z[3] = {0, 0, 0};
};

// Where the estimator gave other values deviations, a value without one is a fit whose
// covariance broke down (identify's rule, docs/identification.md "Table IV ranges"): as uncertain
// as can be. Where none has one (an estimator that gives none), they stay unknown (NaN).
void MissingDeviationsAreUnknown(std::vector<BranchSample>& samples) {
  bool any_f = false, any_z = false;
  for (const BranchSample& s : samples) {
    any_f |= std::isfinite(s.frequency_std_hz);
    any_z |= std::isfinite(s.damping_std);
  }
  constexpr double kUnknown = std::numeric_limits<double>::infinity();
  for (BranchSample& s : samples) {
    if (any_f && std::isnan(s.frequency_std_hz)) s.frequency_std_hz = kUnknown;
    if (any_z && std::isnan(s.damping_std)) s.damping_std = kUnknown;
  }
}

// Sets every measured branch's material from `m`; throws when a branch is not in the tree or
// none is measured.
Measured ApplyMeasuredMaterials(const identification::MaterialsFile& m, Tree& tree) {
  Measured out;
  out.branch.assign(tree.size(), false);
  std::vector<double> ratio_f[3], ratio_z[3];
  for (size_t i = 0; i < m.branches.size(); ++i) {
    const identification::BranchMaterial& b = m.branches[i];
    if (b.branch < 0 || b.branch >= tree.size()) {
      throw InputError("materials", fmt::format("branches[{}].branch", i),
                       fmt::format("branch {} is not in the tree (it has {} branches: is this "
                                   "the static tree the markers were placed on?)",
                                   b.branch, tree.size()));
    }
    Material material;
    material.modes = b.modes;
    material.source = MaterialSource::kMeasured;
    tree.branches[b.branch].material = material;
    out.branch[b.branch] = true;
    // The twist mode carries the link's dominant value (a marker centre cannot see twist).
    const Mode& dominant = b.modes[2];
    out.samples.push_back({b.branch, dominant.frequency_hz, dominant.damping_ratio,
                           b.frequency_std_hz, b.damping_std});
    for (int k = 0; k < 3; ++k) {
      ratio_f[k].push_back(b.modes[k].frequency_hz / dominant.frequency_hz);
      ratio_z[k].push_back(b.modes[k].damping_ratio / dominant.damping_ratio);
    }
  }
  if (out.samples.empty()) ThrowNothingMeasured(m);
  MissingDeviationsAreUnknown(out.samples);
  for (int k = 0; k < 3; ++k) {
    out.mode_f[k] = Median(ratio_f[k]);
    out.mode_z[k] = Median(ratio_z[k]);
  }
  return out;
}

// Unmeasured branches: the interpolated dominant value, spread over the three modes by the
// measured branches' median ratios between modes. Returns how many branches it set.
int InterpolateUnmeasured(const Measured& measured, const InterpolationModel& model, Tree& tree) {
  int count = 0;
  for (Branch& b : tree.branches) {
    if (measured.branch[b.id]) continue;
    const double f = model.Frequency(tree, b.id);
    const double z = model.Damping(b.level);
    Material material;
    for (int k = 0; k < 3; ++k) {
      material.modes[k].frequency_hz = f * measured.mode_f[k];
      material.modes[k].damping_ratio = std::min(0.99, z * measured.mode_z[k]);
    }
    material.source = MaterialSource::kInterpolated;
    b.material = material;
    ++count;
  }
  return count;
}

// What SetAsideUncertain decided: each flagged branch's note, and the branches that keep their
// measured frequency but take the interpolation's damping.
struct SetAside {
  std::vector<std::pair<int, std::string>> notes;
  std::vector<int> damping_replaced;
};

// The samples whose frequency (or damping ratio) is not flagged; all of them when every one is.
std::vector<BranchSample> Trusted(const std::vector<BranchSample>& samples,
                                  const std::vector<SampleVerdict>& verdicts, bool frequency) {
  std::vector<BranchSample> out;
  for (size_t i = 0; i < samples.size(); ++i) {
    if (!(frequency ? verdicts[i].frequency_flag : verdicts[i].damping_flag)) {
      out.push_back(samples[i]);
    }
  }
  return out.empty() ? samples : out;  // nothing trusted: nothing is more certain either
}

// The measured values to trust (uncertain_values.h): a flagged frequency is left out of the
// interpolation's frequency fit, a flagged damping ratio out of its damping; a flagged frequency
// the interpolation predicts more certainly makes its branch interpolated, a flagged damping
// ratio alone only the branch's damping.
SetAside SetAsideUncertain(const BuildOptions& options, const Tree& tree, Measured& measured,
                           BuildReport& report) {
  const std::vector<BranchSample>& samples = measured.samples;
  const std::vector<SampleVerdict> verdicts =
      JudgeSamples(tree, samples, options.uncertainty, options.interpolation);
  const std::vector<BranchSample> trusted_f = Trusted(samples, verdicts, true);
  const std::vector<BranchSample> trusted_z = Trusted(samples, verdicts, false);
  report.interpolation = FitInterpolationModel(tree, trusted_f, options.interpolation);
  const InterpolationModel damping = FitInterpolationModel(tree, trusted_z, options.interpolation);
  report.interpolation.level_damping = damping.level_damping;
  report.interpolation.median_damping = damping.median_damping;
  SetAside out;
  for (size_t i = 0; i < verdicts.size(); ++i) {
    const SampleVerdict& v = verdicts[i];
    if (v.why.empty()) continue;
    const BranchSample& s = samples[i];
    const bool replace_f = options.uncertainty.replace && trusted_f.size() < samples.size() &&
                           FrequencyIsLessCertain(v, report.interpolation);
    const bool replace_z = options.uncertainty.replace && trusted_z.size() < samples.size() &&
                           !replace_f && DampingIsLessCertain(v, s, trusted_z);
    const char* what = replace_f                     ? "replaced by the interpolation"
                       : replace_z                   ? "damping replaced by the interpolation"
                       : options.uncertainty.replace ? "kept (the interpolation is no more certain)"
                                                     : "kept (--keep-uncertain)";
    std::string note = fmt::format("measured {:.3f} Hz, damping {:.3f}: {}; {}", s.frequency_hz,
                                   s.damping_ratio, v.why, what);
    report.flagged_why.push_back(fmt::format("branch {}: {}", s.branch, note));
    ++report.flagged;
    if (replace_f) {
      measured.branch[s.branch] = false;
      ++report.replaced;
    }
    if (replace_z) out.damping_replaced.push_back(s.branch);
    out.notes.emplace_back(s.branch, std::move(note));
  }
  report.measured = static_cast<int>(samples.size()) - report.replaced;
  return out;
}

// Flagged branches' notes, and the interpolation's damping where it replaced only the damping.
void MarkUncertain(const SetAside& set_aside, const Measured& measured,
                   const InterpolationModel& model, Tree& tree) {
  for (int b : set_aside.damping_replaced) {
    Material& material = *tree.branches[b].material;
    const double z = model.Damping(tree.branches[b].level);
    for (int k = 0; k < 3; ++k) {
      material.modes[k].damping_ratio = std::min(0.99, z * measured.mode_z[k]);
    }
  }
  for (const auto& [branch, note] : set_aside.notes)
    tree.branches[branch].material->uncertain = note;
}

// Every branch's modal mass and stiffness (paper Eq. 6); returns the whole tree's mass.
double AssignMassAndStiffness(const BuildOptions& options, Tree& tree) {
  double total_mass_kg = 0.0;
  const std::vector<double> subtree = SubtreeMasses(tree, options.wood_density_kg_m3);
  for (int b = 0; b < tree.size(); ++b) {
    if (tree.branches[b].parent < 0) total_mass_kg = subtree[b];
    Material& material = *tree.branches[b].material;
    material.mass_kg =
        BranchModalMass(tree, b, options.wood_density_kg_m3,
                        options.include_subtree_mass ? subtree : std::vector<double>{});
    material.stiffness = ModalStiffness(material.mass_kg, material.modes[0].frequency_hz);
  }
  return total_mass_kg;
}

// The static tree with levels and frames, ready for materials; throws for an empty tree.
Tree PrepareStaticTree(const Tree& static_tree) {
  if (static_tree.empty()) throw InputError("tree", "", "the static tree has no branches");
  Tree tree = static_tree;
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

// The finished tree: renumbered if asked, validated as simulation-ready.
Tree FinishSimulationReadyTree(Tree tree, const BuildOptions& options) {
  if (options.renumber_depth_first) tree = RenumberDepthFirst(tree);
  ValidationOptions validation;
  validation.require_materials = true;
  Validate(tree, "simulation-ready tree", validation);
  return tree;
}

}  // namespace

Tree BuildSimulationReadyTree(const Tree& static_tree,
                              const identification::MaterialsFile& materials,
                              const BuildOptions& options, BuildReport* report_out) {
  options.Validate();
  BuildReport report;
  Tree tree = PrepareStaticTree(static_tree);
  // Measured branches first: the interpolation of the others is fitted on them.
  Measured measured = ApplyMeasuredMaterials(MaterialsOnTree(tree, materials), tree);
  // Uncertain values are set aside before the interpolation is fitted on the rest.
  const SetAside set_aside = SetAsideUncertain(options, tree, measured, report);
  report.interpolated = InterpolateUnmeasured(measured, report.interpolation, tree);
  MarkUncertain(set_aside, measured, report.interpolation, tree);
  report.total_mass_kg = AssignMassAndStiffness(options, tree);
  if (report_out) *report_out = std::move(report);
  return FinishSimulationReadyTree(std::move(tree), options);
}

Tree BuildAssumedSimulationReadyTree(const Tree& static_tree, const AssumedMaterial& assumed,
                                     const BuildOptions& options, BuildReport* report_out) {
  options.Validate();
  CheckNested("assumed", assumed);
  BuildReport report;
  Tree tree = PrepareStaticTree(static_tree);
  for (Branch& b : tree.branches) {
    b.material = Material::FromFrequencyDampingStiffness(
        assumed.frequency_hz, assumed.damping_ratio, 0.0, MaterialSource::kAssumed);
  }
  report.assumed = tree.size();
  report.total_mass_kg = AssignMassAndStiffness(options, tree);
  if (report_out) *report_out = std::move(report);
  return FinishSimulationReadyTree(std::move(tree), options);
}

}  // namespace simtree::simready
