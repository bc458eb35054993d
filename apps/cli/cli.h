#pragma once
// The command line's shared pieces on CLI11: one-line errors, typed image
// sizes, the GL platform.
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "mvr/scene.h"
#include "mvr/frames/supersampling.h"


namespace mvr::app {

// Parses argv into app. Help and --version print and give their exit code;
// every other parse error becomes an mvr::Error (one line, naming the
// option). nullopt: parsed, carry on.
std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv);

// "WxH" with sides 1..Limits::kMaxSide; errors name the flag.
std::pair<int, int> parseSize(const std::string& flag, const std::string& text);

// An option holding "WxH" into size (validated while parsing).
CLI::Option* addSizeOption(CLI::App& app, const std::string& name, std::pair<int, int>& size,
                           const std::string& description);

// --views N (views per row) and --rows M (full parallax), bounded by Limits.
void addViewCountOptions(CLI::App& app, int& views, int& rows);

// --aa S (S x S samples per pixel) and --aa-views P (P samples per view
// along the track) into aa: box-filtered supersampling, every back end.
void addAntialiasingOptions(CLI::App& app, Supersampling& aa);

// --gl egl|osmesa|glfw|auto into platform.
CLI::Option* addGlOption(CLI::App& app, std::string& platform);

// --threads N: the pool's workers (mvr/parallel.h) for slicing, the CPU
// rasterizer and image encoding; applied as soon as it is parsed. 0 (the
// default): every core.
CLI::Option* addThreadsOption(CLI::App& app);

// --strict: a mesh file's faces that cannot be used are an error instead
// of a warning.
CLI::Option* addStrictOption(CLI::App& app, bool& strict);

// --exposure auto|EV (shading::applyExposure): ev stays empty for auto.
CLI::Option* addExposureOption(CLI::App& app, std::optional<float>& ev);

// How a command lights and exposes its scene.
struct LookOptions {
  std::optional<float> exposure;  // --exposure: empty for auto
  std::string environment;        // --environment FILE: replaces a scene file's
  float environmentIntensity = 1.0f;  // --environment-intensity: scales it
  float environmentRotation = 0.0f;   // --environment-rotation DEG: turns it further about +y
};
// --exposure, --environment, --environment-intensity and --environment-rotation.
void addLookOptions(CLI::App& app, LookOptions& look);
// --tonemap NAME (mvr/tone_map.h), one of toneMapName's.
CLI::Option* addToneMapOption(CLI::App& app, std::string& name);

// The scene a command renders (a .json scene or a bare mesh), with its
// environment loaded (which takes the place of the default light and
// ambient), exposed, with a one-line warning on stderr when faces were
// dropped.
Scene loadInputScene(const std::string& path, bool strict, const LookOptions& look = {});

}  // namespace mvr::app
