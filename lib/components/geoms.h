// Kinds of GeomComponents, shared by geoms.cpp (primitive shapes) and model_geoms.cpp (shapes
// derived from a body's model).
#pragma once

namespace simbob {

enum class GeomKind { Transform, Cuboid, Plane, Sphere, Cylinder, CappedCylinder, ModelMatch, ModelWrap, Empty, Mesh };

}  // namespace simbob
