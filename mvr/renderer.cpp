#include "mvr/renderer.h"

#include "mvr/error.h"

namespace mvr {

void FrameSink::putView(int, int, const Image&) {
  fail("sink", "this sink takes EPIs, not views (wrap it in an EPI adaptor)");
}

void FrameSink::putEpi(int, int, const Image&) {
  fail("sink", "this sink takes views, not EPIs (wrap it in a view adaptor)");
}

}  // namespace mvr
