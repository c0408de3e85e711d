#pragma once
/// Interruption (Ctrl-C): the program's signal handler requests it; long loops stop at their
/// next safe point by calling throwIfInterrupted, which throws Interrupted. A safe point is a
/// place where stopping leaves nothing half-made that could be mistaken for a result (every
/// output is written atomically, io/atomic_file.h).
#include <stdexcept>
#include <string>

namespace rockmass {

/// Records that `signal` asked the program to stop. Async-signal-safe (a lock-free atomic).
void requestInterrupt(int signal) noexcept;

/// True once requestInterrupt was called.
bool interruptRequested() noexcept;

/// The signal passed to requestInterrupt (0 when none).
int interruptSignal() noexcept;

/// Clears the request (tests).
void clearInterrupt() noexcept;

/// Thrown at a safe point after an interruption was requested.
class Interrupted : public std::runtime_error {
 public:
  Interrupted(int signal, const std::string& where);
  int signal() const { return signal_; }
  const std::string& where() const { return where_; }

 private:
  int signal_;
  std::string where_;
};

/// Throws Interrupted naming `where` (e.g. "the DDA, step 120 at t = 0.24 s") when an
/// interruption was requested; otherwise returns at once (one relaxed atomic load).
void throwIfInterrupted(const char* where);
void throwIfInterrupted(const std::string& where);

}  // namespace rockmass
