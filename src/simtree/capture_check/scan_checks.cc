// The scan views' checks: their number, each view's frame, and how they surround the tree.

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "simtree/capture_check/detail/frame_quality.h"
#include "simtree/capture_check/detail/grade.h"
#include "simtree/capture_check/detail/steps.h"
#include "simtree/core/error.h"
#include "simtree/registration/register.h"

namespace simtree::capture_check::detail {

namespace {

Check DistanceCheck(const std::string& subject, double d, const CheckThresholds& t) {
  if (d < t.min_distance_m) {
    Check c = Grade("distance", subject, d, "m",
                    {Better::kLower, t.warn_distance_m, t.max_distance_m}, "", "");
    c.status = Status::kFail;
    c.message = fmt::format(
        "the tree is {:.2f} m away: step back, the depth camera measures "
        "from {:.2f} m",
        d, t.min_distance_m);
    return c;
  }
  return Grade("distance", subject, d, "m", {Better::kLower, t.warn_distance_m, t.max_distance_m},
               fmt::format("the tree is {:.2f} m away", d),
               fmt::format("move closer: depth noise grows with the square of the distance and "
                           "thin branches drop out (the camera measures to {:.2f} m)",
                           t.max_distance_m));
}

Check ExposureCheck(const std::string& subject, const FrameQuality& q, const CheckThresholds& t) {
  const bool bright = q.bright_share >= q.dark_share;
  const double share = std::max(q.bright_share, q.dark_share);
  const std::string found =
      bright ? fmt::format("{:.0f}% of the tree's pixels clipped white", share * 100)
             : fmt::format("{:.0f}% of the tree's pixels too dark to show a colour", share * 100);
  const std::string fix = bright ? "lower the exposure, keep the sun behind the camera"
                                 : "raise the exposure or capture in more light: the tape's "
                                   "colour needs a brightness of 28 of 255";
  return Grade("exposure", subject, share, "%",
               {Better::kLower, t.warn_clipped_share, t.fail_clipped_share}, found, fix, 100);
}

}  // namespace

void CheckFrame(const std::string& subject, const RgbdImage& image,
                const preprocessing::PreprocessedView& view, const CheckThresholds& t,
                std::vector<Check>* out) {
  if (!view.result) {
    out->push_back(Failed("tree", subject,
                          "no tree found (" + view.failure +
                              "): the depth must show the tree, 0.5-3.86 m away, over its ground"));
    return;
  }
  const FrameQuality q = MeasureFrame(image, view.result->cloud, view.result->voxel_size_m);
  out->push_back(Grade("depth on the tree", subject, q.depth_share, "%",
                       {Better::kHigher, t.warn_tree_depth_share, t.fail_tree_depth_share},
                       fmt::format("{:.0f}% of the tree's pixels have depth ({} holes)",
                                   q.depth_share * 100, q.hole_pixels),
                       "depth drops out on the tree: avoid direct sun and backlight on it (they "
                       "drown the camera's infrared), wait for still air, move closer",
                       100));
  out->push_back(DistanceCheck(subject, q.distance_m, t));
  out->push_back(Grade("blur", subject, q.blur, "", {Better::kLower, t.warn_blur, t.warn_blur},
                       fmt::format("blur effect {:.2f} on the tree (0 sharp, 1 blurred)", q.blur),
                       "the colour is blurred: hold the camera still (a tripod), wait for the "
                       "wind to drop, check the focus"));
  out->push_back(ExposureCheck(subject, q, t));
}

namespace {

// The largest angle around the vertical through the trunk's foot without a registered view, and
// the views left out.
void CheckCoverage(const std::vector<preprocessing::PreprocessedView>& preprocessed,
                   const CheckThresholds& t, std::vector<Check>* out) {
  namespace reg = simtree::registration;
  const std::vector<reg::RegistrationView> views = reg::PrepareViews(preprocessed);
  const reg::MultiViewOptions options;
  const reg::MultiViewResult result = reg::RegisterViews(views, options);
  std::vector<double> azimuths;
  std::vector<std::string> left_out;
  for (const reg::ViewRegistration& v : result.views) {
    if (!v.registered()) {
      left_out.push_back(v.name + " (" + v.status + ")");
      continue;
    }
    const Eigen::Vector3d c = v.frame_from_camera.translation();
    azimuths.push_back(std::atan2(c.y(), c.x()) * 180 / std::numbers::pi);
  }
  const int n = static_cast<int>(preprocessed.size());
  const int registered = static_cast<int>(azimuths.size());
  std::string found = fmt::format("{} of {} views registered", registered, n);
  for (const std::string& s : left_out) found += "; left out: " + s;
  out->push_back(Grade("views registered", "scans", registered, "",
                       {Better::kHigher, static_cast<double>(n), 2}, found,
                       "take the views left out again, each overlapping its neighbours (at most "
                       "about 90 degrees apart around the tree)"));
  if (registered < 2) return;
  std::sort(azimuths.begin(), azimuths.end());
  double gap = 360 - (azimuths.back() - azimuths.front());
  for (size_t i = 1; i < azimuths.size(); ++i) gap = std::max(gap, azimuths[i] - azimuths[i - 1]);
  out->push_back(Grade("view coverage", "scans", gap, "deg",
                       {Better::kLower, t.warn_coverage_gap_deg, t.warn_coverage_gap_deg},
                       fmt::format("the largest angle around the tree without a view is {:.0f} "
                                   "degrees",
                                   gap),
                       "add views in that gap: the far side of the tree is missing from the "
                       "merged cloud"));
}

}  // namespace

void CheckScans(const Capture& capture, const CaptureCheckOptions& options,
                std::vector<Check>* out) {
  const CheckThresholds& t = options.thresholds;
  const int n = static_cast<int>(capture.views.size());
  out->push_back(
      Grade("scan views", "scans", n, "", {Better::kHigher, double(t.warn_views), 1},
            fmt::format("{} views", n),
            fmt::format("take at least {} views on a ring around the tree", t.warn_views)));
  if (n == 0) return;
  const std::vector<preprocessing::PreprocessedView> views =
      preprocessing::PreprocessCaptureViews(capture);
  for (size_t i = 0; i < capture.views.size(); ++i) {
    const ScanView& view = capture.views[i];
    RgbdImage image;
    try {
      image = LoadScanView(view);
    } catch (const Error& e) {
      out->push_back(Failed("images", view.name, e.what()));
      continue;
    }
    CheckFrame(view.name, image, views[i], t, out);
  }
  if (!options.register_views) {
    out->push_back(Skipped("view coverage", "scans", "skipped (--no-register)"));
  } else if (n < 2) {
    out->push_back(Skipped("view coverage", "scans", "one view: nothing to register"));
  } else {
    CheckCoverage(views, t, out);
  }
}

}  // namespace simtree::capture_check::detail
