// Timed input for the viewer (`luxel view --script FILE`): each line names when (a frame number,
// or seconds since the first frame with an `s`) and what, in the same words as the menu's actions,
// so a test or a demo replays exactly what a user does. Lines:
//
//   # a comment
//   0     camera 0 1 3.5  0 1 0            eye, target (and optionally the field of view)
//   10    key w down                       keys held and released (walking), or `tap`
//   12    look 30 -5                       turn the heading by degrees (mouse look)
//   20    click 640 360                    pick what is under a pixel (window coordinates)
//   30    light.add-at-camera              any viewer action by name, with its arguments
//   1.5s  screenshot out/frame.png
//
// Actions are checked against the viewer's list when the script is read, so a typo fails before
// the window opens.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace luxel::viewer {

struct Action {
  std::string name;
  std::vector<std::string> args;
  std::string where;  // "FILE:LINE" for errors, empty when typed or clicked
};

struct ScriptEntry {
  int64_t frame = -1;     // at this frame (the first frame is 0), or
  double seconds = -1.0;  // at this time since the first frame
  Action action;
};

struct ActionSpec {
  const char* name;
  int minArgs, maxArgs;
  const char* usage;  // arguments, for the help overlay and errors
  const char* help;
};

// Every action the viewer performs: typed in a script, bound to a key, or a menu item.
const std::vector<ActionSpec>& actionSpecs();
const ActionSpec* findAction(const std::string& name);

// Parses a script; throws luxel::Error naming the file and line of anything malformed (an unknown
// action, a wrong argument count, a time that is not a frame or seconds, times out of order).
std::vector<ScriptEntry> parseScript(const std::string& text, const std::string& fileName);
std::vector<ScriptEntry> readScript(const std::filesystem::path& path);

// Checks an action's argument count against its spec; throws luxel::Error naming `where`.
void checkAction(const Action& action);

// Arguments as numbers, with errors naming the action and where it came from.
float argFloat(const Action& action, size_t i);
int64_t argInt(const Action& action, size_t i);

}  // namespace luxel::viewer
