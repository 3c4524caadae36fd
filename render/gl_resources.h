// The OpenGL objects the scene renderer draws with: meshes uploaded into
// vertex arrays (shape_mesh.h) and the one shading program (Lambert light,
// the ground's 1-m grid). Call with the renderer's context current.
#pragma once

#include "render/shape_mesh.h"

namespace bsg::render {

// A mesh in its own vertex array (GL names: GLuint is unsigned int, GLsizei int).
struct GpuMesh {
  unsigned int array = 0;
  unsigned int buffer = 0;
  int vertex_count = 0;
};

GpuMesh upload(const Mesh& mesh);
void release(GpuMesh& mesh);

// Compiles and links the shading program; throws std::runtime_error with the
// driver's log if it does not compile.
unsigned int build_shading_program();

}  // namespace bsg::render
