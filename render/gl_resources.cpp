#include "render/gl_resources.h"

#include <stdexcept>
#include <string>

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

namespace bsg::render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model_view_projection;
uniform mat4 model;
uniform mat3 normal_matrix;
out vec3 world_position;
out vec3 world_normal;
void main() {
  world_position = (model * vec4(position, 1.0)).xyz;
  world_normal = normal_matrix * normal;
  gl_Position = model_view_projection * vec4(position, 1.0);
}
)";

// Lambert shading under one light from above and behind the default camera;
// the ground gets 1-m grid lines one pixel wide (fwidth) so that motion reads.
constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
uniform vec4 colour;
uniform int grid;
out vec4 fragment;
void main() {
  vec3 base = colour.rgb;
  if (grid == 1) {
    vec2 cell = abs(fract(world_position.xy - 0.5) - 0.5) / fwidth(world_position.xy);
    float line = 1.0 - min(min(cell.x, cell.y), 1.0);
    base = mix(base, base * 0.72, line);
  }
  vec3 light = normalize(vec3(0.35, -0.45, 0.82));
  float diffuse = max(dot(normalize(world_normal), light), 0.0);
  fragment = vec4(base * (0.45 + 0.55 * diffuse), colour.a);
}
)";

GLuint compile(GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("render: shader does not compile: ") + log);
  }
  return shader;
}

}  // namespace

GpuMesh upload(const Mesh& mesh) {
  GpuMesh gpu;
  glGenVertexArrays(1, &gpu.array);
  glGenBuffers(1, &gpu.buffer);
  glBindVertexArray(gpu.array);
  glBindBuffer(GL_ARRAY_BUFFER, gpu.buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(float)),
               mesh.vertices.data(), GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                        reinterpret_cast<const void*>(3 * sizeof(float)));
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  gpu.vertex_count = mesh.vertex_count();
  return gpu;
}

void release(GpuMesh& mesh) {
  glDeleteBuffers(1, &mesh.buffer);
  glDeleteVertexArrays(1, &mesh.array);
}

unsigned int build_shading_program() {
  const GLuint vertex = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fragment = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  return program;
}

}  // namespace bsg::render
