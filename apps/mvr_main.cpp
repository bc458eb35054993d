// The `mvr` command line: info, render, compare (DESIGN.md's contract).
// Every user error is an mvr::Error caught here: one line, exit status 1.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "apps/args.h"
#include "apps/bench_command.h"
#include "apps/render_command.h"
#include "apps/viewer.h"
#include "mvr/error.h"
#include "mvr/gl/gl_context.h"
#include "mvr/io/compare.h"

namespace mvr::app {
namespace {

const char* const kUsage =
    "usage: mvr <command> [options]\n"
    "  info                       GL version and renderer per context platform\n"
    "  render [SCENE] [options]   render a view set (mvr render --help)\n"
    "  compare DIR_A DIR_B        per image PSNR / SSIM / max error / identical / holes\n"
    "  stream [SCENE] --to DEST   EPIs to a pipe, file or socket as they complete\n"
    "  view DIR|SCENE             look at views and EPIs (mvr view --help)\n"
    "  bench [SCENE] [options]    MVR against SVR, svr-layered, deferred (mvr bench --help)\n";

const char* const kCompareHelp =
    "usage: mvr compare DIR_A DIR_B [--json]\n"
    "Pairs view_* and epi_* images by name and prints, per image, PSNR (dB over\n"
    "RGB), SSIM (luma, 11x11 Gaussian window), the largest channel error (0..1),\n"
    "the fraction of identical pixels, and holes and extras: pixels that the\n"
    "first image covers and the second leaves empty (alpha 0), and the reverse.\n"
    "Exits non-zero when the sets differ in names or image sizes.\n";

const char* const kInfoHelp =
    "usage: mvr info\nTries each GL platform (egl, osmesa, glfw) and prints its GL version\n"
    "and renderer, or why it is unavailable.\n";

bool wantsHelp(int argc, char** argv) {
  for (int i = 2; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h") return true;
  return false;
}

int runInfo() {
  int available = 0;
  for (GlPlatform p : {GlPlatform::Egl, GlPlatform::OsMesa, GlPlatform::Glfw}) {
    try {
      auto ctx = GlContext::create(p);
      std::printf("%s\n", ctx->describe().c_str());
      ++available;
    } catch (const Error& e) {
      std::printf("%s: unavailable (%s)\n", glPlatformName(p), e.what());
    }
  }
  return available > 0 ? 0 : 1;
}

int runCompare(int argc, char** argv) {
  Args args(argc, argv, 2, {}, {"json"});
  if (args.positional().size() != 2) fail("compare", "needs two folders (see --help)");
  auto diffs = compareSets(args.positional()[0], args.positional()[1]);
  double worstPsnr = INFINITY, minIdentical = 1.0, maxError = 0.0, minSsim = 1.0;
  long holes = 0;
  for (const auto& d : diffs) {
    worstPsnr = std::min(worstPsnr, d.psnr);
    minIdentical = std::min(minIdentical, d.identicalFraction);
    maxError = std::max(maxError, d.maxError);
    minSsim = std::min(minSsim, d.ssim);
    holes += d.holes;
  }
  if (args.has("json")) {
    nlohmann::json j;
    j["images"] = nlohmann::json::array();
    for (const auto& d : diffs)
      j["images"].push_back({{"name", d.name}, {"psnr_db", std::isinf(d.psnr) ? -1.0 : d.psnr},
                             {"ssim", d.ssim}, {"max_error", d.maxError},
                             {"identical_fraction", d.identicalFraction}, {"holes", d.holes},
                             {"extras", d.extras}});
    j["min_psnr_db"] = std::isinf(worstPsnr) ? -1.0 : worstPsnr;  // -1: identical
    j["min_ssim"] = minSsim;
    j["min_identical_fraction"] = minIdentical;
    j["max_error"] = maxError;
    j["holes"] = holes;
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("%-28s %10s %8s %10s %10s %8s %8s\n", "image", "PSNR_dB", "SSIM", "max_err",
                "identical", "holes", "extras");
    for (const auto& d : diffs)
      std::printf("%-28s %10.2f %8.4f %10.4f %10.6f %8ld %8ld\n", d.name.c_str(), d.psnr, d.ssim,
                  d.maxError, d.identicalFraction, d.holes, d.extras);
    std::printf("%zu images: min PSNR %.2f dB, min SSIM %.4f, max error %.4f, min identical %.6f, "
                "%ld holes\n",
                diffs.size(), worstPsnr, minSsim, maxError, minIdentical, holes);
  }
  return 0;
}

int dispatch(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd == "info") {
    if (wantsHelp(argc, argv)) return std::fputs(kInfoHelp, stdout), 0;
    return runInfo();
  }
  if (cmd == "render") {
    if (wantsHelp(argc, argv)) return std::fputs(kRenderHelp, stdout), 0;
    return runRender(argc, argv);
  }
  if (cmd == "view") {
    if (wantsHelp(argc, argv)) return std::fputs(kViewHelp, stdout), 0;
    return runView(argc, argv);
  }
  if (cmd == "stream") {
    if (wantsHelp(argc, argv)) return std::fputs(kStreamHelp, stdout), 0;
    return runRender(argc, argv, true);
  }
  if (cmd == "bench") {
    if (wantsHelp(argc, argv)) return std::fputs(kBenchHelp, stdout), 0;
    return runBench(argc, argv);
  }
  if (cmd == "compare") {
    if (wantsHelp(argc, argv)) return std::fputs(kCompareHelp, stdout), 0;
    return runCompare(argc, argv);
  }
  fail("mvr", "unknown command '" + cmd + "' (expected info, render, stream, view, compare or bench)");
}

}  // namespace
}  // namespace mvr::app

int main(int argc, char** argv) {
  try {
    return mvr::app::dispatch(argc, argv);
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "mvr: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mvr: internal error: %s\n", e.what());
    return 3;
  }
}
