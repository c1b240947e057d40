// Discrete-event kernel: integer picosecond time, (time, insertion sequence) order,
// zero-delay wake-ups through a FIFO, SystemC-like evaluate/update delta cycles.
// Events are plain function pointers with a context and a 64-bit argument: no heap
// allocation and no std::function per event.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <vector>

#include "endatsim/sim/event_queue.hpp"
#include "endatsim/sim/time.hpp"

namespace endatsim::sim {

struct Action {
  void (*fn)(void* ctx, std::uint64_t arg) = nullptr;
  void* ctx = nullptr;
  std::uint64_t arg = 0;
  void operator()() const { fn(ctx, arg); }
};

// bind<&T::method>(obj, arg): an Action calling obj->method(arg) or obj->method().
template <auto Method, class T>
Action bind(T* obj, std::uint64_t arg = 0) {
  return Action{[](void* ctx, std::uint64_t a) {
                  auto* self = static_cast<T*>(ctx);
                  if constexpr (std::is_invocable_v<decltype(Method), T*, std::uint64_t>) {
                    (self->*Method)(a);
                  } else {
                    (void)a;
                    (self->*Method)();
                  }
                },
                obj, arg};
}

class Signal;
struct Tape;

class Kernel {
 public:
  Kernel();
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;

  Time now() const { return now_; }

  // delay == 0 wakes up in the next delta cycle (FIFO); delay > 0 goes to the queue of timed events (event_queue.hpp).
  void schedule(Time delay, Action action);
  void schedule_at(Time when, Action action);

  // For models that keep their own queue of future work (a timer restarted on every clock
  // edge) and put only its earliest item into the kernel's queue: take_seq() at the
  // moment the work is decided, and schedule_ordered(when, seq, ...) later. The entry runs in
  // the order a schedule() at the moment of take_seq() would have given it, so keeping the
  // queue outside changes no result, only how many entries the queue holds.
  std::uint64_t take_seq() { return seq_++; }
  void schedule_ordered(Time when, std::uint64_t seq, Action action);

  // Runs until no event is left, stop() is called, or the next event lies after `until`.
  void run(Time until = Time::max());
  void stop() { stopped_ = true; }
  // Runs every event up to and including `t` and leaves the time at `t` even when nothing is
  // left to run: an outside simulator that owns time (a co-simulation) moves this kernel along.
  void advance_to(Time t);
  // The earliest pending event's time, if any (a cancelled timer's stale entry counts: waking
  // for it is harmless).
  std::optional<Time> next_event_time() const;
  // Work is waiting at the current time (writes not yet committed, zero-delay wake-ups).
  bool work_pending() const { return !updates_.empty() || fifo_size_ != 0; }

  // Called once at the end of every time step in which something ran (e.g. the VCD writer).
  void on_time_step_end(Action action) { step_end_.push_back(action); }

  std::uint64_t events_processed() const { return events_processed_; }

  // Calls `action` after every `every` events (at an event boundary): a run's owner checks its
  // limits there and may stop(). every == 0 turns it off.
  void watch(std::uint64_t every, Action action) {
    watch_every_ = every;
    watch_ = action;
    next_watch_ = every == 0 ? UINT64_MAX : events_processed_ + every;
  }

  // Records what the monitors are shown (tape.hpp) from now on; nullptr stops. What a model tells
  // its observers goes to the same tape (tape()).
  void record_to(Tape* tape) {
    tape_ = tape;
    if (tape != nullptr) tape_events_from_ = events_processed_;
  }
  Tape* tape() const { return tape_; }
  std::uint64_t events_since_recording() const { return events_processed_ - tape_events_from_; }
  // The end of the current run(), for a stretch played from a tape, which must not pass it.
  Time run_until() const { return until_; }
  // Playing a tape: time moves on to `t` with nothing run. The player makes sure that nothing is
  // queued before the end of what it plays, and says so with replay_done().
  void replay_time(Time t) { now_ = t; }
  // Refuses (std::logic_error) a stretch played up to `last` when an event queued meanwhile falls
  // inside it or work is pending: the stretch must have been all that happened in its time.
  void replay_done(Time last) const;
  // Playing a tape: the actions at the end of a time step (monitors only: the VCD writer).
  void replay_step_end();
  std::size_t step_end_actions() const { return step_end_.size(); }
  // Playing a tape: `n` events count as run (the watch is called as they pass its marks).
  void replay_events(std::uint64_t n) {
    while (n >= next_watch_ - events_processed_) {
      n -= next_watch_ - events_processed_;
      events_processed_ = next_watch_;
      next_watch_ += watch_every_;
      watch_();
    }
    events_processed_ += n;
  }

  // The action of a change arriving on a signal (a delay line's delivery): write(arg != 0) on the
  // Signal `ctx`. The run loop writes it without the indirect call, whose target is hard to
  // predict among the actions of a time step (4 % of the Frame benchmarks' time).
  static void write_signal(void* signal, std::uint64_t value);

  // Used by signals: commit this signal in the next update phase.
  void request_update(Signal* signal) { updates_.push_back(signal); }

 private:
  // Out of line and cold, so that schedule() and schedule_ordered() inline into their callers
  // (an Action handed through a call was copied through the stack, and stalled there).
  [[noreturn]] static void refuse(const char* what);
  // Inlined into run(), as they were before a tape could be recorded (a call each costs ~3 %).
  [[gnu::always_inline]] inline void settle();
  [[gnu::always_inline]] inline void end_time_step();
  void commit_updates();
  // Out of line, so that the time step's end stays inlined into run() when nothing records (not
  // cold: a moving axis records often, and cold code is compiled for size).
  [[gnu::noinline]] void commit_updates_recorded();
  [[gnu::noinline]] void note_step_end();
  void run_fifo_snapshot();
  // A zero-delay wake-up (a delay line of zero delay: every hop of the line `endatsim check` replays
  // a capture onto) is a store and a mask; the ring doubles, out of line, when full.
  void push_fifo(Action a) {
    if (fifo_size_ == fifo_.size()) grow_fifo();
    fifo_[(fifo_head_ + fifo_size_) & (fifo_.size() - 1)] = a;
    ++fifo_size_;
  }
  void grow_fifo();
  void count_event() {
    if (++events_processed_ == next_watch_) {
      next_watch_ += watch_every_;
      watch_();
    }
  }

  Time now_{0};
  std::uint64_t seq_ = 0;
  std::uint64_t events_processed_ = 0;
  bool stopped_ = false;
  std::uint64_t watch_every_ = 0;
  std::uint64_t next_watch_ = UINT64_MAX;
  Action watch_;
  EventQueue<Action> queue_;  // the timed events
  std::vector<Action> fifo_;  // ring buffer, its size a power of two
  std::size_t fifo_head_ = 0;
  std::size_t fifo_size_ = 0;
  std::vector<Signal*> updates_;  // Signal is final: its commit() is a direct call
  std::vector<Signal*> changed_;
  std::vector<Action> step_end_;
  Tape* tape_ = nullptr;
  std::uint64_t tape_events_from_ = 0;
  Time until_ = Time::max();
};

// A cancellable, restartable timer owned by a model. It keeps at most one entry in the
// kernel's queue: a restart to a later expiry (a watchdog restarted on every clock edge) leaves
// the queued entry in place, and when that entry comes up it queues itself again for the
// current expiry, in the order the restart took (Kernel::take_seq). Only a restart to an
// earlier (or the same) expiry queues a second entry; the first one is then stale and ignored.
class Timer {
 public:
  Timer(Kernel& kernel, Action action) : kernel_(kernel), action_(action) {}
  Timer(const Timer&) = delete;
  Timer& operator=(const Timer&) = delete;

  void start(Time delay);
  void cancel() { pending_ = false; }
  bool pending() const { return pending_; }
  Time expiry() const { return expiry_; }

 private:
  static void fire(void* self, std::uint64_t entry);
  void queue(Time when);
  // Out of line and cold, so that start() inlines into the models that restart it on every edge.
  [[noreturn]] static void refuse(Time delay);
  void start_now();
  Kernel& kernel_;
  Action action_;
  bool pending_ = false;
  Time expiry_{0};
  std::uint64_t seq_ = 0;       // the order of the last start()
  bool queued_ = false;         // an entry for this timer is in the kernel
  Time queued_at_{0};           // when that entry comes up
  std::uint64_t entry_ = 0;     // which entry is the live one (older ones are stale)
};

inline void Kernel::schedule(Time delay, Action action) {
  if (delay < Time::zero()) refuse("Kernel::schedule: negative delay");
  if (delay > Time::max() - now_) refuse("Kernel::schedule: the event would fall after Time::max()");
  if (delay == Time::zero()) {
    push_fifo(action);
    return;
  }
  queue_.push({now_ + delay, seq_++, action});
}

inline void Timer::start(Time delay) {
  if (delay < Time::zero() || delay > Time::max() - kernel_.now()) refuse(delay);
  pending_ = true;
  expiry_ = kernel_.now() + delay;
  if (delay == Time::zero()) {
    start_now();
    return;
  }
  seq_ = kernel_.take_seq();
  // An entry due at the same instant carries an older order: only an earlier one can be kept.
  if (!queued_ || queued_at_ >= expiry_) queue(expiry_);
}

inline void Timer::queue(Time when) {
  queued_ = true;
  queued_at_ = when;
  kernel_.schedule_ordered(when, seq_, Action{&Timer::fire, this, ++entry_});
}

// `now` itself only from an event of this instant (a delay line's next change due at once),
// which the running time step still picks up in its order.
inline void Kernel::schedule_ordered(Time when, std::uint64_t seq, Action action) {
  if (when < now_) refuse("Kernel::schedule_ordered: time in the past");
  queue_.push({when, seq, action});
}

}  // namespace endatsim::sim
