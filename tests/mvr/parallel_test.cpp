// The pool's bounded task queue: every task runs, no more than the limit
// are ever queued or running, the first failure surfaces at wait() (or at
// the next submit), and one thread cannot deadlock it. The ordered
// pipeline: items taken in order on the caller's thread, never made more
// than the window ahead, failures stop it.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "mvr/parallel.h"

namespace mvr {
namespace {

TEST(BoundedTasks, RunsEveryTaskWithinTheLimit) {
  for (int threads : {1, 2, 4}) {
    setThreadCount(threads);
    std::atomic<int> done{0}, running{0}, most{0};
    BoundedTasks tasks(3);
    for (int i = 0; i < 200; ++i)
      tasks.submit([&] {
        const int now = ++running;
        for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
        }
        volatile double x = 0;
        for (int k = 0; k < 2000; ++k) x = x + k;
        --running;
        ++done;
      });
    tasks.wait();
    EXPECT_EQ(done.load(), 200) << threads << " threads";
    EXPECT_LE(most.load(), 3) << threads << " threads";
  }
  setThreadCount(0);
}

TEST(BoundedTasks, TheFirstFailureSurfaces) {
  BoundedTasks tasks(2);
  tasks.submit([] { throw std::runtime_error("disk full"); });
  try {
    tasks.wait();
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "disk full");
  }
  tasks.submit([] {});  // the error was reported once; the queue goes on
  EXPECT_NO_THROW(tasks.wait());
  tasks.submit([] { throw std::runtime_error("again"); });
  bool thrown = false;
  for (int i = 0; i < 100 && !thrown; ++i) {
    try {
      tasks.submit([] {});
    } catch (const std::runtime_error&) {
      thrown = true;
    }
  }
  if (!thrown) {
    EXPECT_THROW(tasks.wait(), std::runtime_error);
  }
}

TEST(ParallelOrdered, TakesInOrderOnTheCallerWithinTheWindow) {
  const std::thread::id caller = std::this_thread::get_id();
  for (int threads : {1, 2, 4})
    for (int window : {1, 3, 8}) {
      setThreadCount(threads);
      const int begin = 5, end = 105;
      std::vector<std::atomic<int>> made(end);
      std::atomic<int> taken{begin}, aheadOfWindow{0};
      std::vector<int> order;
      bool offCaller = false;
      parallelOrdered(
          begin, end, window,
          [&](int i) {
            if (i - window >= taken.load()) ++aheadOfWindow;  // take(i - window) not yet returned
            volatile double x = 0;
            for (int k = 0; k < 500 * (i % 7); ++k) x = x + k;  // uneven items
            made[i].store(1);
          },
          [&](int i) {
            if (std::this_thread::get_id() != caller) offCaller = true;
            EXPECT_EQ(made[i].load(), 1) << i;
            order.push_back(i);
            taken.store(i + 1);
          });
      std::vector<int> expected;
      for (int i = begin; i < end; ++i) expected.push_back(i);
      EXPECT_EQ(order, expected) << threads << " threads, window " << window;
      EXPECT_EQ(aheadOfWindow.load(), 0) << threads << " threads, window " << window;
      EXPECT_FALSE(offCaller);
    }
  setThreadCount(0);
}

TEST(ParallelOrdered, ATakeMayRunParallelLoops) {
  std::atomic<int> inner{0};
  int taken = 0;
  parallelOrdered(
      0, 50, 4, [](int) {},
      [&](int) {
        parallelFor(0, 16, [&](int) { ++inner; });
        ++taken;
      });
  EXPECT_EQ(taken, 50);
  EXPECT_EQ(inner.load(), 50 * 16);
}

TEST(ParallelOrdered, TheFirstFailureStopsItAndSurfaces) {
  for (int threads : {1, 2}) {
    setThreadCount(threads);
    int lastTaken = -1;
    try {
      parallelOrdered(
          0, 100, 4,
          [](int i) {
            if (i == 30) throw std::runtime_error("make 30");
          },
          [&](int i) { lastTaken = i; });
      ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "make 30");
    }
    EXPECT_LT(lastTaken, 30) << threads << " threads";
    int takes = 0;
    EXPECT_THROW(parallelOrdered(
                     0, 100, 4, [](int) {},
                     [&](int i) {
                       ++takes;
                       if (i == 10) throw std::runtime_error("take 10");
                     }),
                 std::runtime_error);
    EXPECT_EQ(takes, 11) << threads << " threads";
  }
  setThreadCount(0);
}

}  // namespace
}  // namespace mvr
