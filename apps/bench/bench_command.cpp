// `mvr bench`: every back end on the same scene and camera, in one process
// and one GL context; ratios against svr and svr-layered, error against svr,
// break-even view counts (Halle ch. 7) and plots.
#include "apps/bench/bench_command.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <queue>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "apps/bench/bench_report.h"
#include "apps/cli/cli.h"
#include "apps/cli/job_split.h"
#include "apps/bench/sample_sink.h"
#include "apps/scenes/teacup.h"
#include "apps/scenes/test_scenes.h"
#include "mvr/backends/backend.h"
#include "mvr/error.h"
#include "mvr/frames/frame_chain.h"
#include "mvr/frames/progress.h"
#include "mvr/gl/gl_context.h"
#include "mvr/gl/gpu_clock.h"
#include "mvr/gl/readback_ring.h"
#include "mvr/images/compare.h"
#include "mvr/assets/scene_io.h"
#include "mvr/parallel.h"

namespace mvr::app {

namespace {

const char* const kDefaultBackends =
    "svr,svr-layered,deferred,mvr:quad,mvr:strip,mvr:exact,mvr:spans,mvr:cpu,interp:center:c1,"
    "interp:hierarchical:2:c1";

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

struct Config {
  std::vector<std::pair<int, int>> sizes;
  std::vector<int> views;
  std::vector<std::string> backends;  // specs, as labels
  std::vector<BackendOptions> options;  // the same specs, parsed
  int repeat = 1, errorViews = 8, rows = 1;
  // What `mvr render` writes by default (8-bit sRGB); --linear: 8-bit linear.
  PixelType type = PixelType::Srgb8;
  Supersampling aa;  // every back end renders the samples and filters them alike
};

struct Run {
  double seconds = INFINITY;
  RenderStats stats;
  std::map<int, Image> samples;
};

// With --gpu-times: every measured run's stages, milliseconds of wall
// clock and of GPU time (gpu:STAGE), best run of the repeats.
void printStages(const std::string& name, const ShearingCamera& cam, const RenderStats& stats) {
  std::printf("#   stages %s %dx%d x %d:", name.c_str(), cam.width(), cam.height(), cam.views());
  for (const auto& [stage, s] : stats.times.seconds) std::printf(" %s %.3f", stage.c_str(), s * 1e3);
  std::printf(" (ms)\n");
}

// The filter's time counts: it is part of anti-aliasing's cost.
Run measure(Renderer& renderer, const ShearingCamera& cam, const Supersampling& aa, int repeat,
            const std::vector<int>& sampled, PixelType type) {
  Run best;
  const ShearingCamera samples = aa.active() ? supersampledCamera(cam, aa) : cam;
  for (int k = 0; k < repeat; ++k) {
    SampleSink sink(sampled, cam.width(), cam.height(), type);
    FrameChain chain({.sink = &sink}, {.rendered = renderer.order(), .delivered = renderer.order(),
                                       .width = cam.width(), .height = cam.height(), .views = cam.views(),
                                       .type = type, .aa = aa});
    RenderStats stats;
    gl::GpuClock::discard();
    Stopwatch watch;
    renderer.render(samples, chain.entry(), stats);
    const double s = watch.seconds();
    gl::GpuClock::collect(stats.times);
    if (s < best.seconds) best = {s, stats, sink.samples()};
  }
  if (gl::GpuClock::enabled()) printStages(renderer.name(), samples, best.stats);
  return best;
}

// Seconds to read w x h x frames RGBA8 pixels back through a readback
// ring with nothing drawn, in reads of up to 64 MB: the floor under every
// back end's time for that many frames.
double readbackFloor(int w, int h, long frames, int repeat) {
  const int maxSize = gl::maxTextureSize();
  const long rowBytes = long(w) * 4, totalRows = long(h) * frames;
  const int rows = int(std::clamp<long>((64L << 20) / rowBytes, 1, std::min<long>(maxSize, totalRows)));
  RenderTarget target(w, rows, PixelType::U8);
  target.clear();
  std::vector<Image> landing(4, Image(w, rows, PixelType::U8));  // one per slot and one being read
  double best = INFINITY;
  for (int k = 0; k < repeat; ++k) {
    ReadbackRing ring(size_t(rows) * rowBytes);
    const Stopwatch watch;
    int serial = 0;
    for (long done = 0; done < totalRows; done += rows, ++serial) {
      const int now = int(std::min<long>(rows, totalRows - done));
      ring.readRows(target, 0, now, reinterpret_cast<std::byte*>(landing[serial % 4].row(0)));
      ring.submit([] {});
    }
    ring.drain();
    best = std::min(best, watch.seconds());
  }
  return best;
}

void errorAgainst(const Run& ref, const Run& r, BenchRecord& rec) {
  rec.minPsnr = INFINITY;
  rec.minIdentical = rec.minClose = rec.minSsim = 1.0;
  rec.meanHoles = 0;
  for (const auto& [view, img] : r.samples) {
    ImageDifference d = compareImages(ref.samples.at(view), img);
    rec.minSsim = std::min(rec.minSsim, d.ssim);
    rec.meanHoles += double(d.holes) / double(r.samples.size());
    rec.minPsnr = std::min(rec.minPsnr, d.psnr);
    rec.minIdentical = std::min(rec.minIdentical, d.identicalFraction);
    rec.minClose = std::min(rec.minClose, d.closeFraction);
  }
}

void printRow(const BenchRecord& r) {
  char size[32];
  std::snprintf(size, sizeof size, "%dx%d", r.width, r.height);
  std::printf("%-16s %-9s %6d %-24s %10.4f %10.4f %8.2f %9.2f %8.2f %7.4f %10.6f %7.1f %10.0f\n",
              r.scene.c_str(), size, r.views * r.rows, r.backend.c_str(), r.seconds,
              1e3 * r.seconds / (r.views * r.rows),
              r.speedupSvr, r.speedupLayered, std::isinf(r.minPsnr) ? 99.99 : r.minPsnr,
              r.minSsim, r.minIdentical, r.meanHoles, r.slices);
  std::fflush(stdout);
}

// Every back end of the config on one scene; appends to records.
void benchScene(const std::string& name, const Scene& scene, const Config& cfg,
                std::vector<BenchRecord>& records) {
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (const BackendOptions& options : cfg.options)
    renderers.push_back(makeRenderer(options, scene, cfg.type));
  {  // warm-up: shader compilation and first buffer use are not rendering
    auto [w, h] = cfg.sizes[0];
    ShearingCamera warm(cameraFor(scene, w, h), w, h, 2);
    for (auto& r : renderers) {
      NullSink sink;
      RenderStats stats;
      r->render(warm, sink, stats);
    }
  }
  for (auto [w, h] : cfg.sizes) {
    // The fixed cost: every back end at one view.
    std::vector<double> fixed;
    const ShearingCamera one(cameraFor(scene, w, h), w, h, 1, 1);
    const Supersampling oneAa{.spatial = cfg.aa.spatial};  // one view has no track to sample
    for (auto& r : renderers) fixed.push_back(measure(*r, one, oneAa, cfg.repeat, {0}, cfg.type).seconds);
    for (int n : cfg.views) {
      ShearingCamera cam(cameraFor(scene, w, h), w, h, n, cfg.rows);
      const double floor = readbackFloor(w * cfg.aa.spatial, h * cfg.aa.spatial,
                                         long(n) * cfg.aa.views * cfg.rows, cfg.repeat);
      const std::vector<int> sampled = spreadViews(n, cfg.errorViews);
      std::vector<Run> runs;
      for (auto& r : renderers) runs.push_back(measure(*r, cam, cfg.aa, cfg.repeat, sampled, cfg.type));
      const Run* svr = nullptr;
      const Run* layered = nullptr;
      for (size_t k = 0; k < runs.size(); ++k) {
        if (cfg.backends[k] == "svr") svr = &runs[k];
        if (cfg.backends[k] == "svr-layered") layered = &runs[k];
      }
      const double height = averagePolygonHeight(scene, cam);
      for (size_t k = 0; k < runs.size(); ++k) {
        BenchRecord rec;
        rec.scene = name;
        rec.triangles = scene.triangleCount();
        rec.width = w;
        rec.height = h;
        rec.views = n;
        rec.rows = cfg.rows;
        rec.backend = cfg.backends[k];
        rec.seconds = runs[k].seconds;
        rec.speedupSvr = svr ? svr->seconds / rec.seconds : NAN;
        rec.speedupLayered = layered ? layered->seconds / rec.seconds : NAN;
        if (svr) errorAgainst(*svr, runs[k], rec);
        rec.slices = runs[k].stats.counters.count("slices") ? runs[k].stats.counters.at("slices") : 0;
        rec.averagePolygonHeight = height;
        rec.fixedSeconds = fixed[k];
        const long frames = long(n) * cfg.rows;
        rec.marginalSeconds = frames > 1 ? (rec.seconds - fixed[k]) / double(frames - 1) : NAN;
        rec.floorSeconds = floor;
        rec.stages = runs[k].stats.times.seconds;
        rec.counters = runs[k].stats.counters;
        printRow(rec);
        records.push_back(rec);
      }
    }
  }
}

// Work stealing, simulated from measured times: each rank's row cut into
// kChunksPerRank equal bands per rank, each band rendered alone; a rank that
// is free takes the next band from a shared counter (one MPI fetch-and-add
// each, kGrabSeconds: an assumed InfiniBand round trip) until none is left.
constexpr int kChunksPerRank = 8;
constexpr double kGrabSeconds = 5e-6;

// When the last rank finishes, taking chunks in order as ranks come free.
double stealingMakespan(const std::vector<double>& chunks, int ranks) {
  std::priority_queue<double, std::vector<double>, std::greater<>> freeAt;
  for (int r = 0; r < ranks; ++r) freeAt.push(0.0);
  double last = 0.0;
  for (double t : chunks) {
    const double done = freeAt.top() + kGrabSeconds + t;
    freeAt.pop();
    freeAt.push(done);
    last = std::max(last, done);
  }
  return last;
}

// What a split job's ranks would each render (apps/cli/job_split.h), timed
// one share after another in this process: the per-share costs the split
// balances and the scaling model takes (docs/SCALING.md). Prints, per
// back end and split (static by count, static by cost, work stealing
// simulated from chunk times, and steal* as if a rank paid a render call's
// fixed costs once), the measured imbalance (slowest rank over
// the mean) against the split's estimate, the sum of the shares over the
// whole render (the work the split repeats per share), the parallel
// efficiency (whole render over ranks x the slowest rank) and each
// share's time.
void benchShares(const Scene& scene, const Config& cfg, int ranks) {
  std::printf("# shares of a split over %d ranks, each rendered alone (best of %d); steal: %d chunks "
              "per rank taken as ranks come free, %.0f us a grab\n",
              ranks, cfg.repeat, kChunksPerRank, kGrabSeconds * 1e6);
  std::printf("%-9s %6s %5s %-24s %-6s %9s %10s %10s %10s %10s  %s\n", "size", "views", "rows", "backend",
              "split", "whole_s", "imbalance", "estimated", "sum/whole", "efficiency", "share seconds");
  for (size_t k = 0; k < cfg.options.size(); ++k) {
    auto renderer = makeRenderer(cfg.options[k], scene, cfg.type);
    for (auto [w, h] : cfg.sizes)
      for (int n : cfg.views) {
        const ShearingCamera cam(cameraFor(scene, w, h), w, h, n, cfg.rows);
        auto time = [&](const ShearingCamera& c) {
          double best = INFINITY;
          for (int r = 0; r < cfg.repeat; ++r) {
            NullSink sink;
            RenderStats stats;
            Stopwatch watch;
            renderer->render(c, sink, stats);
            best = std::min(best, watch.seconds());
          }
          return best;
        };
        time(cam);  // warm-up
        const double whole = time(cam);
        auto print = [&](const char* by, const std::vector<double>& seconds, double makespan, double estimate,
                         bool list) {
          double sum = 0.0;
          for (double t : seconds) sum += t;
          std::string text;
          for (double t : list ? seconds : std::vector<double>{}) {
            char item[32];
            std::snprintf(item, sizeof item, " %.4f", t);
            text += item;
          }
          char est[16] = "-";
          if (estimate > 0.0) std::snprintf(est, sizeof est, "%.3f", estimate);
          std::printf("%4dx%-4d %6d %5d %-24s %-6s %9.4f %10.3f %10s %10.3f %10.3f  %s\n", w, h, n, cfg.rows,
                      cfg.backends[k].c_str(), by, whole, makespan * ranks / sum, est, sum / whole,
                      whole / (ranks * makespan), text.empty() ? "" : text.c_str() + 1);
        };
        for (const char* by : {"count", "cost"}) {
          const bool byCost = std::string(by) == "cost";
          if (byCost && renderer->order() == FrameOrder::View) continue;  // views split by count
          const JobSplit split = splitJob(cam, renderer->order(), ranks,
                                          byCost ? scanlineCosts(scene, cam, cfg.rows / 2) : std::vector<double>{});
          std::vector<double> seconds;
          for (const std::vector<RenderShare>& rank : split.shares) {
            double t = 0.0;
            for (const RenderShare& share : rank) t += time(cam.withShare(share));
            seconds.push_back(t);
          }
          print(by, seconds, *std::max_element(seconds.begin(), seconds.end()), split.imbalance, true);
        }
        const bool epi = renderer->order() == FrameOrder::Epi;
        const int axis = epi ? h : n;
        std::vector<double> chunks;
        for (IndexRange part : splitByCost(std::vector<double>(size_t(axis), 1.0), std::min(axis, kChunksPerRank * ranks))) {
          RenderShare share = cam.share();
          (epi ? share.scanlines : share.views) = part;
          chunks.push_back(time(cam.withShare(share)));
        }
        print("steal", chunks, stealingMakespan(chunks, ranks), 0.0, false);
        // The same if a rank kept its state from chunk to chunk: what the
        // chunks cost beyond the whole render, spread evenly, taken off.
        double sum = 0.0;
        for (double t : chunks) sum += t;
        const double overhead = std::max(0.0, sum - whole) / double(chunks.size());
        for (double& t : chunks) t = std::max(0.0, t - overhead);
        print("steal*", chunks, stealingMakespan(chunks, ranks), 0.0, false);
      }
  }
}

std::vector<int> parseViews(const std::string& list) {
  std::vector<int> out;
  for (const std::string& v : splitList(list)) {
    char* end = nullptr;
    long n = std::strtol(v.c_str(), &end, 10);
    if (*end || n < 1 || n > Limits::kMaxViews)
      fail("--views", "'" + v + "' is not a view count 1.." + std::to_string(Limits::kMaxViews));
    out.push_back(int(n));
  }
  if (out.empty()) fail("--views", "no view counts");
  return out;
}

std::vector<std::pair<int, int>> parseSizes(const std::string& list) {
  std::vector<std::pair<int, int>> out;
  for (const std::string& s : splitList(list)) out.push_back(parseSize("--size", s));
  if (out.empty()) fail("--size", "no sizes");
  return out;
}

Scene benchTeacup(int triangles) {
  Scene s = makeTeacup(triangles);
  s.lights = {Light{Light::Type::Directional, glm::normalize(glm::vec3(-0.4f, -0.6f, -1.0f)),
                    glm::vec3(0.85f)}};
  return s;
}

}  // namespace

int runBench(int argc, char** argv) {
  CLI::App app("Renders one scene with several back ends in one process and GL context and "
               "prints time per view, speed-up against svr and svr-layered, and error against "
               "svr (min PSNR, min identical-pixel fraction over sampled views), then the "
               "break-even view count of each back end against svr.",
               "mvr bench");
  std::string scenePath, views, sizes, backends = kDefaultBackends, json, plots, replot, gl = "auto";
  int teacup = 0, slender = 0, thinDeep = 0, knot = 0;
  bool sweep = false;
  Config cfg;
  app.add_option("SCENE", scenePath, "a scene file (default: the bundled scene)");
  app.add_option("--teacup", teacup, "the procedural teacup at about N triangles")
      ->check(CLI::Range(100, 10000000))->type_name("N");
  app.add_option("--slender", slender, "N long slender vertical quads (MVR's bad case)")
      ->check(CLI::Range(1, 10000000))->type_name("N");
  app.add_option("--thin-deep", thinDeep,
                 "N thin bars before a deep open box (what image-based back ends find hard)")
      ->check(CLI::Range(1, 1000))->type_name("N");
  app.add_option("--knot", knot,
                 "a trefoil knot tube at about N triangles (a mesh no back end was tuned on)")
      ->check(CLI::Range(64, 10000000))->type_name("N");
  app.add_flag("--sweep", sweep,
               "Halle's sweep: teacups of 4K, 16K, 63K, 143K triangles at 160x140, 640x480, "
               "1120x840 for 1 to 1000 views");
  app.add_option("--views", views, "view counts, e.g. 1,10,100 (default 100)")->type_name("LIST");
  app.add_option("--size", sizes, "image sizes, e.g. 160x140,640x480 (default 160x140)")->type_name("LIST");
  app.add_option("--rows", cfg.rows, "rows of views (full parallax; times are per view of M x N)")
      ->check(CLI::Range(1, Limits::kMaxRows))->capture_default_str();
  app.add_option("--backends", backends,
                 "back-end specs: mvr:MODE[:direct] textures directly; "
                 "interp[:ACQUIRE][:L][:cT][:vis][:bB][:sK][:oP][:xS][:whole][:passes][:BLEND][:MODE] is "
                 "the image-based back end with L layers, coalescing T pixels, visibility, a budget "
                 "of B source views, K highlight splits, overlap P pixels, outlines sampled S "
                 "columns a pixel, every interval drawn whole, a pass of the mesh per layer, "
                 "blending none, track or angular; warp[:ACQUIRE][:tT][:aA][:bB][:fF][:xS][:gl|:cpu] "
                 "is depth-image warping with tau T, penalty A, a budget of B references, flatness F "
                 "pixels, outlines sampled S columns a pixel (cpu), by GL or on the CPU (default: the CPU where GL renders on the CPU)")
      ->type_name("LIST")->capture_default_str();
  bool linear = false;
  app.add_flag("--linear", linear, "render 8-bit linear values (default: sRGB-encoded, as mvr render writes)");
  app.add_option("--repeat", cfg.repeat, "best of R runs")->check(CLI::Range(1, 100))->capture_default_str();
  app.add_option("--error-views", cfg.errorViews, "views compared against svr")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--json", json, "also write the results as JSON")->type_name("FILE");
  app.add_option("--plots", plots, "write gnuplot scripts and PNG plots (needs gnuplot)")->type_name("DIR");
  app.add_option("--replot", replot, "only plot an earlier run's --json FILE into --plots DIR")
      ->type_name("FILE");
  bool gpuTimes = false;
  app.add_flag("--gpu-times", gpuTimes,
               "also time each stage on the GPU (timestamp queries): printed per run, and in "
               "--json's stages as gpu:STAGE");
  int shares = 0;
  app.add_option("--shares", shares,
                 "instead of the comparison: time each share of a split over K ranks (mpirun), "
                 "split by scanline count and by estimated cost")
      ->check(CLI::Range(2, 4096))->type_name("K");
  addAntialiasingOptions(app, cfg.aa);
  addGlOption(app, gl);
  addThreadsOption(app);
  bool strict = false;
  addStrictOption(app, strict);
  LookOptions look;
  addLookOptions(app, look);
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;
  if (linear) cfg.type = PixelType::U8;

  setProgressEnabled(false);
  gl::GpuClock::enable(gpuTimes);
  if (!replot.empty()) {  // plots from an earlier run's JSON: no GL, no rendering
    if (plots.empty()) fail("--replot", "needs --plots DIR");
    const std::vector<BenchRecord> records = readBenchJson(replot);
    writeBenchPlots(plots, records, findBreakEvens(records));
    return 0;
  }
  cfg.views = parseViews(!views.empty() ? views : sweep ? "1,2,5,10,20,50,100,200,500,1000" : "100");
  cfg.sizes = parseSizes(!sizes.empty() ? sizes : sweep ? "160x140,640x480,1120x840" : "160x140");
  cfg.backends = splitList(backends);
  for (const std::string& spec : cfg.backends) cfg.options.push_back(parseBackendSpec(spec));  // before GL

  // Scenes are built lazily: a 143K teacup is 10 MB of vertices.
  std::vector<std::pair<std::string, std::function<Scene()>>> scenes;
  if (sweep) {
    for (int n : {4000, 16000, 63000, 143000})
      scenes.emplace_back("teacup" + std::to_string(n / 1000) + "k", [n] { return benchTeacup(n); });
  } else if (teacup > 0) {
    const int n = teacup;
    scenes.emplace_back("teacup" + std::to_string(n / 1000) + "k", [n] { return benchTeacup(n); });
  } else if (thinDeep > 0) {
    const int n = thinDeep;
    scenes.emplace_back("thin-deep" + std::to_string(n), [n] { return makeThinAndDeepScene(n); });
  } else if (knot > 0) {
    const int n = knot;
    scenes.emplace_back("knot" + std::to_string(n / 1000) + "k", [n] { return makeKnotScene(n); });
  } else if (slender > 0) {
    const int n = slender;
    scenes.emplace_back("slender" + std::to_string(n), [n] { return makeSlenderScene(n); });
  } else {
    const std::string path = scenePath.empty() ? defaultScenePath() : scenePath;
    Scene s = loadInputScene(path, strict, look);  // load now: bad input fails before GL
    scenes.emplace_back(std::filesystem::path(path).stem().string(), [s] { return s; });
  }

  auto context = GlContext::create(parseGlPlatform(gl));
  BenchMachine machine{context->describe(), cpuModel(), unsigned(threadCount())};
  if (cfg.aa.active()) machine.antialiasing = describe(cfg.aa);
  std::printf("# mvr bench\n# GL: %s\n# CPU: %s, %u cores, %u pool threads\n# output: 8-bit %s\n",
              machine.gl.c_str(), machine.cpu.c_str(), std::thread::hardware_concurrency(),
              machine.threads, cfg.type == PixelType::Srgb8 ? "sRGB" : "linear");
  if (cfg.aa.active())
    std::printf("# anti-aliasing: %s; times include the filter, errors compare filtered views\n",
                describe(cfg.aa).c_str());
  std::printf("%-16s %-9s %6s %-24s %10s %10s %8s %9s %8s %7s %10s %7s %10s\n", "scene", "size",
              "views", "backend", "total_s", "ms/view", "x_svr", "x_layered", "PSNR_dB", "SSIM",
              "identical", "holes", "slices");
  if (shares > 0) {
    for (auto& [name, build] : scenes) {
      std::printf("# scene %s\n", name.c_str());
      benchShares(build(), cfg, shares);
    }
    return 0;
  }
  std::vector<BenchRecord> records;
  for (auto& [name, build] : scenes) {
    Scene scene = build();
    benchScene(name, scene, cfg, records);
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  machine.peakRssMiB = usage.ru_maxrss / 1024.0;
  std::printf("# peak resident memory: %.1f MiB\n", machine.peakRssMiB);
  printCostModel(records);
  const std::vector<BreakEven> breakEvens = findBreakEvens(records);
  printBreakEvens(breakEvens);
  if (!json.empty()) writeBenchJson(json, machine, records, breakEvens);
  if (!plots.empty()) writeBenchPlots(plots, records, breakEvens);
  return 0;
}

}  // namespace mvr::app
