#include "simtree/eval/tracking_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"

namespace simtree::eval {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

double Mean(const std::vector<double>& v) {
  if (v.empty()) return kNaN;
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

// One (frame, marker) sample as the scores see it.
struct Sample {
  int marker_index = 0;  // into the truth's marker order
  bool visible = false;
  bool reported = false;  // state not lost
  bool measured = false;  // tracked with a 3D position
  double confidence = 0.0;
  double iou = 0.0;
  double center_error_px = kNaN;
  double error_mm = kNaN;
  bool swapped = false;
};

std::map<int, size_t> FrameIndex(const std::vector<int>& frames) {
  std::map<int, size_t> index;
  for (size_t i = 0; i < frames.size(); ++i) index[frames[i]] = i;
  return index;
}

// Whether a measured position sits on another marker's true centre instead of its own.
bool IsSwap(const Trajectories& truth, size_t truth_frame, int own_track, const Eigen::Vector3d& p,
            double swap_m) {
  const MarkerTrack& own = truth.tracks[own_track];
  if (own.valid[truth_frame] && (own.positions[truth_frame] - p).norm() <= swap_m) return false;
  for (size_t t = 0; t < truth.tracks.size(); ++t) {
    if (static_cast<int>(t) == own_track || !truth.tracks[t].valid[truth_frame]) continue;
    if ((truth.tracks[t].positions[truth_frame] - p).norm() <= swap_m) return true;
  }
  return false;
}

// Precision, recall and F at the confidence threshold that maximises F.
void ScoreF(const std::vector<Sample>& samples, int visible, TrackingScores* s) {
  std::vector<const Sample*> reported;
  for (const Sample& x : samples) {
    if (x.reported) reported.push_back(&x);
  }
  std::sort(reported.begin(), reported.end(),
            [](const Sample* a, const Sample* b) { return a->confidence > b->confidence; });
  double iou_sum = 0.0;  // reported so far; an invisible report adds 0
  for (size_t k = 0; k < reported.size(); ++k) {
    iou_sum += reported[k]->visible ? reported[k]->iou : 0.0;
    const bool last_of_tau =
        k + 1 == reported.size() || reported[k + 1]->confidence < reported[k]->confidence;
    if (!last_of_tau) continue;
    const double pr = iou_sum / static_cast<double>(k + 1);
    const double re = visible > 0 ? iou_sum / visible : 0.0;
    const double f = pr + re > 0.0 ? 2.0 * pr * re / (pr + re) : 0.0;
    if (f > s->f_score) {
      s->f_score = f;
      s->precision = pr;
      s->recall = re;
      s->f_threshold = reported[k]->confidence;
    }
  }
}

void Summarise(const std::vector<Sample>& samples, const TrackingScoreOptions& options,
               TrackingScores* s) {
  std::vector<double> ious, centre, error;
  for (const Sample& x : samples) {
    if (x.visible) {
      ++s->visible_samples;
      ious.push_back(x.reported ? x.iou : 0.0);
      if (x.measured) {
        ++s->tracked_visible;
        if (std::isfinite(x.center_error_px)) centre.push_back(x.center_error_px);
      }
    } else if (x.measured) {
      ++s->tracked_invisible;
    }
    if (x.measured && std::isfinite(x.error_mm)) error.push_back(x.error_mm);
    if (x.swapped) ++s->swap_samples;
  }
  s->tracked_fraction =
      s->visible_samples > 0 ? static_cast<double>(s->tracked_visible) / s->visible_samples : 0.0;
  s->mean_iou = Mean(ious);
  const int n = std::max(2, options.success_thresholds);
  double area = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / (n - 1);
    const double share = ious.empty()
                             ? 0.0
                             : static_cast<double>(std::count_if(ious.begin(), ious.end(),
                                                                 [&](double v) { return v > t; })) /
                                   static_cast<double>(ious.size());
    s->success_curve.push_back(share);
    area += share;
  }
  s->success_rate = area / n;
  s->median_center_error_px = Median(centre);
  s->mean_center_error_px = Mean(centre);
  s->error_samples = static_cast<int>(error.size());
  s->median_error_mm = Median(error);
  s->mean_error_mm = Mean(error);
  s->p95_error_mm = Quantile(error, 0.95);
  ScoreF(samples, s->visible_samples, s);
}

}  // namespace

double BoxIou(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  if (a[2] <= 0.0 || a[3] <= 0.0 || b[2] <= 0.0 || b[3] <= 0.0) return 0.0;
  const double w = std::min(a[0] + a[2], b[0] + b[2]) - std::max(a[0], b[0]);
  const double h = std::min(a[1] + a[3], b[1] + b[3]) - std::max(a[1], b[1]);
  if (w <= 0.0 || h <= 0.0) return 0.0;
  const double inter = w * h;
  return inter / (a[2] * a[3] + b[2] * b[3] - inter);
}

TrackingScores ScoreTracking(const std::vector<tracking::FrameBoxes>& boxes,
                             const Trajectories& tracked,
                             const std::vector<MarkerFrame2d>& truth_boxes,
                             const Trajectories& truth, const TrackingScoreOptions& options) {
  std::vector<int> box_frames;
  for (const auto& f : boxes) box_frames.push_back(f.frame);
  const auto box_index = FrameIndex(box_frames);
  const auto tracked_index = FrameIndex(tracked.frames);
  const auto truth_index = FrameIndex(truth.frames);
  TrackingScores scores;
  std::vector<Sample> samples;
  std::vector<std::vector<Sample*>> per_marker;
  for (const MarkerFrame2d& gt : truth_boxes) {
    const auto b = box_index.find(gt.frame);
    const auto t = tracked_index.find(gt.frame);
    const auto g = truth_index.find(gt.frame);
    if (b == box_index.end() || t == tracked_index.end() || g == truth_index.end()) continue;
    ++scores.frames;
    const tracking::FrameBoxes& frame = boxes[b->second];
    for (const tracking::MarkerBox& mb : frame.markers) {
      if (std::none_of(gt.markers.begin(), gt.markers.end(),
                       [&](const MarkerBox2d& m) { return m.id == mb.marker; })) {
        throw InputError("boxes.csv", fmt::format("frame {}", frame.frame),
                         fmt::format("marker {} is not in the truth", mb.marker));
      }
    }
    for (size_t mi = 0; mi < gt.markers.size(); ++mi) {
      const MarkerBox2d& truth_box = gt.markers[mi];
      Sample x;
      x.marker_index = static_cast<int>(mi);
      x.visible = truth_box.visible;
      const auto mine = std::find_if(frame.markers.begin(), frame.markers.end(),
                                     [&](const auto& m) { return m.marker == truth_box.id; });
      if (mine != frame.markers.end() && mine->state != tracking::MarkerState::kLost) {
        x.reported = true;
        x.confidence = mine->confidence;
        x.iou = BoxIou(mine->box, truth_box.box);
        const double cx = truth_box.box[0] + 0.5 * truth_box.box[2];
        const double cy = truth_box.box[1] + 0.5 * truth_box.box[3];
        if (mine->state == tracking::MarkerState::kTracked) {
          x.center_error_px = std::hypot(mine->center[0] - cx, mine->center[1] - cy);
        }
      }
      const int track = tracked.IndexOf(truth_box.id);
      const int own = truth.IndexOf(truth_box.id);
      if (track >= 0 && tracked.tracks[track].valid[t->second]) {
        x.measured = true;
        const Eigen::Vector3d p = tracked.tracks[track].positions[t->second];
        if (own >= 0 && truth.tracks[own].valid[g->second]) {
          x.error_mm = 1000.0 * (p - truth.tracks[own].positions[g->second]).norm();
        }
        if (own >= 0) {
          x.swapped = IsSwap(truth, g->second, own, p, options.swap_distance_mm / 1000.0);
        }
      }
      samples.push_back(x);
    }
  }
  if (scores.frames == 0) {
    throw InputError("tracks", "", "the tracks and the truth share no frame number");
  }
  Summarise(samples, options, &scores);
  // Per marker, and swap events (runs of swapped samples).
  const size_t markers = truth_boxes.front().markers.size();
  for (size_t mi = 0; mi < markers; ++mi) {
    MarkerTrackingScore m;
    m.marker = truth_boxes.front().markers[mi].id;
    std::vector<double> errors;
    bool in_swap = false;
    for (const Sample& x : samples) {
      if (x.marker_index != static_cast<int>(mi)) continue;
      m.visible += x.visible;
      m.tracked_visible += x.visible && x.measured;
      if (x.measured && std::isfinite(x.error_mm)) errors.push_back(x.error_mm);
      m.swap_samples += x.swapped;
      if (x.swapped && !in_swap) ++scores.swap_events;
      if (x.measured) in_swap = x.swapped;
    }
    m.median_error_mm = Median(errors);
    scores.markers.push_back(m);
  }
  return scores;
}

}  // namespace simtree::eval
