// The viewer's panels (Dear ImGui): solve controls and a plot of the unshot energy, views and
// exposure, lights, the picked object, and a help overlay listing every key and action.
#include <algorithm>
#include <deque>

#include <fmt/format.h>
#include <imgui.h>

#include "luxel/error.h"
#include "transfer_light.h"
#include "viewer.h"

namespace luxel::viewer {
namespace {

// Keys and mouse bindings, for the help overlay (viewer_window.cpp binds them).
constexpr const char* kBindings[][2] = {
    {"W A S D", "walk (Shift: faster)"},      {"Q E", "down, up"},
    {"right drag", "look"},                   {"left drag", "orbit the pivot (the last picked point)"},
    {"left click", "pick an object"},         {"wheel", "move towards the pivot"},
    {"Space", "pause / resume the solve"},    {"R", "reset the solve"},
    {"L", "place a lamp at the camera"},      {"V", "next view"},
    {"G / P", "element / patch edges"},       {"C", "next scene camera"},
    {"arrows, PgUp/PgDn", "move the picked object"}, {"F5", "reload shaders"},
    {"F12", "screenshot (luxel-view-N.png)"}, {"Tab", "hide the panels"},
    {"F1", "this help"},                      {"Esc", "quit"},
};

}  // namespace

void Viewer::drawUi() {
  std::deque<float>& unshot = ui_.unshot;
  std::deque<float>& frameMs = ui_.frameMs;
  const SolveStats st = session_->stats();
  unshot.push_back(float(std::log10(std::max(st.unshotFraction, 1e-12))));
  if (unshot.size() > 300) unshot.pop_front();
  if (!stats_.frames().empty()) frameMs.push_back(float(stats_.frames().back().frameMs));
  if (frameMs.size() > 300) frameMs.pop_front();
  std::vector<float> u(unshot.begin(), unshot.end()), f(frameMs.begin(), frameMs.end());

  auto act = [&](const std::string& name, std::vector<std::string> args = {}) {
    try {
      perform(Action{name, std::move(args), {}});
    } catch (const Error& e) {
      messages_.push_back(e.what());
      lastError_ = e.what();
    }
  };

  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("luxel");
  ImGui::TextUnformatted(options_.sceneName.c_str());
  ImGui::Text("%s", status().c_str());
  const double ms = f.empty() ? 0.0 : f.back();
  ImGui::Text("%.1f ms/frame (%.0f fps)", ms, ms > 0.0 ? 1000.0 / ms : 0.0);
  ImGui::PlotLines("frame ms", f.data(), int(f.size()), 0, nullptr, 0.0f, 100.0f, ImVec2(0, 40));

  if (ImGui::CollapsingHeader("Solve", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::Button(options_.paused ? "Resume" : "Pause")) act("solve.toggle");
    ImGui::SameLine();
    if (ImGui::Button("Reset")) act("solve.reset");
    ImGui::SameLine();
    int backend = session_->backend() == "gl" ? 1 : 0;
    if (ImGui::RadioButton("CPU", &backend, 0) && session_->backend() != "cpu") act("solve.backend", {"cpu"});
    ImGui::SameLine();
    if (ImGui::RadioButton("GPU", &backend, 1) && session_->backend() != "gl") act("solve.backend", {"gl"});
    ImGui::PlotLines("log10 unshot", u.data(), int(u.size()), 0, nullptr, -8.0f, 0.0f, ImVec2(0, 50));
    ImGui::Text("%zu shots, %.2f s solving", size_t(st.shots), st.secondsTotal);
    int& budget = ui_.budget;
    if (budget == 0) budget = int(session_->surfaces().elements.size());
    ImGui::InputInt("elements", &budget, 1000, 10000);
    ImGui::SameLine();
    if (ImGui::Button("Cut")) act("solve.budget", {std::to_string(budget)});
  }
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    int mode = int(options_.mode);
    for (int m = 0; m < kViewModeCount; ++m) {
      if (m % 4) ImGui::SameLine();
      if (ImGui::RadioButton(viewModeName(ViewMode(m)), &mode, m)) act("view", {viewModeName(ViewMode(m))});
    }
    if (options_.mode == ViewMode::Unshot && !unshotKnown_)
      ImGui::TextUnformatted("this solver keeps no unshot radiosity (progressive and the dynamic solvers do)");
    float exposure = options_.tone.exposure;
    if (ImGui::SliderFloat("exposure", &exposure, -8.0f, 8.0f, "%.1f stops")) options_.tone.exposure = exposure;
    int curve = int(options_.tone.curve);
    const char* curves[] = {"filmic", "reinhard", "clamp"};
    if (ImGui::Combo("tone curve", &curve, curves, 3)) options_.tone.curve = ToneMap::Curve(curve);
    int shadows = int(options_.shadows);
    if (ImGui::RadioButton("shadow maps", &shadows, 0)) act("shadows", {"maps"});
    ImGui::SameLine();
    if (ImGui::RadioButton("shadow volumes", &shadows, 1)) act("shadows", {"volumes"});
    int shading = renderer_->perVertex() ? 1 : 0;
    if (ImGui::RadioButton("per pixel", &shading, 0)) act("shading", {"pixel"});
    ImGui::SameLine();
    if (ImGui::RadioButton("per vertex", &shading, 1)) act("shading", {"vertex"});
    ImGui::Checkbox("element edges", &elementEdges_);
    ImGui::SameLine();
    ImGui::Checkbox("patch edges", &patchEdges_);
    if (options_.mode == ViewMode::Density || options_.mode == ViewMode::Texels) {
      float tpm = options_.texelsPerMetre;
      if (ImGui::SliderFloat("texels/m", &tpm, 1.0f, 256.0f, "%.1f", ImGuiSliderFlags_Logarithmic)) options_.texelsPerMetre = tpm;
      // The texels view is laid out again once the slider is let go, not at every step of a drag.
      if (ImGui::IsItemDeactivatedAfterEdit()) texelRenderer_.reset();
    }
    if (options_.mode == ViewMode::Texels && texelRenderer_)
      ImGui::Text("%zu texels at %.3g/m: %zu invalid (red), %zu overlapping (magenta), %zu bleeding (yellow)",
                  texels_.covered, double(texelsPerMetreShown_), texels_.invalid, texels_.overlapping, texels_.bleeding);
    if (ImGui::Button("Screenshot")) act("screenshot", {fmt::format("luxel-view-{}.png", frameIndex_)});
    ImGui::SameLine();
    if (ImGui::Button("Reload shaders")) act("shaders.reload");
  }
  if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::Button("Lamp at camera")) act("light.add-at-camera");
    float* sun = ui_.sun;
    ImGui::SameLine();
    if (ImGui::SliderFloat2("sun az/el", sun, -180.0f, 180.0f, "%.0f")) act("sun", {fmt::format("{}", sun[0]), fmt::format("{}", sun[1])});
    const Scene& scene = session_->scene();
    for (size_t i = 0; i < scene.lights.size(); ++i) {
      const Light& l = scene.lights[i];
      ImGui::PushID(int(i));
      ImGui::Text("%zu %s", i, l.name.c_str());
      if (l.type == Light::Type::Point || l.type == Light::Type::Spot) {
        float p[3] = {l.position.x, l.position.y, l.position.z};
        if (ImGui::DragFloat3("position", p, 0.01f * session_->surfaces().sceneExtent))
          act("light.move", {std::to_string(i), fmt::format("{}", p[0]), fmt::format("{}", p[1]), fmt::format("{}", p[2])});
      }
      float c[3] = {l.color.x, l.color.y, l.color.z};
      float intensity = l.intensity;
      const bool colour = ImGui::ColorEdit3("colour", c, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
      const bool power = ImGui::DragFloat("intensity", &intensity, 0.01f * std::max(l.intensity, 1.0f), 0.0f, 1e9f);
      if (colour || power)
        act("light.color", {std::to_string(i), fmt::format("{}", c[0]), fmt::format("{}", c[1]), fmt::format("{}", c[2]),
                            fmt::format("{}", intensity)});
      if (ImGui::SmallButton("delete")) act("light.delete", {std::to_string(i)});
      ImGui::PopID();
    }
  }
  // A transfer bake's light (the baked view): the same actions as a script's, relit at once.
  if (transferLight_.bands > 0 && ImGui::CollapsingHeader("Baked light (transfer)", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Text("%d bands, %zu sun%s", transferLight_.bands, transferLight_.suns.size(), transferLight_.suns.size() == 1 ? "" : "s");
    if (!transferLight_.suns.empty()) {
      float* sun = ui_.transferSun;
      if (ImGui::SliderFloat2("baked sun az/el", sun, -180.0f, 180.0f, "%.0f")) {
        sun[1] = std::clamp(sun[1], -90.0f, 90.0f);
        const Vec3 d = sunTravelDirection(session_->scene().up, sun[0], sun[1]);
        act("sun-direction", {fmt::format("{},{},{}", d.x, d.y, d.z)});
      }
      const Vec3 d = transferLight_.suns[0].direction;
      ImGui::Text("travelling along %.3f, %.3f, %.3f", d.x, d.y, d.z);
      const Rgb e = transferLight_.suns[0].irradiance;
      float c[3] = {e.x, e.y, e.z};
      if (ImGui::ColorEdit3("sun irradiance", c, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR))
        act("sun-irradiance", {fmt::format("{},{},{}", std::max(c[0], 0.0f), std::max(c[1], 0.0f), std::max(c[2], 0.0f))});
    }
    float k[3] = {skyScale_.x, skyScale_.y, skyScale_.z};
    if (ImGui::ColorEdit3("sky scale", k, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR))
      act("sky-scale", {fmt::format("{},{},{}", std::max(k[0], 0.0f), std::max(k[1], 0.0f), std::max(k[2], 0.0f))});
  }
  if (selected_ >= 0 && ImGui::CollapsingHeader("Object", ImGuiTreeNodeFlags_DefaultOpen)) {
    const Object& o = session_->scene().objects[size_t(selected_)];
    ImGui::Text("%s%s", o.name.c_str(), o.dynamic ? " (dynamic)" : "");
    const float step = 0.02f * session_->surfaces().sceneExtent;
    const std::string s = fmt::format("{}", step), m = fmt::format("{}", -step);
    if (ImGui::Button("-x")) act("selected.move", {m, "0", "0"});
    ImGui::SameLine();
    if (ImGui::Button("+x")) act("selected.move", {s, "0", "0"});
    ImGui::SameLine();
    if (ImGui::Button("-y")) act("selected.move", {"0", m, "0"});
    ImGui::SameLine();
    if (ImGui::Button("+y")) act("selected.move", {"0", s, "0"});
    ImGui::SameLine();
    if (ImGui::Button("-z")) act("selected.move", {"0", "0", m});
    ImGui::SameLine();
    if (ImGui::Button("+z")) act("selected.move", {"0", "0", s});
    if (ImGui::Button("turn 15")) act("selected.rotate", {"0", "1", "0", "15"});
  }
  char* savePath = ui_.savePath;
  ImGui::InputText("##save", savePath, sizeof ui_.savePath);
  ImGui::SameLine();
  if (ImGui::Button("Save scene")) act("save", {savePath});
  if (!lastError_.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", lastError_.c_str());
  ImGui::End();

  if (showHelp_) {
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 420, 8), ImGuiCond_FirstUseEver);
    ImGui::Begin("help (F1)", &showHelp_);
    for (const auto& b : kBindings) ImGui::Text("%-18s %s", b[0], b[1]);
    ImGui::Separator();
    ImGui::TextUnformatted("script actions (--script FILE):");
    for (const ActionSpec& a : actionSpecs()) ImGui::Text("%s %s", a.name, a.usage);
    ImGui::End();
  }
}

}  // namespace luxel::viewer
