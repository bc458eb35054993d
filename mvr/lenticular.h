#pragma once
// The panel mapping of a lenticular display (issue 48): which view, and
// which texel of the quilt, each subpixel of the panel shows. For panel
// pixel (x, y), y down from the top:
//   u = (x + 0.5) / screenW,  v = 1 - (y + 0.5) / screenH
//   z_i = fract((u' + i / (3 screenW) + v tilt) pitch' - center), i = 0, 1, 2
//   (1 - z_i where invView is set); subpixel i shows view floor(z_i N)
// with pitch' = PanelCalibration::pitchAcross() and tilt =
// PanelCalibration::tilt(), at (u', v') within that view's tile (view 0
// the bottom-left tile, rows of tiles upward). flipImageX and flipImageY
// are applied as Looking Glass's lenticular shader does: u' = 1 - u
// (which moves the lens phase too) and v' = 1 - v (the tile's sample
// only; the phase keeps the panel's own v). Red comes from subpixel ri,
// green from 1, blue from bi: (ri, bi) = (0, 2), or (2, 0) with flipSubp.
//
// Texels are taken nearest (a subpixel shows one view's one texel), and
// every step is a float32 addition, multiplication or floor in a fixed
// order, written once here and once in the GLSL pass (lenticularGlsl):
// the CPU image and the GPU's agree on every subpixel.
#include <string>

#include <glm/glm.hpp>

#include "mvr/image.h"

namespace mvr {

// A lenticular display's calibration, as Looking Glass devices carry it
// (visual.json; read by mvr/images/panel_calibration.h): the lens pitch and
// slope, the phase at the panel's origin, the panel's size and density,
// and the flags for how views run.
struct PanelCalibration {
  double pitch = 0.0;   // lenses per inch across the panel
  double slope = 0.0;   // panel pixels down per pixel across along a lens
  double center = 0.0;  // the lens phase at the panel's origin
  double dpi = 0.0;
  int screenW = 0, screenH = 0;
  bool invView = false, flipSubp = false, flipImageX = false, flipImageY = false;
  double viewCone = 40.0;  // degrees the views span (absent in older files)

  // The lens pitch in lenses per panel width, across the panel's rows
  // (the lenses run at atan(1 / slope) to the vertical).
  double pitchAcross() const;
  // The phase's change per panel height, in panel widths.
  double tilt() const { return screenH / (screenW * slope); }
};

// A quilt's tiles: columns x rows, the first `views` used, each
// tileWidth x tileHeight from the quilt's bottom-left corner.
struct QuiltGrid {
  int columns = 1, rows = 1, views = 1, tileWidth = 0, tileHeight = 0;
};

// The mapping's numbers, float32 as both sides use them.
struct LenticularMap {
  int screenW = 0, screenH = 0;
  float invW = 0, invH = 0, subp = 0, tilt = 0, pitch = 0, center = 0;
  int views = 1, columns = 1, tileW = 0, tileH = 0, quiltHeight = 0;
  bool invView = false, flipX = false, flipY = false;
  int ri = 0, bi = 2;

  // Throws mvr::Error when the grid does not fit a quilt of that height.
  static LenticularMap of(const PanelCalibration& panel, const QuiltGrid& grid, int quiltHeight);
  // The view subpixel i (0 red's place, 1, 2) of panel pixel (x, y) shows.
  int view(int x, int y, int i) const;
  // The texel that subpixel shows: (x, y down from the top) in its view,
  // and the view.
  glm::ivec3 viewTexel(int x, int y, int i) const;
  // The same texel in the quilt (x right, y down from the top).
  glm::ivec2 texel(int x, int y, int i) const;
};

// How the views reach the GL pass: a quilt (a 2D texture, view 0 the
// bottom-left tile); an EPI volume (a 2D array texture: layer s the EPI
// of scanline s, its row v view v's), where the views a panel row samples
// lie close together: on llvmpipe the pass takes a quarter of the
// quilt's time (13 against 48 ms for a Portrait); or a view array (a 2D
// array texture: layer v view v, rows top first), where a view renderer
// on the GPU copies each view it draws (mvr/gl/view_layers.h).
enum class ViewLayout { Quilt, EpiVolume, ViewArray };

// The panel's native image (screenW x screenH, opaque) of an 8-bit quilt,
// on the CPU: the GLSL pass's oracle.
Image nativeImage(const Image& quilt, const LenticularMap& map);

// The same mapping in GLSL: `vec3 lenticular(ivec2 pixel)` over `uniform
// sampler2D quilt` (sampler2DArray for the layered layouts) and the uniforms
// LenticularPass sets (mvr/gl/lenticular_pass.h).
std::string lenticularGlsl(ViewLayout layout);

// An 8-bit quilt's views as an EPI volume (width tileW, tileH x views
// rows: scanline s's EPI, then s + 1's), the layout ViewLayout::EpiVolume
// uploads as layers.
Image epiVolumeOf(const Image& quilt, const QuiltGrid& grid);

}  // namespace mvr
