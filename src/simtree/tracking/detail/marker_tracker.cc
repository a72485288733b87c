#include "simtree/tracking/detail/marker_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "simtree/tracking/detail/hungarian.h"

namespace simtree::tracking::detail {
namespace {

constexpr double kForbidden = std::numeric_limits<double>::infinity();
// A detection this much weaker than the marker's fully visible tape is partly hidden: its box
// comes from the band's remembered size instead.
constexpr double kPartialWeight = 0.7;
// Blobs this close (px at the reference focal length, Scale()) at one depth may be pieces of one
// tape.
constexpr double kFragmentPx = 8.0;
// A blob this much nearer another marker's predicted pixel (and compatible with its depth)
// belongs to that marker (see OwnedByAnother); in the first frame, where two clicks may lie a
// pixel apart on two tapes one behind the other, only a blob far nearer one click than the other.
constexpr double kOwnerRatio = 0.8;
constexpr double kFirstFrameOwnerRatio = 0.5;
// A detection without depth weaker than this share of the marker's usual tape is not taken: a
// few noise pixels of the tape's hue (camera colour) that would drag the marker off its tape.
constexpr double kWeakNoDepth = 0.5;
// While a marker coasts its velocity decays by this per frame: a branch swings back within a
// fraction of a second, and a velocity fitted to a partly hidden tape's jumping centre carried
// markers tens of pixels off before they were lost.
constexpr double kCoastVelocityDecay = 0.7;

}  // namespace

MarkerTracker::MarkerTracker(const TrackOptions& options, const TapeColorModel& model,
                             const CameraIntrinsics& intrinsics, std::vector<int> ids,
                             std::vector<Eigen::Vector2d> pixels)
    : options_(options),
      intrinsics_(intrinsics),
      detector_(model, BlobDetectorOptions{.min_blob_pixels = options.min_blob_pixels,
                                           .max_blob_pixels = 4000,
                                           .split_depth_m = options.split_depth_mm / 1000.0}) {
  motion_params_.kind = options.motion_model;
  motion_params_.process_noise_mps2 = options.process_noise_mps2;
  motion_params_.noise_xy_m = options.measurement_noise_mm / 1000.0;
  motion_params_.noise_z_m = options.measurement_depth_noise_mm / 1000.0;
  for (size_t i = 0; i < ids.size(); ++i) {
    Marker m;
    m.id = ids[i];
    m.pixel = pixels[i];
    m.rest_pixel = pixels[i];
    markers_.push_back(m);
  }
}

void MarkerTracker::PredictAll(double dt) {
  for (Marker& m : markers_) {
    ++m.age;
    if (!m.started || m.coast > options_.max_coast_frames) continue;
    m.motion.Predict(dt);
    const Eigen::Vector3d p = m.motion.position();
    if (p.z() > 0.0) m.pixel = intrinsics_.Project(p);
  }
}

void MarkerTracker::FieldPredict() {
  // A branch carries its markers together: a marker's displacement from its rest pose is close to
  // that of the markers nearest it at rest. A lost marker's last position says little after a
  // release's swing (30 px a frame); its neighbours' displacements say where it went, and they
  // tell its tape from a neighbour's when both come back (identity swaps on acer_rubrum).
  constexpr int kNeighbours = 3;
  for (Marker& m : markers_) {
    m.has_field = false;
    if (!m.started) continue;
    std::vector<std::pair<double, Eigen::Vector3d>> near;
    for (const Marker& o : markers_) {
      if (&o == &m || !o.started || o.coast != 0) continue;
      near.emplace_back((o.motion.rest() - m.motion.rest()).norm(),
                        o.last_position - o.motion.rest());
    }
    if (near.empty()) continue;
    const size_t k = std::min<size_t>(kNeighbours, near.size());
    std::partial_sort(near.begin(), near.begin() + k, near.end(),
                      [](const auto& a, const auto& b) { return a.first < b.first; });
    Eigen::Vector3d shift = Eigen::Vector3d::Zero();
    double total = 0.0;
    for (size_t n = 0; n < k; ++n) {
      const double w = 1.0 / (near[n].first + 0.05);  // 5 cm: neighbours on one branch weigh alike
      shift += w * near[n].second;
      total += w;
    }
    const Eigen::Vector3d p = m.motion.rest() + shift / total;
    if (p.z() <= 0.0) continue;
    m.has_field = true;
    m.field_pixel = intrinsics_.Project(p);
  }
}

std::vector<SearchWindow> MarkerTracker::Windows() const {
  std::vector<SearchWindow> windows;
  const int w = intrinsics_.width, h = intrinsics_.height;
  for (const Marker& m : markers_) {
    const bool active = (m.started || first_frame_) && m.coast <= options_.max_coast_frames;
    if (active) {
      const double r = (options_.search_radius_px + 2.0 * m.coast) * Scale();
      windows.push_back(WindowAround(m.pixel, r, w, h));
    } else {
      const double r = options_.reacquire_radius_px * Scale();
      windows.push_back(WindowAround(m.pixel, r, w, h));
      windows.push_back(WindowAround(m.rest_pixel, r, w, h));
      if (m.has_field) windows.push_back(WindowAround(m.field_pixel, r, w, h));
    }
  }
  return windows;
}

double MarkerTracker::Cost(const Marker& m, const Detection& det) const {
  // Image distance and depth difference, each against its own gate: the depth of a tape a few
  // pixels wide is far noisier than its position across the image.
  const bool active = (m.started || first_frame_) && m.coast <= options_.max_coast_frames;
  const double gate_z = options_.gate_mm / 1000.0;
  if (!m.started || !active) {
    // Found again (or never found yet): near its last pixel or its rest pixel, in the image.
    const double gate =
        (active ? options_.search_radius_px : options_.reacquire_radius_px) * Scale();
    double d2 = std::min((det.center - m.pixel).norm(), (det.center - m.rest_pixel).norm());
    if (m.has_field) d2 = std::min(d2, (det.center - m.field_pixel).norm());
    if (d2 > gate) return kForbidden;
    double cost = (d2 / gate) * (d2 / gate);
    if (m.started && det.has_depth) {
      const double dz = std::min(std::abs(det.position.z() - m.last_position.z()),
                                 std::abs(det.position.z() - m.motion.rest().z()));
      if (dz > 3.0 * gate_z) return kForbidden;
      cost += (dz / (3.0 * gate_z)) * (dz / (3.0 * gate_z));
    }
    return cost;
  }
  if (!det.has_depth && det.weight < kWeakNoDepth * m.typical_weight) return kForbidden;
  const Eigen::Vector3d p = m.motion.position();
  const Eigen::Vector3d sigma = m.motion.position_sigma();
  const double sigma_px = std::max(sigma.x(), sigma.y()) * intrinsics_.fx / std::max(p.z(), 0.1);
  // The gate grows with the prediction's uncertainty while coasting, to at most twice its size.
  const double gate2 =
      options_.gate_px * Scale() + std::min(3.0 * sigma_px, options_.gate_px * Scale());
  const double d2 = (det.center - m.pixel).norm();
  if (d2 > gate2) return kForbidden;
  double cost = (d2 / gate2) * (d2 / gate2);
  if (det.has_depth) {
    const double gate3 = gate_z + std::min(3.0 * sigma.z(), gate_z);
    double dz = std::abs(det.position.z() - p.z());
    Eigen::Vector3d again;
    if (dz > gate3 && RemeasureNear(det, intrinsics_, p.z(), gate_z, &again)) {
      dz = std::abs(again.z() - p.z());
    }
    if (dz > gate3) return kForbidden;
    cost += (dz / gate3) * (dz / gate3);
  }
  return cost;
}

std::vector<int> MarkerTracker::Assign(const std::vector<Detection>& detections) {
  // Markers being tracked choose first; markers lost or not yet found share what is left, so a
  // marker coming back never takes a tracked neighbour's tape.
  std::vector<int> assignment(markers_.size(), -1);
  std::vector<bool> taken(detections.size(), false);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> rows;
    for (size_t i = 0; i < markers_.size(); ++i) {
      const Marker& m = markers_[i];
      const bool active = m.started && m.coast <= options_.max_coast_frames;
      if (active == (pass == 0)) rows.push_back(static_cast<int>(i));
    }
    if (rows.empty() || detections.empty()) continue;
    std::vector<std::vector<double>> cost(rows.size(),
                                          std::vector<double>(detections.size(), kForbidden));
    for (size_t r = 0; r < rows.size(); ++r) {
      for (size_t d = 0; d < detections.size(); ++d) {
        if (taken[d] || OwnedByAnother(rows[r], detections[d])) continue;
        cost[r][d] = Cost(markers_[rows[r]], detections[d]);
      }
    }
    const std::vector<int> solved = SolveAssignment(cost, kForbidden);
    for (size_t r = 0; r < rows.size(); ++r) {
      if (solved[r] < 0) continue;
      assignment[rows[r]] = solved[r];
      taken[solved[r]] = true;
    }
  }
  DropNeighbourFragments(detections, &assignment);
  return assignment;
}

bool MarkerTracker::OwnedByAnother(int i, const Detection& det) const {
  // A blob belongs to the marker whose predicted (or clicked) pixel lies nearest, among markers
  // whose depth it fits: when that marker cannot take it (its tape too faint, its depth off), a
  // neighbour a few pixels away must not either. Camera colour loses tiny tapes for frames at a
  // time, and their neighbours (10-30 px apart on acer_rubrum) took them: identity swaps.
  // A marker not being tracked (lost, or never found) has no depth of its own to tell its tape
  // from the blob a tracked neighbour's depth rejected: the image decides.
  const Marker& m = markers_[i];
  const bool tracked = m.started && m.coast <= options_.max_coast_frames;
  const double own = (det.center - m.pixel).norm();
  for (size_t j = 0; j < markers_.size(); ++j) {
    const Marker& o = markers_[j];
    if (static_cast<int>(j) == i) continue;
    const bool active = (o.started || first_frame_) && o.coast <= options_.max_coast_frames;
    if (!active) {
      // A lost marker owns what lies far nearer where its neighbours put it.
      if (o.has_field && (det.center - o.field_pixel).norm() < kFirstFrameOwnerRatio * own) {
        return true;
      }
      continue;
    }
    const double ratio = o.started ? kOwnerRatio : kFirstFrameOwnerRatio;
    const double theirs = (det.center - o.pixel).norm();
    if (theirs >= ratio * own) continue;
    // Far nearer the other's prediction, the image decides: a tape's depth may jump to what lies
    // behind it for a frame (acer_rubrum seed 2: marker 10 took marker 8's tape that way).
    if (o.started && theirs < kFirstFrameOwnerRatio * own) return true;
    const double gate_z = options_.gate_mm / 1000.0;
    Eigen::Vector3d again;
    const bool depth_fits =
        !tracked || !o.started || !det.has_depth ||
        std::abs(det.position.z() - o.motion.position().z()) <= gate_z ||
        RemeasureNear(det, intrinsics_, o.motion.position().z(), gate_z, &again);
    if (depth_fits) return true;
  }
  return false;
}

void MarkerTracker::DropNeighbourFragments(const std::vector<Detection>& detections,
                                           std::vector<int>* assignment) const {
  // A marker that was not measured in the last frame may not take a blob lying right beside the
  // blob of a marker that was, at its depth or split from the same blob: that is likely a piece
  // of the neighbour's tape (cut by a twig, or its pixels' depths mixed with what is behind), and
  // taking it is how identities swap. The marker waits until its own tape stands apart.
  const double near_px = kFragmentPx * Scale();
  for (size_t i = 0; i < markers_.size(); ++i) {
    const int d = (*assignment)[i];
    if (d < 0 || (markers_[i].started && markers_[i].coast == 0)) continue;
    for (size_t j = 0; j < markers_.size(); ++j) {
      const int e = (*assignment)[j];
      if (j == i || e < 0 || !markers_[j].started || markers_[j].coast != 0) continue;
      const Detection& a = detections[d];
      const Detection& b = detections[e];
      const bool beside = (a.center - b.center).norm() <= near_px;
      const bool same_depth =
          !a.has_depth || !b.has_depth ||
          std::abs(a.position.z() - b.position.z()) < options_.split_depth_mm / 1000.0;
      if (beside && (same_depth || a.source == b.source)) {
        (*assignment)[i] = -1;
        break;
      }
    }
  }
}

MarkerFrameResult MarkerTracker::Measured(Marker& m, const Detection& measured) {
  MarkerFrameResult out;
  Detection det = measured;
  if (det.has_depth && m.started && m.coast <= options_.max_coast_frames) {
    // A depth far from the prediction (a twig in front mixing its depth in): keep the tape
    // pixels that agree with the prediction.
    const double gate_z = options_.gate_mm / 1000.0;
    const double z_pred = m.motion.position().z();
    Eigen::Vector3d again;
    if (std::abs(det.position.z() - z_pred) > 0.5 * gate_z &&
        RemeasureNear(det, intrinsics_, z_pred, 0.5 * gate_z, &again)) {
      det.position = again;
    }
  }
  out.box.marker = m.id;
  out.box.state = MarkerState::kTracked;
  const bool was_lost = m.coast > options_.max_coast_frames;
  if (det.has_depth) {
    if (!m.started) {
      m.motion = MarkerMotionModel(motion_params_, det.position);
      m.rest_pixel = det.center;
      m.started = true;
    } else if (was_lost) {
      m.motion = MarkerMotionModel(motion_params_, det.position, m.motion.rest());
    } else {
      m.motion.Update(det.position);
    }
    m.last_position = det.position;
    out.measured = true;
    out.position = det.position;
  }
  m.pixel = det.center;
  m.coast = 0;
  // The band's box from its model, fed by the frames where the tape shows whole (a partly hidden
  // tape's blob says little of the band's size).
  const double z = det.has_depth ? det.position.z() : m.last_position.z();
  const bool whole = det.weight >= kPartialWeight * m.typical_weight;
  m.typical_weight = std::max(det.weight, 0.97 * m.typical_weight);
  if (whole && z > 0.0) m.band.Observe(det.shape, z);
  const BandShape band = m.band.known() && z > 0.0 ? m.band.At(det.center, z) : det.shape;
  out.box.center = {band.center.x(), band.center.y()};
  out.box.box = band.Box();
  out.box.confidence =
      m.typical_weight > 0.0 ? std::clamp(det.weight / m.typical_weight, 0.0, 1.0) : 1.0;
  return out;
}

MarkerFrameResult MarkerTracker::Unmeasured(Marker& m) {
  MarkerFrameResult out;
  out.box.marker = m.id;
  ++m.coast;
  const bool coasting = m.started && m.coast <= options_.max_coast_frames;
  if (coasting) m.motion.ScaleVelocity(kCoastVelocityDecay);
  out.box.state = coasting ? MarkerState::kPredicted : MarkerState::kLost;
  if (m.started && m.coast == options_.max_coast_frames + 1) {
    m.motion.ResetVelocity();
    m.pixel = intrinsics_.Project(m.last_position);
  }
  const double z = m.started ? m.motion.position().z() : 0.0;
  BandShape band;  // a one-pixel box until the band has been seen
  band.center = m.pixel;
  if (m.band.known() && z > 0.0) band = m.band.At(m.pixel, z);
  out.box.center = {band.center.x(), band.center.y()};
  out.box.box = band.Box();
  out.box.confidence = coasting ? std::pow(0.8, m.coast) : 0.0;
  return out;
}

std::vector<MarkerFrameResult> MarkerTracker::Step(const RgbdImage& image, double dt) {
  if (!first_frame_) PredictAll(dt);
  FieldPredict();
  const std::vector<Blob> blobs = detector_.Find(image, Windows());
  std::vector<Detection> detections;
  detections.reserve(blobs.size());
  for (const Blob& blob : blobs) {
    detections.push_back(MeasureBlob(blob, image, detector_, measure_options_));
  }
  const std::vector<int> assignment = Assign(detections);
  std::vector<MarkerFrameResult> results;
  results.reserve(markers_.size());
  for (size_t i = 0; i < markers_.size(); ++i) {
    results.push_back(assignment[i] >= 0 ? Measured(markers_[i], detections[assignment[i]])
                                         : Unmeasured(markers_[i]));
  }
  last_frame_had_color_ = !detections.empty() || detector_.AnyTapeColor(image.color, 2);
  first_frame_ = false;
  return results;
}

}  // namespace simtree::tracking::detail
