#include "apps/cli/cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mvr/camera.h"
#include "mvr/error.h"
#include "mvr/gl/gl_context.h"
#include "mvr/assets/scene_io.h"
#include "mvr/parallel.h"
#include "mvr/tone_map.h"
#include "shading/image_light.h"
#include "shading/lighting.h"

namespace mvr::app {

std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError&) {
    // CLI11 lists them as it parsed them, backwards; ours in the order given.
    std::vector<std::string> left = app.remaining(), given;
    for (int i = 1; i < argc; ++i)
      if (auto at = std::find(left.begin(), left.end(), argv[i]); at != left.end()) {
        given.push_back(*at);
        left.erase(at);
      }
    given.insert(given.end(), left.begin(), left.end());
    std::string list;
    for (const std::string& a : given) list += (list.empty() ? "" : " ") + a;
    throw Error("unexpected argument" + std::string(given.size() == 1 ? " " : "s ") + list + " (see " +
                app.get_name() + " --help)");
  } catch (const CLI::ParseError& e) {
    // CLI11's own report adds a second line; ours is one, like every error.
    std::string what = e.what();
    for (char& c : what)
      if (c == '\n') c = ' ';
    throw Error(what);
  }
  return std::nullopt;
}

std::pair<int, int> parseSize(const std::string& flag, const std::string& v) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  const int most = Limits::kMaxSide;
  if (std::sscanf(v.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') ||
      w < 1 || h < 1 || w > most || h > most)
    fail(flag, "'" + v + "' is not WxH with sides 1.." + std::to_string(most));
  return {w, h};
}

CLI::Option* addSizeOption(CLI::App& app, const std::string& name, std::pair<int, int>& size,
                           const std::string& description) {
  const std::string flag = "--" + name;
  auto* option = app.add_option_function<std::string>(
      flag, [&size, flag](const std::string& text) { size = parseSize(flag, text); }, description);
  option->type_name("WxH")->default_str(std::to_string(size.first) + "x" + std::to_string(size.second));
  return option;
}

void addViewCountOptions(CLI::App& app, int& views, int& rows) {
  app.add_option("--views", views, "views on the horizontal track")
      ->check(CLI::Range(1, Limits::kMaxViews))
      ->capture_default_str();
  app.add_option("--rows", rows, "rows of views for full parallax")
      ->check(CLI::Range(1, Limits::kMaxRows))
      ->capture_default_str();
}

void addAntialiasingOptions(CLI::App& app, Supersampling& aa) {
  app.add_option("--aa", aa.spatial,
                 "anti-aliasing: S x S samples per pixel, box-filtered in linear light (the back end "
                 "renders S times the width and height)")
      ->type_name("S")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  app.add_option("--aa-views", aa.views,
                 "perspective anti-aliasing: P samples per view spread over its share of the track "
                 "(P times the views; cheap for mvr, P times the work for per-view back ends)")
      ->type_name("P")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
}

CLI::Option* addGlOption(CLI::App& app, std::string& platform) {
  return app.add_option("--gl", platform, "GL platform: " + alternatives(kGlPlatformNames) +
                                              " (auto: egl, else osmesa)")
      ->capture_default_str();
}

CLI::Option* addThreadsOption(CLI::App& app) {
  return app.add_option_function<int>("--threads", [](const int& n) { setThreadCount(n); },
                                      "worker threads for slicing, CPU rasterization and image "
                                      "encoding (default 0: every core)")
      ->check(CLI::Range(0, 4096))
      ->type_name("N");
}

CLI::Option* addStrictOption(CLI::App& app, bool& strict) {
  return app.add_flag("--strict", strict,
                      "faces a mesh file holds but that cannot be used (a repeated corner, a "
                      "missing vertex) are an error instead of a warning");
}

CLI::Option* addExposureOption(CLI::App& app, std::optional<float>& ev) {
  return app
      .add_option_function<std::string>(
          "--exposure",
          [&ev](const std::string& v) {
            if (v == "auto") return ev.reset();
            ev = std::stof(v);
          },
          "camera exposure: EV stops on the scene's radiance (lights in physical units, glTF's lux and "
          "candela, times 2^EV; ambient and emission too), or auto (default: a file's lights scaled so "
          "that their illuminance at the scene's centre sums to 1)")
      ->check([](const std::string& v) -> std::string {
        if (v == "auto") return "";
        try {
          size_t used = 0;
          const float ev = std::stof(v, &used);
          if (used == v.size() && std::isfinite(ev) && std::abs(ev) <= 64.0f) return "";
        } catch (const std::exception&) {
        }
        return "must be auto or a number of stops in [-64, 64]";
      })
      ->type_name("auto|EV");
}

void addLookOptions(CLI::App& app, LookOptions& look) {
  addExposureOption(app, look.exposure);
  app.add_option("--environment", look.environment,
                 "image-based light: an equirectangular .hdr or .exr (three.js's axes: +y at the top row, "
                 "-x at its centre) lighting every lit material's diffuse and metallic-roughness specular; it "
                 "replaces the default light and ambient (a file's own lights stay)")
      ->type_name("FILE");
  app.add_option("--environment-intensity", look.environmentIntensity,
                 "scales the environment's radiance (--environment's or the scene file's)")
      ->check(CLI::Range(0.0f, 1e6f))
      ->type_name("K");
  app.add_option("--environment-rotation", look.environmentRotation,
                 "turns the environment by DEG about +y (after a scene file's rotation)")
      ->check(CLI::Range(-1e6f, 1e6f))
      ->type_name("DEG");
}

CLI::Option* addToneMapOption(CLI::App& app, std::string& name) {
  std::vector<std::string> names;
  for (ToneMap m : kToneMaps) names.push_back(toneMapName(m));
  return app
      .add_option("--tonemap", name,
                  "display transform before the output encoding: none, aces (filmic), agx or neutral (Khronos "
                  "PBR Neutral), as three.js draws them; shades in float without clamping. Not with exr, "
                  "which keeps linear radiance")
      ->check(CLI::IsMember(names))
      ->capture_default_str();
}

namespace {

// The look's environment on the scene, in place of its default lighting.
void lightByEnvironment(Scene& scene, const LookOptions& look) {
  if (!look.environment.empty()) scene.environment = Environment{look.environment};
  if (!scene.environment) {
    if (look.environmentIntensity != 1.0f) fail("--environment-intensity", "the scene has no environment");
    if (look.environmentRotation != 0.0f) fail("--environment-rotation", "the scene has no environment");
    return;
  }
  scene.environment->intensity *= look.environmentIntensity;
  scene.environment->turn(look.environmentRotation);
  if (scene.defaultLights) scene.lights.clear(), scene.defaultLights = false;
  if (scene.defaultAmbient) scene.ambient = glm::vec3(0.0f), scene.defaultAmbient = false;
  shading::loadEnvironment(scene);
}

}  // namespace

Scene loadInputScene(const std::string& path, bool strict, const LookOptions& look) {
  Scene scene = loadScene(path, strict);
  lightByEnvironment(scene, look);
  shading::applyExposure(scene, look.exposure);
  if (const std::string warning = droppedFacesWarning(scene); !warning.empty())
    std::fprintf(stderr, "mvr: warning: %s\n", warning.c_str());
  for (const std::string& warning : scene.warnings) std::fprintf(stderr, "mvr: warning: %s\n", warning.c_str());
  return scene;
}

}  // namespace mvr::app
