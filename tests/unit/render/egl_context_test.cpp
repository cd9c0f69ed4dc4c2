#include "render/egl_context.hpp"

#include "render_test_scenes.hpp"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <string>

namespace tourmap::render {
namespace {

TEST(EglContext, ComesUpWithOpenGL45Core) {
  EglContext& context = test::shared_context();
  EXPECT_FALSE(context.renderer().empty());
  EXPECT_FALSE(context.platform().empty());
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45) << context.version();
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  EXPECT_EQ(context.version().rfind("4.", 0), 0u) << context.version();
  std::printf("GL_RENDERER %s | GL_VERSION %s | EGL platform %s\n", context.renderer().c_str(),
              context.version().c_str(), context.platform().c_str());
}

TEST(EglContext, SecondContextLivesAndDiesBesideTheFirst) {
  EglContext& first = test::shared_context();
  {
    EglContext second;
    EXPECT_EQ(second.renderer(), first.renderer());
    GLint major = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    EXPECT_GE(major, 4);
  }
  // The shared display must survive the second context's destruction.
  first.make_current();
  GLint major = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  EXPECT_GE(major, 4);
}

}  // namespace
}  // namespace tourmap::render
