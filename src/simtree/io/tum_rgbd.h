#pragma once
// TUM RGB-D sequences (the layout of vision.in.tum.de's RGB-D benchmark, also what many RGB-D
// tools export): a folder with rgb.txt and depth.txt ("timestamp filename" per line, '#'
// comments), rgb/*.png (8-bit colour) and depth/*.png (16-bit, `depth_factor` units per metre,
// 5000 in TUM's files), depth registered to the colour image. Colour and depth are paired by
// nearest timestamp within a tolerance. The files carry no intrinsics: the caller gives them
// (a file, or one of TUM's published cameras by name), never guessed.
//
//   TumRgbdOptions options;
//   options.intrinsics = TumCamera("tum-fr3");
//   const std::unique_ptr<RgbdSequence> seq = OpenTumRgbd("rgbd_dataset_freiburg3_...", options);

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simtree/io/rgbd_sequence.h"

namespace simtree {

struct TumRgbdOptions {
  std::optional<CameraIntrinsics> intrinsics;  // required
  double depth_factor = 5000;                  // depth units per metre
  double max_time_difference_s = 0.02;         // colour-depth pairing tolerance
  void Validate() const;
};

// One line of rgb.txt / depth.txt.
struct TumListEntry {
  double time_s = 0;
  std::filesystem::path file;  // resolved against the list's folder
};

// Reads a list; throws InputError naming the file and line for a malformed line, a time that
// does not increase, or a file that does not exist.
std::vector<TumListEntry> ReadTumList(const std::filesystem::path& path);

// TUM's published colour cameras at 640x480: "tum-fr1", "tum-fr2", "tum-fr3", "tum-default" (the
// ROS default the depth was registered with). fr1 and fr2 images keep their lens distortion,
// which simtree does not remove (a warning says so); fr3's were undistorted by TUM.
CameraIntrinsics TumCamera(const std::string& name);
std::vector<std::string> TumCameraNames();

// True when `folder` holds rgb.txt and depth.txt.
bool IsTumRgbdFolder(const std::filesystem::path& folder);

// The paired frames, times from rgb.txt. Throws InputError when the lists are bad, no pair is
// within the tolerance, or no intrinsics are given.
std::unique_ptr<RgbdSequence> OpenTumRgbd(const std::filesystem::path& folder,
                                          const TumRgbdOptions& options);

}  // namespace simtree
