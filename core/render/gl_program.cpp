#include "gl_program.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace tourmap::render {
namespace {

GLuint compile(std::string_view name, GLenum stage, std::string_view source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.data();
  const auto length = static_cast<GLint>(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::string log(4096, '\0');
    GLsizei used = 0;
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), &used, log.data());
    glDeleteShader(shader);
    log.resize(static_cast<std::size_t>(used));
    throw std::runtime_error(std::string(name) + (stage == GL_VERTEX_SHADER ? " vertex" : " fragment") +
                             " shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

void check_gl(const char* where) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(error));
    throw std::runtime_error(std::string("OpenGL error ") + code + " in " + where);
  }
}

GlProgram::GlProgram(std::string_view name, std::string_view vertex_source, std::string_view fragment_source) {
  const GLuint vs = compile(name, GL_VERTEX_SHADER, vertex_source);
  GLuint fs = 0;
  try {
    fs = compile(name, GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::string log(4096, '\0');
    GLsizei used = 0;
    glGetProgramInfoLog(id_, static_cast<GLsizei>(log.size()), &used, log.data());
    glDeleteProgram(id_);
    log.resize(static_cast<std::size_t>(used));
    throw std::runtime_error(std::string(name) + " program does not link: " + log);
  }
}

GlProgram::~GlProgram() { glDeleteProgram(id_); }

StreamBuffer::StreamBuffer() { glCreateBuffers(1, &id_); }

StreamBuffer::~StreamBuffer() { glDeleteBuffers(1, &id_); }

void StreamBuffer::upload(const void* data, std::size_t bytes) {
  // New storage every time (orphaning): draws still queued keep reading the old contents.
  glNamedBufferData(id_, static_cast<GLsizeiptr>(bytes), data, GL_STREAM_DRAW);
}

}  // namespace tourmap::render
