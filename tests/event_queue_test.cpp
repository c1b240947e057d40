#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "endatsim/sim/event_queue.hpp"

using namespace endatsim::sim;

namespace {

using Queue = EventQueue<std::uint64_t>;
using Key = std::tuple<std::int64_t, std::uint64_t, std::uint64_t>;  // when, seq, payload

// Pushes and pops as the kernel does (nothing before the last entry taken out) and compares
// every top and every pop with an ordered set.
void compare_with_a_set(std::mt19937_64& rng, std::int64_t (*next_delay)(std::mt19937_64&), int operations) {
  Queue q;
  std::set<Key> reference;
  std::int64_t now = 0;
  std::uint64_t seq = 0;
  std::set<std::uint64_t> used;
  for (int i = 0; i < operations; ++i) {
    if (reference.empty() || rng() % 100 < 55) {
      const std::int64_t when = now + next_delay(rng);
      // Now and then an entry that takes an earlier place in the order than one already queued
      // (a sequence taken before, as Kernel::take_seq gives): sequences stay unique.
      std::uint64_t s = seq;
      if (rng() % 8 == 0 && seq > 64) {
        s = seq - 1 - rng() % 64;
        if (!used.insert(s).second) s = seq;
      }
      if (s == seq) used.insert(seq);
      seq += 2;
      q.push({Time{when}, s, static_cast<std::uint64_t>(i)});
      reference.emplace(when, s, static_cast<std::uint64_t>(i));
    } else {
      const Key expected = *reference.begin();
      reference.erase(reference.begin());
      ASSERT_EQ(q.top().when.count(), std::get<0>(expected)) << "operation " << i;
      const Queue::Entry e = q.pop();
      ASSERT_EQ(Key(e.when.count(), e.seq, e.payload), expected) << "operation " << i;
      now = e.when.count();
    }
    ASSERT_EQ(q.empty(), reference.empty());
  }
  while (!reference.empty()) {
    const Queue::Entry e = q.pop();
    ASSERT_EQ(Key(e.when.count(), e.seq, e.payload), *reference.begin());
    reference.erase(reference.begin());
  }
  EXPECT_TRUE(q.empty());
}

}  // namespace

TEST(EventQueue, GivesEntriesByTimeThenSequenceAsAnOrderedSetDoes) {
  std::mt19937_64 rng(17);
  // Clock edges and cable delays: many entries per microsecond, some at the same picosecond.
  compare_with_a_set(rng, [](std::mt19937_64& r) { return static_cast<std::int64_t>(r() % 3 == 0 ? 0 : r() % 200'000); },
                     200'000);
}

TEST(EventQueue, KeepsOrderAcrossTheWheelsHorizonAndAroundIt) {
  std::mt19937_64 rng(18);
  // Delays from a picosecond to a second: entries beyond the wheel wait in the heap, and the
  // wheel goes round many times.
  compare_with_a_set(rng, [](std::mt19937_64& r) {
    switch (r() % 4) {
      case 0: return static_cast<std::int64_t>(r() % 1'000);
      case 1: return static_cast<std::int64_t>(r() % 5'000'000);
      case 2: return static_cast<std::int64_t>(4'190'000 + r() % 20'000);  // the horizon's edge
      default: return static_cast<std::int64_t>(r() % 1'000'000'000'000);
    }
  }, 200'000);
}

TEST(EventQueue, AnEntryPushedBeforeTheKnownTopBecomesTheTop) {
  Queue q;
  q.push({ns(100), 0, 1});
  EXPECT_EQ(q.top().payload, 1U);
  q.push({ms(1), 1, 2});  // beyond the wheel
  EXPECT_EQ(q.top().payload, 1U);
  q.push({ns(50), 2, 3});
  EXPECT_EQ(q.top().payload, 3U);
  q.push({ns(50), 3, 4});  // the same instant, a later sequence
  EXPECT_EQ(q.top().payload, 3U);
  EXPECT_EQ(q.pop().payload, 3U);
  EXPECT_EQ(q.pop().payload, 4U);
  EXPECT_EQ(q.pop().payload, 1U);
  q.push({ms(2), 5, 5});
  q.push({ms(1), 6, 6});  // the same instant as the first entry beyond the wheel, later
  EXPECT_EQ(q.pop().payload, 2U);
  EXPECT_EQ(q.pop().payload, 6U);
  EXPECT_EQ(q.pop().payload, 5U);
  EXPECT_TRUE(q.empty());
}
