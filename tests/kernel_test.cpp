#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "endatsim/sim/sim.hpp"

using namespace endatsim::sim;

namespace {

struct Log {
  Kernel* k = nullptr;
  std::vector<std::pair<std::int64_t, std::uint64_t>> entries;
  void record(std::uint64_t tag) { entries.emplace_back(k->now().count(), tag); }
};

}  // namespace

TEST(KernelOrder, RunsEventsByTimeThenInsertionOrder) {
  Kernel k;
  Log log{&k, {}};
  k.schedule(ns(20), bind<&Log::record>(&log, 1));
  k.schedule(ns(10), bind<&Log::record>(&log, 2));
  k.schedule(ns(20), bind<&Log::record>(&log, 3));
  k.schedule(ns(10), bind<&Log::record>(&log, 4));
  k.run();
  const std::vector<std::pair<std::int64_t, std::uint64_t>> expected{
      {10'000, 2}, {10'000, 4}, {20'000, 1}, {20'000, 3}};
  EXPECT_EQ(log.entries, expected);
  EXPECT_EQ(k.events_processed(), 4U);
}

namespace {
struct ZeroDelay {
  Kernel* k;
  Log* log;
  void first() {
    log->record(1);
    k->schedule(Time::zero(), bind<&Log::record>(log, 3));
  }
};
}  // namespace

TEST(KernelOrder, ZeroDelayWakeUpsRunInTheNextDeltaAfterTheTimeStep) {
  Kernel k;
  Log log{&k, {}};
  ZeroDelay z{&k, &log};
  k.schedule(ns(5), bind<&ZeroDelay::first>(&z));
  k.schedule(ns(5), bind<&Log::record>(&log, 2));
  k.run();
  ASSERT_EQ(log.entries.size(), 3U);
  EXPECT_EQ(log.entries[0].second, 1U);
  EXPECT_EQ(log.entries[1].second, 2U);
  EXPECT_EQ(log.entries[2].second, 3U);
  EXPECT_EQ(log.entries[2].first, 5'000);
}

namespace {
// Each wake-up of generation g < 3 queues two of generation g + 1: 100, 200, 400 and 800 wake-ups in
// four delta cycles, so the ring of zero-delay wake-ups wraps and grows while one is running.
struct FanOut {
  Kernel* k;
  std::vector<std::uint64_t> ran;
  std::uint64_t next_tag[4] = {0, 0, 0, 0};
  void wake(std::uint64_t tag) {
    ran.push_back(tag);
    const std::uint64_t g = tag / 10'000;
    if (g == 3) return;
    for (int i = 0; i < 2; ++i) k->schedule(Time::zero(), bind<&FanOut::wake>(this, (g + 1) * 10'000 + next_tag[g + 1]++));
  }
};
}  // namespace

TEST(KernelOrder, ZeroDelayWakeUpsKeepTheirDeltaAndOrderWhileTheirRingWrapsAndGrows) {
  Kernel k;
  FanOut f{&k, {}};
  for (std::uint64_t i = 0; i < 100; ++i) k.schedule(Time::zero(), bind<&FanOut::wake>(&f, i));
  f.next_tag[0] = 100;
  k.run();
  std::vector<std::uint64_t> expected;
  for (std::uint64_t g = 0, n = 100; g < 4; ++g, n *= 2)
    for (std::uint64_t i = 0; i < n; ++i) expected.push_back(g * 10'000 + i);
  EXPECT_EQ(f.ran, expected);
  EXPECT_EQ(k.events_processed(), 1'500U);
}

TEST(KernelDelay, ZeroDelayLinesInSeriesPassAChangeOnOneDeltaEach) {
  Kernel k;
  Signal a(k, "a", false), b(k, "b", false), c(k, "c", false);
  TransportDelay ab(k, a, b, Time::zero()), bc(k, b, c, Time::zero());
  std::vector<std::string> seen;
  struct Watch {
    std::vector<std::string>* seen;
    const char* name;
    void on(std::uint64_t v) { seen->push_back(std::string(name) + (v != 0 ? "1" : "0")); }
  } wa{&seen, "a"}, wb{&seen, "b"}, wc{&seen, "c"};
  a.on_change(bind<&Watch::on>(&wa));
  b.on_change(bind<&Watch::on>(&wb));
  c.on_change(bind<&Watch::on>(&wc));
  struct Drive {
    Signal* a;
    Signal* c;
    void at() {
      a->write(true);
      c->write(true);  // c changes in the first delta, then follows a two deltas later: no change
    }
  } d{&a, &c};
  k.schedule(ns(1), bind<&Drive::at>(&d));
  k.run();
  EXPECT_EQ(seen, (std::vector<std::string>{"a1", "c1", "b1"}));
  EXPECT_EQ(k.now(), ns(1));
  EXPECT_TRUE(b.read());
  EXPECT_TRUE(c.read());
}

TEST(KernelRun, StopsAtTheGivenTimeAndResumes) {
  Kernel k;
  Log log{&k, {}};
  k.schedule(us(1), bind<&Log::record>(&log, 1));
  k.schedule(us(3), bind<&Log::record>(&log, 2));
  k.run(us(2));
  EXPECT_EQ(log.entries.size(), 1U);
  EXPECT_EQ(k.now(), us(2));
  k.run();
  EXPECT_EQ(log.entries.size(), 2U);
  EXPECT_EQ(k.now(), us(3));
}

TEST(KernelRun, RejectsNegativeDelays) {
  Kernel k;
  Log log{&k, {}};
  EXPECT_THROW(k.schedule(ps(-1), bind<&Log::record>(&log, 0)), std::logic_error);
  Timer timer(k, bind<&Log::record>(&log, 1));
  EXPECT_THROW(timer.start(ps(-1)), std::logic_error);
  EXPECT_FALSE(timer.pending());
  k.run();
  EXPECT_TRUE(log.entries.empty());
}

TEST(KernelRun, RejectsAnEventAfterTheLatestTime) {
  Kernel k;
  Log log{&k, {}};
  Timer timer(k, bind<&Log::record>(&log, 2));
  k.schedule(ns(1), bind<&Log::record>(&log, 1));
  k.run();
  ASSERT_EQ(k.now(), ns(1));
  // now + delay would overflow the picosecond count.
  EXPECT_THROW(k.schedule(Time::max(), bind<&Log::record>(&log, 0)), std::logic_error);
  EXPECT_THROW(timer.start(Time::max() - ns(1) + ps(1)), std::logic_error);
  // Up to Time::max() itself is taken.
  EXPECT_NO_THROW(k.schedule(Time::max() - ns(1), bind<&Log::record>(&log, 3)));
  EXPECT_NO_THROW(timer.start(Time::max() - ns(1)));
  EXPECT_EQ(k.next_event_time(), Time::max());
}

TEST(KernelTimer, CancelledTimerDoesNotFire) {
  Kernel k;
  Log log{&k, {}};
  Timer t(k, bind<&Log::record>(&log, 7));
  t.start(ns(10));
  EXPECT_TRUE(t.pending());
  t.cancel();
  k.run();
  EXPECT_TRUE(log.entries.empty());
  EXPECT_FALSE(t.pending());
}

TEST(KernelTimer, RestartReplacesThePendingExpiry) {
  Kernel k;
  Log log{&k, {}};
  Timer t(k, bind<&Log::record>(&log, 7));
  t.start(ns(10));
  t.start(ns(30));
  EXPECT_EQ(t.expiry(), ns(30));
  k.run();
  ASSERT_EQ(log.entries.size(), 1U);
  EXPECT_EQ(log.entries[0].first, 30'000);
}

namespace {
struct Writer {
  Signal* s;
  void high() { s->write(true); }
  void pulse() {
    s->write(true);
    s->write(false);
  }
};
struct Listener {
  Kernel* k;
  std::vector<std::pair<std::int64_t, std::uint64_t>> seen;
  void on(std::uint64_t v) { seen.emplace_back(k->now().count(), v); }
};
}  // namespace

TEST(KernelSignal, WriteTakesEffectInTheUpdatePhase) {
  Kernel k;
  Signal s(k, "s", false);
  Listener l{&k, {}};
  s.on_change(bind<&Listener::on>(&l));
  Writer w{&s};
  k.schedule(ns(1), bind<&Writer::high>(&w));
  k.run();
  EXPECT_TRUE(s.read());
  EXPECT_EQ(s.last_change(), ns(1));
  ASSERT_EQ(l.seen.size(), 1U);
  EXPECT_EQ(l.seen[0], (std::pair<std::int64_t, std::uint64_t>{1'000, 1}));
}

TEST(KernelSignal, WritesThatCancelInOnePhaseAreNoChange) {
  Kernel k;
  Signal s(k, "s", false);
  Listener l{&k, {}};
  s.on_change(bind<&Listener::on>(&l));
  Writer w{&s};
  k.schedule(ns(1), bind<&Writer::pulse>(&w));
  k.run();
  EXPECT_FALSE(s.read());
  EXPECT_TRUE(l.seen.empty());
  EXPECT_EQ(s.changes(), 0U);
}

TEST(KernelDelay, TransportDelayKeepsEveryEdgeExactToThePicosecond) {
  Kernel k;
  Signal in(k, "in", false);
  Signal out(k, "out", false);
  TransportDelay d(k, in, out, ps(1234), ps(987));
  Listener l{&k, {}};
  out.on_change(bind<&Listener::on>(&l));
  Writer w{&in};
  struct Low {
    Signal* s;
    void low() { s->write(false); }
  } low{&in};
  k.schedule(ns(10), bind<&Writer::high>(&w));
  k.schedule(ns(11), bind<&Low::low>(&low));
  k.run();
  ASSERT_EQ(l.seen.size(), 2U);
  EXPECT_EQ(l.seen[0], (std::pair<std::int64_t, std::uint64_t>{11'234, 1}));
  EXPECT_EQ(l.seen[1], (std::pair<std::int64_t, std::uint64_t>{11'987, 0}));
}

namespace {
struct BothHigh {
  Signal* a;
  Signal* b;
  void go() {
    a->write(true);
    b->write(true);
  }
};
struct ReadsOther {
  Signal* other;
  bool seen = false;
  void on(std::uint64_t) { seen = other->read(); }
};
}  // namespace

TEST(KernelSignal, ListenersSeeEverySignalOfTheUpdatePhaseCommitted) {
  Kernel k;
  Signal a(k, "a", false);
  Signal b(k, "b", false);
  ReadsOther l{&b};
  a.on_change(bind<&ReadsOther::on>(&l));  // a is committed before b, yet the listener sees b's new value
  BothHigh w{&a, &b};
  k.schedule(ns(1), bind<&BothHigh::go>(&w));
  k.run();
  EXPECT_TRUE(l.seen);
}

// An outside simulator owns time in a co-simulation: it moves the kernel to each of its own
// instants, writes pins there, and asks when the kernel next needs to be woken.
TEST(KernelAdvance, AdvanceToRunsEventsUpToAndIncludingTheInstantAndStaysThere) {
  Kernel k;
  Log log{&k, {}};
  k.schedule(ns(10), bind<&Log::record>(&log, 1));
  k.schedule(ns(30), bind<&Log::record>(&log, 2));
  EXPECT_EQ(k.next_event_time(), ns(10));
  k.advance_to(ns(10));
  EXPECT_EQ(k.now(), ns(10));
  EXPECT_EQ(log.entries.size(), 1U);
  k.advance_to(ns(25));  // nothing due: time moves anyway
  EXPECT_EQ(k.now(), ns(25));
  EXPECT_EQ(k.next_event_time(), ns(30));
  k.advance_to(ns(40));
  EXPECT_EQ(log.entries.size(), 2U);
  EXPECT_FALSE(k.next_event_time().has_value());
  k.advance_to(ms(1));  // an empty kernel follows as well
  EXPECT_EQ(k.now(), ms(1));
  EXPECT_THROW(k.advance_to(ns(1)), std::logic_error);
}

TEST(KernelAdvance, AWriteAtTheCurrentInstantSettlesThereAndItsListenersRun) {
  Kernel k;
  Signal in(k, "in", false), out(k, "out", false);
  TransportDelay d(k, in, out, ns(7));
  k.advance_to(ns(100));
  in.write(true);
  EXPECT_TRUE(k.work_pending());
  k.advance_to(ns(100));  // the same instant: the write commits, the delay schedules its edge
  EXPECT_FALSE(k.work_pending());
  EXPECT_TRUE(in.read());
  EXPECT_EQ(k.next_event_time(), ns(107));
  k.advance_to(ns(106));
  EXPECT_FALSE(out.read());
  k.advance_to(ns(107));
  EXPECT_TRUE(out.read());
  EXPECT_EQ(out.last_change(), ns(107));
}

// ---- Work queued outside the heap keeps the order a schedule() at decision time gives ----

using Entries = std::vector<std::pair<std::int64_t, std::uint64_t>>;  // (ps, tag) as Log records them

TEST(KernelOrder, ScheduleOrderedRunsInTheOrderOfItsTakenSequence) {
  Kernel k;
  Log log{&k, {}};
  const std::uint64_t early = k.take_seq();         // decided first, queued last
  k.schedule(ns(10), bind<&Log::record>(&log, 2));  // decided second
  k.schedule_ordered(ns(10), early, bind<&Log::record>(&log, 1));
  k.run();
  const Entries expected{{10'000, 1}, {10'000, 2}};
  EXPECT_EQ(log.entries, expected);
  EXPECT_THROW(k.schedule_ordered(ns(5), k.take_seq(), bind<&Log::record>(&log, 3)), std::logic_error);
}

namespace {
// A timer restarted on every step, like a watchdog on every clock edge, beside a plain event
// at its final expiry: which runs first says which order the timer's entry carries.
struct Watchdog {
  Kernel* k;
  Log* log;
  Timer* timer;
  int restarts = 0;
  void step() {
    timer->start(ns(100));
    if (++restarts == 3) k->schedule(ns(120), bind<&Log::record>(log, 2));  // due at 140 ns
    if (restarts < 5) k->schedule(ns(10), bind<&Watchdog::step>(this));
  }
};
}  // namespace

TEST(KernelTimer, ARestartedTimerFiresInTheOrderOfItsLastRestart) {
  Kernel k;
  Log log{&k, {}};
  Timer t(k, bind<&Log::record>(&log, 1));
  Watchdog w{&k, &log, &t};
  // The timer's last restart (at 40 ns, due at 140 ns) came after the plain event due at the
  // same instant was decided (at 20 ns): the plain event runs first...
  k.schedule(Time::zero(), bind<&Watchdog::step>(&w));
  k.run();
  const Entries expected{{140'000, 2}, {140'000, 1}};
  EXPECT_EQ(log.entries, expected);
  // ... and one restart to the same expiry after the plain event was decided fires after it.
  Log same{&k, {}};
  Timer u(k, bind<&Log::record>(&same, 1));
  u.start(ns(50));
  k.schedule(ns(50), bind<&Log::record>(&same, 2));
  u.cancel();
  u.start(ns(50));
  k.run();
  const Entries after{{190'000, 2}, {190'000, 1}};
  EXPECT_EQ(same.entries, after);
}

TEST(KernelTimer, ARestartToAnEarlierExpiryFiresThereOnce) {
  Kernel k;
  Log log{&k, {}};
  Timer t(k, bind<&Log::record>(&log, 7));
  t.start(ns(100));
  t.start(ns(10));
  k.run();
  const Entries expected{{10'000, 7}};
  EXPECT_EQ(log.entries, expected);
}

TEST(KernelDelay, AFasterFallOvertakesAnEarlierRiseAndEveryChangeArrivesOnTime) {
  Kernel k;
  Signal in(k, "in", false), out(k, "out", false);
  TransportDelay d(k, in, out, ns(50), ns(10));  // rise 50 ns, fall 10 ns
  Listener l{&k, {}};
  out.on_change(bind<&Listener::on>(&l));
  Writer w{&in};
  struct Low {
    Signal* s;
    void low() { s->write(false); }
  } low{&in};
  k.schedule(ns(1), bind<&Writer::high>(&w));  // rise reaches out at 51 ns
  k.schedule(ns(5), bind<&Low::low>(&low));    // fall reaches out at 15 ns, before the rise
  k.schedule(ns(8), bind<&Writer::high>(&w));  // rise reaches out at 58 ns
  k.run();
  // The fall at 15 ns finds out already LOW (no change); the rises follow at 51 and 58 ns.
  const Entries expected{{51'000, 1}};
  EXPECT_EQ(l.seen, expected);
  EXPECT_EQ(out.last_change(), ns(51));
  EXPECT_TRUE(out.read());
}
