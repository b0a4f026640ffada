// Tessellation of the model primitives (guide 6.3) into GL immediate-mode calls, in the
// visual's own frame: normals for lighting, texture coordinates for skins with textures.
#pragma once

#include "render/gl_api.h"
#include "simbob/visuals.h"

namespace simbob::render {

/// Draws the surface of `v` (Cuboid sides per SideMask, Plane cells, Ellipsoid, Cylinder parts
/// per ComponentMask, Cone with its base).
void drawShape(const GlApi& gl, const VisualDef& v);
/// Draws the twelve edges of the local bounding box of `v` (quality level Frame).
void drawBoundingBox(const GlApi& gl, const VisualDef& v);

}  // namespace simbob::render
