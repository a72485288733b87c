#include "simtree/io/detail/capture_pairer.h"

#include <cstdlib>
#include <utility>

namespace simtree::azure_detail {

std::optional<AzureCapture> CapturePairer::Admit(int64_t aligned_us, bool taken) {
  std::optional<AzureCapture> closed;
  if (open_ && (taken || std::llabs(aligned_us - open_time_us_) > tolerance_us_)) {
    closed = std::move(open_);
    open_.reset();
  }
  if (!open_) {
    open_.emplace();
    open_->index = next_index_++;
    open_->timestamp_us = aligned_us;
    open_time_us_ = aligned_us;
  }
  return closed;
}

std::optional<AzureCapture> CapturePairer::AddColor(int64_t timestamp_us, RgbImage image) {
  std::optional<AzureCapture> closed = Admit(timestamp_us, open_ && open_->color.has_value());
  open_->color = std::move(image);
  open_->color_timestamp_us = timestamp_us;
  return closed;
}

std::optional<AzureCapture> CapturePairer::AddDepth(int64_t timestamp_us, DepthImage image) {
  std::optional<AzureCapture> closed =
      Admit(timestamp_us - depth_delay_us_, open_ && open_->depth.has_value());
  open_->depth = std::move(image);
  open_->depth_timestamp_us = timestamp_us;
  return closed;
}

std::optional<AzureCapture> CapturePairer::AddIr(int64_t timestamp_us, DepthImage image) {
  std::optional<AzureCapture> closed =
      Admit(timestamp_us - depth_delay_us_, open_ && open_->ir.has_value());
  open_->ir = std::move(image);
  return closed;
}

std::optional<AzureCapture> CapturePairer::Flush() {
  std::optional<AzureCapture> closed = std::move(open_);
  open_.reset();
  return closed;
}

}  // namespace simtree::azure_detail
