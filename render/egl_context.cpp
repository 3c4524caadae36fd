#include "render/egl_context.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace bsg::render {
namespace {

constexpr const char* kInstallHint =
    "install an EGL driver, e.g. Debian's Mesa: apt-get install libegl1 libegl-mesa0 "
    "libgl1-mesa-dri (see scripts/install_deps.sh)";

std::string egl_error(const std::string& what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
  return "EGL: " + what + " (error " + code + "); " + kInstallHint;
}

// An initialised display: EGL devices first, then Mesa's surfaceless platform.
EGLDisplay open_display() {
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  if (get_platform_display == nullptr) return EGL_NO_DISPLAY;
  std::vector<EGLDisplay> candidates;
  if (query_devices != nullptr) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices(16, devices, &count) == EGL_TRUE) {
      for (EGLint i = 0; i < count; ++i) {
        candidates.push_back(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
      }
    }
  }
  candidates.push_back(
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
  for (EGLDisplay display : candidates) {
    EGLint major = 0, minor = 0;
    if (display != EGL_NO_DISPLAY && eglInitialize(display, &major, &minor) == EGL_TRUE) {
      return display;
    }
  }
  return EGL_NO_DISPLAY;
}

}  // namespace

EglContext::EglContext() {
  EGLDisplay display = open_display();
  if (display == EGL_NO_DISPLAY) throw std::runtime_error(egl_error("no headless display could be initialised"));
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    throw std::runtime_error(egl_error("the display offers no desktop OpenGL"));
  }
  const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  // Drawing goes to a framebuffer object, so any config will do; with
  // EGL_KHR_no_config_context none is needed at all.
  eglChooseConfig(display, config_attributes, &config, 1, &config_count);
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, config_count > 0 ? config : EGL_NO_CONFIG_KHR,
                                        EGL_NO_CONTEXT, context_attributes);
  if (context == EGL_NO_CONTEXT) {
    throw std::runtime_error(egl_error("no OpenGL 3.3 core context could be created"));
  }
  display_ = display;
  context_ = context;
  // The display is not terminated in the destructor: EGL shares one display
  // per device across the process, and eglTerminate would pull it from under
  // every other renderer still alive.
}

EglContext::~EglContext() { eglDestroyContext(display_, context_); }

EglContext::Current::Current(const EglContext& context) : context_(context) {
  if (eglMakeCurrent(context.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context.context_) !=
      EGL_TRUE) {
    throw std::runtime_error(egl_error("the OpenGL context could not be made current"));
  }
}

EglContext::Current::~Current() {
  eglMakeCurrent(context_.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace bsg::render
