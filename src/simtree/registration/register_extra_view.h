#pragma once
// One more view placed in the registration frame of views already registered (RegisterViews),
// without moving them: the pull-test camera's first, still frame, so that what is tracked in the
// pull camera's frame lands on the tree reconstructed from the scans.
//
// The view is registered like one more view: paired with every registered view (RegisterPair:
// the same coarse and fine stages and the same checks), the trusted pairs that overlap it most
// each give a pose, and the poses that agree with the best pair's are averaged. It is placed
// only when a trusted pair places it; otherwise the outcome says why and nothing else fails.
//
// Usage:
//   namespace reg = simtree::registration;
//   const simtree::Capture capture = simtree::OpenCapture("scene/");
//   const std::vector<reg::RegistrationView> views =
//       reg::PrepareViews(simtree::preprocessing::PreprocessCaptureViews(capture));
//   const reg::MultiViewResult result = reg::RegisterViews(views);
//   const reg::ExtraViewResult pull = reg::RegisterPullFrame(capture, views, result);
//   if (pull.placed()) { /* pull.frame_from_camera: the pull camera in the frame */ }

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/io/capture.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/registration/detail/pairwise.h"
#include "simtree/registration/register.h"
#include "simtree/registration/registration_view.h"

namespace simtree::registration {

struct ExtraViewOptions {
  PairOptions pair;   // each pair's registration and checks (pairwise.h)
  int max_pairs = 3;  // >= 1: the trusted pairs overlapping the view most make its pose
  // A pair agrees with the best one when their poses of the view differ by at most this
  // rotation and move its key region by at most this distance (as RegisterViews' pose graph).
  double max_rotation_deg = 1.5;  // deg, > 0
  double max_shift_m = 0.025;     // m, > 0

  // Throws InputError naming the field of a nonsense value (pair.min_fitness, ...).
  void Validate() const;
};

// How the extra view ended.
enum class ExtraViewOutcome {
  kPlaced,          // "placed": two or more trusted pairs agree on its pose
  kOnePair,         // "placed by one pair only": no second trusted pair agrees
  kCannotRegister,  // not placed: the view itself cannot be registered (its failure)
  kNoTrustedPair,   // not placed: no pair with a registered view passed its checks
};
const char* ToString(ExtraViewOutcome outcome);

// The extra view paired with one registered view.
struct ExtraViewPair {
  int view = 0;       // the registered view's index
  PairResult result;  // source: the extra view; target: the registered view
  bool used = false;  // among the pairs whose poses were averaged
  // Against the pose found, as DifferenceAt (NaN for a pair that is not trusted).
  double rotation_residual_deg = std::numeric_limits<double>::quiet_NaN();
  double shift_residual_m = std::numeric_limits<double>::quiet_NaN();
};

struct ExtraViewResult {
  std::string name;
  ExtraViewOutcome outcome = ExtraViewOutcome::kNoTrustedPair;
  std::string status;  // ToString(outcome), or why it was not placed
  Eigen::Isometry3d frame_from_camera = Eigen::Isometry3d::Identity();  // when placed
  std::vector<ExtraViewPair> pairs;                                     // one per registered view
  // Quality: the pairs averaged, the largest disagreement of one of them with the pose found,
  // and the whole-view overlap of the best pair (PairResult::view_overlap).
  int pairs_used = 0;
  double rotation_spread_deg = std::numeric_limits<double>::quiet_NaN();
  double shift_spread_m = std::numeric_limits<double>::quiet_NaN();
  double view_overlap = 0.0;
  double seconds = 0.0;

  bool placed() const;
};

// `views` and `registered`: what RegisterViews took and gave; `extra` prepared like the views
// (PrepareView, the same options). Throws InputError for nonsense options or when `views` and
// `registered` do not match.
ExtraViewResult RegisterExtraView(const std::vector<RegistrationView>& views,
                                  const MultiViewResult& registered, const RegistrationView& extra,
                                  const ExtraViewOptions& options = {});

// Frame `frame` of the capture's pull-test stream (its first, still frame by default) as the
// extra view: preprocessed (PreprocessPullFrame) and prepared (PrepareView) with the options the
// scan views had. Throws InputError when the capture has no pull stream.
ExtraViewResult RegisterPullFrame(const Capture& capture,
                                  const std::vector<RegistrationView>& views,
                                  const MultiViewResult& registered,
                                  const preprocessing::PreprocessOptions& preprocess = {},
                                  const RegistrationViewOptions& view_options = {},
                                  const ExtraViewOptions& options = {}, size_t frame = 0);

}  // namespace simtree::registration
