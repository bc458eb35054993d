#include "mvr/frames/supersampling.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr {

ShearingCamera supersampledCamera(const ShearingCamera& camera, const Supersampling& aa) {
  const int s = aa.spatial, p = aa.views;
  if (s < 1 || p < 1) fail("anti-aliasing", "sample counts must be positive");
  if (p > 1 && camera.views() < 2) fail("anti-aliasing", "perspective samples need at least 2 views");
  if (long(camera.width()) * s > Limits::kMaxSide || long(camera.height()) * s > Limits::kMaxSide)
    fail("anti-aliasing", std::to_string(s) + "x" + std::to_string(s) + " samples make the image wider than " +
                              std::to_string(Limits::kMaxSide) + " pixels");
  if (long(camera.views()) * p > Limits::kMaxViews)
    fail("anti-aliasing", std::to_string(p) + " samples per view make more than " +
                              std::to_string(Limits::kMaxViews) + " views");
  CameraSpec spec = camera.spec();
  spec.planeHeight = camera.planeHeight();  // the same rectangle, whatever the rounding
  // The first and last samples lie (P - 1) s / (2P) outside the end views.
  const double reach = 0.5 * camera.viewSpacing() * (p - 1) / p;
  spec.trackLeft -= reach;
  spec.trackRight += reach;
  return ShearingCamera(spec, camera.width() * s, camera.height() * s, camera.views() * p, camera.rows());
}

RenderShare sampleShare(const RenderShare& share, const Supersampling& aa) {
  auto times = [](IndexRange r, int k) { return IndexRange{r.begin * k, r.end * k}; };
  return {share.rows, times(share.scanlines, aa.spatial), times(share.views, aa.views)};
}

namespace {

// Adds row y of in, premultiplied and in linear light, into out: input
// pixels s x .. s x + s - 1 land in output pixel x. The hot loop of
// anti-aliasing: the decode is chosen once per row, not per sample.
template <class Decode>
void addRowAs(const Image& in, int y, int s, float* out, Decode&& decode) {
  const uint8_t* bytes = in.row(y);
  const int outWidth = in.width / s;
  for (int x = 0, i = 0; x < outWidth; ++x) {
    float* o = out + size_t(x) * 4;
    for (int k = 0; k < s; ++k, ++i) {
      float c[4];
      decode(bytes, i, c);
      o[0] += c[0] * c[3];
      o[1] += c[1] * c[3];
      o[2] += c[2] * c[3];
      o[3] += c[3];
    }
  }
}

void addRow(const Image& in, int y, int s, float* out) {
  switch (in.type) {
    case PixelType::F32:
      addRowAs(in, y, s, out, [](const uint8_t* b, int i, float* c) { std::memcpy(c, b + size_t(i) * 16, 16); });
      break;
    case PixelType::Srgb8: {
      const std::array<float, 256>& srgb = detail::srgb8Table().decoded;
      addRowAs(in, y, s, out, [&srgb](const uint8_t* b, int i, float* c) {
        const uint8_t* p = b + size_t(i) * 4;
        c[0] = srgb[p[0]], c[1] = srgb[p[1]], c[2] = srgb[p[2]], c[3] = p[3] * (1.0f / 255);
      });
      break;
    }
    default:
      addRowAs(in, y, s, out, [](const uint8_t* b, int i, float* c) {
        const uint8_t* p = b + size_t(i) * 4;
        for (int j = 0; j < 4; ++j) c[j] = p[j] * (1.0f / 255);
      });
  }
}

// body(y) for every row y in [0, rows), in blocks of rows on the pool.
template <class Body>
void forRowBlocks(int rows, Body&& body) {
  constexpr int kRowsPerTask = 16;
  parallelFor(0, (rows + kRowsPerTask - 1) / kRowsPerTask, [&](int task) {
    const int end = std::min(rows, (task + 1) * kRowsPerTask);
    for (int y = task * kRowsPerTask; y < end; ++y) body(y);
  });
}

}  // namespace

SupersampleSink::SupersampleSink(FrameSink& inner, const Supersampling& aa, int width, int height, int views)
    : inner_(inner), aa_(aa), width_(width), height_(height), views_(views) {}

SupersampleSink::Pending& SupersampleSink::pending(std::map<std::pair<int, int>, Pending>& frames, int row,
                                                   int index, size_t pixels) {
  Pending& p = frames[{row, index}];
  if (p.sums.empty()) p.sums.assign(pixels * 4, 0.0f);
  return p;
}

void SupersampleSink::accumulate(Pending& p, const Image& in, int outWidth, int outHeight, int rowFactor) {
  const int s = aa_.spatial;
  if (in.width != outWidth * s || in.height != outHeight * rowFactor)
    throw std::logic_error("supersampled frame of the wrong size");
  // Output rows are independent: each takes rowFactor input rows.
  forRowBlocks(outHeight, [&](int y) {
    float* out = p.sums.data() + size_t(y) * outWidth * 4;
    for (int k = 0; k < rowFactor; ++k) addRow(in, y * rowFactor + k, s, out);
  });
  ++p.frames;
}

Image SupersampleSink::resolve(const Pending& p, int outWidth, int outHeight, PixelType type) const {
  Image out(outWidth, outHeight, type);
  const float samples = float(aa_.samplesPerPixel());
  forRowBlocks(outHeight, [&](int y) {
    for (int x = 0; x < outWidth; ++x) {
      const float* c = p.sums.data() + (size_t(y) * outWidth + x) * 4;
      const glm::vec3 rgb = c[3] > 0.0f ? glm::vec3(c[0], c[1], c[2]) / c[3] : glm::vec3(0.0f);
      out.setLinear(x, y, glm::vec4(rgb, c[3] / samples));
    }
  });
  return out;
}

std::optional<Image> SupersampleSink::add(std::map<std::pair<int, int>, Pending>& frames, int row, int index,
                                          const Image& in, int outHeight, int rowFactor, int needed) {
  Pending& p = pending(frames, row, index, size_t(width_) * outHeight);
  accumulate(p, in, width_, outHeight, rowFactor);
  if (p.frames < needed) return std::nullopt;
  Image out = resolve(p, width_, outHeight, in.type);
  frames.erase({row, index});
  return out;
}

void SupersampleSink::putView(int row, int view, const Image& image) {
  // A view's P sample views each bring S x S samples per pixel.
  const int index = view / aa_.views;
  if (auto out = add(viewFrames_, row, index, image, height_, aa_.spatial, aa_.views)) inner_.putView(row, index, *out);
}

void SupersampleSink::putEpi(int row, int scanline, const Image& epi) {
  // An EPI's S sample EPIs each bring S x P samples per pixel (x by views).
  const int index = scanline / aa_.spatial;
  if (auto out = add(epiFrames_, row, index, epi, views_, aa_.views, aa_.spatial)) inner_.putEpi(row, index, *out);
}

void SupersampleSink::finish() {
  if (!viewFrames_.empty() || !epiFrames_.empty())
    throw std::logic_error("supersampling: frames still wait for samples at finish");
  inner_.finish();
}

std::string describe(const Supersampling& aa) {
  return std::to_string(aa.spatial) + "x" + std::to_string(aa.spatial) + " samples per pixel, " +
         std::to_string(aa.views) + " per view (box filter)";
}

}  // namespace mvr
