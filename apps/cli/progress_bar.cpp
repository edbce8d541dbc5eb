// Progress bar (progress_bar.h).
#include "progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common.h"

namespace interfere::cli {

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

ProgressBar::ProgressBar(std::string what, std::size_t total, std::string unit, int terminal)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(std::max<std::size_t>(total, 1)),
      terminal_(terminal < 0 ? ::isatty(::fileno(stderr)) == 1 : terminal == 1),
      enabled_(!Progress::quiet()),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && terminal_ && drawn_) std::fputc('\n', stderr);
}

std::string ProgressBar::line(std::size_t done, double seconds) const {
  done = std::min(done, total_);
  const double f = static_cast<double>(done) / static_cast<double>(total_);
  constexpr int kWidth = 24;
  const int filled = static_cast<int>(f * kWidth);
  std::string s = "[interfere] " + what_ + " [" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "] ";
  char buf[160];
  if (!unit_.empty()) {
    std::snprintf(buf, sizeof buf, "%zu/%zu", done, total_);
    s += buf;
  } else {
    std::snprintf(buf, sizeof buf, "%3d %%", static_cast<int>(f * 100));
    s += buf;
  }
  if (done > 0 && seconds > 0) {
    const double rate = static_cast<double>(done) / seconds;
    if (!unit_.empty()) {
      std::snprintf(buf, sizeof buf, rate >= 100 ? "  %.0f %s/s" : rate >= 10 ? "  %.1f %s/s" : "  %.3g %s/s", rate,
                    unit_.c_str());
      s += buf;
    }
    s += "  ETA " + clock_text(static_cast<double>(total_ - done) / rate);
  }
  return s;
}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (!enabled_) return;
  const std::lock_guard lock(mutex_);
  if (total > 0) total_ = total;
  if (done < shown_) return;
  shown_ = done;
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - start_).count();
  if (terminal_) {
    if (done < total_ && drawn_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    drawn_ = true;
    std::fprintf(stderr, "\r%s\x1b[K", line(done, seconds).c_str());  // (\x1b[K: clear the rest of the line)
    std::fflush(stderr);
    return;
  }
  const int tenth = static_cast<int>(10 * std::min(done, total_) / total_);
  if (tenth == last_tenth_) return;
  last_tenth_ = tenth;
  std::fprintf(stderr, "%s\n", line(done, seconds).c_str());
}

}  // namespace interfere::cli
