#include "simtree/viewer/detail/gl_objects.h"

#include <fmt/format.h>

#include <vector>

#include "simtree/core/error.h"

namespace simtree::gl {
namespace {

GLuint Compile(const std::string& name, GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    throw Error(fmt::format("OpenGL: the {} {} shader does not compile: {}", name,
                            kind == GL_VERTEX_SHADER ? "vertex" : "fragment", log.c_str()));
  }
  return shader;
}

}  // namespace

void DeleteProgram(GLuint id) { glDeleteProgram(id); }
void DeleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void DeleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void DeleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void DeleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void DeleteRenderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }

Buffer MakeBuffer() {
  GLuint id = 0;
  glGenBuffers(1, &id);
  return Buffer(id);
}

VertexArray MakeVertexArray() {
  GLuint id = 0;
  glGenVertexArrays(1, &id);
  return VertexArray(id);
}

Texture MakeTexture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  return Texture(id);
}

Program LinkProgram(const std::string& name, const char* vertex_source,
                    const char* fragment_source) {
  const GLuint vs = Compile(name, GL_VERTEX_SHADER, vertex_source);
  const GLuint fs = Compile(name, GL_FRAGMENT_SHADER, fragment_source);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw Error(fmt::format("OpenGL: the {} program does not link: {}", name, log.c_str()));
  }
  return Program(program);
}

GLint Uniform(const Program& program, const char* name) {
  return glGetUniformLocation(program.id(), name);
}

Texture MakeImageTexture(const RgbImage& image) {
  Texture texture = MakeTexture();
  glBindTexture(GL_TEXTURE_2D, texture.id());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE,
               image.pixels.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return texture;
}

void CheckErrors(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    throw Error(fmt::format("OpenGL error 0x{:04x} in {}", static_cast<unsigned>(error), what));
  }
}

std::string RendererName() {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return fmt::format("{} (OpenGL {})", renderer ? renderer : "?", version ? version : "?");
}

}  // namespace simtree::gl
