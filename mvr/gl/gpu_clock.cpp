#include "mvr/gl/gpu_clock.h"

#include "mvr/gl/gl_api.h"

namespace mvr::gl {
namespace {

bool gEnabled = false;

}  // namespace

void GpuClock::enable(bool on) { gEnabled = on; }
bool GpuClock::enabled() { return gEnabled; }

std::vector<GpuClock::Mark>& GpuClock::marks() {
  thread_local std::vector<Mark> all;  // one GL context per thread
  return all;
}

void GpuClock::mark(const char* stage) {
  if (!gEnabled) return;
  GLuint query = 0;
  gl::CreateQueries(GL_TIMESTAMP, 1, &query);
  gl::QueryCounter(query, GL_TIMESTAMP);
  marks().push_back({query, stage});
}

void GpuClock::collect(StageTimes& times) {
  if (!gEnabled) return;
  mark("");
  std::vector<Mark>& all = marks();
  GLuint64 previous = 0;
  for (size_t k = 0; k < all.size(); ++k) {
    GLuint64 at = 0;
    gl::GetQueryObjectui64v(all[k].query, GL_QUERY_RESULT, &at);
    if (k > 0) times.add("gpu:" + all[k - 1].stage, double(at - previous) * 1e-9);
    previous = at;
    gl::DeleteQueries(1, &all[k].query);
  }
  all.clear();
}

void GpuClock::discard() {
  for (Mark& m : marks()) gl::DeleteQueries(1, &m.query);
  marks().clear();
}

}  // namespace mvr::gl
