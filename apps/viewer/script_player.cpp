#include "script_player.h"

#include "viewer.h"

namespace luxel::viewer {

ScriptPlayer::ScriptPlayer(std::vector<ScriptEntry> entries) {
  for (ScriptEntry& e : entries) (e.frame >= 0 ? byFrame_ : byTime_).push_back(std::move(e));
}

void ScriptPlayer::play(Viewer& viewer, int64_t frame, double seconds) {
  while (nextFrame_ < byFrame_.size() && byFrame_[nextFrame_].frame <= frame) viewer.perform(byFrame_[nextFrame_++].action);
  while (nextTime_ < byTime_.size() && byTime_[nextTime_].seconds <= seconds) viewer.perform(byTime_[nextTime_++].action);
}

}  // namespace luxel::viewer
