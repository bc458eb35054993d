// mvr-consume: the display side of `mvr stream`. Reads the EPI-major stream
// from stdin, a file or a socket it listens on, reassembles the views and
// writes them as an image set with a manifest.
//   mvr stream --to - | mvr-consume --from - --out DIR
//   mvr-consume --from unix:/tmp/mvr.sock --out DIR &  mvr stream --to unix:/tmp/mvr.sock
#include <cstdio>
#include <istream>
#include <new>
#include <optional>

#include "apps/cli/cli.h"
#include "apps/cli/memory_check.h"
#include "apps/cli/sequence_flags.h"
#include "mvr/frames/epi_stream.h"
#include "mvr/frames/frame_chain.h"
#include "mvr/error.h"
#include "mvr/files/fd_stream.h"
#include "mvr/images/image_codec.h"
#include "mvr/images/image_file.h"
#include "mvr/images/image_set.h"
#include "mvr/parallel.h"
#include "mvr/timer.h"

namespace {

// One frame's EPIs from the reader into an image set in `out`.
// camera: the producer's, from the header, for the manifest.
size_t consumeFrame(mvr::EpiStreamReader& reader, const std::string& out, const std::string& format,
                    const mvr::ReorderMemory& reorder, const std::string& from,
                    const std::optional<mvr::ShearingCamera>& camera, mvr::EpiStreamReader::Frame& f) {
  mvr::Stopwatch watch;
  const mvr::EpiStreamHeader& h = reader.header();
  const mvr::PixelType type = h.pixelType();
  mvr::ImageSetWriter writer(out, mvr::Manifest{.views = int(h.views), .rows = int(h.rows),
                                                .width = int(h.width), .height = int(h.height),
                                                .format = format, .bits = mvr::defaultBits(format),
                                                .srgb = type != mvr::PixelType::U8});
  // 8-bit PNG views take their rows as the EPIs come (no volume; the
  // files' bytes within the budget, beyond it on their way to disk); the
  // rest is reassembled.
  const size_t rowBytes = h.epiBytes() * h.height;
  const std::optional<mvr::PngRows> pngRows = mvr::planPngRows(writer.manifest(), type, reorder.budget, false);
  if (!pngRows && reorder.spills(rowBytes)) mvr::app::checkScratchFits(rowBytes, reorder.scratchDir);
  mvr::FrameChain chain({.sink = &writer, .set = &writer},
                        {.rendered = mvr::FrameOrder::Epi, .delivered = mvr::FrameOrder::View, .width = int(h.width),
                         .height = int(h.height), .views = int(h.views), .type = type, .reorder = reorder,
                         .pngRows = pngRows});
  mvr::FrameSink& views = chain.entry();
  // In order, all of them (or it throws); the sink leaves a written EPI's
  // buffer in the frame for the next to be read into.
  size_t epis = 0;
  for (; epis < h.episPerFrame(); ++epis) {
    if (!reader.next(f)) mvr::fail("stream", "ended inside a frame");
    views.putEpiInPlace(f.row, f.scanline, f.epi);
  }
  views.finish();
  writer.manifest().info = {{"source", "stream " + from},
                            {"reorder", chain.reorderInfo()},
                            {"timings_s", {{"total", watch.seconds()}}}};
  if (h.frames > 1)
    writer.manifest().info["frame"] = {{"index", f.frame},
                                       {"time_s", h.startTime + (h.frameRate > 0 ? f.frame / h.frameRate : 0.0)}};
  // The producer's camera: the same per-view cameras as its own manifest.
  if (camera) writer.manifest().setCamera(*camera, h.camera->imagePlaneZ);
  writer.commit();
  std::fprintf(stderr, "mvr-consume: %zu EPIs -> %u views in %s%s\n", epis, h.views * h.rows, out.c_str(),
               chain.scratchNote().c_str());
  return epis;
}

int consume(int argc, char** argv) {
  CLI::App app("Listens on a socket (or reads stdin or a file), reads one EPI-major stream and "
               "writes its views as view_0000.png ... with a manifest.json; a sequence's frames each in "
               "frame_0000/, frame_0001/, ...",
               "mvr-consume");
  std::string from, out, format;
  app.add_option("--from", from, "where the stream comes from")
      ->type_name("-|FILE|unix:PATH|tcp:HOST:PORT")
      ->required();
  app.add_option("--out", out, "output folder")->required();
  app.add_option("--format", format, "png, exr or tiff (default: png for 8-bit streams, else exr)");
  mvr::app::addThreadsOption(app);
  mvr::app::MemoryFlags memory;
  memory.add(app, "the output folder");
  if (auto exit = mvr::app::parseCommandLine(app, argc, argv)) return *exit;
  mvr::FdStreamBuf buffer(mvr::openForReading(from));
  std::istream in(&buffer);
  mvr::EpiStreamReader reader(in);
  const mvr::EpiStreamHeader& h = reader.header();
  const mvr::PixelType type = h.pixelType();
  std::optional<mvr::ShearingCamera> camera;  // checked before any output
  if (h.camera) camera.emplace(h.camera->spec, int(h.width), int(h.height), int(h.views), int(h.rows));
  if (format.empty()) format = mvr::isByteType(type) ? "png" : "exr";
  if (format != "png") mvr::preloadImageCodec();  // loads while the stream arrives
  const size_t viewBytes = h.epiBytes() / h.views * h.height, rowBytes = h.epiBytes() * h.height;
  const mvr::ReorderMemory reorder =
      memory.reorder(viewBytes, mvr::BoundedTasks::defaultLimit(), out);
  mvr::app::checkHeldFramesFit({.reorderBytes = reorder.held(rowBytes)},
                               mvr::app::availableMemory(), "give a smaller --memory");
  mvr::EpiStreamReader::Frame f{};
  for (uint32_t k = 0; k < h.frames; ++k)
    consumeFrame(reader, h.frames > 1 ? out + "/" + mvr::app::frameFolderName(int(k)) : out, format, reorder, from,
                 camera, f);
  if (reader.next(f)) mvr::fail("stream", "data after the last frame");  // throws itself first
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return consume(argc, argv);
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "mvr-consume: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "mvr-consume: out of memory for the stream's views (fewer views or a smaller size)\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mvr-consume: internal error: %s\n", e.what());
    return 1;
  }
}
