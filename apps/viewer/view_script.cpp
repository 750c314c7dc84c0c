#include "view_script.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel::viewer {

const std::vector<ActionSpec>& actionSpecs() {
  static const std::vector<ActionSpec> specs = {
      {"camera", 6, 7, "EX EY EZ TX TY TZ [FOV]", "place the camera: eye, target, vertical field of view in degrees"},
      {"camera.scene", 0, 1, "[NAME]", "jump to a camera of the scene (the next one when no name)"},
      {"key", 2, 2, "KEY down|up|tap", "hold or release a key (w a s d q e shift: walking)"},
      {"look", 2, 2, "YAW PITCH", "turn the view by degrees (mouse look)"},
      {"orbit", 2, 2, "YAW PITCH", "turn about the orbit pivot by degrees"},
      {"click", 2, 2, "X Y", "pick the object under a pixel (window coordinates, y down)"},
      {"solve.pause", 0, 0, "", "stop stepping the solver"},
      {"solve.resume", 0, 0, "", "step the solver again"},
      {"solve.toggle", 0, 0, "", "pause or resume"},
      {"solve.reset", 0, 0, "", "start the solve again from the unlit state"},
      {"solve.backend", 1, 1, "cpu|gl", "solve on the CPU or the GPU (starts again)"},
      {"solve.budget", 1, 1, "ELEMENTS", "cut the scene into about this many elements and solve again"},
      {"view", 1, 1, "MODE", "final, indirect, direct, radiosity, patches, elements, density, unshot, baked, texels"},
      {"exposure", 1, 1, "STOPS", "exposure in stops over the automatic exposure"},
      {"edges", 1, 1, "elements|patches|off", "draw (or stop drawing) the elements' or patches' outlines"},
      {"shading", 1, 1, "pixel|vertex", "shade point, spot and sun lights per pixel, or per vertex (Gouraud)"},
      {"shaders.reload", 0, 0, "", "compile the shaders again (from --shaders DIR when given)"},
      {"tonemap", 1, 1, "filmic|reinhard|clamp", "the tone curve"},
      {"shadows", 1, 1, "maps|volumes", "shadows of per-pixel lights: cube shadow maps or stencil shadow volumes"},
      {"light.add-at-camera", 0, 0, "", "place a point lamp at the camera (003's lamp)"},
      {"light.add", 4, 7, "X Y Z INTENSITY [R G B]", "add a point light (intensity in W/sr)"},
      {"light.move", 4, 4, "LIGHT X Y Z", "move a light (its index) to a position"},
      {"light.color", 5, 5, "LIGHT R G B INTENSITY", "recolour a light"},
      {"light.delete", 1, 1, "LIGHT", "remove a light"},
      {"sun", 2, 3, "AZIMUTH ELEVATION [IRRADIANCE]", "turn the sun (degrees; adds one when the scene has none)"},
      {"sky", 1, 4, "RADIANCE [R G B]", "a uniform sky of this radiance (0 removes it)"},
      {"sun-direction", 1, 1, "X,Y,Z", "turn the suns of a transfer bake (the way their light travels) and relight it"},
      {"sun-irradiance", 1, 1, "E|R,G,B", "the irradiance of a transfer bake's suns (facing them), and relight it"},
      {"sky-scale", 1, 1, "S|R,G,B", "scale the stored sky of a transfer bake, and relight it (1: as baked)"},
      {"object.move", 4, 4, "OBJECT X Y Z", "move a dynamic object (name or index) by an offset"},
      {"object.rotate", 5, 5, "OBJECT AX AY AZ DEGREES", "turn a dynamic object about its centre"},
      {"selected.move", 3, 3, "X Y Z", "move the picked object by an offset"},
      {"selected.rotate", 4, 4, "AX AY AZ DEGREES", "turn the picked object about its centre"},
      {"screenshot", 1, 1, "FILE", "write the frame as PNG (tone-mapped) or EXR (radiance)"},
      {"save", 1, 1, "FILE.json", "save the edited scene as scene JSON"},
      {"ui", 1, 1, "on|off", "show or hide the panels"},
      {"quit", 0, 0, "", "close the viewer"},
  };
  return specs;
}

const ActionSpec* findAction(const std::string& name) {
  for (const ActionSpec& s : actionSpecs())
    if (name == s.name) return &s;
  return nullptr;
}

void checkAction(const Action& a) {
  const std::string at = a.where.empty() ? std::string() : a.where + ": ";
  const ActionSpec* spec = findAction(a.name);
  if (!spec) throw Error(fmt::format("{}unknown viewer action '{}' (`luxel view --help-actions` lists them)", at, a.name));
  const int n = int(a.args.size());
  if (n < spec->minArgs || n > spec->maxArgs)
    throw Error(fmt::format("{}'{}' expects {}, got {} argument{}", at, a.name,
                            spec->usage[0] ? fmt::format("'{}'", spec->usage) : std::string("no arguments"), n,
                            n == 1 ? "" : "s"));
}

float argFloat(const Action& a, size_t i) {
  const std::string& s = a.args.at(i);
  char* end = nullptr;
  const float v = std::strtof(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    throw Error(fmt::format("{}{}'{}': argument {} '{}' is not a finite number", a.where, a.where.empty() ? "" : ": ",
                            a.name, i + 1, s));
  return v;
}

int64_t argInt(const Action& a, size_t i) {
  const std::string& s = a.args.at(i);
  int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size())
    throw Error(fmt::format("{}{}'{}': argument {} '{}' is not an integer", a.where, a.where.empty() ? "" : ": ",
                            a.name, i + 1, s));
  return v;
}

std::vector<ScriptEntry> parseScript(const std::string& text, const std::string& fileName) {
  std::vector<ScriptEntry> entries;
  std::istringstream lines(text);
  std::string line;
  int lineNumber = 0;
  double lastSeconds = -1.0;
  int64_t lastFrame = -1;
  while (std::getline(lines, line)) {
    ++lineNumber;
    const std::string where = fmt::format("{}:{}", fileName, lineNumber);
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string when;
    if (!(words >> when)) continue;
    ScriptEntry e;
    const bool inSeconds = when.size() > 1 && when.back() == 's';
    const std::string number = inSeconds ? when.substr(0, when.size() - 1) : when;
    char* end = nullptr;
    if (inSeconds) {
      e.seconds = std::strtod(number.c_str(), &end);
      if (*end != '\0' || !std::isfinite(e.seconds) || e.seconds < 0.0 || e.seconds > 1e6)
        throw Error(fmt::format("{}: '{}' is not a time (seconds, e.g. 1.5s) between 0 and 1e6", where, when));
      if (e.seconds < lastSeconds) throw Error(fmt::format("{}: time {} comes before the line above's", where, when));
      lastSeconds = e.seconds;
    } else {
      const auto [p, ec] = std::from_chars(number.data(), number.data() + number.size(), e.frame);
      if (ec != std::errc() || p != number.data() + number.size() || e.frame < 0 || e.frame > 100000000)
        throw Error(fmt::format("{}: '{}' is not a frame number (0 to 1e8) or a time in seconds (1.5s)", where, when));
      if (e.frame < lastFrame) throw Error(fmt::format("{}: frame {} comes before the line above's", where, when));
      lastFrame = e.frame;
    }
    if (!(words >> e.action.name)) throw Error(fmt::format("{}: '{}' with no action after it", where, when));
    for (std::string arg; words >> arg;) e.action.args.push_back(arg);
    e.action.where = where;
    checkAction(e.action);
    entries.push_back(std::move(e));
  }
  return entries;
}

std::vector<ScriptEntry> readScript(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("cannot read the viewer script '{}'", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return parseScript(text.str(), path.string());
}

}  // namespace luxel::viewer
