#pragma once
// materials.json (`simtree.materials` v1): what `identify` measured, what `build` reads. Prose in
// docs/formats.md. Per marker link: the chosen estimator's frequency and damping (with standard
// deviations when it gives them), each bending plane's, every estimator's reading and a status
// that says why a value is missing. Per branch that carries a marker: the three modes that branch
// gets. Values that could not be estimated are null, never a number.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/core/tree.h"
#include "simtree/identification/identify.h"

namespace simtree::identification {

inline constexpr const char* kMaterialsFormat = "simtree.materials";
inline constexpr int kMaterialsFormatVersion = 1;

struct LinkMaterial {
  int child = 0;  // marker ids
  int parent = -1;
  std::string label;
  std::optional<int> branch;  // the child marker's branch
  DeflectionKind kind = DeflectionKind::kRelativeAngle;
  ModalEstimate value;                  // the chosen estimator's
  std::array<ModalEstimate, 2> planes;  // u, w (or the two principal directions of the root)
  std::vector<std::pair<EstimatorKind, ModalEstimate>> estimators;  // every estimator run
  // Which poles the damped sinusoid fit's value was read on ("shared": the tree's joint poles,
  // "own": the link's own fit) and why; empty when the fit measured nothing.
  std::string poles, poles_why;
  // Both readings of the fit's dominant mode (status kFailed when not made): on the shared poles
  // and on the link's own fit, whichever `poles` chose.
  ModalEstimate shared_reading, own_reading;
  // The joint poles as this link carries them (strength, share, participation) and the mode its
  // branch gets, which `branches` and `build` use (detail/branch_modes.h: the dominant one by
  // default), with the most participating pole beside it; no frequency without joint poles (the
  // branch then takes `value`).
  std::vector<LinkModeShare> modes;
  ModalEstimate branch_mode;
  std::array<ModalEstimate, 2> branch_planes;
  double branch_participation = std::numeric_limits<double>::quiet_NaN();
  double most_participating_hz = std::numeric_limits<double>::quiet_NaN();
  std::string branch_mode_why;
};

// The three modes a measured branch gets. `assumed[k]` is true for a mode taken from the
// dominant value rather than measured in its own plane (twist is never seen by a marker centre).
struct BranchMaterial {
  int branch = 0;
  int link_child = 0;  // the marker whose link measured it
  std::array<Mode, 3> modes;
  std::array<bool, 3> assumed = {false, false, true};
  double frequency_std_hz = std::numeric_limits<double>::quiet_NaN();
  double damping_std = std::numeric_limits<double>::quiet_NaN();
};

struct MaterialsFile {
  EstimatorKind estimator = kDefaultEstimator;  // whose values `value` and `branches` hold
  std::string trajectories;                     // the file it came from
  double frame_rate_hz = 0.0;
  double release_time_s = 0.0;    // on the trajectories' clock
  bool release_detected = false;  // the release was found (detected or given), not assumed
  std::string release_note;
  double window_start_s = 0.0, window_end_s = 0.0;  // the free decay used, s
  std::vector<LinkMaterial> links;
  std::vector<BranchMaterial> branches;
  MaterialRanges ranges;
};

// The file's content from an identification. Branch values come from links whose child marker
// has a branch (markers.json "branch"); `marker_branch` may supply more (marker id -> branch, e.g.
// from a static tree's markers). When several links land on one branch the most certain one
// (smallest relative frequency deviation, else largest amplitude) is kept.
MaterialsFile MaterialsFromIdentification(const IdentificationResult& result,
                                          const std::string& trajectories_name);

// Recomputes `branches` from `links`, taking a link's branch from `marker_branch` (indexed by
// marker id, -1 when unknown) when the link has none.
void AssignBranchMaterials(MaterialsFile& materials, const std::vector<int>& marker_branch = {});

nlohmann::ordered_json MaterialsToJson(const MaterialsFile& materials);
MaterialsFile MaterialsFromJson(const nlohmann::json& doc, const std::string& source);
MaterialsFile ReadMaterialsJson(const std::filesystem::path& path);
void WriteMaterialsJson(const MaterialsFile& materials, const std::filesystem::path& path);

}  // namespace simtree::identification
