#pragma once
// Small OpenGL helpers internal to core/render (this header pulls in libepoxy): a linked shader
// program and an error check. Every call needs the owning EglContext current.

#include <epoxy/gl.h>

#include <string_view>

namespace tourmap::render {

// Throws std::runtime_error naming `where` when glGetError reports an error.
void check_gl(const char* where);

class GlProgram {
 public:
  // Compiles and links; throws std::runtime_error with the driver's log on failure.
  GlProgram(std::string_view name, std::string_view vertex_source, std::string_view fragment_source);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return id_; }
  // -1 when the uniform does not exist or was optimised out (glUniform ignores -1).
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  GLuint id_ = 0;
};

// A GL buffer object that grows on demand; upload() replaces its contents.
class StreamBuffer {
 public:
  StreamBuffer();
  ~StreamBuffer();
  StreamBuffer(const StreamBuffer&) = delete;
  StreamBuffer& operator=(const StreamBuffer&) = delete;

  void upload(const void* data, std::size_t bytes);
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

}  // namespace tourmap::render
