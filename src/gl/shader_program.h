// A linked GLSL program from embedded sources, with the compiler's log in the error.
#pragma once

#include <string>

namespace luxel::gl {

class ShaderProgram {
 public:
  // Compiles and links; throws luxel::Error with `name` and the driver's log on failure.
  ShaderProgram(const std::string& name, const std::string& vertex, const std::string& fragment);
  // With a geometry shader between the two.
  ShaderProgram(const std::string& name, const std::string& vertex, const std::string& geometry,
                const std::string& fragment);
  // A compute program (OpenGL 4.3+), the same way.
  ShaderProgram(const std::string& name, const std::string& compute);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  unsigned id() const { return program_; }
  void use() const;

 private:
  unsigned program_ = 0;
};

}  // namespace luxel::gl
