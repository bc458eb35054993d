#pragma once
// Image comparison: per image PSNR, SSIM, largest channel error, the
// fraction of identical pixels and the coverage difference -- the numbers
// behind every MVR-vs-SVR claim.
//
// SSIM (Wang, Bovik, Sheikh and Simoncelli 2004) on luma (Rec. 601
// weights) with an 11 x 11 Gaussian window of sigma 1.5, C1 = (0.01)^2,
// C2 = (0.03)^2 for a range of 1, edges clamped, averaged over the image.
// Colour is compared as it shows over black: in linear light times alpha
// (files hold straight alpha), so a half-covered edge pixel counts half its
// colour, and an empty pixel's stored colour does not count.
// Coverage comes from alpha (renderers clear to alpha 0): a hole is a pixel
// the first image covers and the second leaves empty; an extra pixel the
// reverse.
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
  double ssim = 1.0;             // mean structural similarity of luma
  long holes = 0;                // covered in the first image, empty in the second
  long extras = 0;               // empty in the first, covered in the second
};

// Throws mvr::Error when the sizes differ.
ImageDifference compareImages(const Image& a, const Image& b, const std::string& name = "");

// Mean SSIM of the two images' luma; throws when the sizes differ.
double ssim(const Image& a, const Image& b);

// Pairs view_* and epi_* images by name. Throws when a folder is missing,
// has no images, or the two sets have different names or sizes.
std::vector<ImageDifference> compareSets(const std::string& dirA, const std::string& dirB);

}  // namespace mvr
