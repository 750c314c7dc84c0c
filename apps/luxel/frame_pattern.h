// The frame number in an output name, `-o DIR/frame%04d.png`: printf's %d and %0Nd (and %% for a
// percent sign), parsed here rather than handed to a format function, so no text of the user's
// is ever read as a format.
#pragma once

#include <cstdint>
#include <string>

namespace luxel::cli {

class FramePattern {
 public:
  // Throws Error naming `option` and `text` when a '%' starts anything but %d, %0Nd (N from 1 to
  // 9) or %%, or when there is more than one number.
  FramePattern(const std::string& text, const std::string& option);

  bool numbered() const { return numbered_; }
  // The name of frame `frame` (the text itself, %% made %, when it has no number).
  std::string at(int64_t frame) const;

 private:
  std::string before_, after_;
  bool numbered_ = false;
  int digits_ = 0;  // zero-padded to this many digits; 0: as many as it takes
};

}  // namespace luxel::cli
