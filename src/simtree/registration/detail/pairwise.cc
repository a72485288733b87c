#include "simtree/registration/detail/pairwise.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <tuple>

#include <fmt/format.h>

#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::registration {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi;
}

// Distance between two lines (point, unit direction) measured at point `at` on the second.
double LineOffsetAt(const Eigen::Vector3d& p1, const Eigen::Vector3d& d1,
                    const Eigen::Vector3d& at) {
  const Eigen::Vector3d v = at - p1;
  return (v - v.dot(d1) * d1).norm();
}

double Spacing(const RegistrationView& source, const RegistrationView& target) {
  return std::max(source.spacing_m, target.spacing_m);
}

// Moves a coarse result (keeping its rotation) so that the trunk axes meet and the grounds
// coincide: the shift SAC-IA gets from skeleton points is off by what one-sided views bias, the
// cylinder and the plane are not.
Eigen::Isometry3d SnapToPriors(Eigen::Isometry3d t, const RegistrationView& source,
                               const RegistrationView& target,
                               const std::optional<SharedKeyRegion>& shared, bool use_ground) {
  const bool cylinders =
      source.trunk && target.trunk && source.trunk->cylinder && target.trunk->cylinder;
  if (cylinders && shared) {
    const Eigen::Vector3d d = target.trunk->cylinder->axis;
    Eigen::Vector3d gap = shared->target.center - t * shared->source.center;
    gap -= gap.dot(d) * d;  // across the axis only
    t.translation() += gap;
  }
  if (use_ground && source.ground && target.ground) {
    Eigen::Vector3d foot = source.trunk ? source.trunk->base : source.cloud->GetCenter();
    foot -= source.ground->SignedDistance(foot) * source.ground->normal;
    t.translation() -= target.ground->SignedDistance(t * foot) * target.ground->normal;
  }
  return t;
}

// The fine stage's ICP options, its distances in metres from the pair's point spacing.
GatedIcpOptions FineIcpOptions(const RegistrationView& source, const RegistrationView& target,
                               const PairOptions& options) {
  GatedIcpOptions icp = options.icp;
  if (!options.icp_distance_factors.empty()) {
    icp.max_distances_m.clear();
    for (double f : options.icp_distance_factors) {
      icp.max_distances_m.push_back(f * Spacing(source, target));
    }
  }
  return icp;
}

// A turn by `angle_deg` about the line through `pivot` along unit `axis`.
Eigen::Isometry3d TurnAbout(const Eigen::Vector3d& axis, const Eigen::Vector3d& pivot,
                            double angle_deg) {
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.linear() = Eigen::AngleAxisd(angle_deg * std::numbers::pi / 180.0, axis).toRotationMatrix();
  turn.translation() = pivot - turn.linear() * pivot;
  return turn;
}

// A turn about the target's trunk axis and a shift along it, applied after a result.
struct TrunkMove {
  double angle_deg = 0.0;
  double shift_m = 0.0;
};

Eigen::Isometry3d MoveAboutTrunk(const RegistrationView& target, const TrunkMove& move) {
  const Eigen::Vector3d axis = TrunkAxis(target).normalized();
  Eigen::Isometry3d t = TurnAbout(axis, target.trunk->base, move.angle_deg);
  t.translation() += move.shift_m * axis;
  return t;
}

// The moves of `result` about the target's trunk axis worth refining: turns every
// `turn_step_deg` around the circle, each at every shift of `shifts_m`, settled by a short ICP on
// a sample of the source view (the fine stage's distances, a few iterations each) and scored by
// its fitness at the last distance, as the full refinement is; best first, one per peak (no two
// within a step and a half of each other or of the result, in turn and in shift). A bare
// overlap count does not tell the turns apart: it needs a distance as wide as half a step moves
// the crown (~13 cm), at which every turn scores alike.
std::vector<TrunkMove> ScreenMoves(const RegistrationView& source, const RegistrationView& target,
                                   const Eigen::Isometry3d& result,
                                   const std::vector<double>& shifts_m, int wanted,
                                   const PairOptions& options) {
  std::vector<TrunkMove> chosen;
  const double step = options.turn_step_deg;
  if (wanted <= 0 || !(step > 0) || !target.trunk || !source.cloud ||
      source.cloud->points_.empty() || shifts_m.empty()) {
    return chosen;
  }
  GatedIcpOptions icp = FineIcpOptions(source, target, options);
  icp.iterations_per_stage = options.turn_screen_iterations;
  icp.max_source_points = options.turn_screen_points;
  // The shifts' spacing: how close two shifts may be and still be one peak.
  double shift_step = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i < shifts_m.size(); ++i) {
    shift_step = std::min(shift_step, std::abs(shifts_m[i] - shifts_m[i - 1]));
  }
  std::vector<std::pair<double, TrunkMove>> scored;  // (fitness, move)
  for (double shift : shifts_m) {
    for (double angle = 0.0; angle < 360.0 - 0.5 * step; angle += step) {
      if (angle == 0.0 && shift == 0.0) continue;  // the result itself
      const TrunkMove move{angle, shift};
      scored.emplace_back(GatedPointToPlaneIcp(*source.cloud, *target.cloud, *target.cloud_tree,
                                               MoveAboutTrunk(target, move) * result, icp,
                                               source.planarity.get(), target.planarity.get())
                              .fitness,
                          move);
    }
  }
  // Best first; ties by the larger turn, then shift (a fixed order).
  std::sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) {
    return std::tuple(a.first, a.second.angle_deg, a.second.shift_m) >
           std::tuple(b.first, b.second.angle_deg, b.second.shift_m);
  });
  auto apart = [&](const TrunkMove& a, const TrunkMove& b) {
    const double d = std::fmod(std::abs(a.angle_deg - b.angle_deg), 360.0);
    return std::min(d, 360.0 - d) > 1.5 * step ||
           std::abs(a.shift_m - b.shift_m) > 1.5 * shift_step;
  };
  for (const auto& [share, move] : scored) {
    if (static_cast<int>(chosen.size()) >= wanted) break;
    bool far = apart(move, TrunkMove{});
    for (const TrunkMove& c : chosen) far = far && apart(move, c);
    if (far) chosen.push_back(move);
  }
  return chosen;
}

// The shifts along the trunk the turn screen tries: none, or every screen_shift_step_factor
// point spacings up to screen_shift_share of the key region's radius either way.
std::vector<double> ScreenShifts(const RegistrationView& source, const RegistrationView& target,
                                 double key_radius_m, const PairOptions& options) {
  std::vector<double> shifts = {0.0};
  const double step = options.screen_shift_step_factor * Spacing(source, target);
  const double reach = options.screen_shift_share * key_radius_m;
  if (!(step > 0) || !(reach >= step)) return shifts;
  for (int k = 1; k * step <= reach + 1e-9; ++k) {
    shifts.push_back(k * step);
    shifts.push_back(-k * step);
  }
  std::sort(shifts.begin(), shifts.end());
  return shifts;
}

}  // namespace

double CoarseOverlap(const open3d::geometry::PointCloud& source,
                     const open3d::geometry::PointCloud& target,
                     const Eigen::Isometry3d& target_from_source, double distance_m) {
  if (source.points_.empty() || target.points_.empty()) return 0.0;
  const open3d::geometry::KDTreeFlann tree(target);
  return MeasureOverlap(source, target, tree, target_from_source, distance_m).share;
}

std::optional<SharedKeyRegion> SharedKeyRegions(const RegistrationView& source,
                                                const RegistrationView& target) {
  if (!source.trunk || !target.trunk || !source.key_region || !target.key_region) {
    return std::nullopt;
  }
  const bool use_ground = source.ground && target.ground;
  SharedKeyRegion shared;
  shared.height_m = std::min(HeightOf(source, source.trunk->branch_point, use_ground),
                             HeightOf(target, target.trunk->branch_point, use_ground));
  const auto a = TrunkPointAtHeight(source, shared.height_m, use_ground);
  const auto b = TrunkPointAtHeight(target, shared.height_m, use_ground);
  if (!a || !b) return std::nullopt;
  const double radius = std::max(source.key_region->radius_m, target.key_region->radius_m);
  shared.source = KeyRegion{*a, radius};
  shared.target = KeyRegion{*b, radius};
  return shared;
}

CoarseSubset SelectCoarse(const RegistrationView& view, const KeyRegion* region) {
  CoarseSubset subset;
  std::vector<size_t> inside;
  if (region) {
    inside = PointsInside(view.coarse, *region);
  } else {
    inside.resize(view.coarse.points_.size());
    for (size_t i = 0; i < inside.size(); ++i) inside[i] = i;
  }
  subset.points = *view.coarse.SelectByIndex(inside);
  if (view.features) {
    subset.features.Resize(static_cast<int>(view.features->Dimension()),
                           static_cast<int>(inside.size()));
    for (size_t k = 0; k < inside.size(); ++k) {
      subset.features.data_.col(k) = view.features->data_.col(inside[k]);
    }
  }
  return subset;
}

Overlap PaperMatch(const RegistrationView& source, const RegistrationView& target,
                   const Eigen::Isometry3d& target_from_source, const PairOptions& options) {
  return MeasureOverlap(*source.cloud, *target.cloud, *target.cloud_tree, target_from_source,
                        options.match_distance_factor * Spacing(source, target));
}

void CheckPair(const RegistrationView& source, const RegistrationView& target,
               const PairOptions& options, PairResult& result) {
  const Eigen::Isometry3d& t = result.target_from_source;
  std::vector<std::string> problems;
  result.failed_checks.clear();
  auto fail = [&](PairCheck check, std::string problem) {
    result.failed_checks.push_back(check);
    problems.push_back(std::move(problem));
  };
  result.up_disagreement_deg = kNaN;
  result.ground_offset_m = kNaN;
  result.trunk_offset_m = kNaN;
  if (source.ground && target.ground) {
    result.up_disagreement_deg =
        AngleDeg(t.linear() * source.ground->normal, target.ground->normal);
    if (options.check_ground && result.up_disagreement_deg > options.max_up_disagreement_deg) {
      fail(PairCheck::kGroundTilt,
           fmt::format("the grounds tilt {:.1f} deg apart (at most {:.1f})",
                       result.up_disagreement_deg, options.max_up_disagreement_deg));
    }
    // The source ground at its trunk's foot (or below its cloud's centre), in the target frame,
    // against the target ground: near the tree both views see the same patch.
    Eigen::Vector3d on_source =
        source.trunk ? source.trunk->base
                     : Eigen::Vector3d(-source.ground->offset * source.ground->normal);
    on_source -= source.ground->SignedDistance(on_source) * source.ground->normal;
    result.ground_offset_m = std::abs(target.ground->SignedDistance(t * on_source));
    if (options.check_ground && result.ground_offset_m > options.max_ground_offset_m) {
      fail(PairCheck::kGroundOffset,
           fmt::format("the grounds are {:.0f} mm apart (at most {:.0f})",
                       1e3 * result.ground_offset_m, 1e3 * options.max_ground_offset_m));
    }
  }
  if (source.trunk && target.trunk && source.trunk->cylinder && target.trunk->cylinder) {
    const TrunkCylinder& a = *source.trunk->cylinder;
    const TrunkCylinder& b = *target.trunk->cylinder;
    const double tilt = AngleDeg(t.linear() * a.axis, b.axis);
    if (tilt > options.max_cylinder_tilt_deg) {
      fail(PairCheck::kCylinderTilt,
           fmt::format("the trunk cylinders tilt {:.1f} deg apart (at most {:.1f})", tilt,
                       options.max_cylinder_tilt_deg));
    }
    result.trunk_offset_m = LineOffsetAt(b.point, b.axis, t * a.point);
    if (result.trunk_offset_m > options.max_cylinder_offset_m) {
      fail(PairCheck::kCylinderOffset,
           fmt::format("the trunk cylinders are {:.0f} mm apart (at most {:.0f})",
                       1e3 * result.trunk_offset_m, 1e3 * options.max_cylinder_offset_m));
    }
  } else if (source.trunk && target.trunk) {
    const double tilt = AngleDeg(t.linear() * source.trunk->axis, target.trunk->axis);
    if (tilt > options.max_trunk_tilt_deg) {
      fail(PairCheck::kTrunkTilt, fmt::format("the trunks tilt {:.1f} deg apart (at most {:.1f})",
                                              tilt, options.max_trunk_tilt_deg));
    }
    result.trunk_offset_m =
        LineOffsetAt(t * source.trunk->branch_point, t.linear() * source.trunk->axis,
                     target.trunk->branch_point);
    const double limit =
        std::max(0.05, options.max_trunk_offset_factor *
                           std::max(source.trunk->visible_width_m, target.trunk->visible_width_m));
    if (result.trunk_offset_m > limit) {
      fail(PairCheck::kTrunkOffset, fmt::format("the trunks are {:.0f} mm apart (at most {:.0f})",
                                                1e3 * result.trunk_offset_m, 1e3 * limit));
    }
  }
  if (result.coarse_overlap < options.min_coarse_overlap) {
    fail(PairCheck::kCoarseOverlap,
         fmt::format("only {:.0f}% of the {} matches (at least {:.0f}%)",
                     100 * result.coarse_overlap, ToString(source.coarse_input),
                     100 * options.min_coarse_overlap));
  }
  // The whole view, crown included: what tells a tree turned about its trunk from a right pair
  // when the trunk and the key region's skeleton look alike from every side.
  if (source.cloud && target.cloud && target.cloud_tree) {
    const double last = options.icp_distance_factors.empty()
                            ? options.icp.max_distances_m.back()
                            : options.icp_distance_factors.back() * Spacing(source, target);
    result.view_overlap =
        MeasureOverlap(*source.cloud, *target.cloud, *target.cloud_tree, t, last).share;
    if (result.view_overlap < options.min_fitness) {
      fail(PairCheck::kViewOverlap,
           fmt::format("only {:.0f}% of points overlap (at least {:.0f}%)",
                       100 * result.view_overlap, 100 * options.min_fitness));
    }
  }
  result.outcome = problems.empty() ? PairOutcome::kOk : PairOutcome::kFailedChecks;
  if (result.ok()) {
    result.status = ToString(result.outcome);
  } else {
    result.status = problems.front();
    for (size_t i = 1; i < problems.size(); ++i) result.status += "; " + problems[i];
  }
}

FineResult RefinePair(const RegistrationView& source, const RegistrationView& target,
                      const Eigen::Isometry3d& initial, const PairOptions& options) {
  options.Validate();
  FineResult result;
  if (!source.cloud || !target.cloud) {
    result.icp.target_from_source = initial;
    return result;
  }
  GatedIcpOptions icp = FineIcpOptions(source, target, options);
  // The trunk axes join the fine stage only when the coarse result already roughly agrees
  // with them (a trunk cylinder fitted across a hidden fork would pull the pair askew).
  IcpPriors priors;
  if (options.trunk_axis_weight > 0 && source.trunk && target.trunk && source.trunk->cylinder &&
      target.trunk->cylinder) {
    const TrunkCylinder& a = *source.trunk->cylinder;
    const TrunkCylinder& b = *target.trunk->cylinder;
    const Eigen::Isometry3d& t = initial;
    if (AngleDeg(t.linear() * a.axis, b.axis) <= options.max_trunk_guard_tilt_deg &&
        LineOffsetAt(b.point, b.axis, t * a.point) <= options.max_trunk_guard_offset_m) {
      priors.line = LineConstraint{a.point, a.axis, a.half_length_m,
                                   b.point, b.axis, options.trunk_axis_weight};
      result.trunk_constraint = true;
    }
  }
  // The ground likewise, guarded the same way (the views may see different patches of an
  // uneven ground).
  if (options.ground_weight > 0 && source.ground && target.ground) {
    const Eigen::Isometry3d& t = initial;
    const preprocessing::GroundPlane& a = *source.ground;
    const preprocessing::GroundPlane& b = *target.ground;
    // Three points on the source ground around the foot of the trunk (or of the view).
    Eigen::Vector3d foot = source.trunk ? source.trunk->base : source.cloud->GetCenter();
    foot -= a.SignedDistance(foot) * a.normal;
    const Eigen::Vector3d e1 = a.normal.unitOrthogonal();
    const Eigen::Vector3d e2 = a.normal.cross(e1);
    const double reach = options.ground_reach_m;
    PlaneConstraint plane{{foot + reach * e1, foot - 0.5 * reach * e1 + 0.87 * reach * e2,
                           foot - 0.5 * reach * e1 - 0.87 * reach * e2},
                          b.normal,
                          b.offset,
                          options.ground_weight};
    bool agrees = AngleDeg(t.linear() * a.normal, b.normal) <= options.max_ground_guard_tilt_deg;
    for (const auto& p : plane.source_points) {
      agrees = agrees && std::abs(b.SignedDistance(t * p)) <= options.max_ground_guard_offset_m;
    }
    if (agrees) {
      priors.plane = plane;
      result.ground_constraint = true;
    }
  }
  result.icp = GatedPointToPlaneIcp(*source.cloud, *target.cloud, *target.cloud_tree, initial, icp,
                                    source.planarity.get(), target.planarity.get(), priors);
  if (!options.medial_distance_factors.empty() && source.medial && target.medial &&
      target.medial_tree) {
    MedialShiftOptions medial = options.medial;
    medial.max_distances_m.clear();
    for (double f : options.medial_distance_factors) {
      medial.max_distances_m.push_back(f * Spacing(source, target));
    }
    const MedialShiftResult shifted = AlignMedialAxes(
        *source.medial, *target.medial, *target.medial_tree, result.icp.target_from_source, medial);
    result.icp.target_from_source = shifted.target_from_source;
    result.medial_shift = shifted.shift;
  }
  return result;
}

namespace {

FineResult AverageWithReverseOnce(const RegistrationView& source, const RegistrationView& target,
                                  const FineResult& forward, const PairOptions& options,
                                  bool may_restart) {
  if (!source.cloud || !target.cloud || !source.cloud_tree || !target.cloud_tree ||
      source.cloud->points_.empty()) {
    return forward;
  }
  const Eigen::Isometry3d f = forward.icp.target_from_source;
  const Eigen::Isometry3d b =
      RefinePair(target, source, f.inverse(), options).icp.target_from_source.inverse();
  const double last = FineIcpOptions(source, target, options).max_distances_m.back();
  auto measured = [&](const Eigen::Isometry3d& t) {
    FineResult r = forward;
    r.icp.target_from_source = t;
    const Overlap overlap =
        MeasureOverlap(*source.cloud, *target.cloud, *target.cloud_tree, t, last);
    r.icp.fitness = overlap.share;
    r.icp.rmse_m = overlap.rmse_m;
    r.icp.correspondences = overlap.matched;
    return r;
  };
  // Two directions that settled in different places (one of them in a wrong basin) are not
  // averaged: the one whose view overlaps more is kept, and when that is the reverse, the
  // forward direction starts again from it.
  double squared = 0.0;
  for (const Eigen::Vector3d& p : source.cloud->points_) squared += (f * p - b * p).squaredNorm();
  const double apart = std::sqrt(squared / static_cast<double>(source.cloud->points_.size()));
  if (apart > options.max_reverse_disagreement_factor * Spacing(source, target)) {
    FineResult one = measured(f), other = measured(b);
    one.reverse_gap_m = other.reverse_gap_m = apart;
    if (other.icp.fitness <= one.icp.fitness) return one;
    if (!may_restart) return other;
    FineResult again = RefinePair(source, target, b, options);
    return AverageWithReverseOnce(source, target, again, options, false);
  }
  const Eigen::Quaterniond qf(f.linear()), qb(b.linear());
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  mean.linear() = qf.slerp(0.5, qb).toRotationMatrix();
  // Halfway between where the two put the source's points.
  const Eigen::Vector3d centre = source.cloud->GetCenter();
  mean.translation() = 0.5 * (f * centre + b * centre) - mean.linear() * centre;
  FineResult result = measured(mean);
  result.reverse_gap_m = apart;
  return result;
}

}  // namespace

FineResult AverageWithReverse(const RegistrationView& source, const RegistrationView& target,
                              const FineResult& forward, const PairOptions& options) {
  options.Validate();
  return AverageWithReverseOnce(source, target, forward, options, true);
}

TurnedFineResult RefineWithTurns(const RegistrationView& source, const RegistrationView& target,
                                 const Eigen::Isometry3d& initial, const PairOptions& options,
                                 const std::vector<double>& shifts_m, int refinements,
                                 const ScreenGate& gate) {
  options.Validate();
  TurnedFineResult result;
  result.fine = RefinePair(source, target, initial, options);
  if (!target.trunk) return result;
  const Eigen::Isometry3d found = result.fine.icp.target_from_source;
  result.screened = result.fine.icp.fitness < options.screen_below_overlap;
  // The result as the pair keeps it when no turn beats it: averaged with the reverse. Computed
  // once, for the gate or at the end.
  std::optional<FineResult> averaged_unturned;
  if (result.screened && gate) {
    averaged_unturned = options.symmetric_fine
                            ? AverageWithReverse(source, target, result.fine, options)
                            : result.fine;
    result.declined =
        gate(averaged_unturned->icp.target_from_source, averaged_unturned->icp.fitness);
    if (!result.declined.empty()) {
      result.fine = std::move(*averaged_unturned);
      result.screened = false;
      return result;
    }
  }
  const int wanted =
      result.screened ? (refinements >= 0 ? refinements : options.turned_refinements) : 0;
  bool turned = false;
  for (const TrunkMove& move : ScreenMoves(source, target, found, shifts_m, wanted, options)) {
    FineResult moved = RefinePair(source, target, MoveAboutTrunk(target, move) * found, options);
    if (moved.icp.fitness > result.fine.icp.fitness) {
      result.fine = std::move(moved);
      result.turned_deg = move.angle_deg;
      result.shifted_m = move.shift_m;
      turned = true;
    }
  }
  if (!turned && averaged_unturned) {
    result.fine = std::move(*averaged_unturned);
  } else if (options.symmetric_fine) {
    result.fine = AverageWithReverse(source, target, result.fine, options);
  }
  return result;
}

namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The key regions whose coarse points a pair aligns: none for a coarse input without key regions
// (every coarse point), else the shared regions or each view's own (own_key_regions).
struct PairRegions {
  std::optional<SharedKeyRegion> shared;
  PairOutcome failure = PairOutcome::kNotRun;  // kNoKeyRegion or kNoSharedKeyRegion: none found
};

PairRegions ChooseKeyRegions(const RegistrationView& source, const RegistrationView& target,
                             const PairOptions& options) {
  PairRegions regions;
  if (!UsesKeyRegion(source.coarse_input)) return regions;
  if (!options.own_key_regions) {
    regions.shared = SharedKeyRegions(source, target);
    if (!regions.shared) regions.failure = PairOutcome::kNoSharedKeyRegion;
    return regions;
  }
  if (!source.key_region || !target.key_region) {
    regions.failure = PairOutcome::kNoKeyRegion;
    return regions;
  }
  // One radius, as SharedKeyRegions takes: the spheres hold the same share of the tree.
  const double radius = std::max(source.key_region->radius_m, target.key_region->radius_m);
  regions.shared = SharedKeyRegion{KeyRegion{source.key_region->center, radius},
                                   KeyRegion{target.key_region->center, radius}, kNaN};
  return regions;
}

// What both views know besides their coarse points, for SAC-IA.
SacIaPrior CoarsePrior(const RegistrationView& source, const RegistrationView& target,
                       const std::optional<SharedKeyRegion>& shared, const PairOptions& options) {
  SacIaPrior prior;
  if (options.up_prior) {
    // One physical direction seen from both views: the trunk's axis (or, when asked, the
    // ground's normal when both see the ground).
    if (options.ground_as_up && source.ground && target.ground) {
      prior.source_up = source.ground->normal;
      prior.target_up = target.ground->normal;
    } else if (source.trunk && target.trunk) {
      prior.source_up = TrunkAxis(source);
      prior.target_up = TrunkAxis(target);
    }
  }
  if (options.center_prior && shared) {
    prior.source_center = shared->source.center;
    prior.target_center = shared->target.center;
    prior.max_center_offset_m = options.max_center_offset_share * shared->source.radius_m;
  }
  return prior;
}

// The fine stage from the coarse result in `result`, the turn screen included: its pose and
// what it measured go into `result`. Returns the gate's reason to decline ("": none).
std::string RefineCoarseResult(const RegistrationView& source, const RegistrationView& target,
                               const std::optional<SharedKeyRegion>& shared,
                               const PairOptions& options, const ScreenGate& gate,
                               PairResult& result) {
  const TurnedFineResult turned =
      RefineWithTurns(source, target, result.target_from_source, options,
                      ScreenShifts(source, target, shared ? shared->source.radius_m : 0.0, options),
                      options.screen_shift_share > 0 ? options.shifted_refinements : -1, gate);
  const FineResult& fine = turned.fine;
  result.turned_deg = turned.turned_deg;
  result.shifted_m = turned.shifted_m;
  result.medial_shift_m = fine.medial_shift.norm();
  result.reverse_gap_m = fine.reverse_gap_m;
  result.fine = fine.icp;
  result.trunk_constraint = fine.trunk_constraint;
  result.ground_constraint = fine.ground_constraint;
  result.target_from_source = fine.icp.target_from_source;
  return turned.declined;
}

// One attempt: key regions, coarse (SAC-IA, snapped to the priors), fine with the turn screen
// (unless `gate` declines it first), then the paper's columns and the checks.
PairResult RegisterPairOnce(const RegistrationView& source, const RegistrationView& target,
                            const PairOptions& options, const ScreenGate& gate = {}) {
  const auto start = std::chrono::steady_clock::now();
  PairResult result;
  result.source = source.name;
  result.target = target.name;
  result.own_key_regions = options.own_key_regions;
  for (const RegistrationView* view : {&source, &target}) {
    if (!view->CanRegister()) {
      result.outcome = PairOutcome::kViewCannotRegister;
      result.status = fmt::format("{}: {}", view->name, view->failure);
      return result;
    }
  }
  const PairRegions regions = ChooseKeyRegions(source, target, options);
  if (regions.failure != PairOutcome::kNotRun) {
    result.outcome = regions.failure;
    result.status = ToString(result.outcome);
    return result;
  }
  const std::optional<SharedKeyRegion>& shared = regions.shared;
  const CoarseSubset source_coarse = SelectCoarse(source, shared ? &shared->source : nullptr);
  const CoarseSubset target_coarse = SelectCoarse(target, shared ? &shared->target : nullptr);
  result.coarse = SampleConsensusInitialAlignment(
      source_coarse.points, source_coarse.features, target_coarse.points, target_coarse.features,
      CoarsePrior(source, target, shared, options), options.sac_ia);
  if (!result.coarse.found) {
    result.outcome = PairOutcome::kNoCoarseResult;
    result.status = ToString(result.outcome);
    result.seconds = SecondsSince(start);
    return result;
  }
  if (options.snap_to_priors) {
    result.coarse.target_from_source = SnapToPriors(result.coarse.target_from_source, source,
                                                    target, shared, options.ground_as_up);
  }
  result.target_from_source = result.coarse.target_from_source;
  std::string declined;
  if (options.run_icp) declined = RefineCoarseResult(source, target, shared, options, gate, result);
  result.seconds = SecondsSince(start);
  result.coarse_overlap =
      CoarseOverlap(source_coarse.points, target_coarse.points, result.target_from_source,
                    options.sac_ia.inlier_distance_m);
  const Overlap match = PaperMatch(source, target, result.target_from_source, options);
  result.match_rate = match.share;
  result.rmse_m = match.rmse_m;
  CheckPair(source, target, options, result);
  if (!declined.empty()) DeclinePair(declined, result);
  return result;
}

// The attempt reached the fine stage (its fitness is a view overlap).
bool Refined(const PairResult& attempt, const PairOptions& options) {
  return options.run_icp &&
         (attempt.outcome == PairOutcome::kOk || attempt.outcome == PairOutcome::kFailedChecks);
}

PairResult::AttemptRun RunOf(const PairResult& found, PairAttempt attempt,
                             const PairOptions& options) {
  return {attempt,
          found.fine.fitness,
          found.seconds,
          Refined(found, options),
          found.coarse_overlap,
          found.failed_checks,
          found.target_from_source};
}

// Keeps whichever of `result` and `retried` (found by `attempt`) overlaps more, charged with the
// time of both; the attempt is added to the pair's list.
void KeepBetterOverlap(PairResult retried, PairAttempt attempt, const PairOptions& options,
                       PairResult* result) {
  result->attempts.push_back(RunOf(retried, attempt, options));
  retried.seconds += result->seconds;
  retried.attempt = attempt;
  if (retried.fine.fitness > result->fine.fitness) {
    retried.attempts = std::move(result->attempts);
    *result = std::move(retried);
  } else {
    result->seconds = retried.seconds;
  }
}

// Why a pair whose result overlaps too little gets no (further) retry; "" when it may have one.
// The overlap declines a pair only when an attempt reached the fine stage: one that found no key
// region or no coarse result says nothing of what the other key regions or priors may find.
std::string WhyNoRetry(const PairResult& result, const PairOptions& options, double seconds) {
  bool refined = false;
  for (const PairResult::AttemptRun& run : result.attempts) refined = refined || run.refined;
  if (refined && result.fine.fitness < options.decline_below_overlap) {
    return fmt::format(
        "declined without {}: {:.0f}% of points overlap at best (retries rescue "
        "none below {:.0f}%)",
        result.attempts.size() == 1 ? "retries" : "more retries", 100 * result.fine.fitness,
        100 * options.decline_below_overlap);
  }
  if (options.max_pair_seconds > 0 && seconds >= options.max_pair_seconds) {
    return fmt::format("declined without more retries: {:.1f} s spent (at most {:.1f})", seconds,
                       options.max_pair_seconds);
  }
  return "";
}

}  // namespace

const char* ToString(PairOutcome outcome) {
  switch (outcome) {
    case PairOutcome::kNotRun:
      return "not registered";
    case PairOutcome::kOk:
      return "ok";
    case PairOutcome::kViewCannotRegister:
      return "a view cannot be registered";
    case PairOutcome::kNoKeyRegion:
      return "no key region in both views";
    case PairOutcome::kNoSharedKeyRegion:
      return "no key region shared by both views (a trunk axis lies flat)";
    case PairOutcome::kNoCoarseResult:
      return "coarse registration found no consistent correspondences";
    case PairOutcome::kFailedChecks:
      return "failed its checks";
  }
  return "?";
}

const char* ToString(PairCheck check) {
  switch (check) {
    case PairCheck::kGroundTilt:
      return "ground tilt";
    case PairCheck::kGroundOffset:
      return "ground offset";
    case PairCheck::kCylinderTilt:
      return "trunk cylinder tilt";
    case PairCheck::kCylinderOffset:
      return "trunk cylinder offset";
    case PairCheck::kTrunkTilt:
      return "trunk tilt";
    case PairCheck::kTrunkOffset:
      return "trunk offset";
    case PairCheck::kCoarseOverlap:
      return "coarse overlap";
    case PairCheck::kViewOverlap:
      return "view overlap";
  }
  return "?";
}

const char* ToString(PairAttempt attempt) {
  switch (attempt) {
    case PairAttempt::kFirst:
      return "first";
    case PairAttempt::kOtherKeyRegions:
      return "other key regions";
    case PairAttempt::kShifts:
      return "shifts";
    case PairAttempt::kWithoutPriors:
      return "without priors";
  }
  return "?";
}

void PairOptions::Validate() const {
  CheckNested("sac_ia", [&] { sac_ia.Validate(); });
  CheckNested("icp", [&] { icp.Validate(); });
  CheckNested("medial", [&] { medial.Validate(); });
  CheckNonNegative("max_center_offset_share", max_center_offset_share);
  CheckPositiveList("icp_distance_factors", icp_distance_factors, true);
  CheckInRange("turn_step_deg", turn_step_deg, 0.0, 360.0);
  CheckNonNegative("turned_refinements", turned_refinements);
  CheckAtLeast("turn_screen_iterations", turn_screen_iterations, 1);
  CheckShare("screen_below_overlap", screen_below_overlap);
  CheckNonNegative("screen_shift_share", screen_shift_share);
  CheckNonNegative("screen_shift_step_factor", screen_shift_step_factor);
  CheckNonNegative("shifted_refinements", shifted_refinements);
  CheckNonNegative("retry_shift_share", retry_shift_share);
  CheckShare("decline_below_overlap", decline_below_overlap);
  CheckNonNegative("max_pair_seconds", max_pair_seconds);
  CheckPositiveList("medial_distance_factors", medial_distance_factors, true);
  CheckNonNegative("max_reverse_disagreement_factor", max_reverse_disagreement_factor);
  CheckNonNegative("trunk_axis_weight", trunk_axis_weight);
  CheckNonNegative("ground_weight", ground_weight);
  CheckNonNegative("ground_reach_m", ground_reach_m);
  CheckPositive("match_distance_factor", match_distance_factor);
  CheckShare("min_fitness", min_fitness);
  CheckShare("min_fitness_without_priors", min_fitness_without_priors);
  CheckInRange("max_up_disagreement_deg", max_up_disagreement_deg, 0.0, 180.0);
  CheckNonNegative("max_ground_offset_m", max_ground_offset_m);
  CheckNonNegative("max_trunk_offset_factor", max_trunk_offset_factor);
  CheckInRange("max_trunk_tilt_deg", max_trunk_tilt_deg, 0.0, 180.0);
  CheckInRange("max_cylinder_tilt_deg", max_cylinder_tilt_deg, 0.0, 180.0);
  CheckNonNegative("max_cylinder_offset_m", max_cylinder_offset_m);
  CheckShare("min_coarse_overlap", min_coarse_overlap);
  CheckInRange("max_trunk_guard_tilt_deg", max_trunk_guard_tilt_deg, 0.0, 180.0);
  CheckNonNegative("max_trunk_guard_offset_m", max_trunk_guard_offset_m);
  CheckInRange("max_ground_guard_tilt_deg", max_ground_guard_tilt_deg, 0.0, 180.0);
  CheckNonNegative("max_ground_guard_offset_m", max_ground_guard_offset_m);
}

PairResult RegisterPairFirstAttempt(const RegistrationView& source, const RegistrationView& target,
                                    const PairOptions& options, const ScreenGate& gate) {
  options.Validate();
  PairResult result = RegisterPairOnce(source, target, options, gate);
  result.attempts.push_back(RunOf(result, PairAttempt::kFirst, options));
  return result;
}

void DeclinePair(const std::string& reason, PairResult& result) {
  result.declined = reason;
  result.status += "; " + reason;
}

void RetryPair(const RegistrationView& source, const RegistrationView& target,
               const PairOptions& options, PairResult& result) {
  options.Validate();
  if (!result.declined.empty()) return;
  // A retry runs when asked for and the result overlaps too little, unless the pair is declined
  // (decline_below_overlap, max_pair_seconds).
  auto retry = [&](bool asked) {
    if (!asked || result.fine.fitness >= options.min_fitness || !result.declined.empty()) {
      return false;
    }
    result.declined = WhyNoRetry(result, options, result.seconds);
    return result.declined.empty();
  };
  // Key regions placed at different physical points (one view's ground or trunk base seen far
  // higher than the other's) make SAC-IA align different parts of the tree; the other choice
  // of key regions is tried before the priors are given up.
  if (retry(options.retry_other_key_regions && UsesKeyRegion(source.coarse_input))) {
    PairOptions other = options;
    other.own_key_regions = !options.own_key_regions;
    KeepBetterOverlap(RegisterPairOnce(source, target, other), PairAttempt::kOtherKeyRegions,
                      options, &result);
  }
  // Both forks may be other branchings (a view that sees one arm of the first fork hidden behind
  // the other finds the next one up): SAC-IA then aligns the two forks, the source lands a
  // fork's spacing too high or low, and no turn mends it. The screen is run once more over
  // shifts along the trunk too, with the key regions that overlapped best.
  if (retry(options.retry_with_shifts && options.screen_shift_share <= 0 && options.run_icp)) {
    PairOptions shifted = options;
    shifted.screen_shift_share = options.retry_shift_share;
    shifted.own_key_regions = result.own_key_regions;
    KeepBetterOverlap(RegisterPairOnce(source, target, shifted), PairAttempt::kShifts, options,
                      &result);
  }
  // A trunk found wrong in one view (a stem beside it, a fork taken for the trunk) misleads the
  // up and centre priors and the snap in every turn; when the result overlaps too little to be
  // trusted, the pair is registered once more without them and the better overlap kept.
  const bool priors = options.up_prior || options.center_prior || options.snap_to_priors;
  if (retry(options.retry_without_priors && priors)) {
    PairOptions plain = options;
    plain.up_prior = plain.center_prior = plain.snap_to_priors = false;
    plain.own_key_regions = result.own_key_regions;
    plain.min_fitness = std::max(options.min_fitness, options.min_fitness_without_priors);
    KeepBetterOverlap(RegisterPairOnce(source, target, plain), PairAttempt::kWithoutPriors, options,
                      &result);
    result.retried_without_priors = true;
  }
  if (!result.declined.empty()) result.status += "; " + result.declined;
}

PairResult RegisterPair(const RegistrationView& source, const RegistrationView& target,
                        const PairOptions& options) {
  PairResult result = RegisterPairFirstAttempt(source, target, options);
  RetryPair(source, target, options, result);
  return result;
}

}  // namespace simtree::registration
