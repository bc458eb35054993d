// The pool's bounded task queue: every task runs, no more than the limit
// are ever queued or running, the first failure surfaces at wait() (or at
// the next submit), and one thread cannot deadlock it.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

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

}  // namespace
}  // namespace mvr
