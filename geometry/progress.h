// Progress of a long stage (cutting, the RQD grid, DDA steps, factor runs): a line on stderr
// with the share done, the elapsed time and an estimate of what is left, at most once per
// interval and at each tenth of the work; each report is a safe point where an interruption
// (Ctrl-C, geometry/interrupt.h) stops the stage.
#pragma once

#include <cstddef>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

namespace rockmass {

class Progress {
 public:
  /// Seconds on a steady clock (tests pass their own).
  using Clock = std::function<double()>;
  /// Where the lines go (default: stderr, one line each).
  using Sink = std::function<void(const std::string&)>;

  /// `label` starts each line ("dda", "rqd: grid"); `total` is the work in `unit`s (> 0;
  /// unit "": a share, not counted in the line).
  Progress(std::string label, double total, std::string unit, double interval = 30.0,
           Sink sink = {}, Clock clock = {});

  /// Whether update() is a safe point (default). A stage whose own loop stops at a more
  /// telling safe point (the DDA: "the DDA at t = ... s") turns it off.
  void setSafePoint(bool on) { safe_point_ = on; }

  /// No line before `seconds` have passed (a stage that may be quick says nothing then).
  void setQuietPeriod(double seconds) { quiet_ = seconds; }

  /// Records `done` units of work (at most `total`); reports when a tenth more is done than
  /// at the last report or `interval` seconds have passed, with `detail` after the numbers.
  /// Throws Interrupted (at this safe point) when an interruption was requested (unless
  /// setSafePoint(false)).
  void update(double done, const std::string& detail = "");

  /// Seconds since construction.
  double elapsed() const;
  /// Linear estimate of the seconds left at `done` units (none before any work is done).
  std::optional<double> remaining(double done) const;
  /// "<label>: 40 % (4 of 10 <unit>), 12 s, about 18 s left[, <detail>]" (without the
  /// parenthesis when the unit is empty).
  std::string line(double done, const std::string& detail) const;

 private:
  std::string label_;
  double total_;
  std::string unit_;
  double interval_;
  Sink sink_;
  Clock clock_;
  double start_;
  double last_time_;
  int last_tenth_ = 0;
  bool safe_point_ = true;
  double quiet_ = 0.0;
};

/// A Progress for work whose total is known only when it starts, reported from several
/// threads (the cutters' regions, the RQD balls' scanlines): callbacks of the form
/// (done, total) call it; the Progress is made at the first call, and calls are serialized.
class SharedProgress {
 public:
  /// `quiet`: Progress::setQuietPeriod.
  SharedProgress(std::string label, std::string unit, double interval = 30.0, double quiet = 0.0,
                 Progress::Sink sink = {});
  /// Reports `done` of `total` units (Progress::update: a safe point, so it may throw
  /// Interrupted on the calling thread).
  void operator()(std::size_t done, std::size_t total);

 private:
  std::string label_;
  std::string unit_;
  double interval_;
  double quiet_;
  Progress::Sink sink_;
  std::mutex mutex_;
  std::optional<Progress> progress_;
};

}  // namespace rockmass
