#pragma once
// A headless OpenGL 4.5 core context through EGL, with no window and no default framebuffer
// (render into an FBO). Created and made current on the calling thread: one context per render
// thread. GL objects made while it is current must be destroyed before it.

#include <string>

namespace tourmap::render {

class EglContext {
 public:
  // Throws std::runtime_error naming the missing piece (EGL display, extension, GL 4.5).
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes the context current on the calling thread (it is current on the creating thread).
  void make_current();

  const std::string& renderer() const { return renderer_; }   // GL_RENDERER, e.g. "llvmpipe (...)"
  const std::string& version() const { return version_; }     // GL_VERSION
  const std::string& platform() const { return platform_; }   // which EGL platform was used

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string renderer_, version_, platform_;
};

}  // namespace tourmap::render
