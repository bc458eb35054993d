#include "apps/bench_command.h"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "apps/args.h"
#include "apps/render_command.h"
#include "apps/sample_sink.h"
#include "apps/teacup.h"
#include "mvr/compare.h"
#include "mvr/error.h"
#include "mvr/gl_context.h"
#include "mvr/progress.h"
#include "mvr/scene_io.h"

namespace mvr::app {

const char* const kBenchHelp =
    "usage: mvr bench [SCENE] [options]\n"
    "Renders one scene with several back ends in one process and GL context and\n"
    "prints time per view, speed-up against svr and svr-layered, and error\n"
    "against svr (min PSNR, min identical-pixel fraction over sampled views).\n"
    "  --teacup N          use the procedural teacup at about N triangles\n"
    "  --views LIST        view counts, e.g. 1,10,100 (default 100)\n"
    "  --size LIST         image sizes, e.g. 160x140,640x480 (default 160x140)\n"
    "  --backends LIST     default svr,svr-layered,deferred,mvr:quad,mvr:strip,\n"
    "                      mvr:exact,mvr:cpu\n"
    "  --repeat R          best of R runs (default 1)\n"
    "  --error-views K     views compared against svr (default 8)\n"
    "  --json FILE         also write the results as JSON\n"
    "  --gl egl|osmesa     GL platform\n";

namespace {

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

BackendChoice parseBackend(const std::string& s) {
  auto colon = s.find(':');
  if (colon == std::string::npos) return {s, "strip"};
  return {s.substr(0, colon), s.substr(colon + 1)};
}

struct Result {
  std::string backend;
  double seconds = INFINITY;
  RenderStats stats;
  std::map<int, Image> samples;
};

Result measure(Renderer& renderer, const std::string& label, const ShearingCamera& cam,
               PixelType type, int repeat, const std::vector<int>& sampled) {
  Result r;
  r.backend = label;
  for (int k = 0; k < repeat; ++k) {
    SampleSink sink(sampled, cam.width(), cam.height(), type);
    RenderStats stats;
    Stopwatch watch;
    renderer.render(cam, sink, stats);
    const double s = watch.seconds();
    if (s < r.seconds) {
      r.seconds = s;
      r.stats = stats;
      r.samples = sink.samples();
    }
  }
  return r;
}

void errorAgainst(const Result& ref, const Result& r, double& psnr, double& identical) {
  psnr = INFINITY;
  identical = 1.0;
  for (const auto& [view, img] : r.samples) {
    ImageDifference d = compareImages(ref.samples.at(view), img);
    psnr = std::min(psnr, d.psnr);
    identical = std::min(identical, d.identicalFraction);
  }
}

}  // namespace

int runBench(int argc, char** argv) {
  Args args(argc, argv, 2,
            {"teacup", "views", "size", "backends", "repeat", "error-views", "json", "gl"}, {});
  setProgressEnabled(false);
  Scene scene;
  std::string sceneName;
  if (args.has("teacup")) {
    const int n = args.getInt("teacup", 4000, 100, 10000000);
    scene = makeTeacup(n);
    scene.lights = {Light{Light::Type::Directional, glm::normalize(glm::vec3(-0.4f, -0.6f, -1.0f)),
                          glm::vec3(0.85f)}};
    sceneName = "teacup(" + std::to_string(n) + ")";
  } else {
    sceneName = args.positional().empty() ? defaultScenePath() : args.positional()[0];
    scene = loadScene(sceneName);
  }
  std::vector<int> viewCounts;
  for (const std::string& v : splitList(args.get("views", "100"))) {
    char* end = nullptr;
    long n = std::strtol(v.c_str(), &end, 10);
    if (*end || n < 1 || n > 65536) fail("--views", "'" + v + "' is not a view count 1..65536");
    viewCounts.push_back(int(n));
  }
  std::vector<std::pair<int, int>> sizes;
  for (const std::string& s : splitList(args.get("size", "160x140"))) {
    int w = 0, h = 0;
    if (std::sscanf(s.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
      fail("--size", "'" + s + "' is not WxH");
    sizes.emplace_back(w, h);
  }
  const auto labels =
      splitList(args.get("backends", "svr,svr-layered,deferred,mvr:quad,mvr:strip,mvr:exact,mvr:cpu"));
  const int repeat = args.getInt("repeat", 1, 1, 100);
  const int errorViews = args.getInt("error-views", 8, 1, 1000);

  auto context = GlContext::create(parseGlPlatform(args.get("gl", "auto")));
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (const std::string& l : labels) renderers.push_back(makeRenderer(parseBackend(l), scene, PixelType::U8));

  std::printf("# mvr bench: %s, %zu triangles\n# GL: %s\n# CPU: %s, %u threads\n", sceneName.c_str(),
              scene.triangleCount(), context->describe().c_str(), cpuModel().c_str(),
              std::thread::hardware_concurrency());
  std::printf("%-9s %6s %-13s %10s %10s %8s %9s %8s %10s %10s\n", "size", "views", "backend",
              "total_s", "ms/view", "x_svr", "x_layered", "PSNR_dB", "identical", "slices");
  {
    // Warm-up: first use compiles shaders and faults in buffers.
    ShearingCamera warm(cameraFor(scene, sizes[0].first, sizes[0].second), sizes[0].first,
                        sizes[0].second, 2);
    for (auto& r : renderers) {
      NullSink sink;
      RenderStats stats;
      r->render(warm, sink, stats);
    }
  }
  nlohmann::json records = nlohmann::json::array();
  for (auto [w, h] : sizes) {
    for (int n : viewCounts) {
      ShearingCamera cam(cameraFor(scene, w, h), w, h, n);
      const std::vector<int> sampled = spreadViews(n, errorViews);
      std::vector<Result> results;
      for (size_t k = 0; k < renderers.size(); ++k)
        results.push_back(measure(*renderers[k], labels[k], cam, PixelType::U8, repeat, sampled));
      const Result* svr = nullptr;
      const Result* layered = nullptr;
      for (const Result& r : results) {
        if (r.backend == "svr") svr = &r;
        if (r.backend == "svr-layered") layered = &r;
      }
      for (const Result& r : results) {
        double psnr = NAN, identical = NAN;
        if (svr) errorAgainst(*svr, r, psnr, identical);
        const double xSvr = svr ? svr->seconds / r.seconds : NAN;
        const double xLayered = layered ? layered->seconds / r.seconds : NAN;
        const double slices = r.stats.counters.count("slices") ? r.stats.counters.at("slices") : 0;
        char size[32];
        std::snprintf(size, sizeof size, "%dx%d", w, h);
        std::printf("%-9s %6d %-13s %10.4f %10.4f %8.2f %9.2f %8.2f %10.6f %10.0f\n", size, n,
                    r.backend.c_str(), r.seconds, 1e3 * r.seconds / n, xSvr, xLayered,
                    std::isinf(psnr) ? 99.99 : psnr, identical, slices);
        records.push_back({{"scene", sceneName},
                           {"triangles", scene.triangleCount()},
                           {"width", w},
                           {"height", h},
                           {"views", n},
                           {"backend", r.backend},
                           {"seconds", r.seconds},
                           {"ms_per_view", 1e3 * r.seconds / n},
                           {"speedup_vs_svr", std::isnan(xSvr) ? nlohmann::json() : nlohmann::json(xSvr)},
                           {"speedup_vs_layered", std::isnan(xLayered) ? nlohmann::json() : nlohmann::json(xLayered)},
                           {"min_psnr_db", std::isfinite(psnr) ? nlohmann::json(psnr) : nlohmann::json()},
                           {"min_identical", std::isnan(identical) ? nlohmann::json() : nlohmann::json(identical)},
                           {"stages_s", r.stats.times.seconds},
                           {"counters", r.stats.counters}});
      }
      std::fflush(stdout);
    }
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("# peak resident memory: %.1f MiB\n", usage.ru_maxrss / 1024.0);
  if (args.has("json")) {
    std::ofstream out(args.get("json", ""));
    out << nlohmann::json{{"gl", context->describe()}, {"cpu", cpuModel()},
                          {"peak_rss_mib", usage.ru_maxrss / 1024.0}, {"results", records}}
               .dump(2)
        << "\n";
    if (!out) fail(args.get("json", ""), "cannot write JSON");
  }
  return 0;
}

}  // namespace mvr::app
