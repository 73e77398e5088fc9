// The thread count of a run beside other programs (thread_share.hpp): decisions from given waiting times.
#include "craterkit/sph/run/thread_share.hpp"

#include <gtest/gtest.h>

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <atomic>
#include <chrono>
#include <latch>
#include <thread>

namespace craterkit::sph {
namespace {

ThreadShareOptions two_threads() {
  ThreadShareOptions options;
  options.max_threads = 2;
  options.window_seconds = 1.0;
  options.waiting_limit = 0.15;
  options.first_retry_seconds = 30.0;
  options.longest_retry_seconds = 240.0;
  return options;
}

TEST(ThreadShare, KeepsEveryThreadWhileNoneWaits) {
  ThreadShare share(two_threads());
  double waiting = 0.0;
  for (int second = 0; second <= 600; ++second) {
    waiting += 0.01;  // 0.5 % of two threads' time: the system's own noise
    const auto decision = share.observe(second, waiting);
    EXPECT_FALSE(decision.threads.has_value()) << "at " << second << " s";
  }
  EXPECT_EQ(share.threads(), 2);
}

TEST(ThreadShare, UsesOneThreadWhileTheOtherWaitsAndTriesBothAgainLessAndLessOften) {
  ThreadShare share(two_threads());
  double waiting = 0.0;
  (void)share.observe(0.0, waiting);
  waiting += 1.0;  // two threads, one second: each waited half of it (a busy program on one of 2 cores)
  auto decision = share.observe(1.0, waiting);
  ASSERT_TRUE(decision.threads.has_value());
  EXPECT_EQ(*decision.threads, 1);
  EXPECT_NE(decision.note.find("2 -> 1"), std::string::npos) << decision.note;

  // One thread beside the busy program does not wait; the full count is tried after 30 s, 60 s, 120 s,
  // 240 s, 240 s, ... while it keeps waiting with two threads.
  std::vector<double> tries;
  double now = 1.0;
  while (now < 1200.0) {
    now += 1.0;
    if (share.threads() == 2) waiting += 1.0;
    decision = share.observe(now, waiting);
    if (decision.threads && *decision.threads == 2) tries.push_back(now);
    if (decision.threads && *decision.threads == 1) {
      EXPECT_TRUE(decision.note.empty()) << "a failed try is quiet";
    }
  }
  ASSERT_GE(tries.size(), 5u);
  EXPECT_DOUBLE_EQ(tries[0], 31.0);
  EXPECT_DOUBLE_EQ(tries[1] - tries[0], 1.0 + 60.0);  // the try's window, then the doubled interval
  EXPECT_DOUBLE_EQ(tries[2] - tries[1], 1.0 + 120.0);
  EXPECT_DOUBLE_EQ(tries[3] - tries[2], 1.0 + 240.0);
  EXPECT_DOUBLE_EQ(tries[4] - tries[3], 1.0 + 240.0);
}

TEST(ThreadShare, KeepsTheFullCountWhenTheOtherProgramHasEnded) {
  ThreadShare share(two_threads());
  double waiting = 0.0;
  (void)share.observe(0.0, waiting);
  waiting += 1.0;
  ASSERT_EQ(share.observe(1.0, waiting).threads.value_or(0), 1);
  double now = 1.0;
  while (share.threads() == 1) {  // the busy program ends; nobody waits any more
    now += 1.0;
    (void)share.observe(now, waiting);
  }
  EXPECT_DOUBLE_EQ(now, 31.0);
  EXPECT_TRUE(share.trying());
  const auto kept = share.observe(now + 1.0, waiting + 0.001);
  EXPECT_FALSE(kept.threads.has_value());
  EXPECT_FALSE(share.trying());
  EXPECT_NE(kept.note.find("back to 2 threads"), std::string::npos) << kept.note;
  for (double t = now + 2.0; t < now + 600.0; t += 1.0)
    EXPECT_FALSE(share.observe(t, waiting + 0.001).threads);
}

TEST(ThreadShare, MeasuresOverWholeWindowsOnly) {
  ThreadShare share(two_threads());
  (void)share.observe(0.0, 0.0);
  EXPECT_FALSE(share.due(0.5));
  EXPECT_FALSE(share.observe(0.5, 0.9).threads) << "half a window decides nothing";
  EXPECT_TRUE(share.due(1.0));
  EXPECT_EQ(share.observe(1.0, 0.9).threads.value_or(0), 1);
}

TEST(ThreadShare, OneThreadIsNeverChanged) {
  ThreadShareOptions options = two_threads();
  options.max_threads = 1;
  ThreadShare share(options);
  EXPECT_FALSE(share.due(0.0));
  for (int second = 0; second < 100; ++second) EXPECT_FALSE(share.observe(second, second * 10.0).threads);
}

TEST(ThreadShare, ManyThreadsKeepTheirShare) {
  ThreadShareOptions options = two_threads();
  options.max_threads = 8;
  ThreadShare share(options);
  (void)share.observe(0.0, 0.0);
  // 8 threads that waited 40 % of a second each get about 60 % of 8 processors: 5 threads.
  EXPECT_EQ(share.observe(1.0, 8 * 0.4).threads.value_or(0), 5);
}

TEST(ThreadShare, ReadsTheWaitingTimeOfThisProcess) {
  const auto before = process_waiting_seconds();
  if (!before) GTEST_SKIP() << "no /proc/self/task/*/schedstat here";
  // Two busy threads on one processor: each waits while the other runs, about 0.1 s of CPU time each.
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  int processor = 0;
  while (!CPU_ISSET(processor, &allowed)) ++processor;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(processor, &one);
  // The threads stay until the waiting is read: an ended thread takes its schedstat along.
  std::latch worked(2), read(1);
  std::atomic<bool> all_pinned = true;
  const auto busy = [&] {
    const bool pinned = pthread_setaffinity_np(pthread_self(), sizeof one, &one) == 0;
    if (!pinned) all_pinned = false;
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    volatile double x = 0;
    timespec cpu{};
    do {  // 0.1 s of processor time, however long that takes in wall time
      for (int i = 0; i < 100000; ++i) x = x + 1.0;
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
    } while (pinned && cpu.tv_sec == 0 && cpu.tv_nsec < 100000000 &&
             std::chrono::steady_clock::now() < give_up);
    worked.count_down();
    read.wait();
  };
  std::thread first(busy), second(busy);
  worked.wait();
  const auto after = process_waiting_seconds();
  read.count_down();
  first.join();
  second.join();
  ASSERT_TRUE(after.has_value());
  if (!all_pinned) GTEST_SKIP() << "threads cannot be bound to one processor here";
  EXPECT_GT(*after - *before, 0.02) << "two threads sharing one processor for 0.2 s waited less than 0.02 s";
}

}  // namespace
}  // namespace craterkit::sph
