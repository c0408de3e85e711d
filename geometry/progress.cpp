#include "geometry/progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "geometry/interrupt.h"

namespace rockmass {

namespace {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// "12 s", "4.2 min", "1.3 h".
std::string duration(double seconds) {
  char text[32];
  if (seconds < 120.0) {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 7200.0) {
    std::snprintf(text, sizeof text, "%.1f min", seconds / 60.0);
  } else {
    std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  }
  return text;
}

}  // namespace

Progress::Progress(std::string label, double total, std::string unit, double interval, Sink sink,
                   Clock clock)
    : label_(std::move(label)),
      total_(std::max(total, 1e-300)),
      unit_(std::move(unit)),
      interval_(interval),
      sink_(sink ? std::move(sink) : Sink([](const std::string& line) {
        std::fprintf(stderr, "%s\n", line.c_str());
      })),
      clock_(clock ? std::move(clock) : Clock(steadySeconds)),
      start_(clock_()),
      last_time_(start_) {}

double Progress::elapsed() const {
  return clock_() - start_;
}

std::optional<double> Progress::remaining(double done) const {
  if (!(done > 0.0)) return std::nullopt;
  return elapsed() * std::max(0.0, total_ - done) / done;
}

std::string Progress::line(double done, const std::string& detail) const {
  char head[160];
  const double share = 100.0 * std::clamp(done / total_, 0.0, 1.0);
  if (unit_.empty()) {
    std::snprintf(head, sizeof head, "%s: %3.0f %%, %s", label_.c_str(), share,
                  duration(elapsed()).c_str());
  } else {
    std::snprintf(head, sizeof head, "%s: %3.0f %% (%.6g of %.6g %s), %s", label_.c_str(), share,
                  done, total_, unit_.c_str(), duration(elapsed()).c_str());
  }
  std::string out = head;
  if (const std::optional<double> left = remaining(done); left && done < total_) {
    out += ", about " + duration(*left) + " left";
  }
  if (!detail.empty()) out += ", " + detail;
  return out;
}

SharedProgress::SharedProgress(std::string label, std::string unit, double interval, double quiet,
                               Progress::Sink sink)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      interval_(interval),
      quiet_(quiet),
      sink_(std::move(sink)) {}

void SharedProgress::operator()(std::size_t done, std::size_t total) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!progress_) {
    progress_.emplace(label_, static_cast<double>(std::max<std::size_t>(total, 1)), unit_,
                      interval_, sink_);
    progress_->setQuietPeriod(quiet_);
  }
  progress_->update(static_cast<double>(done));
}

void Progress::update(double done, const std::string& detail) {
  if (safe_point_) throwIfInterrupted(label_);
  const int tenth = static_cast<int>(std::floor(10.0 * std::clamp(done / total_, 0.0, 1.0)));
  const double now = clock_();
  if (tenth <= last_tenth_ && now - last_time_ < interval_) return;
  last_tenth_ = std::max(last_tenth_, tenth);
  if (now - start_ < quiet_) return;
  last_time_ = now;
  sink_(line(done, detail));
}

}  // namespace rockmass
