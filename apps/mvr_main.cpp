// The `mvr` command line: info, render, stream, synthesize, view, compare,
// bench (docs/CLI.md has every option).
// Every user error is an mvr::Error caught here: one line, exit status 1.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/cli/cli.h"
#include "apps/bench/bench_command.h"
#include "apps/cli/job_split.h"
#include "apps/render/mpi_session.h"
#include "apps/live/live_command.h"
#include "apps/native/native_command.h"
#include "apps/render/render_command.h"
#include "apps/viewer/viewer.h"
#include "mvr/error.h"
#include "mvr/gl/gl_context.h"
#include "mvr/images/compare.h"

namespace mvr::app {
namespace {

const char* const kUsage =
    "Commands:\n"
    "  info                       GL version and renderer per context platform\n"
    "  render [SCENE] [options]   render a view set (mvr render --help)\n"
    "  compare DIR_A DIR_B        per image PSNR / SSIM / max error / identical / holes\n"
    "  stream [SCENE] --to DEST   EPIs to a pipe, file or socket as they complete\n"
    "  synthesize --from DIR      views from RGB-D references (mvr synthesize --help)\n"
    "  view DIR|SCENE             look at views and EPIs (mvr view --help)\n"
    "  native QUILT --calibration FILE --out FILE\n"
    "                             a quilt to a lenticular display's native image\n"
    "  live [SCENE|QUILT]         render into a quilt every frame, shown on the display (mvr live --help)\n"
    "  bench [SCENE] [options]    MVR against SVR, svr-layered, deferred (mvr bench --help)\n";

int runInfo(int argc, char** argv) {
  CLI::App app("Tries each GL platform (egl, osmesa, glfw) and prints its GL version and "
               "renderer, or why it is unavailable.",
               "mvr info");
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;
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
  CLI::App app("Pairs view_* and epi_* images by name and prints, per image, PSNR (dB over "
               "RGB), SSIM (luma, 11x11 Gaussian window), the largest channel error (0..1), the "
               "fraction of identical pixels, the fraction within one 8-bit step (what any GL "
               "promises two renderings of the same image), and holes and extras: pixels that the first image "
               "covers and the second leaves empty (alpha 0), and the reverse. Exits non-zero "
               "when the sets differ in names or image sizes.",
               "mvr compare");
  std::vector<std::string> dirs;
  bool json = false;
  app.add_option("DIR_A DIR_B", dirs, "the two sets")->required()->expected(2);
  app.add_flag("--json", json, "print JSON instead of a table");
  addThreadsOption(app);
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;
  auto diffs = compareSets(dirs[0], dirs[1]);
  double worstPsnr = INFINITY, minIdentical = 1.0, minClose = 1.0, maxError = 0.0, minSsim = 1.0;
  long holes = 0;
  for (const auto& d : diffs) {
    worstPsnr = std::min(worstPsnr, d.psnr);
    minIdentical = std::min(minIdentical, d.identicalFraction);
    minClose = std::min(minClose, d.closeFraction);
    maxError = std::max(maxError, d.maxError);
    minSsim = std::min(minSsim, d.ssim);
    holes += d.holes;
  }
  if (json) {
    nlohmann::json j;
    j["images"] = nlohmann::json::array();
    for (const auto& d : diffs)
      j["images"].push_back({{"name", d.name}, {"psnr_db", std::isinf(d.psnr) ? -1.0 : d.psnr},
                             {"ssim", d.ssim}, {"max_error", d.maxError},
                             {"identical_fraction", d.identicalFraction},
                             {"within_one_step_fraction", d.closeFraction}, {"holes", d.holes},
                             {"extras", d.extras}});
    j["min_psnr_db"] = std::isinf(worstPsnr) ? -1.0 : worstPsnr;  // -1: identical
    j["min_ssim"] = minSsim;
    j["min_identical_fraction"] = minIdentical;
    j["min_within_one_step_fraction"] = minClose;
    j["max_error"] = maxError;
    j["holes"] = holes;
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("%-28s %10s %8s %10s %10s %9s %8s %8s\n", "image", "PSNR_dB", "SSIM", "max_err",
                "identical", "one_step", "holes", "extras");
    for (const auto& d : diffs)
      std::printf("%-28s %10.2f %8.4f %10.4f %10.6f %9.6f %8ld %8ld\n", d.name.c_str(), d.psnr, d.ssim,
                  d.maxError, d.identicalFraction, d.closeFraction, d.holes, d.extras);
    std::printf("%zu images: min PSNR %.2f dB, min SSIM %.4f, max error %.4f, min identical %.6f, "
                "min within one 8-bit step %.6f, %ld holes\n",
                diffs.size(), worstPsnr, minSsim, maxError, minIdentical, minClose, holes);
  }
  return 0;
}

int dispatch(int argc, char** argv) {
  using Command = int (*)(int, char**);
  const std::map<std::string, Command> commands = {
      {"info", runInfo},
      {"render", runRender},
      {"stream", runStream},
      {"synthesize", runSynthesize},
      {"view", runView},
      {"native", runNative},
      {"live", runLive},
      {"compare", runCompare},
      {"bench", runBench}};
  if (argc < 2) {
    std::fprintf(stderr, "usage: mvr <command> [options]\n%s", kUsage);
    return 2;
  }
  if (commands.count(argv[1])) return commands.at(argv[1])(argc, argv);
  // No command: the top level's help, --version, or a one-line error.
  CLI::App app("Multiple viewpoint rendering for 3D displays.", "mvr");
  app.set_version_flag("--version", std::string("mvr ") + MVR_VERSION);
  app.footer(kUsage);
  std::string command;
  app.add_option("COMMAND", command, "info, render, stream, synthesize, view, native, live, compare or bench")->required();
  app.allow_extras();
  if (auto exit = parseCommandLine(app, argc, argv)) return *exit;
  // main prefixes "mvr: ": the error names the command, not the program again.
  throw Error("unknown command '" + command + "' (expected info, render, stream, synthesize, view, native, live, compare or bench)");
}

}  // namespace
}  // namespace mvr::app

namespace {

// Prints an error that ends the program. In a split job, an error before
// the ranks first agreed is a set-up error the others wait to hear of: the
// ranks agree on it, and only the lowest failing rank prints.
int reportError(const std::string& message, int code) {
  using mvr::app::MpiSession;
  if (MpiSession* mpi = MpiSession::current(); mpi && !mpi->agreedOnce()) {
    mpi->agree(message);
    return code;
  }
  std::fprintf(stderr, "mvr: %s\n", message.c_str());
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  // Under mpirun the image-set commands split the job over the ranks
  // (apps/cli/job_split.h); nothing else starts MPI.
  std::optional<mvr::app::MpiSession> mpi;
  const bool renders = argc > 1 && (std::string(argv[1]) == "render" || std::string(argv[1]) == "synthesize" ||
                                    std::string(argv[1]) == "stream");
  try {
    if (renders && mvr::app::launchedRanks() > 1) mpi.emplace(argc, argv);
    return mvr::app::dispatch(argc, argv);
  } catch (const mvr::app::JobFailed&) {
    return 1;  // another rank failed and said why
  } catch (const mvr::Error& e) {
    return reportError(e.what(), 1);
  } catch (const std::exception& e) {
    return reportError(std::string("internal error: ") + e.what(), 3);
  }
}
