#include "apps/bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "mvr/error.h"

namespace mvr::app {
namespace {

std::string sizeName(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// Least squares t = a + c N.
std::pair<double, double> fitLine(const std::vector<std::pair<double, double>>& pts) {
  double sn = 0, st = 0, snn = 0, snt = 0;
  for (auto [n, t] : pts) sn += n, st += t, snn += n * n, snt += n * t;
  const double k = double(pts.size()), det = k * snn - sn * sn;
  if (pts.size() < 2 || det == 0) return {pts.empty() ? 0 : pts[0].second, 0};
  const double c = (k * snt - sn * st) / det;
  return {(st - c * sn) / k, c};
}

using Group = std::map<std::string, std::vector<const BenchRecord*>>;  // backend -> by views

std::map<std::tuple<std::string, int, int>, Group> groupRecords(const std::vector<BenchRecord>& records) {
  std::map<std::tuple<std::string, int, int>, Group> groups;
  for (const BenchRecord& r : records) groups[{r.scene, r.width, r.height}][r.backend].push_back(&r);
  return groups;
}

}  // namespace

std::vector<BreakEven> findBreakEvens(const std::vector<BenchRecord>& records) {
  std::vector<BreakEven> out;
  for (const auto& [key, group] : groupRecords(records)) {
    auto svrIt = group.find("svr");
    if (svrIt == group.end()) continue;
    std::map<int, double> svr;
    std::vector<std::pair<double, double>> svrPts;
    for (const BenchRecord* r : svrIt->second) {
      svr[r->views] = r->seconds;
      svrPts.emplace_back(r->views, r->seconds);
    }
    const auto [aSvr, cSvr] = fitLine(svrPts);
    for (const auto& [backend, rs] : group) {
      if (backend == "svr") continue;
      BreakEven b{std::get<0>(key), backend, std::get<1>(key), std::get<2>(key)};
      std::vector<std::pair<double, double>> pts;
      for (const BenchRecord* r : rs) {
        pts.emplace_back(r->views, r->seconds);
        b.averagePolygonHeight = r->averagePolygonHeight;
        if (b.firstFaster < 0 && svr.count(r->views) && r->seconds < svr[r->views]) b.firstFaster = r->views;
      }
      const auto [a, c] = fitLine(pts);
      // A slope no smaller than svr's never wins at large N.
      b.fitted = c >= cSvr ? INFINITY : std::max(1.0, (a - aSvr) / (cSvr - c));
      if (std::isfinite(b.fitted)) b.svrMsPerView = 1e3 * (aSvr / b.fitted + cSvr);
      out.push_back(b);
    }
  }
  return out;
}

void printBreakEvens(const std::vector<BreakEven>& breakEvens) {
  if (breakEvens.empty()) return;
  std::printf("# break-even against svr: first measured view count where faster, fitted\n"
              "# crossing of t = a + c N, and Halle's rule-of-thumb prediction (average\n"
              "# polygon height in pixels: MVR should win once N exceeds it)\n");
  std::printf("%-16s %-9s %-24s %12s %10s %14s\n", "scene", "size", "backend", "first_faster",
              "fitted_N", "avg_poly_px");
  for (const BreakEven& b : breakEvens) {
    char first[16];
    std::snprintf(first, sizeof first, b.firstFaster < 0 ? "never" : "%d", b.firstFaster);
    std::printf("%-16s %-9s %-24s %12s %10.1f %14.2f\n", b.scene.c_str(),
                sizeName(b.width, b.height).c_str(), b.backend.c_str(), first, b.fitted,
                b.averagePolygonHeight);
  }
}

void printCostModel(const std::vector<BenchRecord>& records) {
  std::printf("# cost model: fixed = time at one view; marginal = (t(N) - fixed) / (N - 1);\n"
              "# floor = reading the same pixels back with nothing drawn; x_floor = total / floor\n");
  std::printf("%-16s %-9s %6s %-24s %10s %12s %10s %8s\n", "scene", "size", "views", "backend",
              "fixed_s", "marginal_ms", "floor_s", "x_floor");
  for (const BenchRecord& r : records)
    std::printf("%-16s %-9s %6d %-24s %10.4f %12.4f %10.4f %8.2f\n", r.scene.c_str(),
                sizeName(r.width, r.height).c_str(), r.views * r.rows, r.backend.c_str(), r.fixedSeconds,
                1e3 * r.marginalSeconds, r.floorSeconds, r.seconds / r.floorSeconds);
}

void writeBenchJson(const std::string& path, const BenchMachine& machine,
                    const std::vector<BenchRecord>& records, const std::vector<BreakEven>& breakEvens) {
  using nlohmann::json;
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(); };
  json j{{"gl", machine.gl}, {"cpu", machine.cpu}, {"threads", machine.threads},
         {"peak_rss_mib", machine.peakRssMiB}, {"results", json::array()}, {"break_even", json::array()}};
  if (!machine.antialiasing.empty()) j["antialiasing"] = machine.antialiasing;
  for (const BenchRecord& r : records)
    j["results"].push_back({{"scene", r.scene}, {"triangles", r.triangles}, {"width", r.width},
                            {"height", r.height}, {"views", r.views}, {"rows", r.rows}, {"backend", r.backend},
                            {"seconds", r.seconds}, {"ms_per_view", 1e3 * r.seconds / (r.views * r.rows)},
                            {"speedup_vs_svr", num(r.speedupSvr)},
                            {"speedup_vs_layered", num(r.speedupLayered)},
                            {"min_psnr_db", num(r.minPsnr)}, {"min_identical", num(r.minIdentical)},
                            {"min_within_one_step", num(r.minClose)},
                            {"min_ssim", num(r.minSsim)}, {"mean_holes", r.meanHoles},
                            {"average_polygon_height_px", r.averagePolygonHeight},
                            {"fixed_s", num(r.fixedSeconds)}, {"marginal_ms_per_view", num(1e3 * r.marginalSeconds)},
                            {"readback_floor_s", num(r.floorSeconds)},
                            {"stages_s", r.stages}, {"counters", r.counters}});
  for (const BreakEven& b : breakEvens)
    j["break_even"].push_back({{"scene", b.scene}, {"width", b.width}, {"height", b.height},
                               {"backend", b.backend}, {"first_faster", b.firstFaster},
                               {"fitted_views", num(b.fitted)},
                               {"average_polygon_height_px", b.averagePolygonHeight}});
  std::ofstream out(path);
  out << j.dump(2) << "\n";
  if (!out) fail(path, "cannot write benchmark JSON");
}

std::vector<BenchRecord> readBenchJson(const std::string& path) {
  using nlohmann::json;
  std::ifstream in(path);
  if (!in) fail(path, "cannot read benchmark JSON");
  const json j = json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("results") || !j["results"].is_array())
    fail(path, "not a benchmark JSON (mvr bench --json)");
  auto num = [](const json& r, const char* key, double fallback) {
    return r.contains(key) && r[key].is_number() ? r[key].get<double>() : fallback;
  };
  std::vector<BenchRecord> records;
  for (const json& r : j["results"]) {
    if (!r.is_object() || !r.contains("scene") || !r.contains("backend") || !r["scene"].is_string() ||
        !r["backend"].is_string())
      fail(path, "a result without scene and backend");
    BenchRecord b;
    b.scene = r["scene"].get<std::string>();
    b.backend = r["backend"].get<std::string>();
    b.triangles = size_t(num(r, "triangles", 0));
    b.width = int(num(r, "width", 0)), b.height = int(num(r, "height", 0));
    b.views = int(num(r, "views", 0)), b.rows = int(num(r, "rows", 1));
    b.seconds = num(r, "seconds", NAN);
    b.speedupSvr = num(r, "speedup_vs_svr", NAN), b.speedupLayered = num(r, "speedup_vs_layered", NAN);
    b.minPsnr = num(r, "min_psnr_db", INFINITY);  // null: identical
    b.minIdentical = num(r, "min_identical", NAN), b.minClose = num(r, "min_within_one_step", NAN);
    b.minSsim = num(r, "min_ssim", NAN), b.meanHoles = num(r, "mean_holes", 0);
    b.averagePolygonHeight = num(r, "average_polygon_height_px", 0);
    if (b.views < 1 || b.width < 1 || b.height < 1 || !(b.seconds > 0))
      fail(path, "result " + b.scene + " " + b.backend + " lacks views, size or seconds");
    records.push_back(std::move(b));
  }
  if (records.empty()) fail(path, "no results");
  return records;
}

namespace {

// Every back end's time per view on the scene with the most triangles at
// this size, break-even points marked.
void plotBackends(const std::filesystem::path& dir, int w, int h, const std::vector<BenchRecord>& records,
                  const std::vector<BreakEven>& breakEvens) {
  const BenchRecord* finest = nullptr;
  for (const BenchRecord& r : records)
    if (r.width == w && r.height == h && (!finest || r.triangles > finest->triangles)) finest = &r;
  if (!finest) return;
  const std::string tag = sizeName(w, h), scene = finest->scene;
  std::ofstream gp(dir / ("backends_" + tag + ".gp"));
  gp << "set terminal pngcairo size 900,600\nset output '" << (dir / ("backends_" + tag + ".png")).string()
     << "'\nset logscale xy\nset xlabel 'views'\nset ylabel 'ms per view'\nset key outside right\n"
     << "set title 'time per view, " << scene << ", " << tag << " (points: break-even with svr)'\nplot ";
  const auto groups = groupRecords(records);
  const Group& group = groups.at({scene, w, h});
  int colour = 1;
  for (const auto& [backend, rs] : group) {
    std::string file = backend;
    std::replace(file.begin(), file.end(), ':', '_');
    const std::string data = (dir / (scene + "_" + tag + "_" + file + ".dat")).string();
    std::ofstream d(data);
    for (const BenchRecord* r : rs) d << r->views << " " << 1e3 * r->seconds / r->views << "\n";
    gp << (colour > 1 ? ", " : "") << "'" << data << "' using 1:2 with linespoints lc " << colour
       << (backend == "svr" ? " dt 2 lw 2" : " dt 1") << " title '" << backend << "'";
    for (const BreakEven& b : breakEvens)
      if (b.scene == scene && b.width == w && b.height == h && b.backend == backend && std::isfinite(b.fitted))
        gp << ", '+' using (" << b.fitted << "):(" << b.svrMsPerView << ") with points pt 7 ps 1.5 lc "
           << colour << " notitle";
    ++colour;
  }
  gp << "\n";
}

// PSNR against svr over time per view at the largest view count.
void plotPsnr(const std::filesystem::path& dir, int w, int h, const std::vector<BenchRecord>& records) {
  const std::string tag = sizeName(w, h);
  std::ofstream gp(dir / ("psnr_vs_time_" + tag + ".gp"));
  gp << "set terminal pngcairo size 900,600\nset output '" << (dir / ("psnr_vs_time_" + tag + ".png")).string()
     << "'\nset logscale x\nset xlabel 'ms per view'\nset ylabel 'min PSNR against svr (dB)'\n"
     << "set title 'PSNR against time, " << tag << ", largest view count'\nset key outside right\nplot ";
  bool first = true;
  int colour = 1;
  for (const auto& [key, group] : groupRecords(records)) {
    if (std::get<1>(key) != w || std::get<2>(key) != h) continue;
    const std::string data = (dir / (std::get<0>(key) + "_" + tag + "_psnr.dat")).string();
    std::ofstream d(data);
    for (const auto& [backend, rs] : group) {
      const BenchRecord* r = rs.back();
      if (backend == "svr" || !std::isfinite(r->minPsnr)) continue;
      d << 1e3 * r->seconds / r->views << " " << r->minPsnr << " " << backend << "\n";
    }
    gp << (first ? "" : ", ") << "'" << data << "' using 1:2:3 with labels point pt 7 lc " << colour
       << " offset 1,0.5 title '" << std::get<0>(key) << "'";
    first = false;
    ++colour;
  }
  gp << "\n";
}

}  // namespace

void writeBenchPlots(const std::string& dir, const std::vector<BenchRecord>& records,
                     const std::vector<BreakEven>& breakEvens) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  std::set<std::pair<int, int>> sizes;
  for (const BenchRecord& r : records) sizes.insert({r.width, r.height});
  const auto groups = groupRecords(records);
  for (auto [w, h] : sizes) {
    const std::string tag = sizeName(w, h);
    // Time per view against view count (Halle figs. 7-5 to 7-8): svr dashed,
    // MVR (strip) solid, one colour per scene; break-even points marked.
    std::ofstream gp(fs::path(dir) / ("time_per_view_" + tag + ".gp"));
    gp << "set terminal pngcairo size 900,600\nset output '" << (fs::path(dir) / ("time_per_view_" + tag + ".png")).string()
       << "'\nset logscale xy\nset xlabel 'views'\nset ylabel 'ms per view'\nset key outside right\n"
       << "set title 'time per view, " << tag << " (dashed: svr, solid: mvr strip, points: break-even)'\nplot ";
    int colour = 1;
    bool first = true;
    for (const auto& [key, group] : groups) {
      if (std::get<1>(key) != w || std::get<2>(key) != h) continue;
      for (const char* backend : {"svr", "mvr:strip"}) {
        auto it = group.find(backend);
        if (it == group.end()) continue;
        const std::string data = (fs::path(dir) / (std::get<0>(key) + "_" + tag + "_" +
                                                    (backend[0] == 's' ? "svr" : "mvr") + ".dat")).string();
        std::ofstream d(data);
        for (const BenchRecord* r : it->second) d << r->views << " " << 1e3 * r->seconds / r->views << "\n";
        gp << (first ? "" : ", ") << "'" << data << "' using 1:2 with linespoints lc " << colour
           << (backend[0] == 's' ? " dt 2" : " dt 1") << " title '" << std::get<0>(key) << " " << backend << "'";
        first = false;
      }
      for (const BreakEven& b : breakEvens)
        if (b.scene == std::get<0>(key) && b.width == w && b.height == h && b.backend == "mvr:strip" &&
            std::isfinite(b.fitted)) {
          gp << ", '+' using (" << b.fitted << "):(" << b.svrMsPerView << ") with points pt 7 ps 1.5 lc " << colour
             << " notitle";
        }
      ++colour;
    }
    gp << "\n";
    gp.close();
    // Error against time per accuracy mode at the largest view count.
    std::ofstream ge(fs::path(dir) / ("error_vs_time_" + tag + ".gp"));
    ge << "set terminal pngcairo size 900,600\nset output '" << (fs::path(dir) / ("error_vs_time_" + tag + ".png")).string()
       << "'\nset logscale x\nset xlabel 'ms per view'\nset ylabel 'pixels differing from svr (%)'\n"
       << "set title 'error against time, " << tag << ", largest view count'\nset key outside right\nplot ";
    first = true;
    for (const auto& [key, group] : groups) {
      if (std::get<1>(key) != w || std::get<2>(key) != h) continue;
      const std::string data = (fs::path(dir) / (std::get<0>(key) + "_" + tag + "_error.dat")).string();
      std::ofstream d(data);
      for (const auto& [backend, rs] : group) {
        if (backend == "svr") continue;
        const BenchRecord* r = rs.back();
        d << 1e3 * r->seconds / r->views << " " << 100.0 * (1.0 - r->minIdentical) << " " << backend << "\n";
      }
      ge << (first ? "" : ", ") << "'" << data << "' using 1:2:3 with labels point pt 7 offset 1,0.5 title '"
         << std::get<0>(key) << "'";
      first = false;
    }
    ge << "\n";
    plotBackends(dir, w, h, records, breakEvens);
    plotPsnr(dir, w, h, records);
  }
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::fprintf(stderr, "mvr: gnuplot not found; plot scripts are in %s\n", dir.c_str());
    return;
  }
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".gp") {
      const std::string cmd = "gnuplot '" + entry.path().string() + "' 2>/dev/null";
      if (std::system(cmd.c_str()) != 0)
        std::fprintf(stderr, "mvr: gnuplot failed on %s\n", entry.path().string().c_str());
    }
}

}  // namespace mvr::app
