#pragma once
// The manifest.json of an image set: what the set holds (views, rows, size,
// format, order) and therefore what its files are called. Every writer of a
// set (render, the stream's consumer) and every reader (the viewer) goes
// through this class, so a name is derived in one place.
#include <string>

#include <nlohmann/json.hpp>

#include "mvr/camera.h"
#include "mvr/images/image_file.h"

namespace mvr {

class Manifest {
 public:
  int views = 1, rows = 1;
  int width = 0, height = 0;
  std::string format = "png";  // png | exr | tiff
  std::string order = "view";  // view: view_* files; epi: epi_* files (rows are views)
  int bits = 8;                // per channel in the files (exr: 16 half or 32 float)
  int compression = kDefaultPngCompression;  // png files: level 0-9 (1 our row coder, 2-9 zlib)
  std::string codec;           // exr and tiff files: their codec ("": the format's default)
  // png and tiff files hold sRGB-encoded colour (else linear; exr always
  // linear). Recorded as color_encoding; a manifest without it is from
  // before sRGB output, whose files were linear.
  bool srgb = true;
  // Everything else the writer records (scene, back end, camera, timings,
  // files, ...), written beside the layout and kept when read back.
  nlohmann::json info = nlohmann::json::object();

  // File names. Numbers have at least four digits (rows three) and as many
  // more as the largest index needs, so names sort in index order.
  std::string viewName(int row, int view) const;
  std::string epiName(int row, int scanline) const;
  // The names as a printf pattern, e.g. "view_%05d" or "view_r%03d_c%04d".
  std::string viewPattern() const;
  std::string epiPattern() const;
  // A view's depth map (render --depth): the view's name with depth_ for
  // view_, always exr.
  std::string depthName(int row, int view) const;
  std::string depthPattern() const;

  // How the set's files store their pixels.
  ImageEncoding encoding() const { return {bits, compression, codec, srgb}; }
  // "srgb" or "linear", as the files hold colour.
  std::string colorEncoding() const { return srgb && format != "exr" ? "srgb" : "linear"; }

  // The camera as the manifest records it (distance, image plane, track,
  // cone and field of view) and every view's K, V and eye. imagePlaneZ:
  // where the rig's image plane lies in the scene's coordinates (render
  // --focal); V and the eyes are given in those. fromFile: the scene's
  // file's coordinates to the scene's (Scene::fromFile without the focal
  // plane's move), recorded as from_file where it is not the identity.
  void setCamera(const ShearingCamera& camera, double imagePlaneZ = 0.0, const glm::dmat4& fromFile = glm::dmat4(1.0));

  nlohmann::json toJson() const;
  // Throws mvr::Error naming `where` for a missing or impossible field.
  static Manifest fromJson(const nlohmann::json& json, const std::string& where);
  // dir/manifest.json; throws naming the file when it is missing or bad.
  static Manifest read(const std::string& dir);
  // Writes dir/manifest.json under a temporary name and renames it.
  void write(const std::string& dir) const;
  // What write() puts in manifest.json.
  std::string text() const;
};

}  // namespace mvr
