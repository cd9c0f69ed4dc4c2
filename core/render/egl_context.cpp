#include "egl_context.hpp"

// libepoxy's headers, not <EGL/egl.h>/<GL/gl.h>: the two sets clash.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace tourmap::render {
namespace {

// EGL displays are process-wide singletons and eglTerminate is not reference counted, so two
// contexts on one display (two render threads, or tests) count their users here and the last
// one terminates it.
std::mutex display_mutex;
std::map<EGLDisplay, int> display_users;

bool has_extension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  std::string_view all(list);
  for (std::size_t pos = 0; pos < all.size();) {
    const std::size_t end = std::min(all.find(' ', pos), all.size());
    if (all.substr(pos, end - pos) == name) return true;
    pos = end + 1;
  }
  return false;
}

std::string egl_error_text(const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  return std::string(what) + " failed (EGL error " + code + ")";
}

bool try_initialize(EGLDisplay display) {
  if (display == EGL_NO_DISPLAY) return false;
  EGLint major = 0, minor = 0;
  return eglInitialize(display, &major, &minor) == EGL_TRUE;
}

// Surfaceless Mesa first (software or the GPU's render node, no window system), then the
// device platform (e.g. NVIDIA's driver), then the default display.
EGLDisplay open_display(std::string& platform) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_EXT_platform_base")) {
    if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
      EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (try_initialize(d)) {
        platform = "surfaceless";
        return d;
      }
    }
    if (has_extension(client, "EGL_EXT_platform_device") && has_extension(client, "EGL_EXT_device_enumeration")) {
      EGLint count = 0;
      eglQueryDevicesEXT(0, nullptr, &count);
      std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(std::max(count, 0)));
      if (count > 0 && eglQueryDevicesEXT(count, devices.data(), &count) == EGL_TRUE) {
        for (EGLint i = 0; i < count; ++i) {
          EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr);
          if (try_initialize(d)) {
            platform = "device " + std::to_string(i);
            return d;
          }
        }
      }
    }
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (try_initialize(d)) {
    platform = "default";
    return d;
  }
  throw std::runtime_error("EglContext: no usable EGL display (tried surfaceless Mesa, EGL devices, default display)");
}

void release_display(EGLDisplay display) {
  std::lock_guard lock(display_mutex);
  if (--display_users[display] == 0) {
    display_users.erase(display);
    eglTerminate(display);
  }
}

}  // namespace

EglContext::EglContext() {
  EGLDisplay display = EGL_NO_DISPLAY;
  {
    std::lock_guard lock(display_mutex);
    display = open_display(platform_);
    ++display_users[display];
  }
  display_ = display;
  try {
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) throw std::runtime_error("EglContext: " + egl_error_text("eglBindAPI(EGL_OPENGL_API)"));
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!has_extension(ext, "EGL_KHR_surfaceless_context"))
      throw std::runtime_error("EglContext: the EGL display lacks EGL_KHR_surfaceless_context (needed to render without a window)");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(ext, "EGL_KHR_no_config_context")) {
      const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint found = 0;
      if (eglChooseConfig(display, want, &config, 1, &found) != EGL_TRUE || found < 1)
        throw std::runtime_error("EglContext: no EGL config supports desktop OpenGL");
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT)
      throw std::runtime_error("EglContext: " + egl_error_text("creating an OpenGL 4.5 core context"));
    context_ = context;
    make_current();
    if (epoxy_gl_version() < 45)
      throw std::runtime_error("EglContext: OpenGL 4.5 needed, the driver gives " + std::to_string(epoxy_gl_version()));
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  } catch (...) {
    if (context_ != nullptr) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, static_cast<EGLContext>(context_));
    }
    release_display(display);
    throw;
  }
}

EglContext::~EglContext() {
  auto display = static_cast<EGLDisplay>(display_);
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_))
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, static_cast<EGLContext>(context_));
  release_display(display);
}

void EglContext::make_current() {
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_)) return;
  auto display = static_cast<EGLDisplay>(display_);
  if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, static_cast<EGLContext>(context_)) != EGL_TRUE)
    throw std::runtime_error("EglContext: " + egl_error_text("eglMakeCurrent"));
}

}  // namespace tourmap::render
