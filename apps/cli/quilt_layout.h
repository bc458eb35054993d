#pragma once
// What --quilt accepts: auto (near square; a grid's own rows), COLSxROWS,
// or a Looking Glass display by name, whose quilt settings come from
// Looking Glass Factory's quilt documentation (lfdocs.lookingglassfactory.com,
// "Quilts", "Quilt Settings by Device": columns, rows and the quilt's
// pixel size; the display aspect where that page states it: Portrait
// 0.75, the 16" and 32" landscape displays 16:9). A preset sets the view
// count (columns x rows) and the tile size unless --views or --size say
// otherwise, and the image plane's aspect to the display's, so that the
// display's stretch of the tiles restores it.
#include <string>
#include <vector>

namespace mvr::app {

struct QuiltLayout {
  int columns = 0, rows = 0;  // 0: auto
  std::string preset;         // the display's name, or empty
  int quiltWidth = 0, quiltHeight = 0;
  double aspect = 0.0;  // the display's width / height; 0: the tiles'

  int tileWidth() const { return columns ? quiltWidth / columns : 0; }
  int tileHeight() const { return rows ? quiltHeight / rows : 0; }
};

// Throws mvr::Error naming --quilt for anything else, listing the presets.
QuiltLayout parseQuilt(const std::string& text);
const std::vector<QuiltLayout>& quiltPresets();

// The layout a quilt's file name states (..._qs{C}x{R}a{aspect}.ext), or
// else its EXIF UserComment (LKGColumns, LKGRows, LKGAspect), and its view
// count: LKGNumViews where present, else C x R. Throws mvr::Error naming
// the file when neither gives a layout or the image does not divide into
// C x R tiles.
struct QuiltFile {
  int columns = 0, rows = 0, views = 0;
  double aspect = 0.0;
};
QuiltFile readQuiltLayout(const std::string& path, int imageWidth, int imageHeight);

// The EXIF UserComment JSON Looking Glass tools read a quilt's layout from
// (LKGNumViews, LKGRows, LKGColumns, LKGAspect, LKGType).
std::string quiltMetadata(int views, int columns, int rows, double aspect);

}  // namespace mvr::app
