#include "simtree/synth/detail/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

constexpr int kLabelHeight = 22;
constexpr int kGap = 4;

cv::Mat ToMat(const RgbImage& image) {
  cv::Mat mat(image.height, image.width, CV_8UC3);
  for (int y = 0; y < image.height; ++y) {
    std::memcpy(mat.ptr<uint8_t>(y), &image.at(0, y), static_cast<size_t>(image.width) * 3);
  }
  return mat;
}

}  // namespace

RgbImage MakeContactSheet(const std::vector<ContactSheetTile>& tiles,
                          const ContactSheetOptions& options) {
  if (tiles.empty()) throw InputError("contact sheet", "", "expected at least one view");
  if (options.columns < 1 || !(options.scale > 0 && options.scale <= 4)) {
    throw InputError("contact sheet", "options", "expected columns >= 1 and 0 < scale <= 4");
  }
  int tile_w = 0, tile_h = 0;
  for (size_t i = 0; i < tiles.size(); ++i) {
    const ContactSheetTile& t = tiles[i];
    if (t.color.width != t.depth.width || t.color.height != t.depth.height || t.color.empty()) {
      throw InputError("contact sheet", t.label,
                       "expected a colour and a depth image of the same, non-zero size");
    }
    tile_w = std::max(tile_w, static_cast<int>(std::lround(t.color.width * options.scale)));
    tile_h = std::max(tile_h, static_cast<int>(std::lround(t.color.height * options.scale)));
  }
  const int cell_w = 2 * tile_w + kGap;
  const int cell_h = tile_h + kLabelHeight;
  const int columns = std::min<int>(options.columns, static_cast<int>(tiles.size()));
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  cv::Mat sheet(rows * (cell_h + kGap) + kGap, columns * (cell_w + kGap) + kGap, CV_8UC3,
                cv::Scalar(32, 32, 32));

  for (size_t i = 0; i < tiles.size(); ++i) {
    const int x0 = kGap + static_cast<int>(i % columns) * (cell_w + kGap);
    const int y0 = kGap + static_cast<int>(i / columns) * (cell_h + kGap);
    // Each image fitted into the tile, its shape kept (the pull stream's colour camera may differ
    // from the scans' shape).
    const double fit = std::min(static_cast<double>(tile_w) / tiles[i].color.width,
                                static_cast<double>(tile_h) / tiles[i].color.height);
    const cv::Size size(
        std::min(tile_w, static_cast<int>(std::lround(tiles[i].color.width * fit))),
        std::min(tile_h, static_cast<int>(std::lround(tiles[i].color.height * fit))));
    cv::Mat color, depth;
    cv::resize(ToMat(tiles[i].color), color, size, 0, 0, cv::INTER_AREA);
    // Nearest neighbour keeps "no measurement" black instead of smearing it into its neighbours.
    cv::resize(ToMat(ColorizeDepth(tiles[i].depth, options.depth)), depth, size, 0, 0,
               cv::INTER_NEAREST);
    color.copyTo(sheet(cv::Rect(x0, y0 + kLabelHeight, size.width, size.height)));
    depth.copyTo(sheet(cv::Rect(x0 + tile_w + kGap, y0 + kLabelHeight, size.width, size.height)));
    cv::putText(sheet, tiles[i].label, cv::Point(x0 + 2, y0 + kLabelHeight - 6),
                cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(235, 235, 235), 1, cv::LINE_AA);
  }

  RgbImage out(sheet.cols, sheet.rows);
  for (int y = 0; y < sheet.rows; ++y) {
    std::memcpy(&out.at(0, y), sheet.ptr<uint8_t>(y), static_cast<size_t>(sheet.cols) * 3);
  }
  return out;
}

}  // namespace simtree::synth
