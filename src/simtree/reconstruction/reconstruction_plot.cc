#include "simtree/reconstruction/reconstruction_plot.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/mesh_io.h"

namespace simtree::reconstruction {
namespace {

const cv::Scalar kInk(30, 30, 30);

// Orthographic view: world (a, z) to pixels, a = x (front) or y (side).
struct View {
  int axis;  // 0: x, 1: y
  cv::Rect box;
  double a0, z0, scale;  // pixels per metre
  cv::Point2d At(const Eigen::Vector3d& p) const {
    return {box.x + (p[axis] - a0) * scale, box.y + box.height - (p.z() - z0) * scale};
  }
};

cv::Scalar LevelBgr(int level) {
  const Eigen::Vector3i rgb = LevelColour(level);
  return cv::Scalar(rgb.z(), rgb.y(), rgb.x());
}

void DrawView(cv::Mat& image, const View& view, const Tree& tree,
              std::span<const Eigen::Vector3d> points, double opacity, int point_size) {
  const int shift = 4;  // sub-pixel drawing
  const double one = 1 << shift;
  auto fixed = [&](const cv::Point2d& p) {
    return cv::Point(static_cast<int>(std::lround(p.x * one)),
                     static_cast<int>(std::lround(p.y * one)));
  };
  for (const Eigen::Vector3d& p : points) {
    const cv::Point2d q = view.At(p);
    if (point_size > 1) {
      cv::circle(image, q, point_size / 2, cv::Scalar(140, 140, 140), cv::FILLED);
    } else if (q.x >= 0 && q.y >= 0 && q.x < image.cols && q.y < image.rows) {
      image.at<cv::Vec3b>(static_cast<int>(q.y), static_cast<int>(q.x)) = cv::Vec3b(140, 140, 140);
    }
  }
  // Silhouettes on a layer blended over the points, so points inside the wood stay visible.
  cv::Mat layer = image.clone();
  for (const int id : tree.DepthFirstOrder()) {
    const Branch& b = tree.branches[id];
    const cv::Scalar colour = LevelBgr(b.level);
    for (size_t k = 0; k + 1 < b.nodes.size(); ++k) {
      const double r = 0.5 * (b.nodes[k].radius + b.nodes[k + 1].radius);
      const int width = std::max(1, static_cast<int>(std::lround(2 * r * view.scale)));
      cv::line(layer, fixed(view.At(b.nodes[k].position)), fixed(view.At(b.nodes[k + 1].position)),
               colour, width, cv::LINE_AA, shift);
    }
  }
  cv::addWeighted(layer, opacity, image, 1.0 - opacity, 0.0, image);
  for (const Branch& b : tree.branches) {
    for (size_t k = 0; k + 1 < b.nodes.size(); ++k) {
      cv::line(image, fixed(view.At(b.nodes[k].position)), fixed(view.At(b.nodes[k + 1].position)),
               kInk, 1, cv::LINE_AA, shift);
    }
  }
  cv::rectangle(image, view.box, cv::Scalar(210, 210, 210), 1);
  // A 50 cm scale bar.
  const cv::Point bar(view.box.x + 10, view.box.y + view.box.height - 10);
  cv::line(image, bar, bar + cv::Point(static_cast<int>(0.5 * view.scale), 0), kInk, 2);
  cv::putText(image, "0.5 m", bar + cv::Point(0, -6), cv::FONT_HERSHEY_SIMPLEX, 0.45, kInk, 1,
              cv::LINE_AA);
  cv::putText(image, view.axis == 0 ? "front (x-z)" : "side (y-z)",
              {view.box.x + 8, view.box.y + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kInk, 1,
              cv::LINE_AA);
}

}  // namespace

void ReconstructionPlotOptions::Validate() const {
  CheckAtLeast("height", height, 1);
  CheckShare("model_opacity", model_opacity);
  CheckAtLeast("point_size", point_size, 1);
}

void WriteReconstructionPlot(const Tree& tree, std::span<const Eigen::Vector3d> points,
                             const std::filesystem::path& path,
                             const ReconstructionPlotOptions& options) {
  options.Validate();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Eigen::Vector3d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (!tree.empty()) {
    Eigen::Vector3d tlo, thi;
    tree.Bounds(&tlo, &thi);
    lo = lo.cwiseMin(tlo);
    hi = hi.cwiseMax(thi);
  }
  if (!lo.allFinite()) lo = hi = Eigen::Vector3d::Zero();
  const Eigen::Vector3d size = (hi - lo).cwiseMax(Eigen::Vector3d::Constant(0.1));
  const int header = 40 + 20 * static_cast<int>(options.caption.size());
  const int margin = 12;
  const int panel_h = std::max(200, options.height - header - 2 * margin);
  const double scale = panel_h / size.z();
  const int front_w = static_cast<int>(std::ceil(size.x() * scale));
  const int side_w = static_cast<int>(std::ceil(size.y() * scale));
  const int width = std::max(front_w + side_w + 3 * margin, 640);
  cv::Mat image(header + panel_h + 2 * margin, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const View front{0, cv::Rect(margin, header + margin, front_w, panel_h), lo.x(), lo.z(), scale};
  const View side{1, cv::Rect(2 * margin + front_w, header + margin, side_w, panel_h), lo.y(),
                  lo.z(), scale};
  DrawView(image, front, tree, points, options.model_opacity, options.point_size);
  DrawView(image, side, tree, points, options.model_opacity, options.point_size);
  cv::putText(image, options.title, {margin, 26}, cv::FONT_HERSHEY_SIMPLEX, 0.65, kInk, 1,
              cv::LINE_AA);
  for (size_t k = 0; k < options.caption.size(); ++k) {
    cv::putText(image, options.caption[k], {margin, 50 + 20 * static_cast<int>(k)},
                cv::FONT_HERSHEY_SIMPLEX, 0.47, kInk, 1, cv::LINE_AA);
  }
  std::vector<uchar> bytes;
  if (!cv::imencode(".png", image, bytes)) {
    throw IoError(fmt::format("{}: could not encode the picture", path.string()));
  }
  WriteFileAtomically(path, std::string(bytes.begin(), bytes.end()));
}

}  // namespace simtree::reconstruction
