#include "simtree/tracking/init_from_tree.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"
#include "simtree/tracking/detail/blob_detector.h"
#include "simtree/tracking/detail/color_model.h"
#include "simtree/tracking/detail/detection.h"
#include "simtree/tracking/detail/projection_match.h"
#include "simtree/tracking/detail/pull_input.h"
#include "simtree/tracking/track.h"

namespace simtree::tracking {
namespace {

// Nearer than this a marker's point is taken as behind the camera (no sensible projection).
constexpr double kMinDepthM = 0.05;

// Every tree marker projected into the frame, those markers.json lacks set apart.
std::vector<MarkerInit> ProjectMarkers(const Tree& tree, const PullStream& stream,
                                       const Eigen::Isometry3d& tree_from_camera) {
  const Eigen::Isometry3d camera_from_tree = tree_from_camera.inverse();
  std::set<int> listed;
  for (const MarkerLink& m : stream.markers) listed.insert(m.id);
  std::vector<MarkerInit> out;
  for (const Marker& marker : tree.markers) {
    MarkerInit m;
    m.id = marker.id;
    const Eigen::Vector3d p = camera_from_tree * marker.position;
    m.depth_m = p.z();
    if (stream.has_markers && !listed.contains(marker.id)) {
      m.status = MarkerInitStatus::kNotInMarkers;
    } else if (p.z() < kMinDepthM) {
      m.status = MarkerInitStatus::kBehindCamera;
    } else {
      m.projected = stream.intrinsics.Project(p);
      m.corrected = m.projected;
      m.status = MarkerInitStatus::kNoBlob;
    }
    out.push_back(m);
  }
  return out;
}

// How far the pose's error may move a projection at this depth (px).
double PoseGate(const InitFromTreeOptions& o, double fx, double depth_m, double scale) {
  return fx * std::tan(DegToRad(o.pose_rotation_deg)) + fx * o.pose_translation_m / depth_m +
         o.match_radius_px * scale;
}

// The tape colour fitted to tape near the projections (the prior when none is near).
detail::TapeColorModel ChooseModel(const std::string& color, const RgbImage& image,
                                   const std::vector<Eigen::Vector2d>& near, double radius) {
  const detail::TapeColorModel prior = detail::ColorModelFromName(color);
  return detail::FitColorModel(prior, image, near, static_cast<int>(std::ceil(radius)));
}

// The measured centres of every tape blob of the frame.
std::vector<Eigen::Vector2d> DetectTape(const RgbdImage& frame, const detail::TapeColorModel& model,
                                        int min_pixels) {
  detail::BlobDetector detector(model, detail::BlobDetectorOptions{.min_blob_pixels = min_pixels});
  const detail::SearchWindow all{0, 0, frame.color.width, frame.color.height};
  std::vector<Eigen::Vector2d> centres;
  for (const detail::Blob& blob : detector.Find(frame, {all})) {
    centres.push_back(detail::MeasureBlob(blob, frame, detector, {}).center);
  }
  return centres;
}

// The markers whose projection, grown by its pose gate, meets the image; the others are marked
// outside it.
struct Candidates {
  std::vector<size_t> index;  // into InitFromTreeResult::markers
  std::vector<Eigen::Vector2d> projections;
  std::vector<double> gates;
};

Candidates SelectCandidates(const InitFromTreeOptions& options, const CameraIntrinsics& k,
                            InitFromTreeResult* r) {
  const double scale = k.fx / kReferenceFocalPx;
  Candidates c;
  for (size_t i = 0; i < r->markers.size(); ++i) {
    MarkerInit& m = r->markers[i];
    if (m.status != MarkerInitStatus::kNoBlob) continue;
    const double gate = PoseGate(options, k.fx, m.depth_m, scale);
    if (m.projected.x() < -gate || m.projected.y() < -gate ||
        m.projected.x() > k.width - 1 + gate || m.projected.y() > k.height - 1 + gate) {
      m.status = MarkerInitStatus::kOutsideImage;
      continue;
    }
    c.index.push_back(i);
    c.projections.push_back(m.projected);
    c.gates.push_back(gate);
    r->gate_px = std::max(r->gate_px, gate);
  }
  return c;
}

// Each candidate's outcome: matched to its blob, kept at its corrected projection, or not.
void ApplyMatch(const detail::ProjectionMatch& match, const Candidates& candidates,
                const std::vector<Eigen::Vector2d>& blobs, const CameraIntrinsics& k,
                bool keep_unmatched, InitFromTreeResult* r) {
  r->match_radius_px = match.gate_px;
  r->shift_px = match.shift_px;
  r->rotation_deg = match.rotation_deg;
  r->scale = match.scale;
  for (const Eigen::Vector2d& b : blobs) {
    spdlog::debug("init from tree: a tape blob at ({:.1f}, {:.1f})", b.x(), b.y());
  }
  for (size_t c = 0; c < candidates.index.size(); ++c) {
    MarkerInit& m = r->markers[candidates.index[c]];
    m.corrected = match.corrected[c];
    spdlog::debug(
        "init from tree: marker {} projects to ({:.1f}, {:.1f}), gate {:.1f} px, "
        "corrected ({:.1f}, {:.1f}), blob {}",
        m.id, m.projected.x(), m.projected.y(), candidates.gates[c], m.corrected.x(),
        m.corrected.y(), match.blob[c]);
    if (match.blob[c] < 0) {
      if (!k.Contains(m.corrected.x(), m.corrected.y())) {
        m.status = MarkerInitStatus::kOutsideImage;
      } else if (keep_unmatched) {
        m.status = MarkerInitStatus::kProjected;
        m.pixel = m.corrected;
        r->init.markers.push_back(MarkerPixel{m.id, m.corrected});
      }
      continue;
    }
    m.status = MarkerInitStatus::kMatched;
    m.pixel = blobs[match.blob[c]];
    m.distance_px = match.distance_px[c];
    r->init.markers.push_back(MarkerPixel{m.id, *m.pixel});
  }
}

// A warning for every marker not matched, and the markers.json ids the tree lacks.
void ListProblems(const Tree& tree, const PullStream& stream, InitFromTreeResult* r) {
  std::set<int> in_tree;
  for (const Marker& m : tree.markers) in_tree.insert(m.id);
  for (const MarkerLink& m : stream.markers) {
    if (!in_tree.contains(m.id)) r->missing.push_back(m.id);
  }
  for (const MarkerInit& m : r->markers) {
    if (m.status != MarkerInitStatus::kMatched) {
      r->warnings.push_back(fmt::format(
          "marker {}{}: {}", m.id,
          m.status == MarkerInitStatus::kProjected ? "" : " not initialised", ToString(m.status)));
    }
  }
  if (!r->missing.empty()) {
    r->warnings.push_back(
        fmt::format("markers.json lists markers the tree lacks: {}", fmt::join(r->missing, ", ")));
  }
}

void CheckMatched(const InitFromTreeResult& r, const std::filesystem::path& first_frame) {
  for (const MarkerInit& m : r.markers) {
    if (m.status == MarkerInitStatus::kMatched) return;
  }
  int in_image = 0;
  for (const MarkerInit& m : r.markers) in_image += m.status == MarkerInitStatus::kNoBlob;
  throw InputError(
      first_frame.string(), "",
      fmt::format("no marker of the tree matched a tape blob ({} projected into the image, {} "
                  "blobs of {}): check that the pose belongs to this tree's frame and this "
                  "camera, --color, or pick the markers by hand (--pick)",
                  in_image, r.blobs, r.color_model));
}

}  // namespace

const char* ToString(MarkerInitStatus status) {
  switch (status) {
    case MarkerInitStatus::kMatched:
      return "matched";
    case MarkerInitStatus::kNotInMarkers:
      return "not in markers.json";
    case MarkerInitStatus::kBehindCamera:
      return "behind the camera";
    case MarkerInitStatus::kOutsideImage:
      return "outside the image";
    case MarkerInitStatus::kNoBlob:
      return "no tape blob in its gate";
    case MarkerInitStatus::kProjected:
      return "no tape blob in its gate; starts at its corrected projection";
  }
  return "?";
}

void InitFromTreeOptions::Validate() const {
  detail::ColorModelFromName(color);
  CheckInRange("pose_rotation_deg", pose_rotation_deg, 0.0, 30.0);
  CheckInRange("pose_translation_m", pose_translation_m, 0.0, 2.0);
  CheckInRange("match_radius_px", match_radius_px, 0.5, 100.0);
  CheckInRange("min_match_radius_px", min_match_radius_px, 0.5, match_radius_px);
  CheckAtLeast("min_blob_pixels", min_blob_pixels, 1);
}

InitFromTreeResult InitFromTree(const std::filesystem::path& pull_dir, const Tree& tree,
                                const Eigen::Isometry3d& tree_from_camera,
                                const InitFromTreeOptions& options,
                                const std::string& tree_source) {
  options.Validate();
  if (tree.markers.empty()) {
    throw InputError(tree_source, "markers",
                     "expected the tree's markers (each a 3D rest position) to project into the "
                     "pull stream, found none: give a tree that carries them (synth's "
                     "gt/tree.json, an earlier run's build/simready.json), or --init / --pick");
  }
  const PullStream stream = detail::OpenPullStream(pull_dir);
  const RgbdImage frame = LoadPullFrame(stream, 0);
  const CameraIntrinsics& k = stream.intrinsics;
  const double scale = k.fx / kReferenceFocalPx;

  InitFromTreeResult r;
  r.init.frame = stream.frames[0].frame;
  r.markers = ProjectMarkers(tree, stream, tree_from_camera);
  const Candidates candidates = SelectCandidates(options, k, &r);
  const detail::TapeColorModel model =
      ChooseModel(options.color, frame.color, candidates.projections, r.gate_px);
  r.color_model = model.Describe();
  const std::vector<Eigen::Vector2d> blobs = DetectTape(frame, model, options.min_blob_pixels);
  r.blobs = static_cast<int>(blobs.size());
  const detail::ProjectionMatch match =
      detail::MatchProjections(candidates.projections, candidates.gates, blobs,
                               detail::ProjectionMatchOptions{
                                   .match_radius_px = options.match_radius_px * scale,
                                   .min_match_radius_px = options.min_match_radius_px * scale,
                               });
  ApplyMatch(match, candidates, blobs, k, options.keep_unmatched, &r);
  ListProblems(tree, stream, &r);
  CheckMatched(r, stream.directory / stream.frames[0].color);
  return r;
}

}  // namespace simtree::tracking
