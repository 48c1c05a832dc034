// Cancelling a run. round_edges() installs RoundOptions::cancelled for the calling thread (CancelScope);
// the passes' long loops call poll_cancel(), which throws RoundingError(ErrorCode::Cancelled) once the
// poll returns true. Without a poll a call costs a thread-local load and a branch; loops whose body is a
// handful of instructions poll only every n-th time (CancelPoll). Without a scope (a pass called on its
// own, as the unit tests do) nothing is polled.
#pragma once
#include <functional>

namespace meshround {

extern const char* const kCancelledMessage;  // "the rounding was cancelled"

namespace detail {
extern thread_local const std::function<bool()>* cancel_poll;
extern thread_local unsigned cancel_ticks;  // CancelPoll's count, shared by all (short calls add up)
[[noreturn]] void throw_cancelled();
}  // namespace detail

inline void poll_cancel() {
  const std::function<bool()>* poll = detail::cancel_poll;
  if (poll && (*poll)()) detail::throw_cancelled();
}

// Polls on about every `every`-th tick() (a power of two) only. The count is the thread's, not the
// object's: a short call made many times (a grid query) polls as often as one long loop.
class CancelPoll {
 public:
  explicit CancelPoll(unsigned every) : mask_(every - 1) {}
  void tick() const {
    if ((++detail::cancel_ticks & mask_) == 0) poll_cancel();
  }

 private:
  unsigned mask_;
};

// Installs `poll` (an empty one: none) as this thread's cancel poll for the scope's lifetime; nests.
class CancelScope {
 public:
  explicit CancelScope(const std::function<bool()>& poll) : outer_(detail::cancel_poll) {
    detail::cancel_poll = poll ? &poll : nullptr;
  }
  ~CancelScope() { detail::cancel_poll = outer_; }
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::function<bool()>* outer_;
};

}  // namespace meshround
