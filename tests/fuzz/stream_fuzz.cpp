// libFuzzer target: the EPI stream reader behind mvr-consume (issue 16).
// Reads the input as a stream to its end; a rejection (mvr::Error) is the
// expected answer to a bad stream, anything else is a defect.
#include <cstdint>
#include <sstream>
#include <string>

#include "mvr/frames/epi_stream.h"
#include "mvr/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    mvr::EpiStreamReader reader(in);
    while (reader.next()) {
    }
  } catch (const mvr::Error&) {
  }
  return 0;
}
