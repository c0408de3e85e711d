#include "geometry/interrupt.h"

#include <atomic>

namespace rockmass {
namespace {

std::atomic<int> requested_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free flag");

}  // namespace

void requestInterrupt(int signal) noexcept {
  requested_signal.store(signal == 0 ? -1 : signal, std::memory_order_relaxed);
}

bool interruptRequested() noexcept {
  return requested_signal.load(std::memory_order_relaxed) != 0;
}

int interruptSignal() noexcept {
  return requested_signal.load(std::memory_order_relaxed);
}

void clearInterrupt() noexcept {
  requested_signal.store(0, std::memory_order_relaxed);
}

Interrupted::Interrupted(int signal, const std::string& where)
    : std::runtime_error("interrupted during " + where), signal_(signal), where_(where) {}

void throwIfInterrupted(const char* where) {
  if (interruptRequested()) throw Interrupted(interruptSignal(), where);
}

void throwIfInterrupted(const std::string& where) {
  if (interruptRequested()) throw Interrupted(interruptSignal(), where);
}

}  // namespace rockmass
