// Struct types: SceneSettings (chapter 5.2 / 3.3.4 plus the physics settings of 7.2),
// FogSettings, the scene root (Simulation) and the global settings INI (3.3.1).
#include <algorithm>

#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

enum class StructKind { SceneSettings, FogSettings, GlobalSettings, Simulation };

const EnumTable kFogMode{"FogMode", {{"Off", 0}, {"Linear", 1}, {"Exponential", 2}, {"Exponential2", 3}}};
const EnumTable kSolver{"Solver", {{"QuickStep", 0}, {"Step", 1}}};
const EnumTable kSpace{"Space", {{"Hash", 0}, {"SweepAndPrune", 1}, {"QuadTree", 2}, {"Simple", 3}}};

// FogSettings
constexpr EnumParam kMode{"Mode"};
constexpr ValueParam<double> kDensity{"Density"};
constexpr ValueParam<double> kStart{"Start"};
constexpr ValueParam<double> kEnd{"End"};
constexpr ValueParam<Color> kColor{"Color"};
// SceneSettings
constexpr ValueParam<Triple> kGravity{"Gravity"};
constexpr ValueParam<double> kMaxTimeStep{"MaxTimeStep"};
constexpr ValueParam<double> kMinTimeStep{"MinTimeStep"};
constexpr ValueParam<double> kMaxAccessTime{"MaxAccessTime"};
constexpr EnumParam kSolverParam{"Solver"};
constexpr ValueParam<int64_t> kSolverIterations{"SolverIterations"};
constexpr ValueParam<double> kERP{"ERP"};
constexpr ValueParam<double> kCFM{"CFM"};
constexpr ValueParam<int64_t> kMaxContacts{"MaxContacts"};
constexpr EnumParam kSpaceParam{"Space"};
constexpr ValueParam<bool> kAutoDisable{"AutoDisable"};
constexpr ValueParam<Vector4> kLightPos{"LightPos"};
constexpr ValueParam<Color> kLightColor{"LightColor"};
constexpr ValueParam<Color> kClearColor{"ClearColor"};
constexpr ValueParam<double> kShadowIntensity{"ShadowIntensity"};
constexpr LinkParam kFogSettings{"FogSettings"};

constexpr int64_t kMaxSolverIterations = 100000;
constexpr int64_t kMaxContactsLimit = 64;

}  // namespace

void registerSettings(Registry& r) {
  r.add({"FogSettings",
         Family::Struct,
         int(StructKind::FogSettings),
         {enumParam(kMode, ValueType::Enum, &kFogMode, 0, "blending formula (Off, Linear, Exponential, Exponential2)"),
          number(kDensity, 0.01, "1/m", "density in the exponential formulas", Range::NonNegative),
          number(kStart, 10, "m", "start distance of linear fog", Range::NonNegative),
          number(kEnd, 100, "m", "end distance of linear fog", Range::NonNegative),
          color(kColor, rgba(0.5, 0.5, 0.5), "fog colour")},
         {},
         "Fog of the rendered views (guide 3.3.4)."});

  TypeSpec scene_settings(
      {"SceneSettings",
       Family::Struct,
       int(StructKind::SceneSettings),
       {triple(kGravity, {0, -9.81, 0}, "m/s^2", "gravity; Y is up"),
        number(kMaxTimeStep, 0.001, "s", "the step size: the physics advances in whole steps of it (--dt overrides)",
               Range::Positive),
        number(kMinTimeStep, 1e-6, "s", "a request this close after a step instant is served at it, not at the next",
               Range::Positive),
        number(kMaxAccessTime, 1.0, "s",
               "wall-clock limit of one access to the simulation (a grant to a controller or peer); past it the run "
               "stops (exit 69)",
               Range::Positive),
        enumParam(kSolverParam, ValueType::Enum, &kSolver, 0, "QuickStep (iterative) or Step (exact LCP)"),
        integer(kSolverIterations, 20, "QuickStep iterations per step", Range::Positive),
        number(kERP, 0.2, "", "error reduction parameter of joints and contacts", Range::Unit),
        number(kCFM, 1e-10, "", "constraint force mixing (softness)", Range::NonNegative),
        integer(kMaxContacts, 4, "contact points per colliding pair of geoms", Range::Positive),
        enumParam(kSpaceParam, ValueType::Enum, &kSpace, 0,
                  "collision space: Hash, SweepAndPrune, QuadTree, Simple (--space)"),
        flag(kAutoDisable, false, "let ODE put resting bodies to sleep (--auto-disable)"),
        valueParam(kLightPos, ValueType::Vector, Vector4{{10, 10, 10, 1}}, "m", "light position"),
        color(kLightColor, rgba(1, 1, 1), "light colour"), color(kClearColor, rgba(0.3, 0.3, 0.5), "background colour"),
        number(kShadowIntensity, 0.5, "", "intensity of projected shadows", Range::Unit),
        structParam(kFogSettings, "FogSettings", "fog")},
       {},
       "Scene and physics settings (guide 3.3.4, 5.2, 7.2)."});
  // Threads never changed a result and paid only where the narrow phase dominates a step: a
  // property of the machine a run is on, not of the scene (2026-12-06).
  scene_settings.retired = {{"Threads",
                             "the thread count is no scene setting since 2026-12-06: give `--threads N` "
                             "to the command (the same bytes for every count)"}};
  r.add(std::move(scene_settings));

  r.add(
      {"Simulation",
       Family::Struct,
       int(StructKind::Simulation),
       {listParam(kCameraListParam, {Family::Camera}, "cameras of the views"),
        structParam(kSceneSettingsParam, "SceneSettings", "scene and physics settings"),
        listParam(kComponentListParam, {Family::Body, Family::GlobalSim, Family::Material, Family::Skin, Family::Model},
                  "the simulated components")},
       {},
       "Root of a scene file (guide chapter 5)."});

  r.add({"GlobalSettings",
         Family::Struct,
         int(StructKind::GlobalSettings),
         {flag(kDocumentIniParam, false, "read camera settings from an INI beside the scene"),
          text(kLogFileParam, "", "also write log messages to this file"),
          text(kDocumentFolderParam, "", "initial folder of file dialogs (unused headless)"),
          text(kExtensionFolderParam, "", "folder of extension plug-ins"),
          text(kTextureFolderParam, "", "folder of texture images")},
         {},
         "Global settings INI, --settings FILE (guide 3.3.1)."});
}

void lowerSettings(CompileContext& ctx, int comp) {
  SolverSettings& s = ctx.model.settings;
  if (comp < 0) return;
  const Component& c = ctx.at(comp);
  const Triple& g = c.get(kGravity);
  s.gravity = {g[0], g[1], g[2]};
  s.max_time_step = c.get(kMaxTimeStep);
  s.min_time_step = c.get(kMinTimeStep);
  s.max_access_time = c.get(kMaxAccessTime);
  s.quickstep = c.get(kSolverParam) == 0;
  if (c.get(kSolverIterations) > kMaxSolverIterations || c.get(kMaxContacts) > kMaxContactsLimit)
    ctx.diag.error(c.loc, "SceneSettings: SolverIterations must be at most 100000 and MaxContacts at most 64");
  s.iterations = static_cast<int>(std::min(c.get(kSolverIterations), kMaxSolverIterations));
  s.erp = c.get(kERP);
  s.cfm = c.get(kCFM);
  s.max_contacts = static_cast<int>(std::min(c.get(kMaxContacts), kMaxContactsLimit));
  s.space = static_cast<SpaceKind>(c.get(kSpaceParam));
  s.auto_disable = c.get(kAutoDisable);
  if (s.min_time_step > s.max_time_step)
    ctx.diag.error(c.slotOf(kMinTimeStep).loc, "SceneSettings: MinTimeStep must not exceed MaxTimeStep");
  // The look of the views (guide 3.3.4); an invalid colour keeps the default.
  ViewSettings& v = ctx.model.view;
  v.light_pos = c.get(kLightPos).v;
  if (c.get(kLightColor).valid) v.light_color = c.get(kLightColor).rgba;
  if (c.get(kClearColor).valid) v.clear_color = c.get(kClearColor).rgba;
  v.shadow_intensity = c.get(kShadowIntensity);
  const Link& fl = c.get(kFogSettings);
  if (fl.comp >= 0) {
    const Component& f = ctx.at(fl.comp);
    v.fog = static_cast<ViewSettings::Fog>(f.get(kMode));
    v.fog_density = f.get(kDensity);
    v.fog_start = f.get(kStart);
    v.fog_end = f.get(kEnd);
    if (f.get(kColor).valid) v.fog_color = f.get(kColor).rgba;
    if (v.fog == ViewSettings::Linear && !(v.fog_end > v.fog_start))
      ctx.diag.error(f.slotOf(kEnd).loc.line ? f.slotOf(kEnd).loc : f.loc,
                     "FogSettings: End must be beyond Start for linear fog");
  }
}

bool readGlobalSettings(const std::string& path, const Registry& reg, GlobalSettings* out, Diagnostics& diag) {
  Scene holder;
  int comp = -1;
  if (!loadStructIni(path, reg, "GlobalSettings", &holder, &comp, diag)) return false;
  const Component& c = holder.at(comp);
  out->log_file = c.get(kLogFileParam);
  out->extension_folder = c.get(kExtensionFolderParam);
  out->texture_folder = c.get(kTextureFolderParam);
  out->document_ini = c.get(kDocumentIniParam);
  return true;
}

}  // namespace simbob
