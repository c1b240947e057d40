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
    // Now and then the top is asked for between pushes, as Kernel::next_event_time() and a run
    // that stops at its end do, so that later pushes meet a top already found.
    if (!reference.empty() && rng() % 3 == 0) {
      const Queue::Entry& top = q.top();
      ASSERT_EQ(Key(top.when.count(), top.seq, top.payload), *reference.begin()) << "operation " << i;
    }
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
  compare_with_a_set(
      rng, [](std::mt19937_64& r) { return static_cast<std::int64_t>(r() % 3 == 0 ? 0 : r() % 200'000); }, 200'000);
}

TEST(EventQueue, KeepsOrderAcrossTheWheelsHorizonAndAroundIt) {
  std::mt19937_64 rng(18);
  // Delays from a picosecond to a second: entries beyond the wheel wait in the heap, and the
  // wheel goes round many times.
  compare_with_a_set(
      rng,
      [](std::mt19937_64& r) {
        switch (r() % 4) {
          case 0:
            return static_cast<std::int64_t>(r() % 1'000);
          case 1:
            return static_cast<std::int64_t>(r() % 5'000'000);
          case 2:
            return static_cast<std::int64_t>(4'190'000 + r() % 20'000);  // the horizon's edge
          default:
            return static_cast<std::int64_t>(r() % 1'000'000'000'000);
        }
      },
      200'000);
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

namespace {
constexpr std::int64_t kBucket = 4'096;           // ps, the wheel's bucket
constexpr std::int64_t kWheel = 1'024 * kBucket;  // its horizon
}  // namespace

TEST(EventQueue, AnEntryBeforeATopFoundBeyondTheWheelBecomesTheTop) {
  Queue q;
  q.push({ms(1), 5, 1});
  EXPECT_EQ(q.top().payload, 1U);  // found, beyond the wheel
  q.push({ns(10), 7, 2});
  EXPECT_EQ(q.top().payload, 2U);
  q.push({ns(10), 6, 3});  // the same instant, an earlier sequence (taken before)
  EXPECT_EQ(q.top().payload, 3U);
  EXPECT_EQ(q.pop().payload, 3U);
  EXPECT_EQ(q.pop().payload, 2U);
  EXPECT_EQ(q.pop().payload, 1U);
}

TEST(EventQueue, FindsTheNextBucketAroundTheWheel) {
  // After an entry in bucket 10, one in bucket 1 033 sits in the same bitmap word below it.
  Queue q;
  q.push({Time{10 * kBucket}, 0, 1});
  EXPECT_EQ(q.pop().payload, 1U);
  q.push({Time{1'033 * kBucket + 5}, 1, 2});
  EXPECT_EQ(q.top().payload, 2U);
  EXPECT_EQ(q.pop().payload, 2U);
  // From the wheel's last word (bucket 1 033 + 990 = 2 023, index 999) to its first.
  q.push({Time{2'023 * kBucket}, 2, 3});
  EXPECT_EQ(q.pop().payload, 3U);
  q.push({Time{2'050 * kBucket}, 3, 4});  // index 2
  q.push({Time{2'030 * kBucket}, 4, 5});  // index 1 006
  EXPECT_EQ(q.pop().payload, 5U);
  EXPECT_EQ(q.pop().payload, 4U);
  EXPECT_TRUE(q.empty());
}

TEST(EventQueue, KeepsTheOrderAtTheHorizonsEdge) {
  // One bucket past the horizon waits in the heap; the bucket before it is in the wheel, and both
  // come after an entry in the next bucket.
  Queue q;
  q.push({Time{kWheel}, 0, 1});
  q.push({Time{kWheel - 1}, 1, 2});
  q.push({Time{kBucket}, 2, 3});
  EXPECT_EQ(q.pop().payload, 3U);
  EXPECT_EQ(q.pop().payload, 2U);
  EXPECT_EQ(q.pop().payload, 1U);
}

TEST(EventQueue, OrdersTimesFarFromZeroAndTheLatestTime) {
  Queue q;
  const std::int64_t far = std::int64_t{1} << 62;
  q.push({Time::max(), 0, 1});
  q.push({Time{far + 3 * kBucket}, 1, 2});
  q.push({Time{far}, 2, 3});
  EXPECT_EQ(q.pop().payload, 3U);
  q.push({Time{far + kBucket}, 3, 4});  // in the wheel, now that the cursor is far from zero
  q.push({Time{far + kWheel + 1}, 4, 5});
  EXPECT_EQ(q.pop().payload, 4U);
  EXPECT_EQ(q.pop().payload, 2U);
  EXPECT_EQ(q.pop().payload, 5U);
  EXPECT_EQ(q.pop().payload, 1U);
  EXPECT_TRUE(q.empty());
}
