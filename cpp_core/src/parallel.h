// Work split over the machine's cores (private to cpp_core), with TBB -- which OCCT links already. The
// result is the one a single thread gets, bit for bit: parts write only their own outputs, reductions are
// deterministic, and of several parts that throw, the first in order is what the caller sees. Each part
// runs with the calling thread's cancel poll (cancel.h), so a cancel stops the parts too.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <array>
#include <exception>
#include <functional>
#include <tuple>
#include <utility>

#include "meshround/cancel.h"

namespace meshround {

namespace detail {
// Runs f with `poll` (the caller's) as this thread's cancel poll.
template <class F>
void with_poll(const std::function<bool()>* poll, F& f) {
  const std::function<bool()>* outer = cancel_poll;
  cancel_poll = poll;
  try {
    f();
  } catch (...) {
    cancel_poll = outer;
    throw;
  }
  cancel_poll = outer;
}
}  // namespace detail

namespace detail {
template <class Part>
void run_part(Part& part, std::exception_ptr& error, const std::function<bool()>* poll) {
  try {
    with_poll(poll, part);
  } catch (...) {
    error = std::current_exception();
  }
}

template <class Tuple, size_t... I>
void invoke_parts(Tuple& parts, std::array<std::exception_ptr, sizeof...(I)>& errors, std::index_sequence<I...>) {
  const std::function<bool()>* poll = cancel_poll;
  tbb::parallel_invoke([&] { run_part(std::get<I>(parts), errors[I], poll); }...);
}
}  // namespace detail

// Runs the parts (two or more callables) at the same time; returns when all are done.
template <class... Parts>
void in_parallel(Parts&&... parts) {
  std::tuple<Parts&...> all(parts...);
  std::array<std::exception_ptr, sizeof...(Parts)> errors;
  detail::invoke_parts(all, errors, std::index_sequence_for<Parts...>{});
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

// body(begin, end, T& partial) over [0, n) in chunks of about `grain`; join(T& into, const T& other) must be
// associative. The chunks and their joining order depend only on n and grain.
template <class T, class Body, class Join>
T reduce_ranges(int n, int grain, T identity, const Body& body, const Join& join) {
  const std::function<bool()>* poll = detail::cancel_poll;
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(0, n, grain), identity,
      [&](const tbb::blocked_range<int>& r, T partial) {
        auto run = [&] { body(r.begin(), r.end(), partial); };
        detail::with_poll(poll, run);
        return partial;
      },
      [&](T a, const T& b) {
        join(a, b);
        return a;
      },
      tbb::simple_partitioner());
}

}  // namespace meshround
