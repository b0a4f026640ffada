// SkinComponents (guide 6.4): appearance only; kept for the renderer.
#include "compile/context.h"
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

int lowerSkin(CompileContext& ctx, const Link& l) {
  if (l.comp < 0) return 0;
  auto it = ctx.skin_index.find(l.comp);
  if (it != ctx.skin_index.end()) return it->second;
  const Component& c = ctx.at(l.comp);
  SkinDef d;
  d.key = c.qkey;
  d.type = c.type->name;
  d.loc = c.loc;
  const auto kind = static_cast<SkinKind>(c.type->kind);
  d.colored = kind != SkinKind::Textured;
  if (d.colored) {
    // Guide 6.4.1: what is left out follows from Color.
    const Rgba base = c.get(kColor).valid ? c.get(kColor).rgba : Rgba{0.8, 0.8, 0.8, 1};
    auto times = [&](double k) { return Rgba{base[0] * k, base[1] * k, base[2] * k, base[3]}; };
    auto pick = [](const Color& col, const Rgba& dflt) { return col.valid ? col.rgba : dflt; };
    d.color = base;
    d.ambient = pick(c.get(kAmbient), times(0.5));
    d.diffuse = pick(c.get(kDiffuse), times(0.5));
    d.specular = pick(c.get(kSpecular), times(2.0));
    d.emission = pick(c.get(kEmission), Rgba{0, 0, 0, base[3]});
  } else {
    // A texture alone: lit white, so the texture shows its own colours.
    d.color = {1, 1, 1, 1};
    d.ambient = {0.5, 0.5, 0.5, 1};
    d.diffuse = {0.5, 0.5, 0.5, 1};
    d.specular = {0, 0, 0, 1};
  }
  if (kind != SkinKind::Colored) {
    d.texture = c.get(kTexture);
    const std::string& f = c.loc.file.str();
    size_t slash = f.find_last_of('/');
    d.base_dir = slash == std::string::npos ? "." : f.substr(0, slash);
  }
  d.shininess = c.get(kShininess);
  d.mode = static_cast<SkinDef::Mode>(c.get(kColorModeParam));
  int index = static_cast<int>(ctx.model.skins.size());
  ctx.model.skins.push_back(std::move(d));
  ctx.skin_index[l.comp] = index;
  return index;
}

}  // namespace simbob
