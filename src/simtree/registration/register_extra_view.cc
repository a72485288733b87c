#include "simtree/registration/register_extra_view.h"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/registration/detail/pose_graph.h"

namespace simtree::registration {
namespace {

// The extra view paired with every registered view, all at once.
std::vector<ExtraViewPair> PairWithRegisteredViews(const std::vector<RegistrationView>& views,
                                                   const MultiViewResult& registered,
                                                   const RegistrationView& extra,
                                                   const PairOptions& options) {
  std::vector<ExtraViewPair> pairs;
  for (size_t v = 0; v < views.size(); ++v) {
    if (!registered.views[v].registered()) continue;
    ExtraViewPair pair;
    pair.view = static_cast<int>(v);
    pairs.push_back(std::move(pair));
  }
  oneapi::tbb::parallel_for(size_t{0}, pairs.size(), [&](size_t k) {
    pairs[k].result = RegisterPair(extra, views[pairs[k].view], options);
  });
  return pairs;
}

// The extra view's pose in the registration frame by one pair.
Eigen::Isometry3d FrameFromExtra(const MultiViewResult& registered, const ExtraViewPair& pair) {
  return registered.views[pair.view].frame_from_camera * pair.result.target_from_source;
}

// The trusted pairs, the one whose whole view overlaps most first, at most `max_pairs`.
std::vector<size_t> BestTrusted(const std::vector<ExtraViewPair>& pairs, int max_pairs) {
  std::vector<size_t> trusted;
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (pairs[k].result.ok()) trusted.push_back(k);
  }
  std::stable_sort(trusted.begin(), trusted.end(), [&](size_t a, size_t b) {
    return pairs[a].result.view_overlap > pairs[b].result.view_overlap;
  });
  if (trusted.size() > static_cast<size_t>(max_pairs)) trusted.resize(max_pairs);
  return trusted;
}

// The mean of poses of one view: the rotations' normalised quaternion sum, and the translation
// that puts its lever point at the mean of where the poses put it.
Eigen::Isometry3d MeanPose(const std::vector<Eigen::Isometry3d>& poses,
                           const RegistrationView& view) {
  const Eigen::Quaterniond first(poses.front().linear());
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  for (const Eigen::Isometry3d& pose : poses) {
    Eigen::Quaterniond q(pose.linear());
    if (q.coeffs().dot(first.coeffs()) < 0) q.coeffs() *= -1.0;
    sum += q.coeffs();
  }
  Eigen::Isometry3d mean = Eigen::Isometry3d::Identity();
  mean.linear() = Eigen::Quaterniond(sum.normalized()).toRotationMatrix();
  const Eigen::Vector3d lever = LeverPoint(view);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Isometry3d& pose : poses) centre += pose * lever;
  centre /= static_cast<double>(poses.size());
  mean.translation() = centre - mean.linear() * lever;
  return mean;
}

// Why no pair placed the view: the first reason of its pairs.
std::string WhyNotPlaced(const std::vector<RegistrationView>& views,
                         const std::vector<ExtraViewPair>& pairs) {
  std::string reason = ToString(ExtraViewOutcome::kNoTrustedPair);
  if (pairs.empty()) return reason + " (no view is registered)";
  return reason +
         fmt::format(" (with {}: {})", views[pairs.front().view].name, pairs.front().result.status);
}

// The pose from the trusted pairs that agree with the best one, and every trusted pair's
// residuals against it.
void PlaceByAgreeingPairs(const MultiViewResult& registered, const RegistrationView& extra,
                          const std::vector<size_t>& best, const ExtraViewOptions& options,
                          ExtraViewResult& result) {
  const Eigen::Isometry3d first = FrameFromExtra(registered, result.pairs[best.front()]);
  std::vector<Eigen::Isometry3d> agreeing;
  for (size_t k : best) {
    const PoseDifference d =
        DifferenceAt(first.inverse() * FrameFromExtra(registered, result.pairs[k]), extra);
    if (d.rotation_deg > options.max_rotation_deg || d.shift_m > options.max_shift_m) continue;
    result.pairs[k].used = true;
    agreeing.push_back(FrameFromExtra(registered, result.pairs[k]));
  }
  result.frame_from_camera = MeanPose(agreeing, extra);
  result.pairs_used = static_cast<int>(agreeing.size());
  result.rotation_spread_deg = result.shift_spread_m = 0.0;
  for (ExtraViewPair& pair : result.pairs) {
    if (!pair.result.ok()) continue;
    const PoseDifference d =
        DifferenceAt(result.frame_from_camera.inverse() * FrameFromExtra(registered, pair), extra);
    pair.rotation_residual_deg = d.rotation_deg;
    pair.shift_residual_m = d.shift_m;
    if (!pair.used) continue;
    result.rotation_spread_deg = std::max(result.rotation_spread_deg, d.rotation_deg);
    result.shift_spread_m = std::max(result.shift_spread_m, d.shift_m);
  }
  result.view_overlap = result.pairs[best.front()].result.view_overlap;
  result.outcome = result.pairs_used >= 2 ? ExtraViewOutcome::kPlaced : ExtraViewOutcome::kOnePair;
  result.status = ToString(result.outcome);
}

}  // namespace

void ExtraViewOptions::Validate() const {
  CheckNested("pair", [&] { pair.Validate(); });
  CheckAtLeast("max_pairs", max_pairs, 1);
  CheckPositive("max_rotation_deg", max_rotation_deg);
  CheckPositive("max_shift_m", max_shift_m);
}

const char* ToString(ExtraViewOutcome outcome) {
  switch (outcome) {
    case ExtraViewOutcome::kPlaced:
      return "placed";
    case ExtraViewOutcome::kOnePair:
      return "placed by one pair only";
    case ExtraViewOutcome::kCannotRegister:
      return "cannot be registered";
    case ExtraViewOutcome::kNoTrustedPair:
      return "no trusted pair with a registered view";
  }
  return "?";
}

bool ExtraViewResult::placed() const {
  return outcome == ExtraViewOutcome::kPlaced || outcome == ExtraViewOutcome::kOnePair;
}

ExtraViewResult RegisterExtraView(const std::vector<RegistrationView>& views,
                                  const MultiViewResult& registered, const RegistrationView& extra,
                                  const ExtraViewOptions& options) {
  options.Validate();
  if (registered.views.size() != views.size()) {
    throw InputError("<memory>", "registered views",
                     fmt::format("expected the result of registering these {} views, got {}",
                                 views.size(), registered.views.size()));
  }
  const auto start = std::chrono::steady_clock::now();
  ExtraViewResult result;
  result.name = extra.name;
  if (!extra.CanRegister()) {
    result.outcome = ExtraViewOutcome::kCannotRegister;
    result.status = extra.failure;
    return result;
  }
  // Registered like one more view: paired with each registered view, each pair checked.
  result.pairs = PairWithRegisteredViews(views, registered, extra, options.pair);
  const std::vector<size_t> best = BestTrusted(result.pairs, options.max_pairs);
  if (best.empty()) {
    result.outcome = ExtraViewOutcome::kNoTrustedPair;
    result.status = WhyNotPlaced(views, result.pairs);
  } else {
    // The best pairs that agree make the pose; one wrong pair that passed its checks does not.
    PlaceByAgreeingPairs(registered, extra, best, options, result);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

ExtraViewResult RegisterPullFrame(const Capture& capture,
                                  const std::vector<RegistrationView>& views,
                                  const MultiViewResult& registered,
                                  const preprocessing::PreprocessOptions& preprocess,
                                  const RegistrationViewOptions& view_options,
                                  const ExtraViewOptions& options, size_t frame) {
  view_options.Validate();
  options.Validate();
  const RegistrationView extra =
      PrepareViews({preprocessing::PreprocessPullFrame(capture, frame, preprocess)}, view_options)
          .front();
  return RegisterExtraView(views, registered, extra, options);
}

}  // namespace simtree::registration
