// A headless OpenGL context through EGL (no X server, no window, no DISPLAY):
// the first EGL device that initialises (a GPU's driver where there is one,
// Mesa's software rasteriser llvmpipe otherwise), or Mesa's surfaceless
// platform. Drawing goes to the renderer's own framebuffer object.
//
// A context is current in at most one thread at a time: Current makes it
// current for one frame in the calling thread and releases it afterwards, so
// an environment may be rendered from any thread (VectorEnv's pool), one at a time.
#pragma once

#include <memory>

namespace bsg::render {

class EglContext {
 public:
  // Throws std::runtime_error naming EGL and the Debian packages to install
  // when no EGL display or OpenGL 3.3 context can be had.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes the context current in this thread for its lifetime.
  class Current {
   public:
    explicit Current(const EglContext& context);
    ~Current();
    Current(const Current&) = delete;
    Current& operator=(const Current&) = delete;

   private:
    const EglContext& context_;
  };

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

}  // namespace bsg::render
