// Kinds of BodyComponents, shared by bodies.cpp (rigid bodies, rods, constructions) and
// clones.cpp (imported and cloned bodies).
#pragma once

namespace simbob {

enum class BodyKind { StaticRigid, MobileRigid, Rod, Construction, Import, Clone };

}  // namespace simbob
