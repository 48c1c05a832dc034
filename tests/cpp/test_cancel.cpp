// Cancelling a run: RoundOptions::cancelled is polled often enough that a request from another thread
// stops round_edges within a fraction of a second, with ErrorCode::Cancelled, at any point of the run
// (the room probe's extra roundings included); a request made before the call is refused at once.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "meshround/round.h"
#include "support.h"

using namespace meshround;
using namespace meshround::test;

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// The poll's timeline in one run: how often it is called, the longest stretch without a call.
struct PollLog {
  Clock::time_point start = Clock::now(), last = start;
  long polls = 0;
  double longest_gap = 0;
  void poll() {
    const auto now = Clock::now();
    longest_gap = std::max(longest_gap, seconds(now - last));
    last = now, ++polls;
  }
  void finish() { longest_gap = std::max(longest_gap, seconds(Clock::now() - last)); }
};

struct Input {
  TriMesh mesh;
  Vec3 seed;
  double radius;
};

// A box whose 40 x 60 x 100 mm faces are meshed in elements of 0.5 mm (about 400k facets): every pass
// has long loops.
const Input& fine_box() {
  static const Input in{mesh_shape(BRepPrimAPI_MakeBox(100, 60, 40).Shape(), 0.5), Vec3(37, 60, 40), 5.0};
  return in;
}

// The acute ridge of test_room.py as a CAD mesh, r = 2: thin new facets start the room probe, which
// rounds the chain again at up to four wider reaches.
const Input& room_probe_ridge() {
  static const Input in = [] {
    BRepBuilderAPI_MakePolygon poly;
    for (auto [y, z] : {std::pair{0., 0.}, {60., 0.}, {60., 8.}, {3., 8.}, {25., 30.}, {0., 30.}}) poly.Add(gp_Pnt(0, y, z));
    poly.Close();
    const TopoDS_Shape solid = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(poly.Wire()).Face(), gp_Vec(60, 0, 0)).Shape();
    return Input{mesh_shape(solid, 0.0), Vec3(30, 25, 30), 2.0};
  }();
  return in;
}

// An uncancelled run with a poll that only watches: the longest time between two polls (or from the
// start to the first, or from the last to the end) bounds how long a request could wait.
PollLog watch_polls(const Input& in, RoundReport* report = nullptr) {
  PollLog log;
  RoundOptions opt;
  opt.radius = in.radius;
  opt.cancelled = [&log] { return log.poll(), false; };
  const RoundResult res = round_edges(in.mesh.V, in.mesh.F, {in.seed}, opt);
  log.finish();
  if (report) *report = res.report;
  return log;
}

// Cancels from another thread `after` seconds into the run; returns the seconds from the request to
// round_edges returning, which must be by a Cancelled error (-1: the run ended before the request).
double cancel_after(const Input& in, double after) {
  std::atomic<bool> flag{false};
  std::atomic<long> polls_after{0};
  std::atomic<long long> last_poll{0};  // Clock ticks of the latest poll
  RoundOptions opt;
  opt.radius = in.radius;
  opt.cancelled = [&] {
    const bool set = flag.load(std::memory_order_relaxed);
    if (set) ++polls_after;
    last_poll.store(Clock::now().time_since_epoch().count());
    return set;
  };
  Clock::time_point requested;
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::duration<double>(after));
    requested = Clock::now();
    flag.store(true);
  });
  bool cancelled = false;
  try {
    round_edges(in.mesh.V, in.mesh.F, {in.seed}, opt);
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::Cancelled) << e.what();
    EXPECT_STREQ(e.what(), "the rounding was cancelled");
    cancelled = e.code == ErrorCode::Cancelled;
  }
  const auto returned = Clock::now();
  canceller.join();
  // The run ended before the request, or the request came after its last poll (the run's tail, where no poll
  // is due: a run faster than the one timed, on a machine whose load dropped): nothing measured.
  if (!cancelled && (returned <= requested || requested.time_since_epoch().count() >= last_poll.load())) return -1;
  EXPECT_TRUE(cancelled) << "the run did not stop";
  // The first poll that sees the request stops the run; a pass that runs on several threads (parallel.h)
  // may have one poll in flight on each of them.
  EXPECT_GE(polls_after.load(), 1);
  EXPECT_LE(polls_after.load(), int(std::max(1u, std::thread::hardware_concurrency()))) << "polls went on after the request";
  return seconds(returned - requested);
}

}  // namespace

TEST(Cancel, RequestBeforeTheCallIsRefusedAtOnce) {
  const Input& in = fine_box();
  int polls = 0;
  RoundOptions opt;
  opt.radius = in.radius;
  opt.cancelled = [&] { return ++polls, true; };
  const auto start = Clock::now();
  try {
    round_edges(in.mesh.V, in.mesh.F, {in.seed}, opt);
    ADD_FAILURE() << "a cancelled run returned a result";
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::Cancelled);
  }
  EXPECT_EQ(polls, 1);
  EXPECT_LT(seconds(Clock::now() - start), 0.05);
}

TEST(Cancel, NoPollAndAPollThatNeverFiresGiveTheSameResult) {
  const Input& in = room_probe_ridge();
  RoundOptions opt;
  opt.radius = in.radius;
  const RoundResult plain = round_edges(in.mesh.V, in.mesh.F, {in.seed}, opt);
  opt.cancelled = [] { return false; };
  const RoundResult polled = round_edges(in.mesh.V, in.mesh.F, {in.seed}, opt);
  EXPECT_EQ(plain.vertices, polled.vertices);
  EXPECT_EQ(plain.triangles, polled.triangles);
}

// The longest stretch between polls is what a request can wait. On an idle core it is a few ms; the
// bound leaves room for a machine shared with other builds. Under ASan + UBSan (tools/sanitize.sh) every
// pass runs 3-6 times slower: the longest stretch on the 786k-facet mesh takes ~0.6-0.7 s there, so the
// bounds (a gap, and the 0.5 s a user may wait after pressing Esc) are scaled by kSlowdown.
#if defined(__SANITIZE_ADDRESS__)
constexpr double kSlowdown = 5;
#else
constexpr double kSlowdown = 1;
#endif
constexpr double kLongestPollGap = 0.3 * kSlowdown;
TEST(Cancel, PollsComeOftenThroughEveryPass) {
  for (const Input* in : {&fine_box(), &room_probe_ridge()}) {
    RoundReport report;
    const PollLog log = watch_polls(*in, &report);
    std::printf("[ cancel ] %ld facets: %ld polls in %.3f s, longest gap %.4f s; passes:", long(in->mesh.F.rows()), log.polls,
                report.seconds_total, log.longest_gap);
    for (const auto& [pass, s] : report.seconds) std::printf(" %s %.3f", pass.c_str(), s);
    std::printf("\n");
    EXPECT_GT(log.polls, 100);
    EXPECT_LT(log.longest_gap, kLongestPollGap);
  }
  RoundReport report;
  watch_polls(room_probe_ridge(), &report);
  EXPECT_GT(report.seconds.count("room"), 0u) << "the ridge is meant to start the room probe";
}

// Requests at several points of a long run, from another thread: each stops it at its next poll.
TEST(Cancel, RequestFromAnotherThreadStopsTheRunMidway) {
  for (const Input* in : {&fine_box(), &room_probe_ridge()}) {
    // The run's length: the fastest of three (on a loaded machine one slow run would put a request past
    // the end of the next).
    double full = INFINITY;
    for (int k = 0; k < 3; ++k) {
      const auto start = Clock::now();
      watch_polls(*in);
      full = std::min(full, seconds(Clock::now() - start));
    }
    for (double share : {0.1, 0.4, 0.7}) {
      // (On a loaded machine a run can still be faster than the fastest of three, and end before a late
      // request: that run is tried again.)
      double latency = -1;
      for (int attempt = 0; attempt < 5 && latency < 0; ++attempt) latency = cancel_after(*in, share * full);
      ASSERT_GE(latency, 0) << "five runs ended before the request at " << 100 * share << "% of the run";
      std::printf("[ cancel ] %ld facets, run of %.3f s cancelled at %.0f%%: stopped %.4f s after the request\n",
                  long(in->mesh.F.rows()), full, 100 * share, latency);
      EXPECT_LT(latency, 0.5 * kSlowdown);
    }
  }
}
