#pragma once
// Progress of long work: "stage  fraction  rate  eta" redrawn in place on a terminal, plain log
// lines (about every 10% or 5 s) otherwise. Thread-safe; Advance() is cheap enough for hot loops
// that report every few hundred items. Advance() is also where long work stops on Ctrl-C: on the
// thread that made the Progress it throws Interrupted once a stop was requested
// (core/interrupt.h); other threads' steps only count.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace simtree {

class Progress {
 public:
  // `total` units of work (0 when unknown); `unit` names them ("frames", "views").
  Progress(std::string stage, int64_t total, std::string unit = "items");
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Throws Interrupted (on the owning thread) when a stop was requested.
  void Advance(int64_t units = 1);
  // Ends the display with a final line (called by the destructor when forgotten).
  void Done();

  // Turns all progress display off or on (the CLI's --quiet, tests).
  static void SetEnabled(bool enabled);

 private:
  void Report(bool final);

  std::string stage_;
  int64_t total_;
  std::string unit_;
  std::atomic<int64_t> done_{0};
  std::thread::id owner_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_report_;
  int last_decile_ = -1;
  bool terminal_ = false;
  bool finished_ = false;
  std::mutex mutex_;
};

}  // namespace simtree
