#pragma once
// The GL 4.5 core entry points as function pointers, loaded from whichever
// context back end is current (EGL, OSMesa, GLFW). libepoxy was the first
// candidate, but it cannot resolve functions under OSMesa (it only knows
// GLX and EGL), so the renderer carries its own small table.
#include <GL/glcorearb.h>

#include <string>

namespace mvr::gl {

#define MVR_GL_FN(name, type) inline type name = nullptr;
#include "mvr/gl/gl_functions.inc"
#undef MVR_GL_FN

using ProcAddressFn = void* (*)(const char* name);

// Loads every entry point; throws mvr::Error naming the first one missing.
void loadFunctions(ProcAddressFn getProcAddress);

bool hasExtension(const std::string& name);

// The current context renders on the CPU (Mesa llvmpipe or softpipe):
// reads are synchronous there, and staging them through buffers only adds
// a copy.
bool rendersOnCpu();

// GL_MAX_TEXTURE_SIZE of the current context.
int maxTextureSize();

// Throws mvr::Error("GL: <what>: <error name>") if glGetError reports one.
void checkError(const char* what);

}  // namespace mvr::gl
