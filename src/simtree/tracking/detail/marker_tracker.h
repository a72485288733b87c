#pragma once
// The multi-marker tracker, one frame at a time: predict each marker, detect blobs near the
// predictions, assign them (gated Hungarian), update, coast or lose, re-identify.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/capture.h"
#include "simtree/tracking/detail/band_model.h"
#include "simtree/tracking/detail/blob_detector.h"
#include "simtree/tracking/detail/detection.h"
#include "simtree/tracking/detail/motion_model.h"
#include "simtree/tracking/track.h"

namespace simtree::tracking::detail {

// One marker's output in one frame.
struct MarkerFrameResult {
  MarkerBox box;
  bool measured = false;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // when measured
};

class MarkerTracker {
 public:
  // `ids` and `pixels`: the markers and their pixels in the first frame tracked.
  MarkerTracker(const TrackOptions& options, const TapeColorModel& model,
                const CameraIntrinsics& intrinsics, std::vector<int> ids,
                std::vector<Eigen::Vector2d> pixels);

  // Tracks one frame `dt` seconds after the previous one (ignored on the first frame).
  std::vector<MarkerFrameResult> Step(const RgbdImage& image, double dt);
  // Whether the last frame had any tape colour at all (checked only when nothing was found).
  bool last_frame_had_color() const { return last_frame_had_color_; }

 private:
  struct Marker {
    int id = 0;
    bool started = false;  // has a 3D state (measured at least once)
    MarkerMotionModel motion;
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();       // last known or predicted pixel
    Eigen::Vector2d rest_pixel = Eigen::Vector2d::Zero();  // first measured pixel
    Eigen::Vector3d last_position = Eigen::Vector3d::Zero();
    BandModel band;               // the tape band's shape, for its box
    double typical_weight = 0.0;  // running tape weight when fully visible
    int coast = 0;                // frames since last measured
    // Where the rest of the tree puts it: its rest position moved as its nearest measured
    // neighbours moved (FieldPredict), projected; valid when `has_field`.
    bool has_field = false;
    Eigen::Vector2d field_pixel = Eigen::Vector2d::Zero();
    int age = 0;  // frames since start
  };

  void PredictAll(double dt);
  void FieldPredict();
  std::vector<SearchWindow> Windows() const;
  double Cost(const Marker& marker, const Detection& det) const;
  std::vector<int> Assign(const std::vector<Detection>& detections);
  bool OwnedByAnother(int marker, const Detection& det) const;
  void DropNeighbourFragments(const std::vector<Detection>& detections,
                              std::vector<int>* assignment) const;
  MarkerFrameResult Measured(Marker& marker, const Detection& det);
  MarkerFrameResult Unmeasured(Marker& marker);
  // The pixel thresholds are set at kReferenceFocalPx (track.h).
  double Scale() const { return intrinsics_.fx / kReferenceFocalPx; }

  TrackOptions options_;
  MotionModelParams motion_params_;
  MeasureOptions measure_options_;
  CameraIntrinsics intrinsics_;
  BlobDetector detector_;
  std::vector<Marker> markers_;
  bool first_frame_ = true;
  bool last_frame_had_color_ = true;
};

}  // namespace simtree::tracking::detail
