// lib/robot/socket_codec.cpp: the socket protocol's lines on their own (docs/socket-protocol.md),
// without a socket or a peer program: the hello of each version and the negotiation, key
// escaping, subscriptions, the state blocks with an image, every request a peer may send and
// every protocol error simbob answers a wrong line with, word for word.
#include <catch2/catch.hpp>

#include <memory>
#include <string>

#include "physics/model_builder.h"
#include "robot/socket_codec.h"
#include "simbob/image.h"
#include "simbob/physics.h"

using namespace simbob;
using namespace simbob::test;
using simbob::robot::protocol::Codec;
using simbob::robot::protocol::Request;
namespace protocol = simbob::robot::protocol;

namespace {

// A robot whose keys need escaping: a body at (1, 2, 3) on a hinge with a velocity drive, a
// range sensor fixed in the world that sees nothing (it reads MaxRange, 5 m), a camera sensor.
Model linkedRobot() {
  Model m = baseModel(0.01);
  m.settings.gravity = {0, 0, 0};
  const int b = addBody(m, {1, 2, 3}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[static_cast<size_t>(b)].key = "Bot.Base";
  addJoint(m, JointKind::Hinge, -1, b, {1, 2, 3}, {0, 0, 1});
  m.joints[0].key = "Bot.Hinge";
  ActuatorDef a;
  a.key = "Bot.Drive";
  a.kind = ActuatorDef::VelDrive;
  a.joint = 0;
  m.actuators.push_back(a);
  SensorDef s;
  s.key = "Bot.Ray 1";
  s.kind = SensorKind::Range;
  m.sensors.push_back(s);
  CameraSensorDef c;
  c.key = "Bot.Eye";
  c.width = 2;
  c.height = 1;
  c.period = 0.1;
  m.camera_sensors.push_back(c);
  return m;
}

// The camera's image: one red and one blue pixel.
struct TwoPixels : CameraImages {
  TwoPixels() {
    img.width = 2;
    img.height = 1;
    img.rgb = {255, 0, 0, 0, 0, 255};
  }
  const Image* image(const std::string& key) const override { return key == "Bot.Eye" ? &img : nullptr; }
  Image img;
};

Codec codecOf(const Model& m) { return Codec(m, "Bot.Link", 0.05, {"Bot.Motion"}); }

std::string errorOf(Codec& c, const std::string& line, bool first = false) {
  const Request r = c.read(line, first);
  REQUIRE(r.kind == Request::Error);
  return r.problem + r.expected;
}

}  // namespace

TEST_CASE("socket codec: keys travel as one word, %XX for blanks, controls, non-ASCII, % and ,") {
  CHECK(protocol::escapeKey("Bot.Ray 1") == "Bot.Ray%201");
  CHECK(protocol::escapeKey("a%b,c\td\xC3\xA9") == "a%25b%2Cc%09d%C3%A9");
  CHECK(protocol::escapeKey("Plain.Key_9") == "Plain.Key_9");
  std::string key;
  REQUIRE(protocol::unescapeKey("a%25b%2cc%09d%C3%A9", &key));  // lower-case hex is read too
  CHECK(key == "a%b,c\td\xC3\xA9");
  CHECK_FALSE(protocol::unescapeKey("Bot%2", &key));
  CHECK_FALSE(protocol::unescapeKey("Bot%zz", &key));
  CHECK(protocol::words(" set\tA  1 ") == std::vector<std::string_view>{"set", "A", "1"});
  double v = 0;
  CHECK((protocol::parseNumber("+1.5e3", &v) && v == 1500));
  CHECK_FALSE(protocol::parseNumber("nan", &v));
  CHECK_FALSE(protocol::parseNumber("inf", &v));
  CHECK_FALSE(protocol::parseNumber("1x", &v));
  CHECK_FALSE(protocol::parseNumber("", &v));
}

TEST_CASE("socket codec: the version 2 hello and state, then negotiating version 3") {
  const Model m = linkedRobot();
  std::unique_ptr<World> w = World::create(m, 0);
  Codec c = codecOf(m);
  CHECK(c.version() == 2);
  // Version 2 names every actuator, motion, joint and body; of the sensors only proximity ones.
  CHECK(c.hello() ==
        "simbob 2 Bot.Link 0.05\nversions 2 3\nactuator Bot.Drive velocity\nmotion Bot.Motion\n"
        "joint Bot.Hinge hinge\nbody Bot.Base\nend\n");
  CHECK(c.state(0, *w, nullptr) == "t 0\njoint Bot.Hinge 0 0\nbody Bot.Base 1 2 3 1 0 0 0\nend\n");
  // The peer's first line may choose: the newest version both speak.
  const Request r = c.read("version 2 3 7", true);
  CHECK(r.kind == Request::Negotiate);
  CHECK(c.version() == 3);
  CHECK(c.hello() ==
        "simbob 3 Bot.Link 0.05\nactuator Bot.Drive velocity\nmotion Bot.Motion\njoint Bot.Hinge hinge\n"
        "sensor Bot.Ray%201 range 1\ncamera Bot.Eye 2 1 0.1\nbody Bot.Base\nend\n");
  // Version 3: every sensor as a vector, body velocities; images only on subscription.
  TwoPixels images;
  CHECK(c.state(toSimTime(0.05).value(), *w, &images) ==
        "t 0.05\njoint Bot.Hinge 0 0\nsensor Bot.Ray%201 5\nbody Bot.Base 1 2 3 1 0 0 0 0 0 0 0 0 0\nend\n");
}

TEST_CASE("socket codec: what `version` refuses") {
  const Model m = linkedRobot();
  Codec c = codecOf(m);
  CHECK(errorOf(c, "version 1 4", true) == "no protocol version in common: simbob speaks 2 and 3");
  CHECK(errorOf(c, "version 3x", true) == "'version': '3x' is not a version number");
  // Only as the first line: later it is a line like any unknown one.
  CHECK(errorOf(c, "version 3", false) == "the peer sent 'version 3': expected 'set KEY VALUE...', 'step' or 'done'");
  CHECK(c.version() == 2);
}

TEST_CASE("socket codec: subscriptions choose what the state blocks carry (version 3)") {
  const Model m = linkedRobot();
  std::unique_ptr<World> w = World::create(m, 0);
  TwoPixels images;
  Codec c = codecOf(m);
  // Version 2 has no `subscribe`.
  CHECK(errorOf(c, "subscribe bodies") ==
        "the peer sent 'subscribe bodies': expected 'set KEY VALUE...', 'step' or 'done'");
  REQUIRE(c.read("version 3", true).kind == Request::Negotiate);
  CHECK(c.read("subscribe bodies", false).kind == Request::Subscribe);  // no key: none
  CHECK(c.read("subscribe sensors", false).kind == Request::Subscribe);
  CHECK(c.read("subscribe joints *", false).kind == Request::Subscribe);
  CHECK(c.read("subscribe cameras Bot.Eye", false).kind == Request::Subscribe);
  std::string expected = "t 0\njoint Bot.Hinge 0 0\nimage Bot.Eye 2 1 6\n";
  expected += std::string("\xFF\x00\x00\x00\x00\xFF", 6);
  expected += "end\n";
  CHECK(c.state(0, *w, &images) == expected);
  // An image not drawn yet is an empty block.
  CHECK(c.state(0, *w, nullptr) == "t 0\njoint Bot.Hinge 0 0\nimage Bot.Eye 0 0 0\nend\n");
  CHECK(c.read("subscribe sensors Bot.Ray%201", false).kind == Request::Subscribe);
  CHECK(c.state(0, *w, nullptr).find("sensor Bot.Ray%201 5\n") != std::string::npos);
  CHECK(errorOf(c, "subscribe planets") == "'subscribe' takes bodies, joints, sensors or cameras, then keys");
  CHECK(errorOf(c, "subscribe") == "'subscribe' takes bodies, joints, sensors or cameras, then keys");
  CHECK(errorOf(c, "subscribe bodies Nobody") == "'subscribe bodies': no body has the key 'Nobody'");
  CHECK(errorOf(c, "subscribe joints Bot.Base") == "'subscribe joints': no joint has the key 'Bot.Base'");
  CHECK(errorOf(c, "subscribe sensors Bot.Ray 1") == "'subscribe sensors': no sensor has the key 'Bot.Ray'");
  CHECK(errorOf(c, "subscribe cameras Bot.Nose") == "'subscribe cameras': no camera sensor has the key 'Bot.Nose'");
  CHECK(errorOf(c, "subscribe bodies Bot%2") == "'subscribe bodies Bot%2': a '%' not followed by two hex digits");
}

TEST_CASE("socket codec: requests: set, step, done, blank lines") {
  const Model m = linkedRobot();
  Codec c = codecOf(m);
  Request r = c.read("set Bot.Drive -1.5", false);
  CHECK(r.kind == Request::Command);
  CHECK(r.index == 0);
  CHECK(r.values == std::vector<double>{-1.5});
  r = c.read("set Bot.Motion 0.2 +1e-1", false);
  CHECK(r.kind == Request::Motion);
  CHECK(r.index == 0);
  CHECK(r.values == std::vector<double>{0.2, 0.1});
  CHECK(c.read("set B%6ft.Drive 1", false).kind == Request::Command);  // an escaped key
  CHECK(c.read("step", false).kind == Request::Step);
  CHECK(c.read(" \t", false).kind == Request::Nothing);
  CHECK(c.read("done", false).kind == Request::Done);
}

TEST_CASE("socket codec: every protocol error a wrong line gets, word for word") {
  const Model m = linkedRobot();
  Codec c = codecOf(m);
  CHECK(errorOf(c, "set Bot.Drive 1 2") == "'set Bot.Drive' takes one value, got 2");
  CHECK(errorOf(c, "set Bot.Motion 1") == "'set Bot.Motion' takes two values (linear angular), got 1");
  CHECK(errorOf(c, "set Bot%2 1") == "'set Bot%2': a '%' not followed by two hex digits");
  CHECK(errorOf(c, "set Bot.Drive nan") == "'set Bot.Drive': 'nan' is not a finite number");
  CHECK(errorOf(c, "set Bot.Drive 1e999") == "'set Bot.Drive': '1e999' is not a finite number");
  CHECK(errorOf(c, "set Nobody 1") == "'set Nobody': no actuator or motion control has that key");
  CHECK(errorOf(c, "set Bot.Drive") == "the peer sent 'set Bot.Drive': expected 'set KEY VALUE...', 'step' or 'done'");
  CHECK(errorOf(c, "step now") == "the peer sent 'step now': expected 'set KEY VALUE...', 'step' or 'done'");
  CHECK(errorOf(c, "jump") == "the peer sent 'jump': expected 'set KEY VALUE...', 'step' or 'done'");
  // A line is echoed as messages echo input: control bytes visible, never raw.
  CHECK(errorOf(c, "jump\x1b[2J") == "the peer sent 'jump\\x1B[2J': expected 'set KEY VALUE...', 'step' or 'done'");
  CHECK(errorOf(c, std::string(4097, 'x')) == "a line longer than 4096 bytes");
  REQUIRE(c.read("version 3", true).kind == Request::Negotiate);
  CHECK(errorOf(c, "jump") == "the peer sent 'jump': expected 'set KEY VALUE...', 'subscribe', 'step' or 'done'");
}
