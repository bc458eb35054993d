#pragma once
// What the benchmark measured, and what follows from it: break-even view
// counts against SVR (Halle 7.4), JSON and gnuplot plots (Halle figs 7-5..7-8).
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace mvr::app {

struct BenchRecord {
  std::string scene, backend;
  size_t triangles = 0;
  int width = 0, height = 0, views = 0, rows = 1;
  double seconds = 0, speedupSvr = 0, speedupLayered = 0;
  double minPsnr = 0, minIdentical = 0, minClose = 0, minSsim = 0;
  double meanHoles = 0;  // per sampled view: pixels svr covers and this back end leaves empty
  double slices = 0, averagePolygonHeight = 0;
  // The cost model t(N) = fixed + (N - 1) marginal from this run and a
  // one-view run, and the floor: reading the same pixels back with nothing
  // drawn (mvr/gl/readback_ring.h), which no back end can beat.
  double fixedSeconds = NAN, marginalSeconds = NAN, floorSeconds = NAN;
  std::map<std::string, double> stages, counters;
};

struct BenchMachine {
  std::string gl, cpu;
  unsigned threads = 0;
  double peakRssMiB = 0;
  std::string antialiasing;  // the run's supersampling; empty: none
};

// Where a back end's total time drops below per-view SVR's.
struct BreakEven {
  std::string scene, backend;
  int width = 0, height = 0;
  int firstFaster = -1;      // smallest measured view count where faster; -1: never
  double fitted = 0;         // from t = a + c N fitted to both; inf: never
  double averagePolygonHeight = 0;  // Halle's rule: MVR wins once N exceeds it
  double svrMsPerView = 0;   // svr's fitted time per view at the fitted crossing
};

std::vector<BreakEven> findBreakEvens(const std::vector<BenchRecord>& records);
// Per record: fixed cost, marginal cost per view, readback floor and the
// total as a multiple of the floor.
void printCostModel(const std::vector<BenchRecord>& records);
void printBreakEvens(const std::vector<BreakEven>& breakEvens);
void writeBenchJson(const std::string& path, const BenchMachine& machine,
                    const std::vector<BenchRecord>& records, const std::vector<BreakEven>& breakEvens);
// The records of a JSON file writeBenchJson wrote (to plot them again);
// throws mvr::Error naming the file when it is not one.
std::vector<BenchRecord> readBenchJson(const std::string& path);
// Data, gnuplot scripts and (when gnuplot is installed) PNGs in dir: per
// size, time per view against views (svr and mvr strip for every scene;
// every back end for the finest scene) and error against time at the
// largest view count (identical-pixel fraction; PSNR).
void writeBenchPlots(const std::string& dir, const std::vector<BenchRecord>& records,
                     const std::vector<BreakEven>& breakEvens);

}  // namespace mvr::app
