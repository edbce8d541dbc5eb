// A progress bar for long work (issue #30, item 5): on a terminal (stderr is a tty) one line
// rewritten in place, `[interfere] frames [#########...........] 45/100  12.3/s  ETA 0:04`, at most
// ten times a second; otherwise (a pipe, a log file) a plain line at every tenth of the work, so
// logs stay readable. Nothing with --quiet. Debian 12 packages no C++ progress-bar library (the
// `indicators` header library is not in it), so this small module is the project's own.
#pragma once
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace interfere::cli {

class ProgressBar {
 public:
  /// `what` names the work ("frames", "simplifying"), `total` its units (> 0), `unit` their name
  /// for the rate ("frames"; empty: the bar shows per cent and no rate). `terminal`: -1 asks
  /// isatty(stderr), 0/1 force the plain or the terminal form (tests).
  ProgressBar(std::string what, std::size_t total, std::string unit = "", int terminal = -1);
  ~ProgressBar();  ///< ends the terminal line
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// `done` of `total` units finished. Thread-safe (worker threads may report at once, in any
  /// order: a count below one already shown is ignored). `total` > 0 replaces the total given at
  /// construction (work whose size the library finds out: a scene's candidate pairs).
  void update(std::size_t done, std::size_t total = 0);

  /// A (done, count) callback for a library's progress option (e.g. SceneClashOptions::progress)
  /// that updates this bar; the bar must outlive the calls.
  std::function<void(std::size_t, std::size_t)> callback() {
    return [this](std::size_t done, std::size_t total) { update(done, total); };
  }

  /// The line shown for `done` units after `seconds` (no control characters): the bar, the count,
  /// the rate and the estimated time left.
  std::string line(std::size_t done, double seconds) const;

 private:
  std::string what_, unit_;
  std::size_t total_;
  bool terminal_, enabled_, drawn_ = false;
  int last_tenth_ = -1;
  std::size_t shown_ = 0;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

/// "0:04", "1:02:03": a duration for the ETA.
std::string clock_text(double seconds);

}  // namespace interfere::cli
