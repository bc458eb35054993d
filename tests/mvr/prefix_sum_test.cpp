// The GPU prefix sum against a serial scan: sizes around the 1024-element
// block and its square (one, two and three levels), an offset start, and
// the empty range.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "mvr/gl/prefix_sum.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

TEST(PrefixSum, MatchesASerialScanAtEveryLevel) {
  test::sharedContext();
  gl::PrefixSum sum;
  std::mt19937 rng(7);
  for (uint32_t count : {0u, 1u, 2u, 15u, 17u, 1023u, 1024u, 1025u, 1048575u, 1048576u, 1048577u, 1200000u}) {
    const uint32_t first = count % 3;  // an offset start leaves the elements before it alone
    std::vector<uint32_t> data(first + count);
    for (uint32_t& x : data) x = rng() % 13;
    const gl::Buffer buffer = gl::makeBuffer(data.data(), data.size(), GL_DYNAMIC_STORAGE_BIT);
    const uint32_t sentinel[2] = {0xDEADBEEFu, 0xDEADBEEFu};
    const gl::Buffer total = gl::makeBuffer(sentinel, 2, GL_DYNAMIC_STORAGE_BIT);
    sum.exclusive(buffer.id(), first, count, total.id(), sizeof(uint32_t));

    std::vector<uint32_t> got(data.size());
    if (!got.empty())
      gl::GetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(got.size() * 4), got.data());
    uint32_t gotTotal[2];
    gl::GetNamedBufferSubData(total.id(), 0, sizeof gotTotal, gotTotal);
    uint32_t run = 0;
    for (uint32_t i = 0; i < first; ++i) ASSERT_EQ(got[i], data[i]);
    for (uint32_t i = first; i < data.size(); ++i) {
      ASSERT_EQ(got[i], run) << "count " << count << " at " << i;
      run += data[i];
    }
    EXPECT_EQ(gotTotal[1], run) << "count " << count;
    EXPECT_EQ(gotTotal[0], 0xDEADBEEFu);  // only the named word is written
  }
}

}  // namespace
}  // namespace mvr
