// SkinComponents (guide 6.4): appearance only; kept for the renderer.
#include "components/families.h"

namespace simbob {

static const EnumTable kColorMode{
    "ColorMode",
    {{"Color", 0}, {"Shading", 1}, {"TransparentColor", 2}, {"TransparentLighting", 3}, {"TransparentLighing", 3}}};

static std::vector<ParamSpec> coloredParams() {
  return {color("Color", rgba(0.8, 0.8, 0.8), "base colour"),
          color("Ambient", noColor(), "ambient reflection (invalid = Color/2)"),
          color("Diffuse", noColor(), "diffuse reflection (invalid = Color/2)"),
          color("Specular", noColor(), "specular reflection (invalid = 2*Color)"),
          color("Emission", noColor(), "emitted light (invalid = black)")};
}

static std::vector<ParamSpec> commonParams() {
  return {
      enumParam("ColorMode", ValueType::Enum, &kColorMode, 1, "Color, Shading, TransparentColor, TransparentLighting"),
      number("Shininess", 0.0, "", "specular exponent", Range::NonNegative)};
}

static std::vector<ParamSpec> concat(std::vector<ParamSpec> a, const std::vector<ParamSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

void registerSkins(Registry& r) {
  const ParamSpec texture = text("Texture", "", "image file name in the TextureFolder");
  r.add({"RCColoredSkin",
         Family::Skin,
         int(SkinKind::Colored),
         concat(coloredParams(), commonParams()),
         {},
         "A coloured surface."});
  r.add({"RCTexturedSkin",
         Family::Skin,
         int(SkinKind::Textured),
         concat({texture}, commonParams()),
         {},
         "A textured surface."});
  r.add({"RCColTexSkin",
         Family::Skin,
         int(SkinKind::ColTex),
         concat(concat(coloredParams(), {texture}), commonParams()),
         {},
         "Base colour blended with a texture."});
}

}  // namespace simbob
