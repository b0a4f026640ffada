// What the renderer draws (issue #12): the compiled visuals of a scene as plain data — models
// (guide 6.3) at body-relative or global poses, skins (6.4), cameras (3.5) and the look settings
// of SceneSettings (3.3.4). The physics never reads them. Nothing here includes GL.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/frames.h"

namespace simbob {

using Rgba = std::array<double, 4>;

/// Which GL implementation renders: Auto tries EGL (surfaceless, then device platform), then
/// OSMesa.
enum class GlBackend { Auto, Egl, OsMesa };

/// A surface's appearance (RCColoredSkin, RCTexturedSkin, RCColTexSkin).
struct SkinDef {
  std::string key;                  ///< fully qualified key of the skin ("" = the default skin)
  Rgba color{0.8, 0.8, 0.8, 1};     ///< base colour: unlit modes and the default of the others
  Rgba ambient{0.4, 0.4, 0.4, 1};   ///< Ambient, or Color/2 (guide 6.4.1)
  Rgba diffuse{0.4, 0.4, 0.4, 1};   ///< Diffuse, or Color/2
  Rgba specular{1.0, 1.0, 1.0, 1};  ///< Specular, or 2*Color (clamped to 1 by GL)
  Rgba emission{0, 0, 0, 1};        ///< Emission, or black
  double shininess = 0;             ///< specular exponent (GL clamps to 128)
  enum Mode : uint8_t { Color, Shading, TransparentColor, TransparentLighting } mode = Shading;
  bool colored = true;   ///< has a base colour (RCColoredSkin, RCColTexSkin)
  std::string texture;   ///< Texture as written ("" = none)
  std::string base_dir;  ///< directory of the file the skin is written in (textures beside the scene)
  std::string type;      ///< RCColoredSkin, RCTexturedSkin, RCColTexSkin (for messages)
  SourceLoc loc;         ///< where it is written
};

/// One visible primitive: a model of the tree of a body (or a ground, sky, sandbox wall, rod).
struct VisualDef {
  enum Shape : uint8_t {
    Cuboid,     ///< box from corner a to corner b (local), SideMask, Wire
    Plane,      ///< rectangle in the local XY plane, normal +Z, size = ExtensionX, ExtensionY
    Ellipsoid,  ///< radii = size
    Cylinder,   ///< along local Z, centred (z in [-L/2, L/2]); size = radius, length
    Cone,       ///< base at z = 0, apex at z = Length; size = radius, length
    Mesh,       ///< the triangles of Model::meshes[mesh] (m, the mesh's own frame); size unused
  } shape = Cuboid;
  int body = -1;             ///< Model::bodies index; -1 = static: `pose` is global
  Transform pose;            ///< relative to the body frame, or global when body == -1
  Vec3 a{-0.5, -0.5, -0.5};  ///< Cuboid corners (local)
  Vec3 b{0.5, 0.5, 0.5};
  Vec3 size{1, 1, 1};  ///< see Shape (m)
  int skin = 0;        ///< Model::skins index ([0] is the default skin)
  uint32_t mask = 63;  ///< Cuboid SideMask (1 -X, 2 +X, 4 -Y, 8 +Y, 16 -Z, 32 +Z); Cylinder ComponentMask
                       ///< (1 jacket, 2 flat front +Z, 4 flat back -Z, 8 capped front, 16 capped back); Cone 1 = base
  bool wire = false;   ///< always a wire frame (a Cuboid's Wire; collision shapes over models)
  bool triangles = false;     ///< Ellipsoid: subdivided icosahedron instead of quads
  int accuracy = 2;           ///< tessellation level (guide 6.3.3)
  bool shadow_plane = false;  ///< Plane: shadows are projected onto it
  bool one_sided = false;     ///< drawn only where its front faces the eye (collision planes)
  double tex_scale = 1;       ///< texture repeats per metre (negative: per extension)
  double tex_scale2 = 1;      ///< Cylinder: LinTexScale (tex_scale is AngTexScale)
  double max_cell = -1;       ///< Plane: largest cell, m (negative: one cell)
  int mesh = -1;              ///< Mesh: index into Model::meshes
  bool hull = false;          ///< Mesh: draw the mesh's convex hull (a hull collision shape), not its triangles
  std::string key;            ///< owner's qualified key (for messages)
};

/// A camera of the CameraList (guide 3.5). A camera looks along its local -Z axis, +Y up.
struct CameraDef {
  std::string key;  ///< fully qualified key
  enum Kind : uint8_t { Static, Mounted, Spotlight, Tracking } kind = Static;
  Transform pose;                ///< Static/Spotlight: global (Spotlight: position only); Mounted: relative to body
  int body = -1;                 ///< Model::bodies index followed (Mounted, Spotlight, Tracking); -1 = static
  Vec3 target{0, 0, 0};          ///< a static body's position (Spotlight/Tracking on a static body)
  double view_angle = 60;        ///< deg, horizontal field of view
  double near_clip = 0.1;        ///< m
  double far_clip = 1000;        ///< m
  bool auto_view_angle = false;  ///< Spotlight: keep the body's apparent size
  double distance = 5;           ///< Tracking: m kept from the body
};

/// The look of the views: SceneSettings of guide 3.3.4.
struct ViewSettings {
  std::array<double, 4> light_pos{10, 10, 10, 1};  ///< m (w = 0: a direction)
  Rgba light_color{1, 1, 1, 1};
  Rgba clear_color{0.3, 0.3, 0.5, 1};
  double shadow_intensity = 0.5;  ///< 0 = no darkening, 1 = black shadows
  enum Fog : uint8_t { Off, Linear, Exponential, Exponential2 } fog = Off;
  double fog_density = 0.01;  ///< 1/m
  double fog_start = 10;      ///< m
  double fog_end = 100;       ///< m
  Rgba fog_color{0.5, 0.5, 0.5, 1};
};

}  // namespace simbob
