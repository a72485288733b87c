#pragma once
// OpenGL for the viewer module only: core profile 3.3 declarations, called directly. Every entry
// point is exported by the GL vendor-neutral dispatch library (libOpenGL), which forwards to the
// context made current by GLFW (a window) or EGL (headless), so no loader is needed.

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
