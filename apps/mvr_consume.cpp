// mvr-consume: the display side of `mvr stream`. Reads the EPI-major stream
// from stdin, a file or a socket it listens on, reassembles the views and
// writes them as an image set with a manifest.
//   mvr stream --to - | mvr-consume --from - --out DIR
//   mvr-consume --from unix:/tmp/mvr.sock --out DIR &  mvr stream --to unix:/tmp/mvr.sock
#include <cstdio>
#include <istream>

#include "apps/args.h"
#include "epi/epi_stream.h"
#include "epi/volume.h"
#include "mvr/error.h"
#include "mvr/io/fd_stream.h"
#include "mvr/io/image_set.h"
#include "mvr/timer.h"

namespace {

const char* const kHelp =
    "usage: mvr-consume --from -|FILE|unix:PATH|tcp:HOST:PORT --out DIR [--format png|exr|tiff]\n"
    "Listens on a socket (or reads stdin or a file), reads one EPI-major stream\n"
    "and writes its views as view_0000.png ... with a manifest.json.\n";

int consume(int argc, char** argv) {
  mvr::app::Args args(argc, argv, 1, {"from", "out", "format"}, {});
  if (!args.has("from") || !args.has("out")) mvr::fail("mvr-consume", "needs --from and --out (see --help)");
  mvr::Stopwatch watch;
  mvr::FdStreamBuf buffer(mvr::openForReading(args.get("from", "-")));
  std::istream in(&buffer);
  mvr::EpiStreamReader reader(in);
  const mvr::EpiStreamHeader& h = reader.header();
  const mvr::PixelType type = h.bytesPerChannel == 1 ? mvr::PixelType::U8 : mvr::PixelType::F32;
  const std::string format = args.get("format", type == mvr::PixelType::U8 ? "png" : "exr");
  mvr::Manifest layout;
  layout.views = int(h.views);
  layout.rows = int(h.rows);
  layout.width = int(h.width);
  layout.height = int(h.height);
  layout.format = format;
  mvr::ImageSetWriter writer(args.get("out", ""), layout);
  mvr::EpisToViews views(writer, int(h.width), int(h.height), int(h.views), type);
  size_t frames = 0;
  while (auto f = reader.next()) {
    if (f->scanline < 0 || f->scanline >= int(h.height) || f->row < 0 || f->row >= int(h.rows))
      mvr::fail("stream", "EPI outside the header's size");
    views.putEpi(f->row, f->scanline, f->epi);
    ++frames;
  }
  if (frames != size_t(h.height) * h.rows)
    mvr::fail("stream", "ended after " + std::to_string(frames) + " of " +
                            std::to_string(size_t(h.height) * h.rows) + " EPIs");
  writer.manifest().info = {{"source", "stream " + args.get("from", "-")},
                            {"timings_s", {{"total", watch.seconds()}}}};
  writer.commit();
  std::fprintf(stderr, "mvr-consume: %zu EPIs -> %u views in %s\n", frames, h.views * h.rows,
               args.get("out", "").c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::fputs(kHelp, stdout);
    return 0;
  }
  try {
    return consume(argc, argv);
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "mvr-consume: %s\n", e.what());
    return 1;
  }
}
