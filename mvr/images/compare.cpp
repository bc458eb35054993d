#include "mvr/images/compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "mvr/error.h"
#include "mvr/images/image_file.h"
#include "mvr/parallel.h"

namespace mvr {
namespace fs = std::filesystem;

namespace {

// A pixel as it shows over black, in the image's stored encoding: colour
// times alpha in linear light (alpha straight in the file), alpha itself.
// Where alpha is 0 or 1 that is the stored pixel, rgb 0 where empty; a
// partly covered edge counts by how much of its colour shows.
glm::vec4 shown(const Image& img, int x, int y) {
  const glm::vec4 p = img.pixel(x, y);
  if (p.a >= 1.0f) return p;
  if (img.type != PixelType::Srgb8) return glm::vec4(glm::vec3(p) * p.a, p.a);
  uint8_t rgba[4];
  encodeSrgb8(glm::vec4(glm::vec3(img.linear(x, y)) * p.a, p.a), rgba);
  return glm::vec4(rgba[0], rgba[1], rgba[2], rgba[3]) / 255.0f;
}

}  // namespace

ImageDifference compareImages(const Image& a, const Image& b, const std::string& name) {
  if (a.width != b.width || a.height != b.height)
    fail(name.empty() ? "compare" : name,
         "size mismatch " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
             std::to_string(b.width) + "x" + std::to_string(b.height));
  ImageDifference d;
  d.name = name;
  double sumSq = 0;
  long identical = 0, close = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      glm::vec4 pa = shown(a, x, y), pb = shown(b, x, y);
      glm::vec4 diff = glm::abs(pa - pb);
      if (diff == glm::vec4(0)) ++identical;
      if (pa.a > 0.0f && pb.a == 0.0f) ++d.holes;
      if (pa.a == 0.0f && pb.a > 0.0f) ++d.extras;
      if (glm::all(glm::lessThanEqual(diff, glm::vec4(1.0f / 255.0f + 1e-6f)))) ++close;
      d.maxError = std::max<double>(d.maxError, std::max({diff.r, diff.g, diff.b, diff.a}));
      sumSq += double(diff.r) * diff.r + double(diff.g) * diff.g + double(diff.b) * diff.b;
    }
  }
  const double n = double(a.width) * a.height;
  const double mse = sumSq / (3.0 * n);
  d.psnr = mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
  d.identicalFraction = identical / n;
  d.closeFraction = close / n;
  d.differingPixels = long(n) - identical;
  d.ssim = ssim(a, b);
  return d;
}

namespace {

// A separable Gaussian blur (11 taps, sigma 1.5) with clamped edges.
std::vector<double> blur(const std::vector<double>& in, int w, int h) {
  constexpr int r = 5;
  double weights[2 * r + 1], sum = 0;
  for (int i = -r; i <= r; ++i) sum += weights[i + r] = std::exp(-i * i / (2 * 1.5 * 1.5));
  for (double& k : weights) k /= sum;
  std::vector<double> tmp(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double acc = 0;
      for (int i = -r; i <= r; ++i) acc += weights[i + r] * in[size_t(y) * w + std::clamp(x + i, 0, w - 1)];
      tmp[size_t(y) * w + x] = acc;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double acc = 0;
      for (int i = -r; i <= r; ++i) acc += weights[i + r] * tmp[size_t(std::clamp(y + i, 0, h - 1)) * w + x];
      out[size_t(y) * w + x] = acc;
    }
  return out;
}

std::vector<double> luma(const Image& img) {
  std::vector<double> y(size_t(img.width) * img.height);
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i) {
      const glm::vec4 p = shown(img, i, j);
      y[size_t(j) * img.width + i] = 0.299 * p.r + 0.587 * p.g + 0.114 * p.b;
    }
  return y;
}

}  // namespace

double ssim(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) fail("ssim", "size mismatch");
  const int w = a.width, h = a.height;
  const std::vector<double> x = luma(a), y = luma(b);
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (size_t i = 0; i < x.size(); ++i) xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
  const std::vector<double> mx = blur(x, w, h), my = blur(y, w, h);
  const std::vector<double> sxx = blur(xx, w, h), syy = blur(yy, w, h), sxy = blur(xy, w, h);
  constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  double total = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cxy = sxy[i] - mx[i] * my[i];
    total += (2 * mx[i] * my[i] + c1) * (2 * cxy + c2) /
             ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
  }
  return total / double(x.size());
}

namespace {

std::vector<std::string> imageNames(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(dir, "no such folder");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string n = entry.path().filename().string();
    if ((n.rfind("view_", 0) == 0 || n.rfind("epi_", 0) == 0) && n.find(".part") == std::string::npos)
      names.push_back(n);
  }
  std::sort(names.begin(), names.end());
  if (names.empty()) fail(dir, "no view_* or epi_* images");
  return names;
}

}  // namespace

std::vector<ImageDifference> compareSets(const std::string& dirA, const std::string& dirB) {
  std::vector<std::string> a = imageNames(dirA), b = imageNames(dirB);
  if (a != b)
    fail(dirB, "image names differ from " + dirA + " (" + std::to_string(a.size()) + " vs " +
                   std::to_string(b.size()) + " images)");
  // Every core reads, decodes and compares (SSIM's windows dominate).
  std::vector<ImageDifference> out(a.size());
  parallelFor(0, int(a.size()), [&](int i) {
    const std::string& n = a[size_t(i)];
    out[size_t(i)] = compareImages(readImage((fs::path(dirA) / n).string()),
                                   readImage((fs::path(dirB) / n).string()), n);
  });
  return out;
}

}  // namespace mvr
