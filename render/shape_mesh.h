// Triangle meshes for drawing Bullet collision shapes and the tasks' markings:
// interleaved (position xyz, normal xyz) per vertex, three vertices per
// triangle, in the shape's own frame. CPU only; the renderer uploads them once.
#pragma once

#include <vector>

class btConvexShape;

namespace bsg::render {

struct Mesh {
  std::vector<float> vertices;  // 6 floats per vertex
  int vertex_count() const { return static_cast<int>(vertices.size() / 6); }
};

// A sphere of radius 1 at the origin, smooth normals.
Mesh unit_sphere_mesh();
// A box with half extents 1 (the cube [−1, 1]³).
Mesh unit_box_mesh();
// A cylinder of radius 1 from z = 0 to z = 1, with caps.
Mesh unit_cylinder_mesh();
// A disc of radius 1 in the plane z = 0, facing +z.
Mesh unit_disc_mesh();
// A ring between radii `inner` (in (0, 1)) and 1 in the plane z = 0, facing +z.
Mesh ring_mesh(double inner);
// Any convex shape (capsules, multi-spheres, convex hulls, cylinders, boxes):
// the convex hull of its support points, margin included, over a fan of
// directions (Bullet's collision surface), flat-shaded.
Mesh convex_shape_mesh(const btConvexShape& shape);

}  // namespace bsg::render
