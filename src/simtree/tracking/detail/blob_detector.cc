#include "simtree/tracking/detail/blob_detector.h"

#include <algorithm>
#include <cmath>

namespace simtree::tracking::detail {

bool OnDepthEdge(const DepthImage& depth, int x, int y, double edge_units) {
  const double d = depth.at(x, y);
  const int dx[4] = {1, -1, 0, 0};
  const int dy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int nx = x + dx[k], ny = y + dy[k];
    if (nx < 0 || ny < 0 || nx >= depth.width || ny >= depth.height) continue;
    const double n = depth.at(nx, ny);
    if (n == 0.0 || std::abs(n - d) > edge_units) return true;
  }
  return false;
}

SearchWindow WindowAround(const Eigen::Vector2d& center, double half_size, int width, int height) {
  SearchWindow w;
  w.x0 = std::clamp(static_cast<int>(std::floor(center.x() - half_size)), 0, width);
  w.y0 = std::clamp(static_cast<int>(std::floor(center.y() - half_size)), 0, height);
  w.x1 = std::clamp(static_cast<int>(std::ceil(center.x() + half_size)) + 1, 0, width);
  w.y1 = std::clamp(static_cast<int>(std::ceil(center.y() + half_size)) + 1, 0, height);
  return w;
}

BlobDetector::BlobDetector(const TapeColorModel& model, const BlobDetectorOptions& options)
    : model_(model), options_(options) {}

void BlobDetector::Prepare(const RgbImage& image) {
  if (image.width != width_ || image.height != height_) {
    width_ = image.width;
    height_ = image.height;
    const size_t n = image.pixel_count();
    tested_.assign(n, 0);
    is_tape_.assign(n, 0);
    claimed_.assign(n, 0);
    weighed_.assign(n, 0);
    weight_.assign(n, 0.0f);
    stamp_ = 0;
  }
  ++stamp_;
}

bool BlobDetector::IsTape(const RgbImage& image, int index) {
  if (tested_[index] != stamp_) {
    tested_[index] = stamp_;
    const uint8_t* p = &image.pixels[static_cast<size_t>(index) * 3];
    is_tape_[index] = model_.Contains(p[0], p[1], p[2]) ? 1 : 0;
  }
  return is_tape_[index] != 0;
}

float BlobDetector::WeightAt(const RgbImage& image, int index) {
  if (weighed_[index] != stamp_) {
    weighed_[index] = stamp_;
    const uint8_t* p = &image.pixels[static_cast<size_t>(index) * 3];
    weight_[index] = model_.Weight(p[0], p[1], p[2]);
  }
  return weight_[index];
}

Blob BlobDetector::Grow(const RgbImage& image, int seed) {
  Blob blob;
  claimed_[seed] = stamp_;
  blob.pixels.push_back(seed);
  for (size_t head = 0; head < blob.pixels.size(); ++head) {
    const int x = blob.pixels[head] % width_;
    const int y = blob.pixels[head] / width_;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
        const int n = ny * width_ + nx;
        if (claimed_[n] == stamp_ || !IsTape(image, n)) continue;
        if (static_cast<int>(blob.pixels.size()) >= options_.max_blob_pixels) continue;
        claimed_[n] = stamp_;
        blob.pixels.push_back(n);
      }
    }
  }
  return blob;
}

void BlobDetector::SplitByDepth(const RgbImage& color, const DepthImage& depth,
                                double depth_scale_m, Blob blob, std::vector<Blob>* out) {
  // Depths of the blob's clean tape pixels: a pixel that mixes the tape with what is behind it
  // (weaker colour) may carry the background's depth, so it takes no part in finding the layers.
  const double edge_units = options_.split_depth_m / depth_scale_m;
  std::vector<char> clean(blob.pixels.size(), 0);
  std::vector<uint16_t> values;
  values.reserve(blob.pixels.size());
  for (size_t k = 0; k < blob.pixels.size(); ++k) {
    const int i = blob.pixels[k];
    clean[k] = depth.pixels[i] != 0 && WeightAt(color, i) >= kCleanWeight;
    if (clean[k]) values.push_back(depth.pixels[i]);
  }
  std::sort(values.begin(), values.end());
  // The widest gap between consecutive depths, each layer keeping a fifth of the pixels.
  const int keep = std::max(options_.min_blob_pixels,
                            static_cast<int>(std::ceil(0.2 * static_cast<double>(values.size()))));
  double best_gap = 0.0;
  double threshold = 0.0;
  for (int k = keep; k + keep <= static_cast<int>(values.size()); ++k) {
    const double gap = values[k] - values[k - 1];
    if (gap > best_gap) {
      best_gap = gap;
      threshold = 0.5 * (values[k] + values[k - 1]);
    }
  }
  if (best_gap < edge_units) {
    out->push_back(std::move(blob));
    return;
  }
  Blob near, far;
  std::vector<int> unknown;
  Eigen::Vector2d near_sum = Eigen::Vector2d::Zero(), far_sum = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < blob.pixels.size(); ++k) {
    const int i = blob.pixels[k];
    const Eigen::Vector2d p(i % depth.width, i / depth.width);
    if (!clean[k]) {
      unknown.push_back(i);
    } else if (depth.pixels[i] < threshold) {
      near.pixels.push_back(i);
      near_sum += p;
    } else {
      far.pixels.push_back(i);
      far_sum += p;
    }
  }
  // Pixels without a clean depth join the layer whose centre is nearer in the image.
  const Eigen::Vector2d near_c = near_sum / static_cast<double>(near.pixels.size());
  const Eigen::Vector2d far_c = far_sum / static_cast<double>(far.pixels.size());
  for (int i : unknown) {
    const Eigen::Vector2d p(i % depth.width, i / depth.width);
    ((p - near_c).squaredNorm() <= (p - far_c).squaredNorm() ? near : far).pixels.push_back(i);
  }
  near.source = far.source = blob.source;
  out->push_back(std::move(near));
  out->push_back(std::move(far));
}

void BlobDetector::MergeFragments(const DepthImage& depth, std::vector<Blob>* blobs) const {
  // Bounding boxes and median depths of the blobs.
  struct Extent {
    int x0, y0, x1, y1;
    double depth;
  };
  std::vector<Extent> ext;
  for (const Blob& b : *blobs) {
    Extent e{width_, height_, -1, -1, 0.0};
    std::vector<uint16_t> d;
    for (int i : b.pixels) {
      e.x0 = std::min(e.x0, i % width_);
      e.x1 = std::max(e.x1, i % width_);
      e.y0 = std::min(e.y0, i / width_);
      e.y1 = std::max(e.y1, i / width_);
      if (depth.pixels[i] != 0) d.push_back(depth.pixels[i]);
    }
    if (!d.empty()) {
      std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
      e.depth = d[d.size() / 2];
    }
    ext.push_back(e);
  }
  const int gap = options_.fragment_gap_px;
  const double same_depth = options_.split_depth_m;
  for (size_t a = 0; a < blobs->size(); ++a) {
    for (size_t b = a + 1; b < blobs->size(); ++b) {
      if ((*blobs)[b].pixels.empty() || (*blobs)[a].pixels.empty()) continue;
      const Extent& p = ext[a];
      const Extent& q = ext[b];
      const bool near =
          p.x0 - gap <= q.x1 && q.x0 - gap <= p.x1 && p.y0 - gap <= q.y1 && q.y0 - gap <= p.y1;
      const bool same = p.depth == 0.0 || q.depth == 0.0 ||
                        std::abs(p.depth - q.depth) * depth_scale_m_ < same_depth;
      if (!near || !same) continue;
      // b is a fragment of the same tape (a twig across it): a takes its pixels.
      auto& pa = (*blobs)[a].pixels;
      pa.insert(pa.end(), (*blobs)[b].pixels.begin(), (*blobs)[b].pixels.end());
      (*blobs)[b].pixels.clear();
      ext[a] = Extent{std::min(p.x0, q.x0), std::min(p.y0, q.y0), std::max(p.x1, q.x1),
                      std::max(p.y1, q.y1), p.depth != 0.0 ? p.depth : q.depth};
      b = a;  // look again from a: its box grew
    }
  }
  blobs->erase(
      std::remove_if(blobs->begin(), blobs->end(), [](const Blob& b) { return b.pixels.empty(); }),
      blobs->end());
}

std::vector<Blob> BlobDetector::Find(const RgbdImage& image,
                                     const std::vector<SearchWindow>& windows) {
  Prepare(image.color);
  depth_scale_m_ = image.intrinsics.depth_scale_m;
  std::vector<Blob> grown;
  for (const SearchWindow& w : windows) {
    for (int y = w.y0; y < w.y1; ++y) {
      for (int x = w.x0; x < w.x1; ++x) {
        const int i = y * width_ + x;
        if (claimed_[i] == stamp_ || !IsTape(image.color, i)) continue;
        grown.push_back(Grow(image.color, i));
      }
    }
  }
  MergeFragments(image.depth, &grown);
  std::vector<Blob> blobs;
  for (size_t g = 0; g < grown.size(); ++g) {
    Blob& blob = grown[g];
    if (static_cast<int>(blob.pixels.size()) < options_.min_blob_pixels) continue;
    blob.source = static_cast<int>(g);
    SplitByDepth(image.color, image.depth, image.intrinsics.depth_scale_m, std::move(blob), &blobs);
  }
  // The soft ring: background neighbours that may hold part of the tape.
  for (Blob& blob : blobs) {
    for (int i : blob.pixels) {
      const int x = i % width_, y = i / width_;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
          const int n = ny * width_ + nx;
          if (claimed_[n] == stamp_) continue;
          claimed_[n] = stamp_;  // each ring pixel belongs to one blob
          blob.ring.push_back(n);
        }
      }
    }
  }
  return blobs;
}

bool BlobDetector::AnyTapeColor(const RgbImage& image, int step) const {
  for (int y = 0; y < image.height; y += step) {
    for (int x = 0; x < image.width; x += step) {
      if (model_.Contains(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2))) return true;
    }
  }
  return false;
}

}  // namespace simtree::tracking::detail
