// mvr-encode OUT WIDTH HEIGHT FPS CRF FRAMES [yuv420p|yuv444p]: a quilt
// video's encoder, in a process of its own (mvr/images/quilt_video.h starts
// it). Reads FRAMES frames of WIDTH x HEIGHT sRGB-encoded RGBA8 (rows top
// first) from stdin and writes OUT, an MP4 of H.264 in yuv420p (BT.709
// limited range, as players expect; yuv444p for a panel's native image,
// whose neighbouring subpixels belong to different views), through
// FFmpeg's libraries. OUT appears only once every frame is
// in it. Errors: one line on stderr, exit 1.
//
// Why a process: FFmpeg's libraries (and their codecs' own, some hundred)
// would load at every start of mvr, and here the encoding runs beside the
// rendering on its own cores, fed through a pipe.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "mvr-encode: %s\n", what.c_str());
  std::exit(1);
}

std::string averror(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

bool readFully(int fd, uint8_t* to, size_t n) {
  while (n > 0) {
    const ssize_t got = read(fd, to, n);
    if (got == 0) return false;
    if (got < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    to += got, n -= size_t(got);
  }
  return true;
}

class Encoder {
 public:
  Encoder(const std::string& path, int w, int h, double fps, int crf, AVPixelFormat yuv) : path_(path), w_(w), h_(h) {
    if (avformat_alloc_output_context2(&format_, nullptr, "mp4", path.c_str()) < 0 || !format_)
      die(path + ": cannot set up an MP4 file");
    const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
    if (!codec) codec = avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!codec) die("this FFmpeg has no H.264 encoder");
    stream_ = avformat_new_stream(format_, nullptr);
    codec_ = avcodec_alloc_context3(codec);
    if (!stream_ || !codec_) die("out of memory");
    codec_->width = w, codec_->height = h;
    codec_->pix_fmt = yuv;
    codec_->framerate = av_d2q(fps, 100000);
    codec_->time_base = av_inv_q(codec_->framerate);
    codec_->color_range = AVCOL_RANGE_MPEG;
    codec_->colorspace = AVCOL_SPC_BT709;
    codec_->color_primaries = AVCOL_PRI_BT709;
    codec_->color_trc = AVCOL_TRC_IEC61966_2_1;  // the quilt's sRGB values
    if (format_->oformat->flags & AVFMT_GLOBALHEADER) codec_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    av_opt_set(codec_->priv_data, "crf", std::to_string(crf).c_str(), 0);
    // superfast: the encoder shares the cores with the renderer; on 2 cores
    // a 12-frame Portrait turntable took 5.8 s at medium, 4.4 s at veryfast
    // and 3.7 s here (the PNG quilts alone: 2.1 s). crf holds the quality;
    // the file is larger.
    av_opt_set(codec_->priv_data, "preset", "superfast", 0);
    // x264's own choice (1.5 threads a core) by the machine's cores, not by
    // those this process is bound to: the thread count shapes the bytes,
    // and a rank of an MPI job, bound to its share, must write one
    // process's file (x264 is deterministic for a given count).
    codec_->thread_count = std::max(1, int(std::thread::hardware_concurrency()) * 3 / 2);
    if (const int e = avcodec_open2(codec_, codec, nullptr); e < 0) die("cannot open the H.264 encoder: " + averror(e));
    if (avcodec_parameters_from_context(stream_->codecpar, codec_) < 0) die("cannot describe the video stream");
    stream_->time_base = codec_->time_base;
    stream_->avg_frame_rate = codec_->framerate;
    if (const int e = avio_open(&format_->pb, path.c_str(), AVIO_FLAG_WRITE); e < 0)
      die(path + ": cannot write: " + averror(e));
    if (const int e = avformat_write_header(format_, nullptr); e < 0) die(path + ": cannot write: " + averror(e));
    frame_ = av_frame_alloc();
    packet_ = av_packet_alloc();
    if (!frame_ || !packet_) die("out of memory");
    frame_->format = yuv, frame_->width = w, frame_->height = h;
    frame_->color_range = AVCOL_RANGE_MPEG, frame_->colorspace = AVCOL_SPC_BT709;
    if (av_frame_get_buffer(frame_, 0) < 0) die("out of memory");
    scale_ = sws_getContext(w, h, AV_PIX_FMT_RGBA, w, h, yuv, SWS_BICUBIC | SWS_ACCURATE_RND, nullptr, nullptr, nullptr);
    if (!scale_) die("cannot convert RGBA to YUV");
    // Full-range RGB in, BT.709 limited-range YUV out.
    sws_setColorspaceDetails(scale_, sws_getCoefficients(SWS_CS_ITU709), 1, sws_getCoefficients(SWS_CS_ITU709), 0, 0,
                             1 << 16, 1 << 16);
  }

  // Everything given back: a leak checker (the sanitizer builds) fails a
  // process that exits holding memory.
  ~Encoder() {
    sws_freeContext(scale_);
    av_packet_free(&packet_);
    av_frame_free(&frame_);
    avcodec_free_context(&codec_);
    if (format_ && format_->pb) avio_closep(&format_->pb);
    avformat_free_context(format_);
  }
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;

  void add(const uint8_t* rgba, int64_t index) {
    if (av_frame_make_writable(frame_) < 0) die("out of memory");
    const uint8_t* src[1] = {rgba};
    const int stride[1] = {4 * w_};
    sws_scale(scale_, src, stride, 0, h_, frame_->data, frame_->linesize);
    frame_->pts = index;
    send(frame_);
  }

  void finish() {
    send(nullptr);
    if (const int e = av_write_trailer(format_); e < 0) die(path_ + ": cannot write: " + averror(e));
    if (const int e = avio_closep(&format_->pb); e < 0) die(path_ + ": cannot write: " + averror(e));
  }

 private:
  void send(const AVFrame* frame) {
    if (const int e = avcodec_send_frame(codec_, frame); e < 0) die("encoding failed: " + averror(e));
    for (;;) {
      const int e = avcodec_receive_packet(codec_, packet_);
      if (e == AVERROR(EAGAIN) || e == AVERROR_EOF) return;
      if (e < 0) die("encoding failed: " + averror(e));
      av_packet_rescale_ts(packet_, codec_->time_base, stream_->time_base);
      packet_->stream_index = stream_->index;
      if (const int w = av_interleaved_write_frame(format_, packet_); w < 0) die(path_ + ": cannot write: " + averror(w));
    }
  }

  std::string path_;
  int w_, h_;
  AVFormatContext* format_ = nullptr;
  AVStream* stream_ = nullptr;
  AVCodecContext* codec_ = nullptr;
  AVFrame* frame_ = nullptr;
  AVPacket* packet_ = nullptr;
  SwsContext* scale_ = nullptr;
};

long number(const char* text, const char* what, long lo, long hi) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (!*text || *end || v < lo || v > hi) die(std::string(what) + " '" + text + "' is not a number in range");
  return v;
}

}  // namespace

// The encoder is one serial job beside the renderers: started by a rank
// that mpirun bound to its share of the cores, it may still run on any,
// as the cores the other ranks leave idle. Where a cpuset forbids it, it
// keeps the cores it has.
static void takeEveryCore() {
  cpu_set_t all;
  CPU_ZERO(&all);
  for (int c = 0; c < int(std::thread::hardware_concurrency()) && c < CPU_SETSIZE; ++c) CPU_SET(c, &all);
  sched_setaffinity(0, sizeof all, &all);
}

int main(int argc, char** argv) {
  if (argc != 7 && argc != 8)
    die("usage: mvr-encode OUT WIDTH HEIGHT FPS CRF FRAMES [yuv420p|yuv444p] (frames of RGBA8 on stdin)");
  const std::string chroma = argc == 8 ? argv[7] : "yuv420p";
  if (chroma != "yuv420p" && chroma != "yuv444p") die("chroma '" + chroma + "' is not yuv420p or yuv444p");
  const AVPixelFormat yuv = chroma == "yuv444p" ? AV_PIX_FMT_YUV444P : AV_PIX_FMT_YUV420P;
  const std::string out = argv[1];
  const int w = int(number(argv[2], "width", 2, 16384)), h = int(number(argv[3], "height", 2, 16384));
  char* end = nullptr;
  const double fps = std::strtod(argv[4], &end);
  if (*end || !(fps > 0.0 && fps <= 1000.0)) die(std::string("fps '") + argv[4] + "' is not in (0, 1000]");
  const int crf = int(number(argv[5], "crf", 0, 51));
  const long frames = number(argv[6], "frames", 1, 1000000);
  if (yuv == AV_PIX_FMT_YUV420P && (w % 2 || h % 2)) die("yuv420p needs an even width and height, not " + std::to_string(w) + "x" + std::to_string(h));
  av_log_set_level(AV_LOG_ERROR);
  takeEveryCore();
  const std::string part = out + ".part";
  {
    Encoder encoder(part, w, h, fps, crf, yuv);
    std::vector<uint8_t> rgba(size_t(w) * h * 4);
    for (long k = 0; k < frames; ++k) {
      if (!readFully(STDIN_FILENO, rgba.data(), rgba.size())) {
        std::remove(part.c_str());
        die("the input ended after " + std::to_string(k) + " of " + std::to_string(frames) + " frames");
      }
      encoder.add(rgba.data(), k);
    }
    encoder.finish();
  }
  if (std::rename(part.c_str(), out.c_str()) != 0) {
    std::remove(part.c_str());
    die(out + ": cannot write: " + std::strerror(errno));
  }
  return 0;
}
