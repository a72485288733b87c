#pragma once
// Tape blobs near given image positions: connected components of tape-coloured pixels (8-
// connected), grown across search windows so a blob cut by a window's edge stays whole, fragments
// of one tape (a twig across it) merged when they lie within a few pixels at one depth, split
// where markers cross (two depth layers in one blob), each measured (detection.h).
//
// The detector keeps frame-sized scratch buffers between frames (reset by a frame stamp, not
// cleared), so one detector per stream makes a frame cost only the pixels searched.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/capture.h"
#include "simtree/tracking/detail/color_model.h"

namespace simtree::tracking::detail {

struct BlobDetectorOptions {
  int min_blob_pixels = 3;      // fewer tape pixels: not a detection
  int max_blob_pixels = 4000;   // a blob stops growing here (a red object, not a tape)
  double split_depth_m = 0.04;  // a depth gap this large inside a blob splits it
  int fragment_gap_px = 2;      // blobs this close at one depth are one tape (merged)
};

// A blob: its tape pixels (indices y * width + x) and the soft ring around them.
struct Blob {
  std::vector<int> pixels;
  std::vector<int> ring;  // 8-neighbours of `pixels` not in any blob (mixed tape/background)
  int source = 0;         // the blob it was split from (blobs of one source share it)
};

// A pixel at least this much tape (TapeColorModel::Weight) is clean: its depth is the tape's.
inline constexpr float kCleanWeight = 0.75f;

// Whether pixel (x, y) has a 4-neighbour without depth or more than `edge_units` away.
bool OnDepthEdge(const DepthImage& depth, int x, int y, double edge_units);

// A square search window, pixels [x0, x1) x [y0, y1).
struct SearchWindow {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
SearchWindow WindowAround(const Eigen::Vector2d& center, double half_size, int width, int height);

class BlobDetector {
 public:
  BlobDetector(const TapeColorModel& model, const BlobDetectorOptions& options);

  // The blobs with a tape pixel inside any of `windows`, split by depth. Call once per frame.
  std::vector<Blob> Find(const RgbdImage& image, const std::vector<SearchWindow>& windows);
  // Whether any pixel of the image (every `step`-th row and column) has the tape's colour.
  bool AnyTapeColor(const RgbImage& image, int step) const;

  const TapeColorModel& model() const { return model_; }
  // The soft weight of a pixel index in the last frame searched (computed on demand).
  float WeightAt(const RgbImage& image, int index);

 private:
  void Prepare(const RgbImage& image);
  bool IsTape(const RgbImage& image, int index);
  Blob Grow(const RgbImage& image, int seed);
  void MergeFragments(const DepthImage& depth, std::vector<Blob>* blobs) const;
  void SplitByDepth(const RgbImage& color, const DepthImage& depth, double depth_scale_m, Blob blob,
                    std::vector<Blob>* out);

  TapeColorModel model_;
  BlobDetectorOptions options_;
  int width_ = 0, height_ = 0;
  double depth_scale_m_ = 0.001;
  uint32_t stamp_ = 0;
  std::vector<uint32_t> tested_;   // == stamp_: tape test done this frame
  std::vector<uint8_t> is_tape_;   // its result
  std::vector<uint32_t> claimed_;  // == stamp_: pixel belongs to a blob this frame
  std::vector<uint32_t> weighed_;  // == stamp_: weight computed this frame
  std::vector<float> weight_;
};

}  // namespace simtree::tracking::detail
