#include "render/shape_mesh.h"

#include <cmath>
#include <numbers>
#include <utility>

#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <LinearMath/btConvexHullComputer.h>

namespace bsg::render {
namespace {

constexpr double kPi = std::numbers::pi;

void add_vertex(Mesh& mesh, const btVector3& p, const btVector3& n) {
  for (const double v : {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()}) {
    mesh.vertices.push_back(static_cast<float>(v));
  }
}

// A triangle of a convex hull, wound so that its normal points away from the
// hull's inner point `inside`.
void add_flat_triangle(Mesh& mesh, const btVector3& a, btVector3 b, btVector3 c,
                       const btVector3& inside) {
  btVector3 n = (b - a).cross(c - a);
  if (n.length2() < 1e-24) return;
  n.normalize();
  if (n.dot(a - inside) < 0) {
    std::swap(b, c);
    n = -n;
  }
  add_vertex(mesh, a, n);
  add_vertex(mesh, b, n);
  add_vertex(mesh, c, n);
}

btVector3 sphere_point(int ring, int rings, int segment, int segments) {
  const double theta = kPi * ring / rings;             // from +z down
  const double phi = 2 * kPi * segment / segments;
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

}  // namespace

Mesh unit_sphere_mesh() {
  constexpr int kRings = 12, kSegments = 18;
  Mesh mesh;
  for (int r = 0; r < kRings; ++r) {
    for (int s = 0; s < kSegments; ++s) {
      const btVector3 a = sphere_point(r, kRings, s, kSegments);
      const btVector3 b = sphere_point(r + 1, kRings, s, kSegments);
      const btVector3 c = sphere_point(r + 1, kRings, s + 1, kSegments);
      const btVector3 d = sphere_point(r, kRings, s + 1, kSegments);
      // On a unit sphere a point is its own normal.
      if (r > 0) {
        add_vertex(mesh, a, a);
        add_vertex(mesh, b, b);
        add_vertex(mesh, d, d);
      }
      if (r < kRings - 1) {
        add_vertex(mesh, d, d);
        add_vertex(mesh, b, b);
        add_vertex(mesh, c, c);
      }
    }
  }
  return mesh;
}

Mesh unit_box_mesh() {
  Mesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {-1.0, 1.0}) {
      btVector3 n(0, 0, 0), u(0, 0, 0), v(0, 0, 0);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = 1;
      if (sign < 0) std::swap(u, v);  // counter-clockwise seen from outside
      const btVector3 c0 = n - u - v, c1 = n + u - v, c2 = n + u + v, c3 = n - u + v;
      for (const btVector3& p : {c0, c1, c2, c0, c2, c3}) add_vertex(mesh, p, n);
    }
  }
  return mesh;
}

Mesh unit_cylinder_mesh() {
  constexpr int kSegments = 32;
  Mesh mesh;
  const btVector3 up(0, 0, 1), down(0, 0, -1);
  for (int s = 0; s < kSegments; ++s) {
    const double a0 = 2 * kPi * s / kSegments, a1 = 2 * kPi * (s + 1) / kSegments;
    const btVector3 n0(std::cos(a0), std::sin(a0), 0), n1(std::cos(a1), std::sin(a1), 0);
    const btVector3 b0 = n0, b1 = n1, t0 = n0 + up, t1 = n1 + up;
    for (const auto& [p, n] : {std::pair{b0, n0}, {b1, n1}, {t1, n1}, {b0, n0}, {t1, n1}, {t0, n0}}) {
      add_vertex(mesh, p, n);
    }
    add_vertex(mesh, up, up);
    add_vertex(mesh, t0, up);
    add_vertex(mesh, t1, up);
    add_vertex(mesh, btVector3(0, 0, 0), down);
    add_vertex(mesh, b1, down);
    add_vertex(mesh, b0, down);
  }
  return mesh;
}

Mesh unit_disc_mesh() {
  constexpr int kSegments = 64;
  Mesh mesh;
  const btVector3 up(0, 0, 1);
  for (int s = 0; s < kSegments; ++s) {
    const double a0 = 2 * kPi * s / kSegments, a1 = 2 * kPi * (s + 1) / kSegments;
    add_vertex(mesh, btVector3(0, 0, 0), up);
    add_vertex(mesh, btVector3(std::cos(a0), std::sin(a0), 0), up);
    add_vertex(mesh, btVector3(std::cos(a1), std::sin(a1), 0), up);
  }
  return mesh;
}

Mesh ring_mesh(double inner) {
  constexpr int kSegments = 96;
  Mesh mesh;
  const btVector3 up(0, 0, 1);
  for (int s = 0; s < kSegments; ++s) {
    const double a0 = 2 * kPi * s / kSegments, a1 = 2 * kPi * (s + 1) / kSegments;
    const btVector3 o0(std::cos(a0), std::sin(a0), 0), o1(std::cos(a1), std::sin(a1), 0);
    const btVector3 i0 = o0 * inner, i1 = o1 * inner;
    for (const btVector3& p : {i0, o0, o1, i0, o1, i1}) add_vertex(mesh, p, up);
  }
  return mesh;
}

Mesh convex_shape_mesh(const btConvexShape& shape) {
  constexpr int kRings = 10, kSegments = 16;
  std::vector<btVector3> points;
  for (int r = 0; r <= kRings; ++r) {
    for (int s = 0; s < (r == 0 || r == kRings ? 1 : kSegments); ++s) {
      points.push_back(shape.localGetSupportingVertex(sphere_point(r, kRings, s, kSegments)));
    }
  }
  btConvexHullComputer hull;
  hull.compute(&points[0].x(), sizeof(btVector3), static_cast<int>(points.size()), 0, 0);
  btVector3 inside(0, 0, 0);
  for (int v = 0; v < hull.vertices.size(); ++v) inside += hull.vertices[v];
  inside /= static_cast<double>(hull.vertices.size());
  Mesh mesh;
  for (int f = 0; f < hull.faces.size(); ++f) {
    // Each face is a cycle of edges; fan it from its first vertex.
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    const btVector3& a = hull.vertices[first->getSourceVertex()];
    const btConvexHullComputer::Edge* edge = first->getNextEdgeOfFace();
    while (edge->getTargetVertex() != first->getSourceVertex()) {
      add_flat_triangle(mesh, a, hull.vertices[edge->getSourceVertex()],
                        hull.vertices[edge->getTargetVertex()], inside);
      edge = edge->getNextEdgeOfFace();
    }
  }
  return mesh;
}

}  // namespace bsg::render
