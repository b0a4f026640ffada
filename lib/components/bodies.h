// Kinds of BodyComponents, shared by bodies.cpp (rigid bodies, rods, constructions) and
// clones.cpp (imported and cloned bodies) and urdf_import.cpp (RCImportURDF and its links).
#pragma once

namespace simbob {

enum class BodyKind { StaticRigid, MobileRigid, Rod, Construction, Import, Clone, Urdf, UrdfLink };

}  // namespace simbob
