// Plug-in types through the C ABI (simbob/plugin_c.h, lib/components/plugin_types.cpp):
// registerPlugin refuses incomplete descriptions with the reason, and a scene using a plug-in's
// sensor, actuator and controller compiles to SensorKind::Plugin, ActuatorDef::Plugin and
// ControllerDef::Plugin with their numbers, poses and refs.
#include <catch2/catch.hpp>

#include <string>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/plugin.h"
#include "simbob/registry.h"

using namespace simbob;

namespace {

void* create(const double*, char*) {
  static int instance;
  return &instance;
}
int act(void*, const SimbobHost*, double, char*) { return 0; }
int read(void*, const SimbobHost*, double, double* out, int, char*) {
  out[0] = 0;
  return 0;
}
int apply(void*, const SimbobHost*, double, double, double, double*, double*, char*) { return 0; }

const SimbobNumber kRangeNumbers[] = {{"MinRange", 0.1, "m", ""}, {"MaxRange", 2.0, "m", ""}, {"Gain", 3.0, "", ""}};
const SimbobNumber kMinOnly[] = {{"MinRange", 0.1, "m", ""}};
const char* const kQuantities[] = {"distance"};
const SimbobRef kRefs[] = {{"Drive", "RCDriver", ""}, {"Eye", "RCRangeSensor", ""}, {"Hull", "RCBody", ""}};

SimbobType sensorType(const char* name, const SimbobNumber* numbers, int count, const char* interface) {
  SimbobType t{};
  t.kind = SIMBOB_SENSOR;
  t.name = name;
  t.numbers = numbers;
  t.number_count = count;
  t.quantities = kQuantities;
  t.quantity_count = 1;
  t.interface = interface;
  t.create = create;
  t.read = read;
  return t;
}

std::string errorsOf(const Diagnostics& d) {
  std::string out;
  for (const Error& e : d.errors()) out += e.str() + "\n";
  return out;
}

std::string registerOne(Registry& r, const SimbobType& t) {
  static SimbobType kept[16];  // the registry keeps pointers into the description
  static int used = 0;
  kept[used] = t;
  const SimbobPlugin p{SIMBOB_PLUGIN_ABI_VERSION, "test", &kept[used++], 1};
  return registerPlugin(r, p);
}

const char* const kScene = R"(<Simulation><ComponentList>
  <RCRobot Key="Bot"><Construction><RCConstruction Key="Cart">
    <Body><RCMobileRigidBody Key="Box">
      <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom/></Geom><Inertia><RCInertiaByGeom><Mass Value="2"/></RCInertiaByGeom></Inertia>
    </RCMobileRigidBody></Body>
    <ChildList>
      <PJet Key="Jet"><Pose><RCLocalCoordinates><Pose Value="0.5 0 0 0 0 0"/></RCLocalCoordinates></Pose><Force Value="4"/></PJet>
      <PEye Key="Eye"><MaxRange Value="3"/><Period Value="0.1"/></PEye>
      <RCImuSensor Key="Imu"/>
    </ChildList>
  </RCConstruction></Construction>
  <ControllerList><PCtl Key="Ctl"><Drive Ref="Bot.Cart.Jet"/><Eye Ref="Bot.Cart.Eye"/><Hull Ref="Bot.Cart.Box"/><Period Value="0.02"/></PCtl></ControllerList>
  </RCRobot>
</ComponentList></Simulation>)";

}  // namespace

TEST_CASE("plugin types: incomplete descriptions are refused with the reason", "[scene][plugins]") {
  Registry r;
  REQUIRE(registerBuiltins(r));
  SimbobType no_read = sensorType("NoRead", nullptr, 0, nullptr);
  no_read.read = nullptr;
  CHECK(registerOne(r, no_read) == "type 'NoRead': a sensor needs read");
  CHECK(registerOne(r, sensorType("NoMax", kMinOnly, 1, "RCRangeSensor")) ==
        "type 'NoMax': an RCRangeSensor needs the number MaxRange");
  SimbobType no_quantities = sensorType("NoQ", nullptr, 0, nullptr);
  no_quantities.quantity_count = 0;
  CHECK(registerOne(r, no_quantities) == "type 'NoQ': a sensor needs at least one quantity");
  SimbobType bad_kind = sensorType("Odd", nullptr, 0, nullptr);
  bad_kind.kind = 7;
  CHECK(registerOne(r, bad_kind) == "type 'Odd': kind 7 is none of SIMBOB_CONTROLLER, SIMBOB_SENSOR, SIMBOB_ACTUATOR");
  SimbobType ctl{};
  ctl.kind = SIMBOB_CONTROLLER;
  ctl.name = "NoAct";
  CHECK(registerOne(r, ctl) == "type 'NoAct': a controller needs act");
  CHECK(registerOne(r, sensorType("RCRangeSensor", nullptr, 0, nullptr)) ==
        "component type 'RCRangeSensor': the name 'RCRangeSensor' is already registered");
  CHECK(r.find("NoRead") == nullptr);
}

TEST_CASE("plugin types: a plug-in's sensor, actuator and controller compile to the model", "[scene][plugins]") {
  Registry r;
  REQUIRE(registerBuiltins(r));
  REQUIRE(registerOne(r, sensorType("PEye", kRangeNumbers, 3, "RCRangeSensor")).empty());
  SimbobType jet{};
  jet.kind = SIMBOB_ACTUATOR;
  jet.name = "PJet";
  static const SimbobNumber kForce[] = {{"Force", 1.0, "N", ""}};
  jet.numbers = kForce;
  jet.number_count = 1;
  jet.apply = apply;
  REQUIRE(registerOne(r, jet).empty());
  SimbobType ctl{};
  ctl.kind = SIMBOB_CONTROLLER;
  ctl.name = "PCtl";
  ctl.refs = kRefs;
  ctl.ref_count = 3;
  ctl.act = act;
  REQUIRE(registerOne(r, ctl).empty());
  CHECK(r.find("PJet")->implements("RCDriver"));  // an actuator without an interface is an RCDriver
  CHECK(r.find("PEye")->implements("RCRangeSensor"));

  Scene s;
  Diagnostics d;
  REQUIRE(loadSceneFromText(kScene, "p.xml", Format::Xml, r, &s, d));
  Model m;
  const bool ok = compileScene(s, &m, d);
  INFO(errorsOf(d));
  REQUIRE(ok);
  REQUIRE(m.sensors.size() == 2);
  const SensorDef& eye = m.sensors[0];
  CHECK(eye.kind == SensorKind::Plugin);
  CHECK(eye.body == 0);
  CHECK(eye.numbers == std::vector<double>{0.1, 3.0, 3.0});
  CHECK(eye.min_range == 0.1);  // what RCObstacleAvoider reads of an RCRangeSensor
  CHECK(eye.max_range == 3.0);
  CHECK(eye.period == 0.1);
  CHECK(sensorQuantities(eye) == std::vector<std::string>{"distance"});
  CHECK(eye.plugin_who == "plug-in 'test', type 'PEye'");
  REQUIRE(m.actuators.size() == 1);
  const ActuatorDef& a = m.actuators[0];
  CHECK(a.kind == ActuatorDef::Plugin);
  CHECK(a.body == 0);
  CHECK(a.joint == -1);
  CHECK(a.pose.p == Vec3{0.5, 0, 0});
  CHECK(a.numbers == std::vector<double>{4.0});
  REQUIRE(m.controllers.size() == 1);
  REQUIRE(m.controllers[0].kind() == ControllerDef::Plugin);
  const PluginControllerDef& c = m.controllers[0].as<PluginControllerDef>();
  CHECK(c.period == 0.02);
  CHECK(c.refs == std::vector<int>{0, 0, 0});  // actuator 0, sensor 0, body 0
  CHECK(c.ref_kind == std::vector<uint8_t>{0, 1, 2});
}

TEST_CASE("plugin types: a controller's ref must offer its interface", "[scene][plugins]") {
  Registry r;
  REQUIRE(registerBuiltins(r));
  REQUIRE(registerOne(r, sensorType("PEye", kRangeNumbers, 3, "RCRangeSensor")).empty());
  SimbobType jet{};
  jet.kind = SIMBOB_ACTUATOR;
  jet.name = "PJet";
  static const SimbobNumber kForce[] = {{"Force", 1.0, "N", ""}};
  jet.numbers = kForce;
  jet.number_count = 1;
  jet.apply = apply;
  REQUIRE(registerOne(r, jet).empty());
  SimbobType ctl{};
  ctl.kind = SIMBOB_CONTROLLER;
  ctl.name = "PCtl";
  ctl.refs = kRefs;
  ctl.ref_count = 3;
  ctl.act = act;
  REQUIRE(registerOne(r, ctl).empty());
  std::string text = kScene;
  text.replace(text.find("<Eye Ref=\"Bot.Cart.Eye\"/>"), 25, "<Eye Ref=\"Bot.Cart.Imu\"/>");
  Scene s;
  Diagnostics d;
  const bool loaded = loadSceneFromText(text, "p.xml", Format::Xml, r, &s, d);
  INFO(errorsOf(d));
  REQUIRE(loaded);
  Model m;
  CHECK_FALSE(compileScene(s, &m, d));
  REQUIRE(!d.errors().empty());
  CHECK(d.errors()[0].message ==
        "PCtl 'Bot.Ctl': parameter 'Eye' must refer to a component implementing RCRangeSensor, but RCImuSensor "
        "'Bot.Cart.Imu' does not");
}
