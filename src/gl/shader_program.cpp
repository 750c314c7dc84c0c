#include "gl/shader_program.h"

#include <epoxy/gl.h>

#include <span>
#include <vector>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel::gl {
namespace {

GLuint compile(const std::string& name, GLenum stage, const std::string& source) {
  GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw Error(fmt::format("OpenGL: {} {} shader does not compile: {}", name,
                            stage == GL_VERTEX_SHADER     ? "vertex"
                            : stage == GL_GEOMETRY_SHADER ? "geometry"
                            : stage == GL_FRAGMENT_SHADER ? "fragment"
                                                          : "compute",
                            log));
  }
  return shader;
}

GLuint link(const std::string& name, std::span<const GLuint> shaders) {
  GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw Error(fmt::format("OpenGL: {} program does not link: {}", name, log));
  }
  return program;
}

}  // namespace

ShaderProgram::ShaderProgram(const std::string& name, const std::string& compute) {
  const GLuint shader = compile(name, GL_COMPUTE_SHADER, compute);
  program_ = link(name, {&shader, 1});
}

ShaderProgram::ShaderProgram(const std::string& name, const std::string& vertex, const std::string& fragment)
    : ShaderProgram(name, vertex, std::string(), fragment) {}

ShaderProgram::ShaderProgram(const std::string& name, const std::string& vertex, const std::string& geometry,
                             const std::string& fragment) {
  std::vector<GLuint> shaders;
  try {
    shaders.push_back(compile(name, GL_VERTEX_SHADER, vertex));
    if (!geometry.empty()) shaders.push_back(compile(name, GL_GEOMETRY_SHADER, geometry));
    shaders.push_back(compile(name, GL_FRAGMENT_SHADER, fragment));
  } catch (...) {
    for (GLuint s : shaders) glDeleteShader(s);
    throw;
  }
  program_ = link(name, shaders);
}

ShaderProgram::~ShaderProgram() {
  if (program_) glDeleteProgram(program_);
}

void ShaderProgram::use() const { glUseProgram(program_); }

}  // namespace luxel::gl
