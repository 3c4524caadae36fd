#include "render/scene_renderer.h"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "render/egl_context.h"
#include "render/gl_resources.h"
#include "envs/physics/world.h"
#include "render/shape_mesh.h"

namespace bsg::render {
namespace {

struct Colour {
  float r, g, b, a = 1;
};

// The palette of the header comment.
constexpr Colour kSky{0.78f, 0.85f, 0.93f};
constexpr Colour kGround{0.86f, 0.86f, 0.84f};
constexpr Colour kAgent{0.10f, 0.30f, 0.95f};
constexpr Colour kWall{0.55f, 0.56f, 0.60f};
constexpr Colour kBody{0.98f, 0.55f, 0.10f};
constexpr Colour kGoal{0.15f, 0.80f, 0.30f, 0.75f};
constexpr Colour kHazardZone{0.60f, 0.20f, 0.80f, 0.75f};
constexpr Colour kPillar{0.60f, 0.20f, 0.80f};
constexpr Colour kApple{0.05f, 0.95f, 0.0f};
constexpr Colour kBomb{0.95f, 0.05f, 0.0f};
constexpr Colour kCollected{0.55f, 0.55f, 0.55f};
constexpr Colour kBoundary{0.90f, 0.08f, 0.08f};
constexpr Colour kTrack{0.98f, 0.80f, 0.15f, 0.85f};
constexpr Colour kPathSafe{0.05f, 0.10f, 0.45f};  // darker than the agent
constexpr Colour kPathCost{0.95f, 0.10f, 0.05f};

// Placement of a mesh: world transform (rotation and origin) and a scale per
// axis applied first, in the mesh's own frame.
struct Placement {
  btTransform transform = btTransform::getIdentity();
  btVector3 scale{1, 1, 1};
};

// What tells two convex shapes apart: type, margin, local bounding box.
using ShapeGeometry = std::array<double, 8>;

ShapeGeometry geometry_of(const btConvexShape& shape) {
  btVector3 low, high;
  shape.getAabb(btTransform::getIdentity(), low, high);
  return {static_cast<double>(shape.getShapeType()), shape.getMargin(), low.x(), low.y(), low.z(),
          high.x(), high.y(), high.z()};
}

Placement at(const envs::Vec3& position, const btVector3& scale) {
  Placement placement;
  placement.transform.setOrigin(btVector3(position[0], position[1], position[2]));
  placement.scale = scale;
  return placement;
}

}  // namespace

struct SceneRenderer::Gl {
  EglContext context;
  int width = 0;
  int height = 0;
  GLuint framebuffer = 0;
  GLuint colour_buffer = 0;
  GLuint depth_buffer = 0;
  GLuint program = 0;
  GLint model_view_projection = -1, model = -1, normal_matrix = -1, colour = -1, grid = -1;
  GpuMesh sphere, box, cylinder, disc;
  // Meshes of convex shapes by address and geometry: a shape of a destroyed
  // environment may leave its address to a different shape of the next.
  std::map<std::pair<const btCollisionShape*, ShapeGeometry>, GpuMesh> convex_meshes;
  std::unordered_map<double, GpuMesh> rings;  // by inner radius over outer
  Mat4 view_projection{};
  std::vector<std::uint8_t> rows;  // glReadPixels' bottom-up RGBA rows

  void draw_mesh(const GpuMesh& mesh, const Placement& placement, const Colour& c,
                 bool ground_grid = false) {
    const btMatrix3x3& basis = placement.transform.getBasis();
    const btVector3& origin = placement.transform.getOrigin();
    Mat4 model_matrix{};
    float normals[9];
    for (int col = 0; col < 3; ++col) {
      for (int row = 0; row < 3; ++row) {
        model_matrix[static_cast<size_t>(col * 4 + row)] = basis[row][col] * placement.scale[col];
        // (R·S)^{-T} = R·S^{-1} for a rotation R and a diagonal scale S.
        normals[col * 3 + row] = static_cast<float>(basis[row][col] / placement.scale[col]);
      }
      model_matrix[static_cast<size_t>(12 + col)] = origin[col];
    }
    model_matrix[15] = 1;
    const Mat4 mvp = multiply(view_projection, model_matrix);
    float mvp_f[16], model_f[16];
    for (size_t i = 0; i < 16; ++i) {
      mvp_f[i] = static_cast<float>(mvp[i]);
      model_f[i] = static_cast<float>(model_matrix[i]);
    }
    glUniformMatrix4fv(model_view_projection, 1, GL_FALSE, mvp_f);
    glUniformMatrix4fv(model, 1, GL_FALSE, model_f);
    glUniformMatrix3fv(normal_matrix, 1, GL_FALSE, normals);
    glUniform4f(colour, c.r, c.g, c.b, c.a);
    glUniform1i(grid, ground_grid ? 1 : 0);
    glBindVertexArray(mesh.array);
    glDrawArrays(GL_TRIANGLES, 0, mesh.vertex_count);
  }

  // Draws a collision shape (recursing into compounds) at `transform`.
  void draw_shape(const btCollisionShape* shape, const btTransform& transform, const Colour& c,
                  bool ground_grid) {
    if (const auto* compound = dynamic_cast<const btCompoundShape*>(shape)) {
      for (int i = 0; i < compound->getNumChildShapes(); ++i) {
        draw_shape(compound->getChildShape(i), transform * compound->getChildTransform(i), c,
                   ground_grid);
      }
      return;
    }
    Placement placement;
    placement.transform = transform;
    if (const auto* sphere_shape = dynamic_cast<const btSphereShape*>(shape)) {
      const double r = sphere_shape->getRadius();
      placement.scale = btVector3(r, r, r);
      draw_mesh(sphere, placement, c, ground_grid);
    } else if (const auto* box_shape = dynamic_cast<const btBoxShape*>(shape)) {
      placement.scale = box_shape->getHalfExtentsWithMargin();
      draw_mesh(box, placement, c, ground_grid);
    } else if (const auto* convex = dynamic_cast<const btConvexShape*>(shape)) {
      const auto key = std::pair{shape, geometry_of(*convex)};
      auto found = convex_meshes.find(key);
      if (found == convex_meshes.end()) {
        found = convex_meshes.emplace(key, upload(convex_shape_mesh(*convex))).first;
      }
      draw_mesh(found->second, placement, c, ground_grid);
    }
    // Concave shapes (triangle meshes, heightfields) are not used by any environment.
  }

  // A disc, or with `ring_width_m` a ring of that width inside its rim, just
  // above the ground (top face z = 0), below every body.
  void draw_flat_marking(const envs::Marking& marking, const Colour& c, double ring_width_m = 0) {
    envs::Vec3 position = marking.position;
    position[2] = std::max(position[2], 0.0) + 0.004;
    const GpuMesh* mesh = &disc;
    if (ring_width_m > 0) {
      const double inner = 1 - ring_width_m / marking.radius;
      auto found = rings.find(inner);
      if (found == rings.end()) found = rings.emplace(inner, upload(ring_mesh(inner))).first;
      mesh = &found->second;
    }
    draw_mesh(*mesh, at(position, btVector3(marking.radius, marking.radius, 1)), c);
  }

  // A strip of `width_m` on the ground from a to b.
  void draw_strip(const envs::Vec3& a, const envs::Vec3& b, double width_m, double lift_m,
                  const Colour& c) {
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double length = std::sqrt(dx * dx + dy * dy);
    if (length <= 0) return;
    Placement placement;
    placement.transform.setOrigin(btVector3((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, lift_m));
    placement.transform.setRotation(btQuaternion(btVector3(0, 0, 1), std::atan2(dy, dx)));
    placement.scale = btVector3(length / 2 + width_m / 2, width_m / 2, 0.002);
    draw_mesh(box, placement, c);
  }
};

void SceneRenderer::require_valid_size(int width, int height) {
  for (const auto& [name, value] : {std::pair{"width", width}, {"height", height}}) {
    if (value < 1 || value > kMaxSide) {
      throw std::invalid_argument(std::string("render: ") + name + " must be in [1, " +
                                  std::to_string(kMaxSide) + "], got " + std::to_string(value));
    }
  }
}

SceneRenderer::SceneRenderer(int width, int height) {
  require_valid_size(width, height);
  gl_ = std::make_unique<Gl>();
  Gl& gl = *gl_;
  gl.width = width;
  gl.height = height;
  EglContext::Current current(gl.context);
  glGenFramebuffers(1, &gl.framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
  glGenRenderbuffers(1, &gl.colour_buffer);
  glBindRenderbuffer(GL_RENDERBUFFER, gl.colour_buffer);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            gl.colour_buffer);
  glGenRenderbuffers(1, &gl.depth_buffer);
  glBindRenderbuffer(GL_RENDERBUFFER, gl.depth_buffer);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, gl.depth_buffer);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("render: the OpenGL driver cannot make a " + std::to_string(width) +
                             "x" + std::to_string(height) + " framebuffer");
  }
  gl.program = build_shading_program();
  gl.model_view_projection = glGetUniformLocation(gl.program, "model_view_projection");
  gl.model = glGetUniformLocation(gl.program, "model");
  gl.normal_matrix = glGetUniformLocation(gl.program, "normal_matrix");
  gl.colour = glGetUniformLocation(gl.program, "colour");
  gl.grid = glGetUniformLocation(gl.program, "grid");
  gl.sphere = upload(unit_sphere_mesh());
  gl.box = upload(unit_box_mesh());
  gl.cylinder = upload(unit_cylinder_mesh());
  gl.disc = upload(unit_disc_mesh());
}

SceneRenderer::~SceneRenderer() {
  Gl& gl = *gl_;
  EglContext::Current current(gl.context);
  for (GpuMesh* mesh : {&gl.sphere, &gl.box, &gl.cylinder, &gl.disc}) release(*mesh);
  for (auto& [shape, mesh] : gl.convex_meshes) release(mesh);
  for (auto& [inner, mesh] : gl.rings) release(mesh);
  glDeleteProgram(gl.program);
  glDeleteRenderbuffers(1, &gl.colour_buffer);
  glDeleteRenderbuffers(1, &gl.depth_buffer);
  glDeleteFramebuffers(1, &gl.framebuffer);
}

int SceneRenderer::width() const { return gl_->width; }
int SceneRenderer::height() const { return gl_->height; }

void SceneRenderer::draw(const envs::SceneView& scene, const Camera& camera, Image& image,
                         std::vector<float>* depth,
                         std::span<const std::vector<PathPoint>> paths) {
  Gl& gl = *gl_;
  EglContext::Current current(gl.context);
  glBindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
  glViewport(0, 0, gl.width, gl.height);
  glClearColor(kSky.r, kSky.g, kSky.b, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  // Every mesh is closed and wound counter-clockwise seen from outside (the
  // flat markings face up, and cameras look from above): back faces, the
  // ground's bottom among them, need no shading.
  glEnable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glUseProgram(gl.program);
  const double aspect = static_cast<double>(gl.width) / gl.height;
  gl.view_projection = multiply(projection_matrix(camera, aspect), view_matrix(camera));

  // Lines stay at least a few pixels wide however far the camera is (trajectory
  // plots of a long Run): metres per pixel at the target's distance.
  const double metres_per_pixel =
      2 * camera.distance_m * std::tan(camera.vertical_fov_deg * std::numbers::pi / 360) / gl.height;
  const double boundary_width_m = std::max(0.15, 2 * metres_per_pixel);
  const double path_width_m = std::max(0.12, 2.5 * metres_per_pixel);

  const auto& objects = scene.world->dynamics().getCollisionObjectArray();
  const btCollisionObject* ground = scene.world->ground();
  gl.draw_shape(ground->getCollisionShape(), ground->getWorldTransform(), kGround, true);

  // Flat markings and paths lie on the ground: blended, without writing depth.
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  for (const envs::Marking& marking : scene.markings) {
    using Kind = envs::Marking::Kind;
    switch (marking.kind) {
      case Kind::kCircleTrack:
        gl.draw_flat_marking(marking, kTrack, 0.15);
        break;
      case Kind::kGoalZone: gl.draw_flat_marking(marking, kGoal); break;
      case Kind::kPuddle: gl.draw_flat_marking(marking, kHazardZone); break;
      case Kind::kSafetyBoundary: gl.draw_strip(marking.position, marking.end, boundary_width_m, 0.006, kBoundary); break;
      default: break;
    }
  }
  for (const std::vector<PathPoint>& path : paths) {
    for (size_t i = 1; i < path.size(); ++i) {
      gl.draw_strip({path[i - 1].x, path[i - 1].y, 0}, {path[i].x, path[i].y, 0}, path_width_m, 0.01,
                    path[i].cost ? kPathCost : kPathSafe);
    }
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);

  for (const envs::Marking& marking : scene.markings) {
    using Kind = envs::Marking::Kind;
    const double r = marking.radius;
    if (marking.kind == Kind::kApple || marking.kind == Kind::kBomb) {
      const Colour& c = !marking.active ? kCollected : marking.kind == Kind::kApple ? kApple : kBomb;
      gl.draw_mesh(gl.sphere, at(marking.position, btVector3(r, r, r)), c);
    } else if (marking.kind == Kind::kPillar) {
      gl.draw_mesh(gl.cylinder, at(marking.position, btVector3(r, r, marking.height)), kPillar);
    }
  }
  for (int i = 0; i < objects.size(); ++i) {
    const btCollisionObject* object = objects[i];
    if (object == ground) continue;
    const bool is_agent = std::find(scene.agent_colliders.begin(), scene.agent_colliders.end(),
                                    object) != scene.agent_colliders.end();
    const Colour& c = is_agent ? kAgent : object->isStaticObject() ? kWall : kBody;
    gl.draw_shape(object->getCollisionShape(), object->getWorldTransform(), c, false);
  }

  // RGBA is the framebuffer's own layout (drivers copy it without converting);
  // alpha is dropped here. OpenGL's rows run bottom-up, the image's top-down.
  const auto w = static_cast<size_t>(gl.width), h = static_cast<size_t>(gl.height);
  gl.rows.resize(w * h * 4);
  glReadPixels(0, 0, gl.width, gl.height, GL_RGBA, GL_UNSIGNED_BYTE, gl.rows.data());
  image.width = gl.width;
  image.height = gl.height;
  image.rgb.resize(w * h * 3);
  for (size_t y = 0; y < h; ++y) {
    const std::uint8_t* source = gl.rows.data() + (h - 1 - y) * w * 4;
    std::uint8_t* target = image.rgb.data() + y * w * 3;
    for (size_t x = 0; x < w; ++x) {
      target[3 * x] = source[4 * x];
      target[3 * x + 1] = source[4 * x + 1];
      target[3 * x + 2] = source[4 * x + 2];
    }
  }
  if (depth != nullptr) {
    std::vector<float> window(static_cast<size_t>(gl.width) * static_cast<size_t>(gl.height));
    glReadPixels(0, 0, gl.width, gl.height, GL_DEPTH_COMPONENT, GL_FLOAT, window.data());
    depth->resize(window.size());
    const double n = camera.near_m, f = camera.far_m;
    for (int y = 0; y < gl.height; ++y) {
      for (int x = 0; x < gl.width; ++x) {
        // Window depth d in [0, 1] back to eye-space distance: z_ndc = 2d − 1,
        // z = 2fn / (f + n − z_ndc·(f − n)).
        const double d = window[static_cast<size_t>((gl.height - 1 - y) * gl.width + x)];
        const double z_ndc = 2 * d - 1;
        (*depth)[static_cast<size_t>(y * gl.width + x)] =
            static_cast<float>(2 * f * n / (f + n - z_ndc * (f - n)));
      }
    }
  }
}

}  // namespace bsg::render
