// The renderer: fixed-function GL over the compiled visuals. One light (LightPos, LightColor),
// the skins' materials, quality levels of guide 3.3.3, planar shadows on shadow planes, fog.
#include <filesystem>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <sys/stat.h>

#include "render/gl_context.h"
#include "render/shapes.h"
#include "image/texture_file.h"
#include "simbob/renderer.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

using render::GlApi;

const char* const kQualityNames[] = {"frame",    "wire",    "plane",        "flat", "smooth",
                                     "textures", "shadows", "transparency", "fog"};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool isFile(const std::string& p) {
  struct stat st {};
  return stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

/// Column-major 4x4 of a rigid transform (GL's layout).
std::array<double, 16> matrixOf(const Transform& t) {
  const Mat3 r = toMatrix(t.q);
  return {r[0], r[3], r[6], 0, r[1], r[4], r[7], 0, r[2], r[5], r[8], 0, t.p[0], t.p[1], t.p[2], 1};
}

void setMaterial(const GlApi& gl, GLenum what, const Rgba& c) {
  const GLfloat f[4] = {static_cast<GLfloat>(c[0]), static_cast<GLfloat>(c[1]), static_cast<GLfloat>(c[2]),
                        static_cast<GLfloat>(c[3])};
  gl.Materialfv(GL_FRONT_AND_BACK, what, f);
}

/// A camera's world frame: it looks along its local -Z with +Y up. `look` turns -Z towards
/// `target` keeping +Y as near to world up as possible.
Transform lookAt(const Vec3& eye, const Vec3& target) {
  Vec3 f = sub(target, eye);
  const double len = norm(f);
  if (!(len > 1e-12)) return Transform{eye, {1, 0, 0, 0}};
  f = scale(f, 1 / len);
  Vec3 up{0, 1, 0};
  if (std::fabs(dot(f, up)) > 0.999) up = {0, 0, -1};
  Vec3 x = cross(f, up);
  x = scale(x, 1 / norm(x));
  const Vec3 y = cross(x, f);
  const Vec3 z = scale(f, -1);
  // Rotation matrix with columns x, y, z -> quaternion.
  const double m00 = x[0], m11 = y[1], m22 = z[2];
  const double tr = m00 + m11 + m22;
  Quat q;
  if (tr > 0) {
    const double s = std::sqrt(tr + 1) * 2;
    q = {s / 4, (y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s};
  } else if (m00 > m11 && m00 > m22) {
    const double s = std::sqrt(1 + m00 - m11 - m22) * 2;
    q = {(y[2] - z[1]) / s, s / 4, (y[0] + x[1]) / s, (z[0] + x[2]) / s};
  } else if (m11 > m22) {
    const double s = std::sqrt(1 + m11 - m00 - m22) * 2;
    q = {(z[0] - x[2]) / s, (y[0] + x[1]) / s, s / 4, (z[1] + y[2]) / s};
  } else {
    const double s = std::sqrt(1 + m22 - m00 - m11) * 2;
    q = {(x[1] - y[0]) / s, (z[0] + x[2]) / s, (z[1] + y[2]) / s, s / 4};
  }
  return Transform{eye, q};
}

struct Texture {
  GLuint id = 0;
};

class GlRenderer : public Renderer {
 public:
  GlRenderer(const Model& m, const RenderOptions& o, std::unique_ptr<render::GlContext> ctx)
      : model_(m), opts_(o), ctx_(std::move(ctx)), gl_(ctx_->gl), skins_(m.skins), meshes_(m.meshes) {
    if (o.draw_models) visuals_ = m.visuals;
    if (o.draw_geoms) addGeomVisuals(!o.draw_models);
  }

  ~GlRenderer() override {
    for (GLuint id : texture_ids_) gl_.DeleteTextures(1, &id);
    meshes_.release(gl_);
  }

  bool init(Error* err) {
    if (!chooseCamera(err)) return false;
    return loadTextures(err);
  }

  const Error* acquire() override {
    if (ctx_->makeCurrent()) return nullptr;
    error_ = Error{ErrorKind::Internal, {}, ctx_->name() + " refused to make the GL context current on this thread"};
    return &error_;
  }
  void release() override { ctx_->release(); }

  std::string backendName() const override { return ctx_->name(); }
  std::string glRenderer() const override {
    const auto* s = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
    return s ? s : "(unknown)";
  }
  std::string cameraName() const override { return camera_ ? camera_->key : "(default)"; }

  void follow(const std::vector<Transform>& poses) override {
    double va = 0, near_clip = 0, far_clip = 0;
    cameraFrame(poses, &va, &near_clip, &far_clip);
  }

  const Error* render(const std::vector<Transform>& poses, double /*t*/, Image* out) override {
    // Another renderer on this thread (a camera sensor's, Python's) may have made its own
    // context current since: GL calls go to the current one.
    if (const Error* e = acquire()) return e;
    const int w = opts_.width, h = opts_.height;
    const ViewSettings& view = model_.view;
    const Quality q = opts_.quality;
    gl_.Viewport(0, 0, w, h);
    gl_.ClearColor(static_cast<GLfloat>(view.clear_color[0]), static_cast<GLfloat>(view.clear_color[1]),
                   static_cast<GLfloat>(view.clear_color[2]), 1.0F);
    gl_.ClearStencil(0);
    gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LEQUAL);
    gl_.Enable(GL_NORMALIZE);

    if (!camera_) frameBodies(poses);
    // Projection: ViewAngle is the horizontal field of view (guide 3.5).
    double va = 60, near_clip = 0.1, far_clip = 1000;
    const Transform eye = cameraFrame(poses, &va, &near_clip, &far_clip);
    const double right = near_clip * std::tan(va * kPi / 360);
    const double top = right * h / w;
    gl_.MatrixMode(GL_PROJECTION);
    gl_.LoadIdentity();
    gl_.Frustum(-right, right, -top, top, near_clip, far_clip);
    gl_.MatrixMode(GL_MODELVIEW);
    const std::array<double, 16> view_m = matrixOf(inverse(eye));
    gl_.LoadMatrixd(view_m.data());

    // The light, placed in world coordinates under the view matrix.
    const GLfloat lp[4] = {static_cast<GLfloat>(view.light_pos[0]), static_cast<GLfloat>(view.light_pos[1]),
                           static_cast<GLfloat>(view.light_pos[2]), static_cast<GLfloat>(view.light_pos[3])};
    const GLfloat lc[4] = {static_cast<GLfloat>(view.light_color[0]), static_cast<GLfloat>(view.light_color[1]),
                           static_cast<GLfloat>(view.light_color[2]), 1.0F};
    // Light ambient = diffuse = LightColor and no global ambient: a skin with the derived
    // Ambient = Diffuse = Color/2 shows its Color where it faces the light, half of it in shade.
    const GLfloat ambient[4] = {0.0F, 0.0F, 0.0F, 1.0F};
    gl_.Lightfv(GL_LIGHT0, GL_POSITION, lp);
    gl_.Lightfv(GL_LIGHT0, GL_DIFFUSE, lc);
    gl_.Lightfv(GL_LIGHT0, GL_SPECULAR, lc);
    gl_.Lightfv(GL_LIGHT0, GL_AMBIENT, lc);
    gl_.LightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
    gl_.LightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
    gl_.Enable(GL_LIGHT0);
    gl_.ShadeModel(q == Quality::Flat ? GL_FLAT : GL_SMOOTH);
    gl_.PolygonMode(GL_FRONT_AND_BACK, q == Quality::Wire ? GL_LINE : GL_FILL);

    if (q >= Quality::Fog && view.fog != ViewSettings::Off) {
      gl_.Enable(GL_FOG);
      gl_.Fogi(GL_FOG_MODE, view.fog == ViewSettings::Linear        ? GL_LINEAR
                            : view.fog == ViewSettings::Exponential ? GL_EXP
                                                                    : GL_EXP2);
      gl_.Fogf(GL_FOG_DENSITY, static_cast<GLfloat>(view.fog_density));
      gl_.Fogf(GL_FOG_START, static_cast<GLfloat>(view.fog_start));
      gl_.Fogf(GL_FOG_END, static_cast<GLfloat>(view.fog_end));
      const GLfloat fc[4] = {static_cast<GLfloat>(view.fog_color[0]), static_cast<GLfloat>(view.fog_color[1]),
                             static_cast<GLfloat>(view.fog_color[2]), 1.0F};
      gl_.Fogfv(GL_FOG_COLOR, fc);
      gl_.Hint(GL_FOG_HINT, GL_NICEST);
    } else {
      gl_.Disable(GL_FOG);
    }

    // Shadow planes first (stencil 1 where they show), then the shadows on them, then the rest.
    const bool shadows = q >= Quality::Shadows;
    std::vector<size_t> planes, opaque, transparent;
    for (size_t i = 0; i < visuals_.size(); ++i) {
      const VisualDef& v = visuals_[i];
      if (shadows && v.shape == VisualDef::Plane && v.shadow_plane)
        planes.push_back(i);
      else if (q >= Quality::Transparency && isTransparent(v))
        transparent.push_back(i);
      else
        opaque.push_back(i);
    }
    for (size_t i : planes) {
      gl_.Enable(GL_STENCIL_TEST);
      gl_.StencilFunc(GL_ALWAYS, 1, 0xFF);
      gl_.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      drawVisual(i, poses);
      gl_.Disable(GL_STENCIL_TEST);
      drawShadows(i, poses);
    }
    for (size_t i : opaque) drawVisual(i, poses);
    if (!transparent.empty()) {
      gl_.Enable(GL_BLEND);
      gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      gl_.DepthMask(GL_FALSE);
      for (size_t i : transparent) drawVisual(i, poses);
      gl_.DepthMask(GL_TRUE);
      gl_.Disable(GL_BLEND);
    }
    gl_.Disable(GL_FOG);
    if (opts_.draw_sensors) drawSensorRays(poses);

    // Read back (GL's rows are bottom first).
    Image img(w, h);
    std::vector<uint8_t> rows(img.rgb.size());
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.ReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
    const size_t stride = static_cast<size_t>(w) * 3;
    for (int y = 0; y < h; ++y)
      std::copy_n(rows.data() + stride * static_cast<size_t>(h - 1 - y), stride, img.pixel(0, y));
    if (GLenum e = gl_.GetError(); e != GL_NO_ERROR) {
      error_ = Error{ErrorKind::Internal, {}, "GL error " + std::to_string(e) + " while rendering"};
      return &error_;
    }
    *out = std::move(img);
    return nullptr;
  }

 private:
  bool isTransparent(const VisualDef& v) const {
    const SkinDef& s = skins_[static_cast<size_t>(v.skin)];
    return (s.mode == SkinDef::TransparentColor || s.mode == SkinDef::TransparentLighting) && s.color[3] < 1;
  }

  Transform worldPose(const VisualDef& v, const std::vector<Transform>& poses) const {
    if (v.body < 0 || static_cast<size_t>(v.body) >= poses.size()) return v.pose;
    return compose(poses[static_cast<size_t>(v.body)], v.pose);
  }

  void drawVisual(size_t i, const std::vector<Transform>& poses) {
    const VisualDef& v = visuals_[i];
    const SkinDef& s = skins_[static_cast<size_t>(v.skin)];
    const Quality q = opts_.quality;
    const bool unlit = q <= Quality::Plane || s.mode == SkinDef::Color || s.mode == SkinDef::TransparentColor;
    const double alpha = q >= Quality::Transparency ? s.color[3] : 1.0;
    if (unlit) {
      gl_.Disable(GL_LIGHTING);
      gl_.Color4d(s.color[0], s.color[1], s.color[2], alpha);
    } else {
      gl_.Enable(GL_LIGHTING);
      Rgba diffuse = s.diffuse;
      diffuse[3] = alpha;
      setMaterial(gl_, GL_AMBIENT, s.ambient);
      setMaterial(gl_, GL_DIFFUSE, diffuse);
      // Shininess 0 would make the highlight cover every lit surface (x^0 = 1): no highlight.
      setMaterial(gl_, GL_SPECULAR, s.shininess > 0 ? s.specular : Rgba{0, 0, 0, 1});
      setMaterial(gl_, GL_EMISSION, s.emission);
      gl_.Materialf(GL_FRONT_AND_BACK, GL_SHININESS, static_cast<GLfloat>(std::min(s.shininess, 128.0)));
    }
    const Texture& tex = textures_[static_cast<size_t>(v.skin)];
    const bool textured = q >= Quality::Textures && tex.id != 0;
    if (textured) {
      gl_.Enable(GL_TEXTURE_2D);
      gl_.BindTexture(GL_TEXTURE_2D, tex.id);
      // A textured skin without colour shows the texture lit; a coloured one blends both.
      gl_.TexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    }
    gl_.PushMatrix();
    const std::array<double, 16> m = matrixOf(worldPose(v, poses));
    gl_.MultMatrixd(m.data());
    if (q == Quality::Frame) {
      gl_.Disable(GL_LIGHTING);
      render::drawBoundingBox(gl_, v, meshes_);
    } else if (v.wire && q != Quality::Wire) {
      // Pulled towards the eye a little, so that lines on a model's surface (a collision
      // shape over its model) are not hidden by it.
      gl_.PolygonMode(GL_FRONT_AND_BACK, GL_LINE);
      gl_.Enable(GL_POLYGON_OFFSET_LINE);
      gl_.PolygonOffset(-1, -1);
      render::drawShape(gl_, v, meshes_);
      gl_.Disable(GL_POLYGON_OFFSET_LINE);
      gl_.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    } else if (v.one_sided) {
      gl_.Enable(GL_CULL_FACE);
      gl_.CullFace(GL_BACK);
      render::drawShape(gl_, v, meshes_);
      gl_.Disable(GL_CULL_FACE);
    } else {
      render::drawShape(gl_, v, meshes_);
    }
    gl_.PopMatrix();
    if (textured) gl_.Disable(GL_TEXTURE_2D);
  }

  /// Projects every other visual onto shadow plane `pi` from the light (a planar shadow
  /// matrix) into the stencil only (1 -> 2 where the plane showed), then draws the plane again
  /// in black at ShadowIntensity over those pixels, each once. The second pass has the plane's
  /// own depths, so fog treats a shadow as the ground it lies on: GL's fog colour of the black
  /// blended over the fogged ground gives fog(ground * (1 - ShadowIntensity)) exactly. (The
  /// projected vertices have w != 1, and fixed-function fog reads their eye z undivided: drawn
  /// directly, the shadows came out as fully fogged, brighter than the lit ground.)
  void drawShadows(size_t pi, const std::vector<Transform>& poses) {
    const VisualDef& pv = visuals_[pi];
    const Transform pt = worldPose(pv, poses);
    const Vec3 n = rotate(pt.q, {0, 0, 1});
    const double d = -dot(n, pt.p);
    const std::array<double, 4> plane{n[0], n[1], n[2], d};
    const std::array<double, 4>& l = model_.view.light_pos;
    const double dl = plane[0] * l[0] + plane[1] * l[1] + plane[2] * l[2] + plane[3] * l[3];
    if (!(dl > 0)) return;  // the light is behind the plane: no shadows on it
    // M = (P.L) I - L P^T, column-major.
    std::array<double, 16> m{};
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        m[static_cast<size_t>(c) * 4 + static_cast<size_t>(r)] = (r == c ? dl : 0) - l[r] * plane[c];
    gl_.Disable(GL_LIGHTING);
    gl_.Disable(GL_DEPTH_TEST);
    gl_.Enable(GL_STENCIL_TEST);
    gl_.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl_.DepthMask(GL_FALSE);
    gl_.StencilFunc(GL_EQUAL, 1, 0xFF);
    gl_.StencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    for (size_t i = 0; i < visuals_.size(); ++i) {
      const VisualDef& v = visuals_[i];
      // Nor does a shadow plane, nor a collision shape drawn as a wire frame over the models.
      const bool overlay = v.wire && v.skin >= static_cast<int>(model_.skins.size());
      if (i == pi || (v.shape == VisualDef::Plane && v.shadow_plane) || overlay) continue;
      // Only what lies on the light's side of the plane casts a shadow on it.
      const Transform t = worldPose(v, poses);
      if (dot(n, t.p) + d < 0) continue;
      gl_.PushMatrix();
      gl_.MultMatrixd(m.data());
      const std::array<double, 16> mv = matrixOf(t);
      gl_.MultMatrixd(mv.data());
      render::drawShape(gl_, v, meshes_);
      gl_.PopMatrix();
    }
    gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.StencilFunc(GL_EQUAL, 2, 0xFF);
    gl_.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    gl_.Enable(GL_BLEND);
    gl_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl_.Color4d(0, 0, 0, model_.view.shadow_intensity);
    gl_.PushMatrix();
    const std::array<double, 16> pm = matrixOf(pt);
    gl_.MultMatrixd(pm.data());
    render::drawShape(gl_, pv, meshes_);
    gl_.PopMatrix();
    gl_.Disable(GL_BLEND);
    gl_.Disable(GL_STENCIL_TEST);
    gl_.DepthMask(GL_TRUE);
    gl_.Enable(GL_DEPTH_TEST);
    // The next shadow plane starts from a clear stencil: no shadow of it lands on this one.
    gl_.Clear(GL_STENCIL_BUFFER_BIT);
  }

  void setSensorRays(const std::vector<double>& lengths) override { rays_ = lengths; }

  /// --draw sensors: each range sensor's and scanner's rays from the sensor's origin to its
  /// reading (red), and the hit points (readings below MaxRange, yellow), over the scene (not
  /// hidden by it): the rays start inside the robot.
  void drawSensorRays(const std::vector<Transform>& poses) {
    gl_.Disable(GL_LIGHTING);
    gl_.Disable(GL_TEXTURE_2D);
    gl_.Disable(GL_DEPTH_TEST);
    std::vector<Vec3> hits;
    size_t at = 0;
    gl_.LineWidth(1.0F);
    gl_.Color4d(1.0, 0.0, 0.0, 1.0);
    gl_.Begin(GL_LINES);
    for (const SensorDef& s : model_.sensors) {
      int rays = 0;
      switch (s.kind) {
        case SensorKind::Range:
          rays = 1;
          break;
        case SensorKind::Scanner:
          rays = s.rays;
          break;
        case SensorKind::Proximity:
        case SensorKind::Imu:
        case SensorKind::Encoder:
        case SensorKind::Plugin:
          break;
      }
      const bool on_body = s.body >= 0 && static_cast<size_t>(s.body) < poses.size();
      const Transform frame = on_body ? compose(poses[static_cast<size_t>(s.body)], s.pose) : s.pose;
      for (int k = 0; k < rays; ++k, ++at) {
        const double len = at < rays_.size() ? rays_[at] : s.max_range;
        const double a = s.kind == SensorKind::Scanner ? scannerRayAngle(s, k) : 0.0;
        const Vec3 end = add(frame.p, scale(rotate(frame.q, Vec3{-std::sin(a), 0, -std::cos(a)}), len));
        gl_.Vertex3d(frame.p[0], frame.p[1], frame.p[2]);
        gl_.Vertex3d(end[0], end[1], end[2]);
        if (len < s.max_range) hits.push_back(end);
      }
    }
    gl_.End();
    gl_.PointSize(5.0F);
    gl_.Color4d(1.0, 1.0, 0.0, 1.0);
    gl_.Begin(GL_POINTS);
    for (const Vec3& h : hits) gl_.Vertex3d(h[0], h[1], h[2]);
    gl_.End();
    gl_.PointSize(1.0F);
    gl_.Enable(GL_DEPTH_TEST);
  }

  /// The camera's world frame and view at these poses.
  Transform cameraFrame(const std::vector<Transform>& poses, double* va, double* near_clip, double* far_clip) {
    if (!camera_) {
      *va = default_va_;
      *near_clip = default_near_;
      *far_clip = default_far_;
      return default_eye_;
    }
    const CameraDef& c = *camera_;
    *va = c.view_angle;
    *near_clip = c.near_clip;
    *far_clip = c.far_clip;
    const bool on_body = c.body >= 0 && static_cast<size_t>(c.body) < poses.size();
    const Vec3 target = on_body ? poses[static_cast<size_t>(c.body)].p : c.target;
    switch (c.kind) {
      case CameraDef::Static:
        return c.pose;
      case CameraDef::Mounted:
        return on_body ? compose(poses[static_cast<size_t>(c.body)], c.pose) : c.pose;
      case CameraDef::Spotlight: {
        const double dist = norm(sub(target, c.pose.p));
        if (c.auto_view_angle && dist > 0) {
          // Keep the body's apparent size: the view angle it had at the first frame's distance.
          if (spot_dist0_ < 0) spot_dist0_ = dist;
          *va = 2 * std::atan(std::tan(c.view_angle * kPi / 360) * spot_dist0_ / dist) * 180 / kPi;
        }
        return lookAt(c.pose.p, target);
      }
      case CameraDef::Tracking: {
        // Pulled like a rod of length Distance: keep the direction from the body, fix the length.
        if (!track_init_) {
          track_pos_ = add(target, scale(Vec3{0, 0.5, 1}, c.distance / std::sqrt(1.25)));
          track_init_ = true;
        }
        Vec3 away = sub(track_pos_, target);
        const double len = norm(away);
        if (len > 1e-12) track_pos_ = add(target, scale(away, c.distance / len));
        return lookAt(track_pos_, target);
      }
    }
    return c.pose;
  }

  bool chooseCamera(Error* err) {
    if (!opts_.camera.empty()) {
      // The scene's cameras, then the camera sensors' (RCCameraSensor): a sensor's image is this
      // renderer's picture through its camera.
      for (const CameraDef& c : model_.cameras)
        if (!camera_ && c.key == opts_.camera) camera_ = &c;
      for (const CameraSensorDef& s : model_.camera_sensors)
        if (!camera_ && s.camera.key == opts_.camera) camera_ = &s.camera;
      if (!camera_) {
        std::string known;
        for (const CameraDef& c : model_.cameras) known += (known.empty() ? "" : ", ") + c.key;
        for (const CameraSensorDef& s : model_.camera_sensors) known += (known.empty() ? "" : ", ") + s.key;
        err->kind = ErrorKind::InvalidInput;
        err->message = "no camera '" + opts_.camera + "' in the scene (" +
                       (known.empty() ? std::string("it has none") : "cameras: " + known) + ")";
        return false;
      }
    } else if (!model_.cameras.empty()) {
      camera_ = &model_.cameras[0];
    }
    return true;
  }

  /// The default view (no camera in the scene): from the front (+Z), a little above, far enough
  /// for the sphere around the bodies (and the static models that are not planes) to fit the
  /// view. It frames the bodies at the poses drawn; in a recording, at every pose drawn so far,
  /// so the view only widens as they spread and never jumps back.
  void frameBodies(const std::vector<Transform>& poses) {
    std::vector<std::pair<Vec3, double>> balls;  // centre, radius
    for (const VisualDef& v : visuals_) {
      if (v.shape == VisualDef::Plane && v.body < 0) continue;  // grounds, skies: unbounded in effect
      const Transform t = worldPose(v, poses);
      double r = 0;
      switch (v.shape) {
        case VisualDef::Cuboid:
          r = norm(sub(v.b, v.a)) / 2;
          balls.push_back({add(t.p, rotate(t.q, scale(add(v.a, v.b), 0.5))), r});
          continue;
        case VisualDef::Plane:
          r = std::hypot(v.size[0], v.size[1]) / 2;
          break;
        case VisualDef::Ellipsoid:
          r = std::max({v.size[0], v.size[1], v.size[2]});
          break;
        case VisualDef::Cylinder:
          r = std::hypot(v.size[0], v.size[1] / 2) + ((v.mask & 24u) ? v.size[0] : 0);
          break;
        case VisualDef::Cone:
          r = std::hypot(v.size[0], v.size[1]);
          break;
        case VisualDef::Mesh: {
          const MeshData& mesh = *model_.meshes[static_cast<size_t>(v.mesh)].data;
          r = norm(sub(mesh.hi, mesh.lo)) / 2;
          balls.push_back({add(t.p, rotate(t.q, scale(add(mesh.lo, mesh.hi), 0.5))), r});
          continue;
        }
      }
      balls.push_back({t.p, r});
    }
    for (const Transform& p : poses) balls.push_back({p.p, 0.1});
    if (balls.empty()) balls.push_back({{0, 0, 0}, 0});
    if (!framed_) frame_lo_ = frame_hi_ = balls[0].first;
    framed_ = true;
    for (const auto& b : balls)
      for (int k = 0; k < 3; ++k) {
        frame_lo_[k] = std::min(frame_lo_[k], b.first[k] - b.second);
        frame_hi_[k] = std::max(frame_hi_[k], b.first[k] + b.second);
      }
    const Vec3 center = scale(add(frame_lo_, frame_hi_), 0.5);
    const double radius = std::max(0.5, norm(sub(frame_hi_, frame_lo_)) / 2);
    // The narrower of the two view angles decides the distance.
    const double half_h = default_va_ * kPi / 360;
    const double half_v = std::atan(std::tan(half_h) * opts_.height / opts_.width);
    const double dist = radius / std::sin(std::min(half_h, half_v));
    const Vec3 dir = scale(Vec3{0, 0.5, 1}, 1 / std::sqrt(1.25));
    default_eye_ = lookAt(add(center, scale(dir, dist)), center);
    default_near_ = std::max(0.01, (dist - radius) * 0.5);
    default_far_ = dist + radius * 4 + 100;
  }

  /// The collision shapes as visuals: filled and lit in their own skins (`alone`), else as
  /// wire frames over the models. Sensor geoms detect contacts only and are not drawn.
  void addGeomVisuals(bool alone) {
    SkinDef mobile, fixed;
    mobile.key = "(collision shapes)";
    mobile.color = alone ? Rgba{0.9, 0.55, 0.2, 1} : Rgba{1, 0.9, 0, 1};
    fixed.key = "(static collision shapes)";
    fixed.color = alone ? Rgba{0.6, 0.6, 0.6, 1} : Rgba{1, 0.9, 0, 1};
    for (SkinDef* s : {&mobile, &fixed}) {
      s->ambient = s->diffuse = {s->color[0] / 2, s->color[1] / 2, s->color[2] / 2, 1};
      s->specular = {0, 0, 0, 1};
      s->mode = alone ? SkinDef::Shading : SkinDef::Color;
    }
    const int mobile_skin = static_cast<int>(skins_.size());
    skins_.push_back(mobile);
    skins_.push_back(fixed);
    for (const GeomDef& g : model_.geoms) {
      if (g.sensor) continue;
      VisualDef v;
      v.body = g.body;
      v.pose = g.offset;
      v.skin = g.body >= 0 ? mobile_skin : mobile_skin + 1;
      v.key = g.key;
      v.wire = !alone;
      v.accuracy = 2;
      switch (g.shape) {
        case GeomShape::Box:
          v.shape = VisualDef::Cuboid;
          v.a = scale(g.size, -0.5);
          v.b = scale(g.size, 0.5);
          break;
        case GeomShape::Sphere:
          v.shape = VisualDef::Ellipsoid;
          v.size = {g.size[0], g.size[0], g.size[0]};
          break;
        case GeomShape::Cylinder:
          v.shape = VisualDef::Cylinder;
          v.size = {g.size[0], g.size[1], 0};
          v.mask = 1u | 2u | 4u;  // jacket and flat ends
          break;
        case GeomShape::Capsule:
          v.shape = VisualDef::Cylinder;
          v.size = {g.size[0], g.size[1], 0};
          v.mask = 1u | 8u | 16u;  // jacket and round ends
          break;
        case GeomShape::Plane: {
          // An infinite plane n.p = d: a 40 m square of 1 m cells around the point nearest the
          // origin, catching the shadows when drawn alone. Seen only from the free side, so
          // that a wall or a sky does not hide what it bounds from a camera beyond it.
          const Vec3 n{g.plane[0], g.plane[1], g.plane[2]};
          v.shape = VisualDef::Plane;
          v.body = -1;
          v.pose.p = scale(n, g.plane[3]);
          const Vec3 z{0, 0, 1};
          const Vec3 axis = cross(z, n);
          const double s = norm(axis), c = dot(z, n);
          v.pose.q = s > 1e-12 ? quatAxisAngle(scale(axis, 1 / s), std::atan2(s, c))
                               : (c > 0 ? Quat{1, 0, 0, 0} : quatAxisAngle({1, 0, 0}, kPi));
          v.size = {40, 40, 0};
          v.max_cell = 1;
          v.shadow_plane = alone;
          v.one_sided = true;
          break;
        }
        case GeomShape::ConvexHull:
        case GeomShape::TriMesh:
          v.shape = VisualDef::Mesh;
          v.mesh = g.mesh;
          v.hull = g.shape == GeomShape::ConvexHull;
          break;
      }
      visuals_.push_back(v);
    }
  }

  bool loadTextures(Error* err) {
    textures_.assign(skins_.size(), Texture{});
    if (opts_.quality < Quality::Textures) return true;
    // Each file is read and uploaded once, however many skins name it (one GL texture each).
    TextureFiles files;
    for (size_t i = 0; i < skins_.size(); ++i) {
      const SkinDef& s = skins_[i];
      if (s.texture.empty()) continue;
      std::vector<std::string> tried;
      std::string found;
      for (const std::string& dir : {opts_.texture_folder, s.base_dir}) {
        if (dir.empty()) continue;
        for (const char* ext : {"", ".bmp", ".png"}) {
          const std::string p = (s.texture[0] == '/' ? "" : dir + "/") + s.texture + ext;
          if (found.empty() && isFile(p)) found = p;
        }
        tried.push_back(dir);
      }
      if (found.empty()) {
        err->kind = ErrorKind::MissingInput;
        std::string where;
        for (const std::string& d : tried) where += (where.empty() ? "" : " or ") + d;
        err->message = "texture '" + s.texture + "' of skin '" + s.key + "' not found in " + where +
                       " (TextureFolder of the global settings, then beside the scene)";
        return false;
      }
      Image img;
      size_t slot = 0;
      bool fresh = false;
      if (!files.load(found, &slot, &img, &fresh, err)) return false;
      if (!fresh) {
        textures_[i].id = texture_ids_[slot];
        continue;
      }
      GLuint id = 0;
      gl_.GenTextures(1, &id);
      gl_.BindTexture(GL_TEXTURE_2D, id);
      gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
      gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
      // GL's first row is t = 0, the bottom of the image: the rows go in bottom first, so that
      // t grows upwards in the picture and a face seen from its front shows the image upright.
      std::vector<uint8_t> rows(img.rgb.size());
      const size_t stride = static_cast<size_t>(img.width) * 3;
      for (int y = 0; y < img.height; ++y)
        std::copy_n(img.pixel(0, img.height - 1 - y), stride, rows.data() + stride * static_cast<size_t>(y));
      gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB, img.width, img.height, 0, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
      textures_[i].id = id;
      texture_ids_.push_back(id);  // slot `slot`: slots count distinct files from 0
    }
    return true;
  }

  const Model& model_;
  RenderOptions opts_;
  std::unique_ptr<render::GlContext> ctx_;
  const GlApi& gl_;
  const CameraDef* camera_ = nullptr;  ///< null: the default view
  std::vector<SkinDef> skins_;         ///< the model's, then those of the collision shapes
  std::vector<VisualDef> visuals_;     ///< what is drawn: the models and/or the collision shapes
  Transform default_eye_;
  Vec3 frame_lo_{0, 0, 0}, frame_hi_{0, 0, 0};  ///< what the default view has framed so far
  bool framed_ = false;
  double default_va_ = 60, default_near_ = 0.1, default_far_ = 1000;
  double spot_dist0_ = -1;
  bool track_init_ = false;
  Vec3 track_pos_{0, 0, 0};
  std::vector<double> rays_;         ///< sensor ray lengths for draw_sensors (setSensorRays)
  std::vector<Texture> textures_;    ///< per skin
  std::vector<GLuint> texture_ids_;  ///< per texture file (TextureFiles' slot): what the destructor deletes
  render::MeshLists meshes_;         ///< Model::meshes uploaded as display lists on first draw
  Error error_;
};

}  // namespace

bool parseQuality(const std::string& text, Quality* out) {
  const std::string t = lower(text);
  for (size_t i = 0; i < std::size(kQualityNames); ++i)
    if (t == kQualityNames[i]) {
      *out = static_cast<Quality>(i);
      return true;
    }
  return false;
}

const char* qualityName(Quality q) { return kQualityNames[static_cast<size_t>(q)]; }

bool parseGlBackend(const std::string& text, GlBackend* out) {
  const std::string t = lower(text);
  if (t == "egl")
    *out = GlBackend::Egl;
  else if (t == "osmesa")
    *out = GlBackend::OsMesa;
  else if (t == "auto" || t.empty())
    *out = GlBackend::Auto;
  else
    return false;
  return true;
}

std::vector<Transform> initialPoses(const Model& model) {
  std::vector<Transform> p;
  p.reserve(model.bodies.size());
  for (const BodyDef& b : model.bodies) p.push_back(b.pose);
  return p;
}

bool modelsShowNoBody(const Model& model) {
  bool any_geom = false;
  for (const GeomDef& g : model.geoms) any_geom |= !g.sensor;
  if (!any_geom) return false;
  if (model.visuals.empty()) return true;
  if (model.bodies.empty()) return false;
  for (const VisualDef& v : model.visuals)
    if (v.body >= 0) return false;
  return true;
}

Renderer::~Renderer() = default;

std::vector<std::string> textureFiles(const Model& model, const std::string& texture_folder) {
  std::vector<std::string> files;
  for (const SkinDef& s : model.skins) {
    if (s.texture.empty()) continue;
    for (const std::string& dir : {texture_folder, s.base_dir}) {
      if (dir.empty()) continue;
      for (const char* ext : {"", ".bmp", ".png"}) {
        const std::string p = (s.texture[0] == '/' ? "" : dir + "/") + s.texture + ext;
        std::error_code ec;
        if (std::filesystem::is_regular_file(p, ec)) files.push_back(p);
      }
    }
  }
  return files;
}

std::string drawFallbackNote(const Model& model, const RenderOptions& options) {
  if (options.draw_chosen || !modelsShowNoBody(model)) return "";
  return "no body has a model: drawing the collision shapes (--draw geoms; --draw models for the models alone)";
}

std::unique_ptr<Renderer> Renderer::create(const Model& model, const RenderOptions& opts, Error* err) {
  if (opts.width < 1 || opts.height < 1 || opts.width > kMaxImageSide || opts.height > kMaxImageSide) {
    err->kind = ErrorKind::InvalidInput;
    err->message = "image size must be 1 to " + std::to_string(kMaxImageSide) + " pixels per side";
    return nullptr;
  }
  std::unique_ptr<render::GlContext> ctx = render::createContext(opts.backend, opts.width, opts.height, err);
  if (!ctx) return nullptr;
  RenderOptions o = opts;
  if (!o.draw_chosen && modelsShowNoBody(model)) {
    o.draw_models = false;
    o.draw_geoms = true;
  }
  auto r = std::make_unique<GlRenderer>(model, o, std::move(ctx));
  if (!r->init(err)) return nullptr;
  return r;
}

}  // namespace simbob
