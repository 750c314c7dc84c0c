// Errors: one exception type that the CLI turns into a single message and a non-zero exit code.
#pragma once

#include <stdexcept>
#include <string>

namespace luxel {

// A failure with a message that names what and where ("scene.json: lights[2]: unknown type 'spto'").
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Thrown when a progress callback asks to stop.
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
};

}  // namespace luxel
