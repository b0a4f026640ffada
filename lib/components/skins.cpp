// SkinComponents (guide 6.4): appearance only; kept for the renderer.
#include "components/families.h"

namespace simbob {

namespace {

enum class SkinKind { Colored, Textured, ColTex };

constexpr ValueParam<Color> kColor{"Color"};
constexpr ValueParam<Color> kAmbient{"Ambient"};
constexpr ValueParam<Color> kDiffuse{"Diffuse"};
constexpr ValueParam<Color> kSpecular{"Specular"};
constexpr ValueParam<Color> kEmission{"Emission"};
constexpr EnumParam kColorModeParam{"ColorMode"};
constexpr ValueParam<double> kShininess{"Shininess"};
constexpr ValueParam<std::string> kTexture{"Texture"};

const EnumTable kColorMode{
    "ColorMode",
    {{"Color", 0}, {"Shading", 1}, {"TransparentColor", 2}, {"TransparentLighting", 3}, {"TransparentLighing", 3}}};

std::vector<ParamSpec> coloredParams() {
  return {color(kColor, rgba(0.8, 0.8, 0.8), "base colour"),
          color(kAmbient, noColor(), "ambient reflection (invalid = Color/2)"),
          color(kDiffuse, noColor(), "diffuse reflection (invalid = Color/2)"),
          color(kSpecular, noColor(), "specular reflection (invalid = 2*Color)"),
          color(kEmission, noColor(), "emitted light (invalid = black)")};
}

std::vector<ParamSpec> commonParams() {
  return {enumParam(kColorModeParam, ValueType::Enum, &kColorMode, 1,
                    "Color, Shading, TransparentColor, TransparentLighting"),
          number(kShininess, 0.0, "", "specular exponent", Range::NonNegative)};
}

std::vector<ParamSpec> concat(std::vector<ParamSpec> a, const std::vector<ParamSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

void registerSkins(Registry& r) {
  const ParamSpec texture = text(kTexture, "", "image file name in the TextureFolder");
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
