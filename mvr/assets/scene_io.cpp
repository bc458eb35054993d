#include "mvr/assets/scene_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "mvr/error.h"
#include "mvr/assets/mesh_check.h"
#include "mvr/assets/mesh_io.h"

#ifndef MVR_ASSET_DIR
#define MVR_ASSET_DIR "assets"
#endif

namespace mvr {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

std::string droppedFaces(const Scene& scene) {
  return std::to_string(scene.droppedFaces) + " faces dropped (a repeated corner or a vertex that does not exist)";
}

// Reads one scene file, remembering the file name for every error.
class SceneReader {
 public:
  explicit SceneReader(std::string path) : path_(std::move(path)) {}

  Scene read() {
    Json root = parse();
    expectObject(root, "", {"meshes", "materials", "lights", "ambient", "environment", "camera"});
    Scene scene;
    scene.source = path_;
    if (root.contains("materials")) readMaterials(root["materials"]);
    if (!root.contains("meshes")) fail(path_, "no \"meshes\"");
    const Json& meshes = root["meshes"];
    if (!meshes.is_array() || meshes.empty()) bad("meshes", "must be a non-empty array");
    std::vector<Light> fileLights;  // a glTF's KHR_lights_punctual, where the scene file names none
    for (size_t i = 0; i < meshes.size(); ++i) {
      const Scene mesh = readMesh(meshes[i], "meshes[" + std::to_string(i) + "]");
      fileLights.insert(fileLights.end(), mesh.lights.begin(), mesh.lights.end());
      scene.append(mesh);
    }
    if (root.contains("lights")) readLights(root["lights"], scene);
    else if (fileLights.empty()) scene.lights = defaultLights(), scene.defaultLights = true;
    else scene.lights = fileLights;
    if (scene.lights.size() > size_t(kMaxLights)) {
      scene.warnings.push_back(path_ + ": the meshes' files hold " + std::to_string(scene.lights.size()) +
                               " lights: the first " + std::to_string(kMaxLights) + " are used");
      scene.lights.resize(size_t(kMaxLights));
    }
    if (root.contains("ambient")) scene.ambient = color(root["ambient"], "ambient"), scene.defaultAmbient = false;
    if (root.contains("environment")) scene.environment = readEnvironment(root["environment"]);
    if (root.contains("camera")) scene.camera = readCamera(root["camera"]);
    return scene;
  }

 private:
  [[noreturn]] void bad(const std::string& where, const std::string& what) const {
    fail(path_, where + ": " + what);
  }

  Json parse() const {
    std::ifstream in(path_);
    if (!in) fail(path_, "cannot open scene file");
    try {
      return Json::parse(in);
    } catch (const Json::exception& e) {  // syntax, and numbers beyond a double (1e999)
      fail(path_, std::string("bad JSON: ") + e.what());
    }
  }

  void expectObject(const Json& j, const std::string& where,
                    std::initializer_list<const char*> keys) const {
    if (!j.is_object()) bad(where.empty() ? "top level" : where, "must be an object");
    std::set<std::string> allowed(keys.begin(), keys.end());
    for (auto it = j.begin(); it != j.end(); ++it)
      if (!allowed.count(it.key()))
        bad(where.empty() ? "top level" : where, "unknown key \"" + it.key() + "\"");
  }

  double number(const Json& j, const std::string& where) const {
    if (!j.is_number()) bad(where, "must be a number");
    double v = j.get<double>();
    if (!std::isfinite(v)) bad(where, "must be finite");
    return v;
  }

  float unit(const Json& j, const std::string& where) const {
    const double v = number(j, where);
    if (v < 0.0 || v > 1.0) bad(where, "must be in [0, 1]");
    return float(v);
  }

  glm::vec3 vec3(const Json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 3) bad(where, "must be an array of 3 numbers");
    return {float(number(j[0], where)), float(number(j[1], where)), float(number(j[2], where))};
  }

  // A reflectance or light colour: each channel in [0, 1].
  glm::vec3 color(const Json& j, const std::string& where) const {
    const glm::vec3 c = vec3(j, where);
    if (!isUnitColor(c)) bad(where, "colour channels must be in [0, 1]");
    return c;
  }

  std::string relative(const Json& j, const std::string& where) const {
    if (!j.is_string() || j.get<std::string>().empty()) bad(where, "must be a file name");
    fs::path p(j.get<std::string>());
    return p.is_absolute() ? p.string() : (fs::path(path_).parent_path() / p).string();
  }

  Material readMaterial(const Json& j, const std::string& where) const {
    expectObject(j, where,
                 {"diffuse", "texture", "specular", "shininess", "specular_model",
                  "reflection_map", "reflectivity", "two_sided", "emission", "emission_texture", "unlit",
                  "alpha_cutoff", "base_color", "metallic", "roughness"});
    Material m;
    if (j.contains("base_color") || j.contains("metallic") || j.contains("roughness")) {
      // glTF's metallic-roughness; its F0 and c_diff replace specular and diffuse.
      for (const char* key : {"diffuse", "specular", "shininess", "specular_model"})
        if (j.contains(key)) bad(where + "." + key, "is not used with base_color, metallic and roughness");
      const glm::vec3 base = j.contains("base_color") ? color(j["base_color"], where + ".base_color") : glm::vec3(1.0f);
      const float metallic = j.contains("metallic") ? unit(j["metallic"], where + ".metallic") : 0.0f;
      const float roughness = j.contains("roughness") ? unit(j["roughness"], where + ".roughness") : 1.0f;
      m.setMetallicRoughness(base, metallic, roughness);
    }
    if (j.contains("diffuse")) m.diffuse = color(j["diffuse"], where + ".diffuse");
    if (j.contains("texture")) m.texture = relative(j["texture"], where + ".texture");
    if (j.contains("specular")) m.specular = color(j["specular"], where + ".specular");
    if (j.contains("shininess")) m.shininess = float(number(j["shininess"], where + ".shininess"));
    if (j.contains("specular_model")) {
      const Json& model = j["specular_model"];
      if (model == "phong") m.specularModel = SpecularModel::Phong;
      else if (model == "blinn-phong") m.specularModel = SpecularModel::BlinnPhong;
      else bad(where + ".specular_model", "must be \"phong\" or \"blinn-phong\"");
    }
    if (m.shininess < 0 || m.shininess > 10000) bad(where + ".shininess", "must be in [0, 10000]");
    if (j.contains("reflection_map"))
      m.reflectionMap = relative(j["reflection_map"], where + ".reflection_map");
    if (j.contains("reflectivity")) m.reflectivity = color(j["reflectivity"], where + ".reflectivity");
    if (j.contains("emission_texture")) {
      m.emissionTexture = relative(j["emission_texture"], where + ".emission_texture");
      m.emission = glm::vec3(1.0f);  // the texels as they are, unless scaled
    }
    if (j.contains("emission")) m.emission = color(j["emission"], where + ".emission");
    if (j.contains("unlit")) {
      if (!j["unlit"].is_boolean()) bad(where + ".unlit", "must be true or false");
      m.unlit = j["unlit"].get<bool>();
    }
    if (j.contains("alpha_cutoff")) {
      m.alphaCutoff = float(number(j["alpha_cutoff"], where + ".alpha_cutoff"));
      if (!(m.alphaCutoff >= 0.0f && m.alphaCutoff <= 1.0f)) bad(where + ".alpha_cutoff", "must be in [0, 1]");
    }
    if (j.contains("two_sided")) {
      if (!j["two_sided"].is_boolean()) bad(where + ".two_sided", "must be true or false");
      m.twoSided = j["two_sided"].get<bool>();
    }
    return m;
  }

  void readMaterials(const Json& j) {
    if (!j.is_object()) bad("materials", "must be an object of named materials");
    for (auto it = j.begin(); it != j.end(); ++it) {
      Material m = readMaterial(it.value(), "materials." + it.key());
      m.name = it.key();
      materials_[it.key()] = m;
    }
  }

  glm::mat4 readTransform(const Json& j, const std::string& where) const {
    expectObject(j, where, {"translate", "scale", "rotate"});
    glm::mat4 m(1.0f);
    if (j.contains("translate")) m = glm::translate(m, vec3(j["translate"], where + ".translate"));
    if (j.contains("rotate")) {
      const Json& r = j["rotate"];
      if (!r.is_array() || r.size() != 4) bad(where + ".rotate", "must be [degrees, x, y, z]");
      glm::vec3 axis(float(number(r[1], where)), float(number(r[2], where)),
                     float(number(r[3], where)));
      if (glm::length(axis) == 0) bad(where + ".rotate", "axis must not be zero");
      m = glm::rotate(m, glm::radians(float(number(r[0], where))), glm::normalize(axis));
    }
    if (j.contains("scale")) {
      const Json& s = j["scale"];
      glm::vec3 v = s.is_array() ? vec3(s, where + ".scale") : glm::vec3(float(number(s, where)));
      if (v.x == 0 || v.y == 0 || v.z == 0) bad(where + ".scale", "must not be zero");
      m = glm::scale(m, v);
    }
    return m;
  }

  Scene readMesh(const Json& j, const std::string& where) const {
    expectObject(j, where, {"file", "transform", "material", "materials"});
    if (!j.contains("file")) bad(where, "no \"file\"");
    Scene mesh;
    try {
      mesh = loadMesh(relative(j["file"], where + ".file"));
    } catch (const Error& e) {
      bad(where + ".file", e.what());
    }
    if (j.contains("transform")) mesh.transform(readTransform(j["transform"], where + ".transform"));
    if (j.contains("material") && j.contains("materials"))
      bad(where, "\"material\" (the whole file's) and \"materials\" (by name) exclude each other");
    if (j.contains("material")) {  // one material for every face of the file
      mesh.materials = {materialOrName(j["material"], where + ".material")};
      mesh.materialIds.assign(mesh.triangles.size(), 0);
    }
    if (j.contains("materials")) overrideByName(mesh, j["materials"], where + ".materials");
    return mesh;
  }

  // A material given inline, or by the name of one in "materials".
  Material materialOrName(const Json& m, const std::string& where) const {
    if (!m.is_string()) {
      Material out = readMaterial(m, where);
      out.name = where;
      return out;
    }
    auto it = materials_.find(m.get<std::string>());
    if (it == materials_.end()) bad(where, "no material \"" + m.get<std::string>() + "\"");
    return it->second;
  }

  // "materials": {"NAME": material}: each replaces the file's material of
  // that name (an MTL's newmtl, a glTF material's name).
  void overrideByName(Scene& mesh, const Json& j, const std::string& where) const {
    if (!j.is_object()) bad(where, "must be an object of the file's material names");
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string at = where + "." + it.key();
      auto named = std::find_if(mesh.materials.begin(), mesh.materials.end(),
                                [&](const Material& m) { return m.name == it.key(); });
      if (named == mesh.materials.end()) bad(at, "the file has no material of this name");
      *named = materialOrName(it.value(), at);
    }
  }

  void readLights(const Json& j, Scene& scene) const {
    if (!j.is_array()) bad("lights", "must be an array");
    if (j.size() > size_t(kMaxLights)) bad("lights", "more than " + std::to_string(kMaxLights) + " lights");
    for (size_t i = 0; i < j.size(); ++i) {
      const std::string where = "lights[" + std::to_string(i) + "]";
      expectObject(j[i], where, {"type", "direction", "position", "color", "inner_angle", "outer_angle"});
      Light light;
      std::string type = j[i].value("type", "directional");
      if (type == "directional") {
        light.type = Light::Type::Directional;
        light.vector = direction(j[i], where, "directional");
      } else if (type == "point" || type == "spot") {
        light.type = type == "point" ? Light::Type::Point : Light::Type::Spot;
        if (!j[i].contains("position")) bad(where, type + " light needs \"position\"");
        light.vector = vec3(j[i]["position"], where + ".position");
      } else {
        bad(where + ".type", "must be \"directional\", \"point\" or \"spot\"");
      }
      if (light.type == Light::Type::Spot) readCone(j[i], where, light);
      if (j[i].contains("color")) light.color = color(j[i]["color"], where + ".color");
      scene.lights.push_back(light);
    }
  }

  glm::vec3 direction(const Json& j, const std::string& where, const std::string& type) const {
    if (!j.contains("direction")) bad(where, type + " light needs \"direction\"");
    const glm::vec3 d = vec3(j["direction"], where + ".direction");
    if (glm::length(d) == 0) bad(where + ".direction", "must not be zero");
    return glm::normalize(d);
  }

  // A spot's cone: half angles off its axis in degrees, glTF's defaults.
  void readCone(const Json& j, const std::string& where, Light& light) const {
    light.axis = direction(j, where, "spot");
    const auto angle = [&](const char* key, double fallback, double lo) {
      const double a = j.contains(key) ? number(j[key], where + "." + key) : fallback;
      if (!(a >= lo && a <= 90.0)) bad(where + "." + key, "must be in [" + std::to_string(int(lo)) + ", 90] degrees");
      return a;
    };
    const double outer = angle("outer_angle", 45.0, 0.0);
    const double inner = angle("inner_angle", 0.0, 0.0);
    if (inner > outer) bad(where + ".inner_angle", "must not be wider than outer_angle");
    light.cosOuter = float(std::cos(glm::radians(outer)));
    light.cosInner = float(std::cos(glm::radians(inner)));
  }

  // "environment": "FILE" or {"file", "intensity", "rotation"} (degrees about +y).
  Environment readEnvironment(const Json& j) const {
    Environment e;
    if (j.is_string()) {
      e.file = relative(j, "environment");
      return e;
    }
    expectObject(j, "environment", {"file", "intensity", "rotation"});
    if (!j.contains("file")) bad("environment", "no \"file\"");
    e.file = relative(j["file"], "environment.file");
    if (j.contains("intensity")) {
      e.intensity = float(number(j["intensity"], "environment.intensity"));
      if (!(e.intensity >= 0.0f && e.intensity <= 1e6f)) bad("environment.intensity", "must lie in [0, 1e6]");
    }
    if (j.contains("rotation")) {
      const double degrees = number(j["rotation"], "environment.rotation");
      if (!(std::abs(degrees) <= 1e6)) bad("environment.rotation", "degrees must lie in [-1e6, 1e6]");
      e.turn(float(degrees));
    }
    return e;
  }

  CameraSpec readCamera(const Json& j) const {
    expectObject(j, "camera", {"distance", "image_plane", "fov", "track", "cone", "rows", "near", "far"});
    CameraSpec c;
    auto pair = [&](const char* key, double& a, double& b) {
      const Json& v = j[key];
      if (!v.is_array() || v.size() != 2) bad(std::string("camera.") + key, "must be [a, b]");
      a = number(v[0], std::string("camera.") + key);
      b = number(v[1], std::string("camera.") + key);
    };
    for (const char* key : {"distance", "near", "far"})
      if (!j.contains(key)) bad("camera", std::string("no \"") + key + "\"");
    // One of each pair: the plane or the field of view, the track or the cone.
    for (auto [a, b] : {std::pair{"image_plane", "fov"}, std::pair{"track", "cone"}})
      if (j.contains(a) == j.contains(b))
        bad("camera", std::string("give \"") + a + "\" or \"" + b + "\" (one of them)");
    c.distance = number(j["distance"], "camera.distance");
    // Degrees in (0, 180) as tan of the half angle, times the distance.
    auto halfWidth = [&](const char* key) {
      const double deg = number(j[key], std::string("camera.") + key);
      if (!(deg > 0.0 && deg < 180.0)) bad(std::string("camera.") + key, "degrees must lie in (0, 180)");
      return c.distance * std::tan(0.5 * deg * 3.14159265358979323846 / 180.0);
    };
    const Json& plane = j.contains("fov") ? j["fov"] : j["image_plane"];
    if (j.contains("fov")) {
      c.planeWidth = 2.0 * halfWidth("fov");
    } else if (plane.is_number()) {
      c.planeWidth = number(plane, "camera.image_plane");
    } else {
      pair("image_plane", c.planeWidth, c.planeHeight);
      // A height of 0 would silently mean "from the aspect ratio".
      if (!(c.planeHeight > 0)) bad("camera.image_plane", "height must be positive");
    }
    if (j.contains("cone")) {
      c.trackRight = halfWidth("cone");
      c.trackLeft = -c.trackRight;
    } else {
      pair("track", c.trackLeft, c.trackRight);
    }
    if (j.contains("rows")) pair("rows", c.rowTop, c.rowBottom);
    c.nearDistance = number(j["near"], "camera.near");
    c.farDistance = number(j["far"], "camera.far");
    try {
      ShearingCamera check(c, 1, 1, 1);
    } catch (const Error& e) {
      fail(path_, e.what());
    }
    return c;
  }

  std::string path_;
  std::map<std::string, Material> materials_;

 public:
  static std::vector<Light> defaultLights() {
    Light key;
    key.vector = glm::normalize(glm::vec3(-0.4f, -0.6f, -1.0f));
    key.color = glm::vec3(0.85f);
    return {key};
  }

};

}  // namespace

Scene loadScene(const std::string& path, bool strict) {
  Scene scene;
  if (fs::path(path).extension() != ".json") {
    scene = loadMesh(path);
    checkSceneGeometry(scene, path);  // before centring: bounds of a stray vertex overflow
    if (scene.lights.empty()) scene.lights = SceneReader::defaultLights(), scene.defaultLights = true;  // else the file's (glTF)
    scene.transform(glm::translate(glm::mat4(1.0f), -scene.bounds().center()));
  } else {
    scene = SceneReader(path).read();
    checkSceneGeometry(scene, path);  // after the meshes' transforms
  }
  if (strict && scene.droppedFaces) fail(path, droppedFaces(scene) + " (--strict)");
  return scene;
}

std::string droppedFacesWarning(const Scene& scene) {
  return scene.droppedFaces ? scene.source + ": " + droppedFaces(scene) : "";
}

std::string defaultScenePath() {
  const char* env = std::getenv("MVR_ASSETS");
  return (fs::path(env ? env : MVR_ASSET_DIR) / "default.json").string();
}

CameraSpec cameraFor(const Scene& scene, int width, int height) {
  return scene.camera ? *scene.camera : ShearingCamera::frame(scene.bounds(), width, height);
}

}  // namespace mvr
