#pragma once
// A video read back as a player reads it, with FFmpeg's libraries (the
// tests that write quilt and native videos link them).
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <filesystem>

#include "mvr/image.h"

namespace mvr::test {

// What a player reads: the frame count, the size, the pixel format, and the
// last frame in RGBA.
struct VideoRead {
  int frames = 0, width = 0, height = 0;
  AVPixelFormat format = AV_PIX_FMT_NONE;
  AVCodecID codec = AV_CODEC_ID_NONE;
  Image last;
};

inline VideoRead readVideo(const std::filesystem::path& path) {
  VideoRead v;
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) return v;
  avformat_find_stream_info(format, nullptr);
  const AVCodecParameters* par = format->streams[0]->codecpar;
  v.width = par->width, v.height = par->height, v.format = AVPixelFormat(par->format), v.codec = par->codec_id;
  const AVCodec* codec = avcodec_find_decoder(par->codec_id);
  AVCodecContext* decoder = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(decoder, par);
  avcodec_open2(decoder, codec, nullptr);
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  auto drain = [&] {
    while (avcodec_receive_frame(decoder, frame) == 0) {
      ++v.frames;
      v.last = Image(frame->width, frame->height, PixelType::U8);
      SwsContext* rgb = sws_getContext(frame->width, frame->height, AVPixelFormat(frame->format), frame->width,
                                       frame->height, AV_PIX_FMT_RGBA, SWS_BICUBIC, nullptr, nullptr, nullptr);
      sws_setColorspaceDetails(rgb, sws_getCoefficients(SWS_CS_ITU709), 0, sws_getCoefficients(SWS_CS_ITU709), 1, 0,
                               1 << 16, 1 << 16);
      uint8_t* dst[1] = {v.last.bytes.data()};
      const int stride[1] = {4 * frame->width};
      sws_scale(rgb, frame->data, frame->linesize, 0, frame->height, dst, stride);
      sws_freeContext(rgb);
    }
  };
  while (av_read_frame(format, packet) >= 0) {
    avcodec_send_packet(decoder, packet);
    av_packet_unref(packet);
    drain();
  }
  avcodec_send_packet(decoder, nullptr);
  drain();
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&decoder);
  avformat_close_input(&format);
  return v;
}

}  // namespace mvr::test
