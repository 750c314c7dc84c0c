// The viewer without a display: a headless OpenGL 4.5 context through EGL (the GPU backend's own,
// gl/gl_context.h) and an offscreen framebuffer standing in for the window, with the panels drawn
// into it too, so that a scripted run on a GPU server times what a user's window would.
#include <iostream>

#include <epoxy/gl.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "luxel/error.h"
#include "run_control.h"
#include "viewer_run.h"

namespace luxel::viewer {

int runHeadless(Scene scene, ViewerOptions options, const RunOptions& run) {
  if (run.frames <= 0 && run.script.empty())
    throw Error("luxel view --headless needs --frames N or a --script that ends with quit: nobody can close it");
  gl::Context context;
  // The stand-in for the window's framebuffer.
  GLuint fbo = 0, colour = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &colour);
  glTextureStorage2D(colour, 1, GL_RGBA8, options.width, options.height);
  glCreateFramebuffers(1, &fbo);
  glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, colour, 0);
  struct Release {
    GLuint fbo, colour;
    ~Release() {
      glDeleteFramebuffers(1, &fbo);
      glDeleteTextures(1, &colour);
    }
  } release{fbo, colour};

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(float(options.width), float(options.height));
  // Debian's Dear ImGui loads its GL functions from libGL.so.1 (GLX's library), which a headless
  // server may lack while EGL works: the frames are then drawn without panels, saying so.
  const bool ui = ImGui_ImplOpenGL3_Init("#version 450");
  if (!ui)
    std::cerr << "luxel view: warning: no panels: Dear ImGui could not load OpenGL through libGL.so.1 "
                 "(install libglvnd's libgl1); frames are drawn and timed without them\n";
  struct ImGuiDown {
    bool ui;
    ~ImGuiDown() {
      if (ui) ImGui_ImplOpenGL3_Shutdown();
      ImGui::DestroyContext();
    }
  } imguiDown{ui};

  const int width = options.width, height = options.height;
  Viewer viewer(std::move(scene), options);
  RunControl control(run);
  for (;;) {
    const double dt = control.beforeFrame(viewer);
    viewer.frame(dt, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    viewer.present(width, height);
    if (ui) {
      io.DeltaTime = float(std::max(dt, 1e-4));
      ImGui_ImplOpenGL3_NewFrame();
      ImGui::NewFrame();
      if (viewer.uiVisible()) viewer.drawUi();
      ImGui::Render();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
    glFinish();  // as a swap would: the frame's time includes its drawing
    if (!control.afterFrame(viewer)) break;
  }
  control.finish(viewer, width, height);
  return 0;
}

}  // namespace luxel::viewer
