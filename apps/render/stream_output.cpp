// The EPI-major stream (docs/EPI_STREAM.md) as a job's output: to a file,
// stdout or a socket as EPIs complete, from one process or from every rank
// of a split job.
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "apps/render/job_phase.h"
#include "apps/render/render_job.h"
#include "apps/render/split_output.h"
#include "mvr/error.h"
#include "mvr/frames/epi_stream.h"
#include "mvr/frames/progress.h"
#include "mvr/frames/stream_queue.h"
#include "mvr/files/atomic_file.h"
#include "mvr/files/fd_stream.h"

namespace mvr::app {

namespace {

// Whether the stream goes to a file written under a temporary name and
// renamed when complete: a regular file, or a path with nothing there yet.
// A device or named pipe (/dev/null, a FIFO a consumer reads) is written
// in place: a rename would replace it with a regular file (as root, even
// /dev/null), and elsewhere its folder is seldom writable.
bool isPlainFile(const std::string& endpoint) {
  if (endpoint == "-" || endpoint.rfind("unix:", 0) == 0 || endpoint.rfind("tcp:", 0) == 0) return false;
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(endpoint, ec);
  return !std::filesystem::exists(status) || std::filesystem::is_regular_file(status);
}

EpiStreamHeader streamHeader(const ShearingCamera& cam, PixelType type, double imagePlaneZ,
                             const StreamedFrames& frames = {}) {
  EpiStreamHeader header{uint32_t(cam.width()), uint32_t(cam.height()), uint32_t(cam.views()),
                         uint32_t(cam.rows()), 4, uint32_t(Image::channelBytes(type)),
                         type == PixelType::Srgb8};
  header.frames = uint32_t(frames.count);
  header.startTime = frames.startTime, header.frameRate = frames.frameRate;
  header.camera = StreamCamera{cam.spec(), imagePlaneZ};
  header.camera->spec.planeHeight = cam.planeHeight();
  return header;
}

// One frame's EPIs on to the stream, which stays open when the frame ends.
class FrameOfStream final : public FrameSink {
 public:
  explicit FrameOfStream(FrameSink& stream) : stream_(stream) {}
  void putEpi(int row, int scanline, const Image& epi) override { stream_.putEpi(row, scanline, epi); }
  void putEpiInPlace(int row, int scanline, Image& epi) override { stream_.putEpiInPlace(row, scanline, epi); }

 private:
  FrameSink& stream_;
};

// EPIs to a file, stdout or socket as they complete, through a bounded
// queue, frame after frame. A regular file is written under a temporary
// name and renamed when done; a device or named pipe in place (isPlainFile).
int streamTo(const RenderJob& job, PreparedJob& p, const StreamedFrames& frames) {
  std::signal(SIGPIPE, SIG_IGN);  // a vanished consumer is an error, not a kill
  std::signal(SIGXFSZ, SIG_IGN);  // so is a file-size limit
  const std::string& endpoint = job.stream;
  const ShearingCamera& cam = *p.camera;
  const bool file = isPlainFile(endpoint);
  const std::string target = file ? partName(endpoint) : endpoint;
  const EpiStreamHeader header = streamHeader(cam, job.type, p.imagePlaneZ, frames);
  Stopwatch watch;
  size_t highWater = 0;
  std::string note;
  std::optional<FdStreamBuf> buffer;
  try {
    buffer.emplace(openForWriting(target));
    std::ostream out(&*buffer);
    QueuedEpiStream stream(out, header, size_t(job.queue));
    FrameOfStream frame(stream);
    FrameChainSpec spec = p.chainSpec(job);
    spec.delivered = FrameOrder::Epi;
    for (int k = 0; k < frames.count; ++k) {
      if (frames.beforeFrame) frames.beforeFrame(k);
      FrameChain chain({.sink = &frame}, spec);
      ProgressSink progress(chain.entry(), *p.renderCamera, long(cam.views()) * cam.rows(), p.renderer->name());
      RenderStats stats;
      p.renderer->render(*p.renderCamera, progress, stats);
      progress.finish();
      note = chain.scratchNote();
      if (frames.afterFrame) frames.afterFrame(k);
    }
    stream.finish();
    highWater = stream.highWater();
    buffer.reset();  // closed before the rename
  } catch (...) {
    if (file) removePart(endpoint);
    if (buffer && buffer->writeError())  // the system's reason, not the writer's guess
      fail(endpoint, std::string("cannot write stream: ") + std::strerror(buffer->writeError()));
    throw;
  }
  if (file) commitPart(endpoint);
  const std::string ofFrames = frames.count > 1 ? " in each of " + std::to_string(frames.count) + " frames" : "";
  std::fprintf(stderr, "mvr: streamed %d EPIs of %dx%d%s to %s in %.3f s (queue high water %zu of %d%s)\n",
               cam.height() * cam.rows(), cam.width(), cam.views(), ofFrames.c_str(), endpoint.c_str(),
               watch.seconds(), highWater, job.queue, note.c_str());
  return 0;
}

// The whole stream from a shared file, in order, to a pipe or socket.
void relayStream(SharedFile& records, uint64_t bytes, FdStreamBuf& buffer, const std::string& endpoint) {
  std::ostream out(&buffer);
  std::vector<std::byte> piece;
  for (uint64_t at = 0; at < bytes; at += piece.size()) {
    piece.resize(size_t(std::min<uint64_t>(uint64_t(16) << 20, bytes - at)));
    records.read(at, piece);
    out.write(reinterpret_cast<const char*>(piece.data()), std::streamsize(piece.size()));
    if (!out) break;
  }
  out.flush();
  if (!out || buffer.writeError())
    fail(endpoint, std::string("cannot write stream: ") + std::strerror(buffer.writeError() ? buffer.writeError() : EIO));
}

// The stream of a job split over ranks: every rank writes its EPIs'
// records at their offsets in one shared file, so the stream is the
// single process's byte for byte and no rank holds more than its frames.
// For a plain file that file is the stream (under a temporary name until
// every rank is done); a pipe or socket is fed by rank 0 from a scratch
// file once every rank is done, in stream order.
int streamSplit(const RenderJob& job, PreparedJob& p, const JobSplit& split, const EpiStreamHeader& header) {
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
  MpiSession& mpi = *p.mpi;
  const ShearingCamera& cam = *p.camera;
  const std::string& endpoint = job.stream;
  const bool file = isPlainFile(endpoint);
  const std::string path = file ? partName(endpoint) : ".mvr_split_stream";
  const uint64_t bytes = header.recordOffset(cam.rows(), 0);
  Stopwatch watch;
  std::optional<SharedFile> records;
  std::optional<FdStreamBuf> pipe;  // rank 0's, connected before anything is rendered
  inPhase(&mpi, [&] {
    try {
      records.emplace(path, file ? SharedFile::Lifetime::Kept : SharedFile::Lifetime::Scratch);
    } catch (const Error&) {
      if (file) fail(endpoint, "cannot create the stream file");
      throw;
    }
    if (!file && mpi.rank() == 0) pipe.emplace(openForWriting(endpoint));
  });
  try {
    EpiRecordSink sink(header, [&](uint64_t at, std::span<const std::byte> b) { records->write(at, b); });
    SplitOutput out(mpi, cam, split,
                    SplitOutputSpec{.rendered = p.renderer->order(), .toViews = false, .type = header.pixelType(),
                                    .dir = ".", .reorder = p.reorder},
                    sink, nullptr);
    FrameChain chain({.sink = &out.sink()}, p.chainSpec(job));
    inPhase(&mpi, [&] {
      if (mpi.rank() != 0) return;
      const std::vector<uint8_t> head = header.encode();
      records->write(0, std::as_bytes(std::span(head)));
    });
    RenderStats stats;
    renderPhase(&mpi, *p.renderer, rendersOf(*p.renderCamera, &out, job.aa), chain.entry(),
                long(cam.views()) * cam.rows(), p.renderer->name(), stats);
    inPhase(&mpi, [&] { out.assemble(); });
    if (!file) inPhase(&mpi, [&] { if (pipe) relayStream(*records, bytes, *pipe, endpoint); });
    records.reset();  // collective; a kept file is complete
    if (file) inPhase(&mpi, [&] {
      if (mpi.rank() == 0) commitPart(endpoint);
    });
  } catch (...) {
    records.reset();  // every rank is here: phases end on every rank alike
    if (file && mpi.rank() == 0) removePart(endpoint);
    throw;
  }
  if (mpi.rank() == 0)
    std::fprintf(stderr, "mvr: streamed %d EPIs of %dx%d to %s in %.3f s with %d ranks\n", cam.height() * cam.rows(),
                 cam.width(), cam.views(), endpoint.c_str(), watch.seconds(), mpi.ranks());
  return 0;
}

}  // namespace

int writeStream(const RenderJob& job, PreparedJob& p, const StreamedFrames& frames) {
  if (!p.mpi) return streamTo(job, p, frames);
  const JobSplit split = splitFor(job, p);
  const EpiStreamHeader header = streamHeader(*p.camera, job.type, p.imagePlaneZ);
  // The grid's views meet in a scratch file; a pipe's records in another.
  const uint64_t streamBytes = header.recordOffset(job.rows, 0);
  checkScratchFits((p.reorders && split.gridBegin() < job.rows ? p.rowBytes * job.rows : 0) +
                       (isPlainFile(job.stream) ? 0 : streamBytes),
                   ".");
  if (!p.mpi->agree("")) throw JobFailed{};
  return streamSplit(job, p, split, header);
}

}  // namespace mvr::app
