#pragma once
// Checks a mesh file before OpenMesh reads it. OpenMesh's readers trust
// their input: an OBJ face naming a vertex that does not exist corrupts
// the heap (ImporterT::set_texcoord), a PLY header with a mangled keyword
// crashes its format probe, one cut inside the header makes it spin, and
// one cut inside its data loses faces silently (issue 16). These checks
// are bounded and read the file once; each rejection is one line naming
// the file and the line or element.
#include <string>

namespace mvr {

// OBJ: every v/vt/vn reference of every face in range of the elements
// defined before it (negative indices count back), at least three corners
// per face. PLY: a complete header (ply, one format line, elements with
// counts, properties of known types, end_header), and data long enough for
// every element (binary: at least each element's fixed bytes; ASCII: a
// line per element). Other formats pass. Throws mvr::Error.
void checkMeshFile(const std::string& path);

}  // namespace mvr
