#pragma once
// Image comparison: per image PSNR, largest channel error and the fraction
// of identical pixels -- the numbers behind every MVR-vs-SVR claim.
#include <string>
#include <vector>

#include "mvr/image.h"

namespace mvr {

struct ImageDifference {
  std::string name;
  double psnr = 0;               // dB over RGB; infinity when identical
  double maxError = 0;           // largest channel difference, 0..1
  double identicalFraction = 0;  // pixels whose four channels all match
  double closeFraction = 0;      // pixels within one 8-bit step (1/255) in every channel
  long differingPixels = 0;
};

// Throws mvr::Error when the sizes differ.
ImageDifference compareImages(const Image& a, const Image& b, const std::string& name = "");

// Pairs view_* and epi_* images by name. Throws when a folder is missing,
// has no images, or the two sets have different names or sizes.
std::vector<ImageDifference> compareSets(const std::string& dirA, const std::string& dirB);

}  // namespace mvr
