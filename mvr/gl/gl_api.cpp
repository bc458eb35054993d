#include "mvr/gl/gl_api.h"

#include "mvr/error.h"

namespace mvr::gl {

void loadFunctions(ProcAddressFn getProcAddress) {
#define MVR_GL_FN(name, type)                                                 \
  name = reinterpret_cast<type>(getProcAddress("gl" #name));                  \
  if (!name) fail("GL", "context lacks gl" #name " (GL 4.5 core required)");
#include "mvr/gl/gl_functions.inc"
#undef MVR_GL_FN
}

bool hasExtension(const std::string& name) {
  GLint count = 0;
  GetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* ext = reinterpret_cast<const char*>(GetStringi(GL_EXTENSIONS, GLuint(i)));
    if (ext && name == ext) return true;
  }
  return false;
}

bool rendersOnCpu() {
  const auto* renderer = reinterpret_cast<const char*>(GetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  return name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos;
}

int maxTextureSize() {
  GLint size = 4096;
  GetIntegerv(GL_MAX_TEXTURE_SIZE, &size);
  return size;
}

void checkError(const char* what) {
  GLenum err = GetError();
  if (err == GL_NO_ERROR) return;
  const char* text = "unknown error";
  switch (err) {
    case GL_INVALID_ENUM: text = "GL_INVALID_ENUM"; break;
    case GL_INVALID_VALUE: text = "GL_INVALID_VALUE"; break;
    case GL_INVALID_OPERATION: text = "GL_INVALID_OPERATION"; break;
    case GL_INVALID_FRAMEBUFFER_OPERATION: text = "GL_INVALID_FRAMEBUFFER_OPERATION"; break;
    case GL_OUT_OF_MEMORY: text = "GL_OUT_OF_MEMORY (reduce --size or --views)"; break;
  }
  fail("GL", std::string(what) + ": " + text);
}

}  // namespace mvr::gl
