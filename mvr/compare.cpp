#include "mvr/compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "mvr/error.h"

namespace mvr {
namespace fs = std::filesystem;

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
      glm::vec4 pa = a.pixel(x, y), pb = b.pixel(x, y);
      glm::vec4 diff = glm::abs(pa - pb);
      if (diff == glm::vec4(0)) ++identical;
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
  return d;
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
  std::vector<ImageDifference> out;
  for (const std::string& n : a)
    out.push_back(compareImages(readImage((fs::path(dirA) / n).string()),
                                readImage((fs::path(dirB) / n).string()), n));
  return out;
}

}  // namespace mvr
