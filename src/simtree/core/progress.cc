#include "simtree/core/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "simtree/core/interrupt.h"

namespace simtree {
namespace {

std::atomic<bool> g_enabled{true};

std::string FormatSeconds(double s) {
  if (s < 60) return fmt::format("{:.0f} s", s);
  return fmt::format("{:.0f} min {:02.0f} s", s / 60 - 0.5, std::fmod(s, 60.0));
}

}  // namespace

Progress::Progress(std::string stage, int64_t total, std::string unit)
    : stage_(std::move(stage)),
      total_(total),
      unit_(std::move(unit)),
      owner_(std::this_thread::get_id()),
      start_(std::chrono::steady_clock::now()),
      last_report_(start_),
      terminal_(::isatty(STDERR_FILENO) != 0) {}

Progress::~Progress() { Done(); }

void Progress::SetEnabled(bool enabled) { g_enabled = enabled; }

void Progress::Advance(int64_t units) {
  done_ += units;
  if (std::this_thread::get_id() == owner_) ThrowIfInterrupted();
  if (!g_enabled) return;
  const auto now = std::chrono::steady_clock::now();
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || finished_) return;
  const double since = std::chrono::duration<double>(now - last_report_).count();
  const int decile = total_ > 0 ? static_cast<int>(10 * done_ / total_) : -1;
  const bool due = terminal_ ? since > 0.2 : (decile != last_decile_ || since > 5.0);
  if (!due) return;
  last_report_ = now;
  last_decile_ = decile;
  Report(false);
}

void Progress::Done() {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (g_enabled) Report(true);
}

void Progress::Report(bool final) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const int64_t done = done_;
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  std::string line = fmt::format("{}: {}", stage_, done);
  if (total_ > 0) {
    line += fmt::format("/{} {} ({:.0f}%)", total_, unit_, 100.0 * done / total_);
  } else {
    line += " " + unit_;
  }
  line += fmt::format(", {:.1f} {}/s", rate, unit_);
  if (final && InterruptRequested()) {
    line += fmt::format(", stopped after {}", FormatSeconds(elapsed));
  } else if (final) {
    line += fmt::format(", done in {}", FormatSeconds(elapsed));
  } else if (total_ > 0 && rate > 0) {
    line += fmt::format(", {} left", FormatSeconds((total_ - done) / rate));
  }
  if (terminal_) {
    std::fprintf(stderr, "\r\033[K%s%s", line.c_str(), final ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  std::fflush(stderr);
}

}  // namespace simtree
