#include "frame_pattern.h"

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel::cli {

FramePattern::FramePattern(const std::string& text, const std::string& option) {
  auto bad = [&](const std::string& why) {
    return Error(fmt::format("{} {}: {} (a frame number is %d or %04d; a percent sign is %%)",
                             option, text, why));
  };
  std::string* out = &before_;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      *out += text[i];
      continue;
    }
    size_t j = i + 1;
    if (j < text.size() && text[j] == '%') {
      *out += '%';
      i = j;
      continue;
    }
    int digits = 0;
    if (j < text.size() && text[j] == '0') {
      ++j;
      if (j >= text.size() || text[j] < '1' || text[j] > '9')
        throw bad(fmt::format("'%' at byte {} is not a frame number", i));
      digits = text[j++] - '0';
    }
    if (j >= text.size() || text[j] != 'd')
      throw bad(fmt::format("'%' at byte {} is not a frame number", i));
    if (numbered_) throw bad("it has more than one frame number");
    numbered_ = true;
    digits_ = digits;
    out = &after_;
    i = j;
  }
}

std::string FramePattern::at(int64_t frame) const {
  if (!numbered_) return before_;
  return before_ + fmt::format("{:0{}d}", frame, digits_) + after_;
}

}  // namespace luxel::cli
