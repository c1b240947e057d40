// The kernel's queue of timed events, ordered by (time, sequence): a timing wheel of 4 ns
// buckets for what falls within the next 4 us (a frame's clock edges and line delays), and a
// binary heap for what lies beyond (the next frame's start, long timeouts).
//
// A binary heap of the 8 to 10 entries a run holds spends most of its time in the comparisons of
// each sift, whose outcome depends on the data and is mispredicted. A wheel puts an event in its
// bucket by its time alone and finds the earliest bucket with a bit scan; a bucket rarely holds
// more than one entry. Every correct priority queue over a total order gives the same events in
// the same order, so the choice changes no result, only how fast it is found.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "endatsim/sim/time.hpp"

namespace endatsim::sim {

template <class Payload>
class EventQueue {
 public:
  struct Entry {
    Time when;
    std::uint64_t seq;
    Payload payload;
  };

  EventQueue() {
    nodes_.reserve(256);
    overflow_.reserve(64);
  }

  bool empty() const { return wheel_size_ == 0 && overflow_.empty(); }

  // `entry.when` must not lie before the last entry taken out (the kernel's present).
  void push(const Entry& entry) {
    const std::uint64_t bucket = bucket_of(entry.when);
    if (bucket - cursor_ >= kBuckets) {
      // Later than every entry in the wheel: the top only if the heap's front is the top already.
      overflow_.push_back(entry);
      std::push_heap(overflow_.begin(), overflow_.end(), Later{});
      return;
    }
    const bool earliest = top_ != kNone && later(top_ == kOverflow ? overflow_.front() : node(top_).entry, entry);
    const std::uint32_t n = allocate();
    Node& fresh = nodes_[n];
    fresh.entry = entry;
    const std::size_t b = bucket & kMask;
    fresh.next = heads_[b];
    heads_[b] = n;
    words_[b >> 6] |= std::uint64_t{1} << (b & 63);
    summary_ |= std::uint64_t{1} << (b >> 6);
    ++wheel_size_;
    if (earliest) top_ = n;
  }

  // The earliest entry; the queue must not be empty.
  const Entry& top() const {
    if (top_ == kNone) find_top();
    return top_ == kOverflow ? overflow_.front() : node(top_).entry;
  }

  // Takes the earliest entry out and returns it.
  Entry pop() {
    if (top_ == kNone) find_top();
    Entry taken;
    if (top_ == kOverflow) {
      std::pop_heap(overflow_.begin(), overflow_.end(), Later{});
      taken = overflow_.back();
      overflow_.pop_back();
    } else {
      taken = unlink(top_);
    }
    cursor_ = bucket_of(taken.when);
    top_ = kNone;
    return taken;
  }

 private:
  static constexpr unsigned kShift = 12;         // 4 096 ps per bucket
  static constexpr std::size_t kBuckets = 1024;  // 4.2 us ahead
  static constexpr std::size_t kMask = kBuckets - 1;
  static constexpr std::size_t kWords = kBuckets / 64;  // one bit of summary_ each
  static_assert(kWords >= 1 && kWords <= 64);
  static constexpr std::uint32_t kEnd = UINT32_MAX;
  static constexpr std::uint32_t kNone = UINT32_MAX;
  static constexpr std::uint32_t kOverflow = UINT32_MAX - 1;

  struct Node {
    Entry entry;
    std::uint32_t next;
  };
  struct Later {
    bool operator()(const Entry& a, const Entry& b) const { return later(a, b); }
  };
  static bool later(const Entry& a, const Entry& b) { return a.when != b.when ? a.when > b.when : a.seq > b.seq; }
  static std::uint64_t bucket_of(Time t) { return static_cast<std::uint64_t>(t.count()) >> kShift; }
  Node& node(std::uint32_t n) { return nodes_[n]; }
  const Node& node(std::uint32_t n) const { return nodes_[n]; }

  std::uint32_t allocate() {
    if (free_ != kEnd) {
      const std::uint32_t n = free_;
      free_ = nodes_[n].next;
      return n;
    }
    nodes_.push_back(Node{});
    return static_cast<std::uint32_t>(nodes_.size() - 1);
  }

  // The first non-empty bucket at or after the cursor's, around the wheel.
  std::size_t first_bucket() const {
    const std::size_t from = cursor_ & kMask;
    const std::size_t w = from >> 6;
    const std::uint64_t here = words_[w] & (~std::uint64_t{0} << (from & 63));
    if (here != 0) return (w << 6) + static_cast<std::size_t>(std::countr_zero(here));
    const std::uint64_t after = w + 1 == kWords ? 0 : summary_ & (~std::uint64_t{0} << (w + 1));
    const std::uint64_t s = after != 0 ? after : summary_;  // around: words 0 .. w (w's low bits)
    const std::size_t w2 = static_cast<std::size_t>(std::countr_zero(s));
    return (w2 << 6) + static_cast<std::size_t>(std::countr_zero(words_[w2]));
  }

  void find_top() const {
    if (wheel_size_ != 0) {
      const std::size_t b = first_bucket();
      std::uint32_t best = heads_[b];
      for (std::uint32_t n = node(best).next; n != kEnd; n = node(n).next)
        if (later(node(best).entry, node(n).entry)) best = n;
      top_ = best;
      if (!overflow_.empty() && later(node(best).entry, overflow_.front())) top_ = kOverflow;
      return;
    }
    top_ = kOverflow;
  }

  Entry unlink(std::uint32_t n) {
    const std::size_t b = bucket_of(node(n).entry.when) & kMask;
    std::uint32_t* link = &heads_[b];
    while (*link != n) link = &nodes_[*link].next;
    const std::uint32_t next = nodes_[n].next;
    *link = next;
    // The bucket is empty when its head went and nothing followed (known without reading back
    // the head just stored, which waits for the store).
    if (link == &heads_[b] && next == kEnd) {
      std::uint64_t& word = words_[b >> 6];
      word &= ~(std::uint64_t{1} << (b & 63));
      if (word == 0) summary_ &= ~(std::uint64_t{1} << (b >> 6));
    }
    --wheel_size_;
    nodes_[n].next = free_;
    free_ = n;
    return nodes_[n].entry;
  }

  std::vector<Node> nodes_;
  std::uint32_t free_ = kEnd;
  std::array<std::uint32_t, kBuckets> heads_ = filled();
  std::array<std::uint64_t, kWords> words_{};
  std::uint64_t summary_ = 0;
  std::size_t wheel_size_ = 0;
  std::uint64_t cursor_ = 0;  // the bucket of the last entry taken out
  std::vector<Entry> overflow_;
  mutable std::uint32_t top_ = kNone;  // the earliest entry's node, kOverflow, or kNone: not known

  static std::array<std::uint32_t, kBuckets> filled() {
    std::array<std::uint32_t, kBuckets> a;
    a.fill(kEnd);
    return a;
  }
};

}  // namespace endatsim::sim
