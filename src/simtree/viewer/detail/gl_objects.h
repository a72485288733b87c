#pragma once
// Small owners of OpenGL objects (a program, a buffer, a vertex array, a texture), each deleted
// with its C++ object. They need a current context when created and destroyed.

#include <string>
#include <utility>

#include "simtree/io/image_io.h"
#include "simtree/viewer/detail/gl.h"

namespace simtree::gl {

// A GL name with its deleter: movable, not copyable.
template <void (*Delete)(GLuint)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  ~Handle() { Reset(); }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      Reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  GLuint id() const { return id_; }
  void Reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

void DeleteProgram(GLuint id);
void DeleteBuffer(GLuint id);
void DeleteVertexArray(GLuint id);
void DeleteTexture(GLuint id);
void DeleteFramebuffer(GLuint id);
void DeleteRenderbuffer(GLuint id);

using Program = Handle<DeleteProgram>;
using Buffer = Handle<DeleteBuffer>;
using VertexArray = Handle<DeleteVertexArray>;
using Texture = Handle<DeleteTexture>;
using Framebuffer = Handle<DeleteFramebuffer>;
using Renderbuffer = Handle<DeleteRenderbuffer>;

Buffer MakeBuffer();
VertexArray MakeVertexArray();
Texture MakeTexture();

// Compiles and links; throws simtree::Error with the driver's log naming `name` on failure.
Program LinkProgram(const std::string& name, const char* vertex_source,
                    const char* fragment_source);
GLint Uniform(const Program& program, const char* name);

// A mipmapped, repeating RGB texture of an image.
Texture MakeImageTexture(const RgbImage& image);

// Throws simtree::Error naming `what` when glGetError() reports anything.
void CheckErrors(const char* what);

// The GL_RENDERER and GL_VERSION strings of the current context.
std::string RendererName();

}  // namespace simtree::gl
