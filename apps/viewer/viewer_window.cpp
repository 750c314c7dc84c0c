// The viewer in a desktop window: GLFW for the window, OpenGL 4.5 core context and input, Dear
// ImGui (its GLFW and OpenGL 3 backends, Debian's libimgui-dev) for the panels. Keys and the
// mouse become Viewer calls and actions; the help overlay (F1) lists the bindings.
#include <epoxy/gl.h>
// After epoxy, and without GLFW's own GL header (epoxy provides every entry point).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <memory>
#include <string>

#include <fmt/format.h>

#include "luxel/error.h"
#include "run_control.h"
#include "viewer_run.h"

namespace luxel::viewer {
namespace {

std::string glfwFailure() {
  const char* what = nullptr;
  const int code = glfwGetError(&what);
  return code == GLFW_NO_ERROR ? std::string("no reason given") : fmt::format("{} (GLFW error 0x{:x})", what ? what : "", code);
}

// What the callbacks reach.
struct WindowState {
  Viewer* viewer = nullptr;
  double lastX = 0.0, lastY = 0.0;
  bool looking = false, orbiting = false, dragged = false;
  double pressX = 0.0, pressY = 0.0;
  std::string error;
};

WindowState& state(GLFWwindow* w) { return *static_cast<WindowState*>(glfwGetWindowUserPointer(w)); }

void perform(WindowState& s, const std::string& name, std::vector<std::string> args = {}) {
  try {
    s.viewer->perform(Action{name, std::move(args), {}});
  } catch (const Error& e) {
    s.error = e.what();
  }
}

void onKey(GLFWwindow* w, int key, int, int action, int mods) {
  if (ImGui::GetIO().WantCaptureKeyboard) return;
  WindowState& s = state(w);
  Viewer& v = *s.viewer;
  const bool down = action != GLFW_RELEASE;
  const char* walk = nullptr;
  switch (key) {
    case GLFW_KEY_W: walk = "w"; break;
    case GLFW_KEY_A: walk = "a"; break;
    case GLFW_KEY_S: walk = "s"; break;
    case GLFW_KEY_D: walk = "d"; break;
    case GLFW_KEY_Q: walk = "q"; break;
    case GLFW_KEY_E: walk = "e"; break;
    case GLFW_KEY_LEFT_SHIFT:
    case GLFW_KEY_RIGHT_SHIFT: walk = "shift"; break;
    default: break;
  }
  if (walk) {
    v.setKey(walk, down);
    return;
  }
  if (action != GLFW_PRESS && !(action == GLFW_REPEAT && (key >= GLFW_KEY_RIGHT && key <= GLFW_KEY_PAGE_DOWN))) return;
  const float step = 0.02f * v.session().surfaces().sceneExtent * ((mods & GLFW_MOD_SHIFT) ? 5.0f : 1.0f);
  auto moveSelected = [&](Vec3 d) {
    perform(s, "selected.move", {fmt::format("{}", d.x), fmt::format("{}", d.y), fmt::format("{}", d.z)});
  };
  const Vec3 r = v.camera().right(), f = glm::cross(v.camera().up(), r);
  switch (key) {
    case GLFW_KEY_ESCAPE: perform(s, "quit"); break;
    case GLFW_KEY_SPACE: perform(s, "solve.toggle"); break;
    case GLFW_KEY_R: perform(s, "solve.reset"); break;
    case GLFW_KEY_L: perform(s, "light.add-at-camera"); break;
    case GLFW_KEY_V: perform(s, "view", {viewModeName(ViewMode((int(v.mode()) + 1) % kViewModeCount))}); break;
    case GLFW_KEY_G: perform(s, "edges", {"elements"}); break;
    case GLFW_KEY_P: perform(s, "edges", {"patches"}); break;
    case GLFW_KEY_C: perform(s, "camera.scene"); break;
    case GLFW_KEY_F1: v.toggleHelp(); break;
    case GLFW_KEY_TAB: v.toggleUi(); break;
    case GLFW_KEY_F5: perform(s, "shaders.reload"); break;
    case GLFW_KEY_F12: perform(s, "screenshot", {fmt::format("luxel-view-{}.png", v.frameCount())}); break;
    case GLFW_KEY_LEFT: moveSelected(-r * step); break;
    case GLFW_KEY_RIGHT: moveSelected(r * step); break;
    case GLFW_KEY_UP: moveSelected(f * step); break;
    case GLFW_KEY_DOWN: moveSelected(-f * step); break;
    case GLFW_KEY_PAGE_UP: moveSelected(v.camera().up() * step); break;
    case GLFW_KEY_PAGE_DOWN: moveSelected(-v.camera().up() * step); break;
    default: break;
  }
}

void onMouseButton(GLFWwindow* w, int button, int action, int) {
  WindowState& s = state(w);
  if (ImGui::GetIO().WantCaptureMouse && action == GLFW_PRESS) return;
  glfwGetCursorPos(w, &s.lastX, &s.lastY);
  if (button == GLFW_MOUSE_BUTTON_RIGHT) s.looking = action == GLFW_PRESS;
  if (button == GLFW_MOUSE_BUTTON_LEFT) {
    if (action == GLFW_PRESS) {
      s.orbiting = true;
      s.dragged = false;
      s.pressX = s.lastX, s.pressY = s.lastY;
    } else if (s.orbiting) {
      s.orbiting = false;
      if (!s.dragged) {
        // A click, not a drag: pick in framebuffer pixels (they differ from window units on HiDPI).
        int ww = 0, wh = 0, fw = 0, fh = 0;
        glfwGetWindowSize(w, &ww, &wh);
        glfwGetFramebufferSize(w, &fw, &fh);
        const int x = ww > 0 ? int(s.pressX * fw / ww) : 0, y = wh > 0 ? int(s.pressY * fh / wh) : 0;
        perform(s, "click", {std::to_string(x), std::to_string(y)});
      }
    }
  }
}

void onCursor(GLFWwindow* w, double x, double y) {
  WindowState& s = state(w);
  const float dx = float(x - s.lastX), dy = float(y - s.lastY);
  s.lastX = x, s.lastY = y;
  if (s.looking) s.viewer->mouseLook(dx, dy);
  if (s.orbiting) {
    if (std::abs(x - s.pressX) + std::abs(y - s.pressY) > 3.0) s.dragged = true;
    if (s.dragged) s.viewer->mouseOrbit(dx, dy);
  }
}

void onScroll(GLFWwindow* w, double, double dy) {
  if (ImGui::GetIO().WantCaptureMouse) return;
  state(w).viewer->scroll(float(dy));
}

}  // namespace

int runInWindow(Scene scene, ViewerOptions options, const RunOptions& run) {
  if (!glfwInit())
    throw Error(fmt::format("luxel view: no window can be opened here ({}); set DISPLAY, run it under xvfb-run, or "
                            "give --headless",
                            glfwFailure()));
  struct Terminate {
    ~Terminate() { glfwTerminate(); }
  } terminate;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  if (run.hiddenWindow) glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  const std::string title = fmt::format("luxel view: {}", options.sceneName);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, title.c_str(), nullptr, nullptr);
  if (!window)
    throw Error(fmt::format("luxel view: no OpenGL 4.5 core window ({}); --headless uses EGL instead", glfwFailure()));
  struct Destroy {
    GLFWwindow* w;
    ~Destroy() { glfwDestroyWindow(w); }
  } destroy{window};
  glfwMakeContextCurrent(window);
  glfwSwapInterval(run.vsync ? 1 : 0);

  WindowState ws;
  glfwSetWindowUserPointer(window, &ws);
  // Ours first: ImGui's backend calls the callbacks it finds installed after its own.
  glfwSetKeyCallback(window, onKey);
  glfwSetMouseButtonCallback(window, onMouseButton);
  glfwSetCursorPosCallback(window, onCursor);
  glfwSetScrollCallback(window, onScroll);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450");
  struct ImGuiDown {
    ~ImGuiDown() {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
  } imguiDown;

  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window, &fw, &fh);
  options.width = std::max(fw, 1);
  options.height = std::max(fh, 1);
  Viewer viewer(std::move(scene), options);
  ws.viewer = &viewer;
  RunControl control(run);
  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    if (!ws.error.empty()) {
      std::fprintf(stderr, "luxel view: %s\n", ws.error.c_str());
      ws.error.clear();
    }
    glfwGetFramebufferSize(window, &fw, &fh);
    if (fw < 1 || fh < 1) {  // minimised
      glfwWaitEvents();
      continue;
    }
    const double dt = control.beforeFrame(viewer);
    viewer.frame(dt, fw, fh);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    viewer.present(fw, fh);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (viewer.uiVisible()) viewer.drawUi();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(window);
    if (!control.afterFrame(viewer)) break;
  }
  control.finish(viewer, fw, fh);
  return 0;
}

}  // namespace luxel::viewer
