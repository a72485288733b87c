#pragma once
// An RGB-D recording in a layout other than Azure Kinect's .mkv (a TUM RGB-D sequence, an Open3D
// reconstruction-system folder, a RealSense .bag): frames with a time, colour and depth already
// registered to each other (same pixels), one pinhole camera. capture-from turns one into a scan
// view (its sharpest still frame) or the pull stream (io/capture_from_recordings.h).
//
//   const std::unique_ptr<RgbdSequence> seq = OpenTumRgbd("rgbd_dataset_freiburg1_xyz", tum);
//   for (size_t i = 0; i < seq->size(); ++i) {
//     const RgbdImage frame = seq->Load(i);  // depth in millimetres, sizes checked
//   }

#include <filesystem>
#include <string>
#include <vector>

#include "simtree/io/capture.h"

namespace simtree {

class RgbdSequence {
 public:
  virtual ~RgbdSequence() = default;
  // The file or folder read, for messages.
  virtual const std::string& source() const = 0;
  // capture.json's sensor: "tum_rgbd", "open3d_folder", "realsense_bag".
  virtual std::string sensor() const = 0;
  // The camera of every frame; depth_scale_m is 0.001 (frames are given in millimetres).
  virtual const CameraIntrinsics& intrinsics() const = 0;
  virtual size_t size() const = 0;
  // Seconds, increasing, on the recording's own clock.
  virtual double time_s(size_t index) const = 0;
  // Frame `index` with depth converted to millimetres; throws InputError naming the frame's files
  // when an image is missing, unreadable or of another size than the intrinsics.
  virtual RgbdImage Load(size_t index) const = 0;
  // Only the colour (scoring scan frames needs no depth).
  virtual RgbImage LoadColor(size_t index) const { return Load(index).color; }
};

// Depth in `units_per_m` units per metre (TUM 5000, Open3D and RealSense 1000) to millimetres,
// rounded; 0 stays 0 (no measurement) and a value beyond 65.535 m becomes 0, counted in
// `out_of_range`.
DepthImage DepthToMillimetres(const DepthImage& raw, double units_per_m, int* out_of_range);

// A sequence of colour and depth image files (TUM, Open3D folders).
struct RgbdFileFrame {
  double time_s = 0;
  std::filesystem::path color;
  std::filesystem::path depth;
};

class RgbdFileSequence : public RgbdSequence {
 public:
  RgbdFileSequence(std::string source, std::string sensor, const CameraIntrinsics& intrinsics,
                   double depth_units_per_m, std::vector<RgbdFileFrame> frames);
  const std::string& source() const override { return source_; }
  std::string sensor() const override { return sensor_; }
  const CameraIntrinsics& intrinsics() const override { return intrinsics_; }
  size_t size() const override { return frames_.size(); }
  double time_s(size_t index) const override { return frames_.at(index).time_s; }
  RgbdImage Load(size_t index) const override;
  RgbImage LoadColor(size_t index) const override;
  const std::vector<RgbdFileFrame>& frames() const { return frames_; }

 private:
  std::string source_;
  std::string sensor_;
  CameraIntrinsics intrinsics_;
  double depth_units_per_m_;
  std::vector<RgbdFileFrame> frames_;
};

}  // namespace simtree
