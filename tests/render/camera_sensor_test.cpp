// Camera sensors (RCCameraSensor, lib/simulation/camera_sensors.cpp): the image a Simulation
// holds at t is, byte for byte, what the renderer of `simbob render --camera KEY --size WxH
// --at t` draws at the poses of t (one renderer, the same poses: no tolerance); it is held
// between Period instants; and the physics does not see the camera (bit-identical poses).
#include <catch2/catch.hpp>
#include <memory>
#include <string>
#include <vector>

#include "render/reference_frames.h"
#include "simbob/physics.h"
#include "simbob/renderer.h"
#include "simbob/simulation.h"
#include "test_registry.h"

using namespace simbob;
using namespace simbob::test;

namespace {

// A box falls 1 m towards the ground with a camera on it looking along -Z at two walls; the
// scene has no models, so it is drawn as collision shapes, as `simbob render` draws it.
std::string scene(bool with_camera) {
  const std::string camera = R"(
      <ChildList>
        <RCCameraSensor Key="Eye">
          <Pose><RCLocalCoordinates><Pose Value="0 0.1 0 -10 0 0"/></RCLocalCoordinates></Pose>
          <Width Value="64"/><Height Value="48"/><Period Value="0.1"/>
        </RCCameraSensor>
      </ChildList>)";
  return std::string(R"(<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/></SceneSettings>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 -3 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="2"/><Height Value="1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCStaticRigidBody Key="Post">
      <Pose><RCGlobalCoordinates><Pose Value="0.8 1 -2 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="2"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCConstruction Key="Bot">
      <Body><RCMobileRigidBody Key="Chassis">
        <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
        <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
      </RCMobileRigidBody></Body>)") +
         (with_camera ? camera : "") + R"(
    </RCConstruction>
  </ComponentList>
</Simulation>)";
}

std::unique_ptr<Simulation> open(bool with_camera) {
  SimulationOptions o;
  o.gl = backend();
  Diagnostics d;
  auto sim = Simulation::fromText(scene(with_camera), "camera.xml", testRegistry(), o, d);
  INFO((d.errors().empty() ? std::string() : d.errors()[0].str()));
  REQUIRE(sim);
  return sim;
}

// What `simbob render --camera Bot.Eye --size 64x48` draws at the simulation's current poses.
Image renderNow(const Simulation& sim) {
  RenderOptions ro;
  ro.width = 64;
  ro.height = 48;
  ro.camera = "Bot.Eye";
  ro.backend = backend();
  ro.draw_models = false;  // the scene has no models: `simbob render` draws the collision shapes
  ro.draw_geoms = true;
  Error err;
  std::unique_ptr<Renderer> r = Renderer::create(sim.model(), ro, &err);
  INFO(err.message);
  REQUIRE(r);
  std::vector<Transform> poses;
  for (int i = 0; i < sim.world().bodyCount(); ++i) poses.push_back(sim.world().body(i).pose);
  Image img;
  REQUIRE(r->render(poses, sim.time(), &img) == nullptr);
  return img;
}

}  // namespace

TEST_CASE("a camera sensor's image at t is the renderer's picture through its camera at t") {
  auto sim = open(true);
  REQUIRE(modelsShowNoBody(sim->model()));
  REQUIRE(sim->cameraImage("Bot.Eye") != nullptr);
  CHECK(sim->cameraImage("Bot.Nose") == nullptr);
  REQUIRE(sim->step(0));  // serves t = 0
  const Image first = *sim->cameraImage("Bot.Eye");
  REQUIRE(first.width == 64);
  REQUIRE(first.height == 48);
  CHECK(first.rgb == renderNow(*sim).rgb);

  REQUIRE(sim->runUntil(0.3));
  const Image at = *sim->cameraImage("Bot.Eye");
  CHECK(at.rgb == renderNow(*sim).rgb);
  CHECK(at.rgb != first.rgb);  // the box has fallen: the view moved

  // Held between Period instants: at 0.35 it is still the picture of 0.3.
  REQUIRE(sim->runUntil(0.35));
  CHECK(sim->cameraImage("Bot.Eye")->rgb == at.rgb);
  CHECK(renderNow(*sim).rgb != at.rgb);
  REQUIRE(sim->runUntil(0.4));
  CHECK(sim->cameraImage("Bot.Eye")->rgb == renderNow(*sim).rgb);
}

TEST_CASE("a camera sensor leaves the physics alone: the same poses bit for bit") {
  auto with = open(true);
  auto without = open(false);
  for (int k = 0; k < 600; ++k) {
    REQUIRE(with->step(1));
    REQUIRE(without->step(1));
  }
  const Transform a = with->world().body(0).pose;
  const Transform b = without->world().body(0).pose;
  CHECK(a.p == b.p);
  CHECK(a.q == b.q);
  CHECK(a.p[1] < 0.5);  // it fell and landed
}

namespace {

// A controller's view: at 0.2 s it reads the camera sensor's image of that instant from the
// Simulation that draws it (the socket peer's way: the World is physics only and has none).
class Reader : public Party {
 public:
  explicit Reader(const Simulation& sim) : sim_(sim) {}
  SimTime first() override { return toSimTime(0.2).value_or(kNever); }
  SimTime onGrant(SimTime /*now*/, World& /*world*/) override {
    if (const Image* img = sim_.cameraImage("Bot.Eye")) seen = *img;
    unknown = sim_.cameraImage("Bot.Nose") != nullptr;
    return kNever;
  }
  Image seen;
  bool unknown = true;

 private:
  const Simulation& sim_;
};

}  // namespace

TEST_CASE("a controller reads the camera sensor's image of its instant from the Simulation") {
  auto sim = open(true);
  Reader reader(*sim);
  sim->addParty(reader);
  REQUIRE(sim->runUntil(0.2));
  CHECK_FALSE(reader.unknown);
  REQUIRE(reader.seen.width == 64);
  CHECK(reader.seen.rgb == renderNow(*sim).rgb);
}
