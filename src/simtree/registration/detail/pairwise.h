#pragma once
// One pair of views, coarse to fine: SAC-IA on the views' coarse points (by default the key
// region's L1-medial skeleton) applied to the whole view, then gated point-to-plane ICP. Then the
// checks that decide whether the result is trusted: a pair that fails them is reported as failed
// with the reason, never passed on as if it had registered.

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/registration/detail/gated_icp.h"
#include "simtree/registration/detail/sac_ia.h"
#include "simtree/registration/registration_view.h"

namespace simtree::registration {

struct PairOptions {
  SacIaOptions sac_ia;  // the coarse stage
  // SAC-IA's priors (sac_ia.h): both views' up directions (their trunk axes) and key-region
  // centres.
  bool up_prior = true;
  bool center_prior = true;
  double max_center_offset_share = 0.5;  // >= 0, of the key region's radius (0: no centre limit)
  // Up from the views' ground planes (in the up prior, and the snap's height) rather than from
  // the trunk axes. Off by default: on an uneven ground each view fits its plane to another
  // patch, and forcing the planes together tilts the pair.
  bool ground_as_up = false;
  bool snap_to_priors = true;  // shift the coarse result so the trunk axes meet (and the grounds)
  // The fine stage's ICP; its max_distances_m are replaced by icp_distance_factors when those are
  // given. No normal gate by default: the gate keeps mostly grazing correspondences, whose pull
  // is the most biased, and the medial fit undoes the shells' pull the gate was meant to prevent.
  GatedIcpOptions icp{.max_normal_angle_deg = 180.0};
  // Point spacings, each > 0, largest first: the ICP stages' distances (empty: icp's own).
  std::vector<double> icp_distance_factors = {6.0, 3.0, 1.5};
  bool run_icp = true;  // false: the coarse result only
  // The turn screen: a result overlapping less than screen_below_overlap is turned about the
  // target's trunk axis every turn_step_deg around the circle, each turn settled by a short ICP
  // and scored by its whole view's overlap (crown included); the turned_refinements best turns
  // are refined fully and the result overlapping most is kept. A tree whose key-region skeleton
  // looks alike from another side (SAC-IA's blind spot) is told apart by its crown.
  double turn_step_deg = 15.0;       // deg, [0, 360] (0: no screen)
  int turned_refinements = 3;        // >= 0 (0: no screen)
  int turn_screen_iterations = 4;    // >= 1: the short ICP's iterations per stage
  size_t turn_screen_points = 1000;  // the short ICP's source points (0: all)
  // [0, 1]: the screen runs only for a result overlapping less than this (1: always). Wrong
  // results overlap less than about 0.5; above, the screen's pick is the same basin a turn step
  // away.
  double screen_below_overlap = 0.55;
  // A result overlapping less than min_fitness is registered once more without the up and centre
  // priors and the snap (a trunk found wrong in one view misleads all three); the better overlap
  // is kept.
  bool retry_without_priors = true;
  // The pair's key regions: false, spheres at the lower of the two views' branching heights
  // (SharedKeyRegions); true, each view's own key region around its own branching point.
  bool own_key_regions = false;
  // A result overlapping less than min_fitness is registered once more with the other choice of
  // key regions (before the retry without priors), keeping the better overlap. The heights
  // SharedKeyRegions compares are measured from each view's ground or visible trunk base, which
  // one view may see far higher than the other (grass, an uneven ground, a plane fitted to another
  // patch): its shared region then sits on the bare trunk below the fork the other view's holds,
  // while both views' own forks agree.
  bool retry_other_key_regions = true;
  // The turn screen also shifts the result along the target's trunk, every
  // screen_shift_step_factor point spacings up to screen_shift_share of the key region's radius
  // either way, refining the shifted_refinements best moves.
  double screen_shift_share = 0.0;         // >= 0 (0: turns only)
  double screen_shift_step_factor = 10.0;  // point spacings, >= 0
  int shifted_refinements = 4;             // >= 0
  // A result still overlapping less than min_fitness after the other key regions is registered
  // once more with the shifts screened at retry_shift_share (before the retry without priors).
  // Both views' forks may be other branchings than the tree's first (a view seeing one arm hidden
  // behind the other finds the next fork up): SAC-IA aligns them and no turn mends the height.
  bool retry_with_shifts = true;
  double retry_shift_share = 0.6;  // >= 0, of the key region's radius
  // [0, 1]: a result overlapping less than this is declined without (more) retries (0: always
  // retry). Retries rescue results that overlap too little, but on the synthetic captures none
  // whose first attempt overlapped less than 0.25 (docs/registration.md, "Fail fast"); views
  // that share no part of the tree stay near 0.1-0.2 whatever is tried.
  double decline_below_overlap = 0.2;
  // s, >= 0: no retry starts once the pair's attempts have taken this long (0: no limit). A last
  // guard for hopeless pairs nothing else declines; it makes the outcome depend on the machine's
  // load, so it is set far above the 10 s the slowest rescued pair took on 2 loaded cores.
  double max_pair_seconds = 30.0;
  // After ICP, the source is moved so the views' medial points (branch axes) meet
  // (AlignMedialAxes) at these distances, in point spacings, each > 0; they replace
  // medial.max_distances_m. Empty: no medial fit.
  std::vector<double> medial_distance_factors = {6.0, 3.0};
  // The medial fit, rigid: ICP leaves the source leaning (the thick branches' one-sided shells
  // pulled together more than the twigs'), which a shift cannot undo; the axis points taken from
  // the branches' silhouettes (RegistrationViewOptions::projection) let a rigid fit remove it.
  MedialShiftOptions medial{.rotation = true};
  // The fine result kept is refined once more the other way round (target onto source, from the
  // result) and the two averaged: each direction's ICP and medial fit err in their own way
  // (one-sided views of the same branches), and the mean is closer to the truth.
  bool symmetric_fine = true;
  // Point spacings (RMS over the source's points), >= 0: two directions further apart than this
  // are in different basins and are not averaged; the one overlapping more is kept.
  double max_reverse_disagreement_factor = 2.0;
  // >= 0: the weight of the views' trunk cylinders' axes (LineConstraint) in fine registration,
  // relative to all surface correspondences (0: not used). Off by default: the one-sided
  // cylinder fits are biased.
  double trunk_axis_weight = 0.0;
  // >= 0: the same for the ground planes (PlaneConstraint at three points `ground_reach_m`
  // around the trunk's foot), when both views found one. Off by default: the views' ground
  // planes fit different patches of an uneven ground.
  double ground_weight = 0.0;
  double ground_reach_m = 0.8;  // m, >= 0
  // Point spacings, > 0: the paper's match rate and RMSE count a source point matched when a
  // target point is this close (no normal test).
  double match_distance_factor = 1.5;

  // Acceptance checks (a failed check flags the pair).
  // [0, 1]: the share of the whole view's points (crown included) with a target point within the
  // last ICP distance, at the result (PairResult::view_overlap). A tree turned about its trunk
  // overlaps less than a right pair.
  double min_fitness = 0.40;
  // [0, 1]: the same share for a result of the retry without priors, which nothing but the checks
  // holds near the trunk axes or the key regions.
  double min_fitness_without_priors = 0.55;
  // Check the ground planes (tilt and offset below). Off by default: right pairs' planes may lie
  // far apart (each view fits its plane to another patch of an uneven ground, or finds none).
  bool check_ground = false;
  double max_up_disagreement_deg = 8.0;  // deg, [0, 180]: both views' ground normals
  // m, >= 0: both views' ground planes apart at the source trunk's foot (where both views see
  // the same patch of ground).
  double max_ground_offset_m = 0.06;
  double max_trunk_offset_factor = 1.5;  // trunk widths (at least 5 cm), >= 0: trunk axes apart
  double max_trunk_tilt_deg = 10.0;      // deg, [0, 180]: trunk axes' directions apart
  // With trunk cylinders in both views, these replace the two above (one-sided fits are loose).
  double max_cylinder_tilt_deg = 8.0;   // deg, [0, 180]
  double max_cylinder_offset_m = 0.05;  // m, >= 0
  // [0, 1]: the share of the source's coarse points (the skeleton) within the SAC-IA inlier
  // distance of the target's, after registration.
  double min_coarse_overlap = 0.45;
  // The trunk and ground constraints join fine registration only when the coarse result puts the
  // cylinders (grounds) within these of each other.
  double max_trunk_guard_tilt_deg = 6.0;    // deg, [0, 180]
  double max_trunk_guard_offset_m = 0.08;   // m, >= 0
  double max_ground_guard_tilt_deg = 4.0;   // deg, [0, 180]
  double max_ground_guard_offset_m = 0.08;  // m, >= 0

  // Throws InputError naming the field of a nonsense value (sac_ia.iterations, ...).
  void Validate() const;
};

// How a pair ended.
enum class PairOutcome {
  kNotRun,              // not registered (yet)
  kOk,                  // registered, every check passed
  kViewCannotRegister,  // a view cannot be registered (RegistrationView::failure)
  kNoKeyRegion,         // own key regions asked for and a view has none
  kNoSharedKeyRegion,   // no key region shared by both views (a trunk axis lies flat)
  kNoCoarseResult,      // SAC-IA found no consistent correspondences
  kFailedChecks,        // registered, but a check failed (PairResult::failed_checks)
};
const char* ToString(PairOutcome outcome);

// The acceptance checks of PairOptions a result can fail.
enum class PairCheck {
  kGroundTilt,      // max_up_disagreement_deg
  kGroundOffset,    // max_ground_offset_m
  kCylinderTilt,    // max_cylinder_tilt_deg
  kCylinderOffset,  // max_cylinder_offset_m
  kTrunkTilt,       // max_trunk_tilt_deg
  kTrunkOffset,     // max_trunk_offset_factor
  kCoarseOverlap,   // min_coarse_overlap
  kViewOverlap,     // min_fitness (min_fitness_without_priors)
};
const char* ToString(PairCheck check);

// Which of RegisterPair's attempts found the result kept.
enum class PairAttempt {
  kFirst,            // "first"
  kOtherKeyRegions,  // "other key regions" (retry_other_key_regions)
  kShifts,           // "shifts" (retry_with_shifts)
  kWithoutPriors,    // "without priors" (retry_without_priors)
};
const char* ToString(PairAttempt attempt);

struct PairResult {
  std::string source, target;
  PairOutcome outcome = PairOutcome::kNotRun;
  std::vector<PairCheck> failed_checks;  // the checks failed, in PairCheck's order
  std::string status;  // "ok", or why the pair is not trusted, with what was measured
  Eigen::Isometry3d target_from_source = Eigen::Isometry3d::Identity();
  CoarseAlignment coarse;
  IcpResult fine;
  // The paper's columns, at match_distance_factor spacings.
  double match_rate = 0.0;
  double rmse_m = 0.0;
  // What the checks measured (NaN when a view lacks the ground or the trunk).
  double up_disagreement_deg = 0.0;
  double ground_offset_m = 0.0;
  double trunk_offset_m = 0.0;
  double coarse_overlap = 0.0;  // skeleton overlap after registration
  double view_overlap = 0.0;    // whole-view overlap after registration (min_fitness)
  double turned_deg = 0.0;      // the turned alternative kept (0: the result as found)
  double shifted_m = 0.0;       // and its shift along the target's trunk
  double medial_shift_m = 0.0;  // the fine stage's medial shift (AlignMedialAxes)
  double reverse_gap_m = std::numeric_limits<double>::quiet_NaN();  // FineResult::reverse_gap_m
  bool retried_without_priors = false;  // the result of the retry without priors (kept or not)
  PairAttempt attempt = PairAttempt::kFirst;  // the attempt that found the result kept
  bool own_key_regions = false;    // the result kept was found with the views' own regions
  bool trunk_constraint = false;   // the trunk axes took part in fine registration
  bool ground_constraint = false;  // the ground planes took part in fine registration
  double seconds = 0.0;            // coarse + fine (view preparation not included)
  // Each attempt run, in order: what it found and what it took.
  struct AttemptRun {
    PairAttempt attempt = PairAttempt::kFirst;
    double view_overlap = 0.0;  // its fine result's fitness (before the checks)
    double seconds = 0.0;
    bool refined = false;                  // it reached the fine stage
    double coarse_overlap = 0.0;           // its skeleton overlap
    std::vector<PairCheck> failed_checks;  // the checks its result failed
    Eigen::Isometry3d target_from_source = Eigen::Isometry3d::Identity();  // its result
  };
  std::vector<AttemptRun> attempts;
  // Why the retries were not run although the result overlaps too little ("": they ran, or were
  // not needed): decline_below_overlap, max_pair_seconds, or (RegisterViews) the chain of
  // trusted pairs agreeing with the first result.
  std::string declined;

  bool ok() const { return outcome == PairOutcome::kOk; }
};

// The fine stage alone from `initial` (target_from_source), as RegisterPair runs it after the
// coarse stage: gated ICP plus the trunk and ground constraints where the start agrees with them.
struct FineResult {
  IcpResult icp;  // target_from_source: the fine result, medial shift included
  Eigen::Vector3d medial_shift = Eigen::Vector3d::Zero();
  // AverageWithReverse: how far apart (RMS over the source's points) the two directions put the
  // source; NaN when not run.
  double reverse_gap_m = std::numeric_limits<double>::quiet_NaN();
  bool trunk_constraint = false;
  bool ground_constraint = false;
};
FineResult RefinePair(const RegistrationView& source, const RegistrationView& target,
                      const Eigen::Isometry3d& initial, const PairOptions& options = {});

// The mean of `forward` (a RefinePair result) and RefinePair the other way round (target onto
// source, started from `forward`'s inverse): half the rotation between them, and the translation
// that puts the source's centre halfway between where the two put it. When the two disagree by
// more than max_reverse_disagreement_factor, whichever overlaps more: the forward one, or the
// reverse one refined forward again and averaged as above (once). Fitness and RMSE are measured
// again at the result.
FineResult AverageWithReverse(const RegistrationView& source, const RegistrationView& target,
                              const FineResult& forward, const PairOptions& options = {});

// RefinePair from `initial`, and from `initial` turned about the target's trunk axis (every
// turn_step_deg) and shifted along it (by each of `shifts_m`) by the moves a short-ICP screen
// finds best, `refinements` of them (-1: turned_refinements), when the result from `initial`
// overlaps less than screen_below_overlap; the result whose view overlaps most
// (IcpResult::fitness) is kept, then averaged with the reverse (symmetric_fine).
//
// `gate` (optional) is asked before the screen, with the result as found (averaged with the
// reverse when symmetric_fine) and its view overlap:
// a reason to stop there ("declined"), or "" to go on. The screen is most of a poorly overlapping
// pair's time; a caller who can tell the result is right without it (RegisterViews: the chain of
// the neighbours' trusted pairs) saves it.
using ScreenGate =
    std::function<std::string(const Eigen::Isometry3d& target_from_source, double view_overlap)>;
struct TurnedFineResult {
  FineResult fine;
  double turned_deg = 0.0;  // the turn kept (0: the result from `initial`)
  double shifted_m = 0.0;   // the shift along the trunk kept
  bool screened = false;    // the screen ran (the result overlapped less than screen_below_overlap)
  std::string declined;     // the gate's reason to stop before the screen ("": it did not)
};
TurnedFineResult RefineWithTurns(const RegistrationView& source, const RegistrationView& target,
                                 const Eigen::Isometry3d& initial, const PairOptions& options = {},
                                 const std::vector<double>& shifts_m = {0.0}, int refinements = -1,
                                 const ScreenGate& gate = {});

// Coarse, fine with turns, checks. While the result overlaps too little (min_fitness), once
// more with the other key regions (retry_other_key_regions), with shifts along the trunk
// screened too (retry_with_shifts), and without the priors (retry_without_priors), in that
// order, keeping the best overlap (PairResult::attempt says which).
PairResult RegisterPair(const RegistrationView& source, const RegistrationView& target,
                        const PairOptions& options = {});

// RegisterPair in two steps, so that a caller who knows more (RegisterViews: the chain of other
// pairs) may decline a pair between them: the first attempt (PairResult::attempts[0]), then the
// retries of a result not declined. `gate` may decline the first attempt before its turn screen
// (RefineWithTurns); the pair is then declined (PairResult::declined).
PairResult RegisterPairFirstAttempt(const RegistrationView& source, const RegistrationView& target,
                                    const PairOptions& options = {}, const ScreenGate& gate = {});
void RetryPair(const RegistrationView& source, const RegistrationView& target,
               const PairOptions& options, PairResult& result);
// Marks `result` declined for `reason` (PairResult::declined, appended to the status): RetryPair
// then leaves it as it is.
void DeclinePair(const std::string& reason, PairResult& result);

// The key regions of a pair: spheres around the same physical point in both views, the point of
// each trunk's axis at the lower of the two views' branching heights (a view that cannot see a
// fork, one arm hidden behind the trunk, finds the next one up; the other view's lower fork is
// the tree's first). Heights are above the ground when both views see it, else above the trunk's
// base. nullopt when a view has no trunk.
struct SharedKeyRegion {
  KeyRegion source, target;
  double height_m = 0.0;
};
std::optional<SharedKeyRegion> SharedKeyRegions(const RegistrationView& source,
                                                const RegistrationView& target);

// A view's coarse points and features inside `region` (all of them when null).
struct CoarseSubset {
  open3d::geometry::PointCloud points;
  open3d::pipelines::registration::Feature features;
};
CoarseSubset SelectCoarse(const RegistrationView& view, const KeyRegion* region);

// The checks alone, for a transform found by any method: sets the measured values, the outcome
// (kOk or kFailedChecks), failed_checks and status.
void CheckPair(const RegistrationView& source, const RegistrationView& target,
               const PairOptions& options, PairResult& result);

// Share of the source's coarse points within `distance_m` of the target's after the transform.
double CoarseOverlap(const open3d::geometry::PointCloud& source,
                     const open3d::geometry::PointCloud& target,
                     const Eigen::Isometry3d& target_from_source, double distance_m);

// The paper's match rate and RMSE of a transform.
Overlap PaperMatch(const RegistrationView& source, const RegistrationView& target,
                   const Eigen::Isometry3d& target_from_source, const PairOptions& options);

}  // namespace simtree::registration
