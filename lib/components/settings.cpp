// Struct types: SceneSettings (chapter 5.2 / 3.3.4 plus the physics settings of 7.2),
// FogSettings, and the global settings INI (3.3.1).
#include "components/families.h"

namespace simbob {

static const EnumTable kFogMode{"FogMode", {{"Off", 0}, {"Linear", 1}, {"Exponential", 2}, {"Exponential2", 3}}};
static const EnumTable kSolver{"Solver", {{"QuickStep", 0}, {"Step", 1}}};
static const EnumTable kSpace{"Space", {{"Hash", 0}, {"SweepAndPrune", 1}, {"QuadTree", 2}, {"Simple", 3}}};

void registerSettings(Registry& r) {
  r.add({"FogSettings",
         Family::Struct,
         int(StructKind::FogSettings),
         {enumParam("Mode", ValueType::Enum, &kFogMode, 0, "blending formula (Off, Linear, Exponential, Exponential2)"),
          number("Density", 0.01, "1/m", "density in the exponential formulas", Range::NonNegative),
          number("Start", 10, "m", "start distance of linear fog", Range::NonNegative),
          number("End", 100, "m", "end distance of linear fog", Range::NonNegative),
          color("Color", rgba(0.5, 0.5, 0.5), "fog colour")},
         {},
         "Fog of the rendered views (guide 3.3.4)."});

  r.add(
      {"SceneSettings",
       Family::Struct,
       int(StructKind::SceneSettings),
       {triple("Gravity", {0, -9.81, 0}, "m/s^2", "gravity; Y is up"),
        number("MaxTimeStep", 0.001, "s", "largest physics step; the step size (--dt overrides)", Range::Positive),
        number("MinTimeStep", 1e-6, "s", "a requested time this close to the clock counts as reached", Range::Positive),
        number("MaxAccessTime", 1.0, "s", "wall-clock limit of one access to the simulation (no effect in batch runs)",
               Range::Positive),
        enumParam("Solver", ValueType::Enum, &kSolver, 0, "QuickStep (iterative) or Step (exact LCP)"),
        integer("SolverIterations", 20, "QuickStep iterations per step", Range::Positive),
        number("ERP", 0.2, "", "error reduction parameter of joints and contacts", Range::Unit),
        number("CFM", 1e-10, "", "constraint force mixing (softness)", Range::NonNegative),
        integer("MaxContacts", 4, "contact points per colliding pair of geoms", Range::Positive),
        enumParam("Space", ValueType::Enum, &kSpace, 0,
                  "collision space: Hash, SweepAndPrune, QuadTree, Simple (--space)"),
        flag("AutoDisable", false, "let ODE put resting bodies to sleep (--auto-disable)"),
        valueParam("LightPos", ValueType::Vector, Vector4{{10, 10, 10, 1}}, "m", "light position"),
        color("LightColor", rgba(1, 1, 1), "light colour"),
        color("ClearColor", rgba(0.3, 0.3, 0.5), "background colour"),
        number("ShadowIntensity", 0.5, "", "intensity of projected shadows", Range::Unit),
        structParam("FogSettings", "FogSettings", "fog")},
       {},
       "Scene and physics settings (guide 3.3.4, 5.2, 7.2)."});

  r.add({"Simulation",
         Family::Struct,
         int(StructKind::Simulation),
         {listParam("CameraList", {Family::Camera}, "cameras of the views"),
          structParam("SceneSettings", "SceneSettings", "scene and physics settings"),
          listParam("ComponentList", {Family::Body, Family::GlobalSim, Family::Material, Family::Skin, Family::Model},
                    "the simulated components")},
         {},
         "Root of a scene file (guide chapter 5)."});

  r.add({"GlobalSettings",
         Family::Struct,
         int(StructKind::GlobalSettings),
         {flag("DocumentIni", false, "read camera settings from an INI beside the scene"),
          text("LogFile", "", "also write log messages to this file"),
          text("DocumentFolder", "", "initial folder of file dialogs (unused headless)"),
          text("ExtensionFolder", "", "folder of extension plug-ins"),
          text("TextureFolder", "", "folder of texture images")},
         {},
         "Global settings INI, --settings FILE (guide 3.3.1)."});
}

}  // namespace simbob
