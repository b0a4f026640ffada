// Reading URDF files (lib/urdf/read.cpp, parse.cpp, paths.cpp): the values with the line of
// every element, urdfdom's rules with simbob's messages, what simbob ignores named once each,
// package:// paths, and every URDF of Debian's dart-doc: each loads or is refused with one line
// naming its file and line.
#include <cmath>
#include <cstdlib>
#include <random>

#include "urdf/urdf.h"
#include "urdf/urdf_test_util.h"

using namespace urdftest;

namespace {

std::shared_ptr<const UrdfRobot> read(const std::string& text, Diagnostics& d, const std::string& file = "r.urdf",
                                      const UrdfPackages& packages = {}) {
  return readUrdf(text, file, packages, d);
}

/// Loads a dart-doc URDF as `simbob check` does (a bare robot over a ground plane).
bool loadDart(const std::string& rel, Model* m, Diagnostics& d) { return compileFile(kDart + "/" + rel, m, d); }

bool hasNote(const Model& m, int line, const std::string& part) {
  for (const ImportReport& r : m.imports)
    for (const Error& n : r.notes)
      if (n.loc.line == line && n.message.find(part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("urdf read: values with the line of each element", "[urdf]") {
  Diagnostics d;
  auto r = read(R"(<?xml version="1.0"?>
<robot name="two">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="a">
    <inertial>
      <origin xyz="0 0 0.1" rpy="0 0 0"/>
      <mass value="2"/>
      <inertia ixx="1" ixy="0.1" ixz="0.2" iyy="2" iyz="0.3" izz="3"/>
    </inertial>
    <visual><geometry><box size="1 2 3"/></geometry><material name="red"/></visual>
    <collision><origin xyz="1 0 0"/><geometry><cylinder radius="0.5" length="2"/></geometry></collision>
  </link>
  <joint name="j" type="revolute">
    <parent link="a"/><child link="b"/>
    <axis xyz="0 0 2"/>
    <limit lower="-1" upper="1" effort="5" velocity="2"/>
    <dynamics damping="0.5" friction="0.25"/>
  </joint>
  <link name="b"/>
</robot>)",
                d);
  INFO(errorText(d));
  REQUIRE(r);
  CHECK(r->name == "two");
  CHECK(r->line == 2);
  REQUIRE(r->links.size() == 2);
  const UrdfLink& a = r->links[0];
  CHECK(a.line == 4);
  REQUIRE(a.has_inertial);
  CHECK(a.inertial.mass == 2);
  CHECK(a.inertial.mass_line == 7);
  CHECK(a.inertial.inertia_line == 8);
  CHECK(a.inertial.inertia == Mat3{1, 0.1, 0.2, 0.1, 2, 0.3, 0.2, 0.3, 3});
  CHECK(a.inertial.origin.p == Vec3{0, 0, 0.1});
  REQUIRE(a.visuals.size() == 1);
  CHECK(a.visuals[0].kind == UrdfShape::Box);
  CHECK(a.visuals[0].size == Vec3{1, 2, 3});
  CHECK(a.visuals[0].line == 10);
  REQUIRE(a.visuals[0].material == 0);
  CHECK(r->materials[0].color == Rgba{1, 0, 0, 1});
  REQUIRE(a.collisions.size() == 1);
  CHECK(a.collisions[0].kind == UrdfShape::Cylinder);
  CHECK(a.collisions[0].size == Vec3{0.5, 2, 0});
  CHECK(a.collisions[0].origin.p == Vec3{1, 0, 0});
  REQUIRE(r->joints.size() == 1);
  const UrdfJoint& j = r->joints[0];
  CHECK(j.type == UrdfJoint::Revolute);
  CHECK(j.line == 13);
  CHECK(j.axis == Vec3{0, 0, 1});  // made unit
  CHECK(j.limit_line == 16);
  CHECK(j.lower == -1);
  CHECK(j.effort == 5);
  CHECK(j.dynamics_line == 17);
  CHECK(j.damping == 0.5);
  CHECK(j.friction == 0.25);
  CHECK(r->root == 0);
  CHECK(r->ignored.empty());
}

TEST_CASE("urdf read: what simbob ignores is named once each, with its first line", "[urdf]") {
  Diagnostics d;
  auto r = read(R"(<robot name="x">
  <link name="a">
    <inertial><mass value="1"/><inertia ixx="1" iyx="0" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision group="default"><geometry><sphere radius="1"/></geometry></collision>
    <sensor name="s"/>
  </link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
    <calibration rising="0"/><safety_controller k_velocity="1"/></joint>
  <link name="b"><inertial><mass value="1"/><inertia ixx="1" iyx="0" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <transmission name="t"/>
  <gazebo reference="a"><material>Gazebo/Grey</material></gazebo>
  <gazebo reference="b"><material>Gazebo/Red</material></gazebo>
</robot>)",
                d);
  INFO(errorText(d));
  REQUIRE(r);
  std::vector<std::string> got;
  for (const UrdfNote& n : r->ignored)
    got.push_back(std::to_string(n.line) + " x" + std::to_string(n.count) + " " + n.text);
  CHECK(got == std::vector<std::string>{
                   "3 x2 attribute 'iyx' of <inertia> ignored",
                   "4 x1 attribute 'group' of <collision> ignored",
                   "5 x1 <sensor> ignored: not an element of URDF inside <robot/link>",
                   "8 x1 <calibration> ignored: joint positions are zero at the URDF's zero configuration",
                   "8 x1 <safety_controller> ignored: simbob has no safety controllers; the <limit> is what stops a "
                   "joint",
                   "10 x1 <transmission> ignored: simbob models no transmissions; RCImportURDF's Drives puts a drive "
                   "on every movable joint",
                   "11 x2 <gazebo> <material> ignored: Gazebo's material scripts are not read (a link's colour is "
                   "its URDF <material>)",
               });
}

TEST_CASE("urdf read: refusals name the file and the line", "[urdf]") {
  auto refuse = [](const std::string& text) {
    Diagnostics d;
    auto r = read(text, d);
    CHECK(!r);
    REQUIRE(d.errors().size() == 1);
    return d.errors()[0].str();
  };
  CHECK(refuse("<robot name=\"x\">\n  <link name=\"a\">\n</robot>") ==
        "r.urdf:3: malformed XML: Start-end tags mismatch");
  CHECK(refuse("<world name=\"w\"/>") ==
        "r.urdf:1: root element is <world>, expected <robot> (a URDF <world> is not read: import each robot with an "
        "RCImportURDF)");
  CHECK(refuse("<robot name=\"x\">\n<link name=\"a\"/>\n<joint name=\"j\" type=\"revolute\">\n"
               "<parent link=\"a\"/><child link=\"b\"/></joint>\n<link name=\"b\"/>\n</robot>") ==
        "r.urdf:3: joint 'j': a revolute joint needs <limit> (lower, upper, effort, velocity)");
  CHECK(
      refuse("<robot name=\"x\">\n<link name=\"a\"/>\n<joint name=\"j\" type=\"continuous\">\n"
             "<parent link=\"a\"/><child link=\"b\"/><mimic joint=\"nope\"/></joint>\n<link name=\"b\"/>\n</robot>") ==
      "r.urdf:4: joint 'j': <mimic> names no joint 'nope'");
}

TEST_CASE("urdf read: what urdfdom refuses is refused, one line at its element's line", "[urdf]") {
  // simbob's reader follows urdfdom's rules (urdf_parser/src/{model,link,joint,pose}.cpp) with
  // messages of its own. Each file below: a link 'a' on line 2, then `body` from line 3.
  auto refuse = [](const std::string& body, const std::string& robot = "<robot name=\"x\">") {
    Diagnostics d;
    auto r = read(robot + "\n<link name=\"a\"/>\n" + body + "\n</robot>", d);
    CHECK(!r);
    std::vector<std::string> out;
    for (const Error& e : d.errors()) out.push_back(e.str());
    return out.size() == 1 ? out[0] : "(" + std::to_string(out.size()) + " errors) " + errorText(d);
  };
  using V = std::vector<std::pair<std::string, std::string>>;
  const std::string link_b = "\n<link name=\"b\"/>";
  auto joint = [&](const std::string& attrs, const std::string& inside) {
    return "<joint name=\"j\" " + attrs + ">\n<parent link=\"a\"/><child link=\"b\"/>" + inside + "</joint>" + link_b;
  };
  for (const auto& [body, message] : V{
           {"<link/>", "r.urdf:3: robot 'x': <link> needs name=\"...\""},
           {"<link name=\"a\"/>", "r.urdf:3: link 'a' is defined twice (first at line 2)"},
           {"<material name=\"m\"/>\n<material name=\"m\"/>",
            "r.urdf:4: material 'm' is defined twice (first at line 3)"},
           {"<material name=\"m\"><color rgba=\"1 0 0\"/></material>",
            "r.urdf:3: material 'm': <color rgba=\"1 0 0\">: 4 numbers expected, found 3"},
           {"<material name=\"m\"><color rgba=\"255 0 0 1\"/></material>",
            "r.urdf:3: material 'm': <color rgba=\"255 0 0 1\">: 255 is outside [0, 1]"},
           {"<link name=\"c\"><inertial><mass value=\"abc\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" "
            "iyz=\"0\" izz=\"1\"/></inertial></link>",
            "r.urdf:3: link 'c': <mass value=\"abc\">: not a number"},
           {"<link name=\"c\"><inertial>\n<mass value=\"1\"/>\n</inertial></link>",
            "r.urdf:3: link 'c': <inertial> needs <mass value=\"...\"> and <inertia ixx=\"...\" ...>"},
           {"<link name=\"c\"><inertial><mass value=\"1\"/>\n<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" "
            "iyz=\"0\"/></inertial></link>",
            "r.urdf:4: link 'c': <inertia> needs izz=\"...\""},
           {"<link name=\"c\"><visual>\n<origin xyz=\"1 2\"/><geometry><sphere radius=\"1\"/></geometry></visual>"
            "</link>",
            "r.urdf:4: link 'c': <visual>: <origin xyz=\"1 2\">: 3 numbers expected, found 2"},
           {"<link name=\"c\"><collision><geometry>\n<box size=\"1 x 3\"/></geometry></collision></link>",
            "r.urdf:4: link 'c': <collision>: <box size=\"1 x 3\">: 'x' is not a number"},
           {"<link name=\"c\"><collision/></link>", "r.urdf:3: link 'c': <collision> needs <geometry>"},
           {"<link name=\"c\"><visual><geometry>\n</geometry></visual></link>",
            "r.urdf:3: link 'c': <visual>: <geometry> holds no shape (<box>, <cylinder>, <sphere> or <mesh>)"},
           {"<link name=\"c\"><visual><geometry>\n<capsule radius=\"1\" length=\"1\"/></geometry></visual></link>",
            "r.urdf:4: link 'c': <visual>: <geometry> holds <capsule>, not a URDF shape (<box>, <cylinder>, "
            "<sphere> or <mesh>)"},
           {"<link name=\"c\"><visual><geometry><cylinder radius=\"1\"/></geometry></visual></link>",
            "r.urdf:3: link 'c': <visual>: <cylinder> needs length=\"...\""},
           {"<link name=\"c\"><visual><geometry><mesh scale=\"1 1 1\"/></geometry></visual></link>",
            "r.urdf:3: link 'c': <visual>: <mesh> needs filename=\"...\""},
           {"<link name=\"c\"><visual><geometry><sphere radius=\"1\"/></geometry>\n<material/></visual></link>",
            "r.urdf:4: link 'c': <visual>: <material> needs name=\"...\""},
           {joint("", ""), "r.urdf:3: joint 'j': <joint> needs type=\"...\""},
           {joint("type=\"revolut\"", ""),
            "r.urdf:3: joint 'j': unknown type 'revolut', did you mean 'revolute'? (revolute, continuous, prismatic, "
            "fixed, floating or planar)"},
           {joint("type=\"prismatic\"", ""),
            "r.urdf:3: joint 'j': a prismatic joint needs <limit> (lower, upper, effort, velocity)"},
           {joint("type=\"revolute\"", "\n<limit lower=\"0\" upper=\"1\" velocity=\"1\"/>"),
            "r.urdf:5: joint 'j': <limit> needs effort=\"...\""},
           {joint("type=\"continuous\"", "\n<axis xyz=\"0 0 1 0\"/>"),
            "r.urdf:5: joint 'j': <axis xyz=\"0 0 1 0\">: 3 numbers expected, found 4"},
           {joint("type=\"continuous\"", "\n<dynamics/>"),
            "r.urdf:5: joint 'j': <dynamics> needs damping=\"...\" or friction=\"...\""},
           {joint("type=\"continuous\"", "\n<mimic multiplier=\"2\"/>"),
            "r.urdf:5: joint 'j': <mimic> needs joint=\"...\""},
           {joint("type=\"continuous\"", "\n<safety_controller k_position=\"1\"/>"),
            "r.urdf:5: joint 'j': <safety_controller> needs k_velocity=\"...\""},
           {joint("type=\"continuous\"", "\n<calibration rising=\"up\"/>"),
            "r.urdf:5: joint 'j': <calibration rising=\"up\">: not a number"},
           {joint("type=\"fixed\"", "\n<origin rpy=\"0 0 1e400\"/>"),
            "r.urdf:5: joint 'j': <origin rpy=\"0 0 1e400\">: '1e400' is not a number"},
           {"<joint name=\"j\" type=\"fixed\"><child link=\"b\"/></joint>" + link_b,
            "r.urdf:3: joint 'j' needs <parent link=\"...\">"},
           {"<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/>\n<child link=\"c\"/></joint>" + link_b,
            "r.urdf:4: joint 'j': <child> names no link 'c' (every link a joint names is a <link> of the robot)"},
           {joint("type=\"fixed\"", "") + "\n<joint name=\"j\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/>"
                                          "</joint><link name=\"c\"/>",
            "r.urdf:6: joint 'j' is defined twice (first at line 3)"},
           {link_b,
            "r.urdf:4: link 'b' is a second root beside 'a' (line 2): no joint has it as child, and a URDF "
            "is one tree with one root link"},
           {joint("type=\"fixed\"", "") + "\n<joint name=\"k\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/>"
                                          "</joint>",
            "r.urdf:6: joint 'k': link 'b' is already the child of joint 'j' (line 3): in a URDF tree each link has "
            "one parent joint"},
           {"<link name=\"b\"/><link name=\"c\"/>\n"
            "<joint name=\"bc\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/></joint>\n"
            "<joint name=\"cb\" type=\"fixed\"><parent link=\"c\"/><child link=\"b\"/></joint>",
            "r.urdf:3: link 'b' is not connected to the root 'a': its joints make a loop"},
       }) {
    INFO(body);
    CHECK(refuse(body) == message);
  }
  CHECK(refuse("", "<robot>") == "r.urdf:1: <robot> needs name=\"...\"");
  CHECK(refuse("", "<robot name=\"x\" version=\"2.0\">") ==
        "r.urdf:1: <robot version=\"2.0\">: simbob reads URDF version 1.0 only");
  CHECK(refuse("<joint name=\"l\" type=\"fixed\"><parent link=\"a\"/><child link=\"a\"/></joint>") ==
        "r.urdf:1: robot 'x' has no root link: every link is some joint's child (its joints make a loop)");
  Diagnostics d;
  CHECK(!read("<robot name=\"x\">\n<material name=\"m\"/>\n</robot>", d));
  CHECK(firstError(d) == "r.urdf:1: robot 'x' has no <link>");
  Diagnostics v;
  CHECK(read("<robot name=\"x\" version=\"1.0\"><link name=\"a\"/></robot>", v));
}

TEST_CASE("urdf read: numbers as urdfdom's C-locale stream reads them, and its defaults", "[urdf]") {
  TempDir dir;
  dir.write("m.stl", "solid a\nendsolid a\n");
  Diagnostics ok;
  auto robot = read(
      "<robot name=\"x\">\n"
      "<link name=\"a\"><inertial><origin xyz=\"+1  .5\t5.\"/><mass value=\" 1e3\"/>"
      "<inertia ixx=\"1E-2\" ixy=\"-0\" ixz=\"1e-400\" iyy=\"+.25e+1\" iyz=\"0\" izz=\"1\"/></inertial>\n"
      "<visual><geometry><mesh filename=\"m.stl\"/></geometry></visual></link>\n"
      "<link name=\"b\"/><link name=\"c\"/>\n"
      "<joint name=\"f\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
      "<joint name=\"r\" type=\"revolute\"><parent link=\"a\"/><child link=\"c\"/>"
      "<limit effort=\"1\" velocity=\"2\"/><mimic joint=\"f\"/><dynamics damping=\"0.5\"/></joint>\n"
      "</robot>",
      ok, (dir.path() / "r.urdf").string());
  INFO(errorText(ok));
  REQUIRE(robot);
  CHECK(robot->links[0].visuals[0].scale == Vec3{1, 1, 1});
  const UrdfInertial& i = robot->links[0].inertial;
  CHECK(i.origin.p == Vec3{1, 0.5, 5});
  CHECK(i.origin.q == Quat{1, 0, 0, 0});
  CHECK(i.mass == 1000);
  CHECK(i.inertia == Mat3{0.01, 0, 0, 0, 2.5, 0, 0, 0, 1});
  const UrdfJoint& f = robot->joints[0];
  CHECK(f.axis == Vec3{0, 0, 0});  // a fixed joint's axis is not read (urdfdom's 0 0 0)
  CHECK(f.origin.p == Vec3{0, 0, 0});
  CHECK(!f.has_limit);
  const UrdfJoint& j = robot->joints[1];
  CHECK(j.axis == Vec3{1, 0, 0});  // no <axis>
  CHECK(j.lower == 0);
  CHECK(j.upper == 0);
  CHECK(j.effort == 1);
  CHECK(j.velocity == 2);
  CHECK(j.mimic == 0);
  CHECK(j.multiplier == 1);
  CHECK(j.offset == 0);
  CHECK(j.damping == 0.5);
  CHECK(j.friction == 0);
  // What the stream refuses: words, hexadecimal, a comma, a magnitude beyond the largest double.
  for (const char* bad : {"inf", "nan", "0x10", "1,5", "1e400", "1e", "--1", "."}) {
    Diagnostics e;
    CHECK(!read(
        std::string("<robot name=\"x\"><link name=\"a\"><inertial><mass value=\"") + bad +
            "\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link></robot>",
        e));
    CHECK(firstError(e) == std::string("r.urdf:1: link 'a': <mass value=\"") + bad + "\">: not a number");
  }
}

TEST_CASE("urdf read: a visual's material is urdfdom's: robot-level, an earlier visual's, or its own", "[urdf]") {
  Diagnostics d;
  auto r = read(
      "<robot name=\"x\">\n<material name=\"red\"><color rgba=\"1 0 0 1\"/></material>\n"
      "<link name=\"a\">\n"
      "<visual><geometry><box size=\"1 1 1\"/></geometry><material name=\"red\"/></visual>\n"
      "<visual><geometry><box size=\"1 1 1\"/></geometry><material name=\"blue\"><color rgba=\"0 0 0.1 1\"/>"
      "</material></visual>\n"
      "<visual><geometry><box size=\"1 1 1\"/></geometry><material name=\"blue\"/></visual>\n"
      "<visual><geometry><box size=\"1 1 1\"/></geometry><material name=\"nowhere\"/></visual>\n"
      "</link>\n</robot>",
      d);
  INFO(errorText(d));
  REQUIRE(r);
  const auto& v = r->links[0].visuals;
  REQUIRE(v.size() == 4);
  CHECK(v[0].material == 0);  // the robot-level one
  REQUIRE(v[1].material == 1);
  CHECK(r->materials[1].color == Rgba{0, 0, static_cast<double>(0.1f), 1});  // single precision, as urdfdom keeps it
  REQUIRE(v[2].material == 2);                                               // blue again: the first visual's colour
  CHECK(r->materials[2].color == r->materials[1].color);
  CHECK(v[3].material == -1);  // defined nowhere: no material
  // name="" (SolidWorks' exporter writes it in every visual, as dart-doc's KR5 has it): urdfdom
  // assigns nothing by it, so each visual keeps its own colour.
  Diagnostics e;
  auto k = read(
      "<robot name=\"x\"><link name=\"a\">\n"
      "<visual><geometry><box size=\"1 1 1\"/></geometry><material name=\"\"><color rgba=\"0 0 0 1\"/>"
      "</material></visual>\n"
      "<visual><geometry><box size=\"1 1 1\"/></geometry><material name=\"\"><color rgba=\"1 1 1 1\"/>"
      "</material></visual>\n"
      "<visual><geometry><box size=\"1 1 1\"/></geometry><material name=\"\"/></visual>\n"
      "</link></robot>",
      e);
  INFO(errorText(e));
  REQUIRE(k);
  const auto& w = k->links[0].visuals;
  REQUIRE(w.size() == 3);
  REQUIRE(w[0].material == 0);
  REQUIRE(w[1].material == 1);
  CHECK(k->materials[0].color == Rgba{0, 0, 0, 1});
  CHECK(k->materials[1].color == Rgba{1, 1, 1, 1});
  CHECK(w[2].material == -1);
}

TEST_CASE("urdf read: a tab or a line break written in a name is a space, as XML reads an attribute", "[urdf]") {
  // Issue 43 item 14: urdfdom (TinyXML) kept a literal tab of a link's name while pugixml made it
  // a space; the two readers disagreed and the import stopped with "internal error: map::at"
  // (70). One reader now: XML's attribute-value normalization makes each tab and line break a
  // space (docs/urdf.md, "How a URDF is read"), in the link's name and in the joint naming it.
  const std::string text =
      "<robot name=\"tabs\">\n<link name=\"base\"><inertial><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n"
      "<link name=\"arm\tone\nend\"><inertial><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n"
      "<joint name=\"j\" type=\"continuous\"><parent link=\"base\"/>"
      "<child link=\"arm\tone\nend\"/></joint>\n</robot>\n";
  Diagnostics d;
  auto r = read(text, d);
  INFO(errorText(d));
  REQUIRE(r);
  REQUIRE(r->links.size() == 2);
  CHECK(r->links[1].name == "arm one end");
  CHECK(r->joints[0].child == 1);
  const Model m = mustCompile(text, "tabs.urdf");
  CHECK(m.bodies.size() == 2);
  CHECK(m.joints.size() == 1);
}

TEST_CASE("urdf read: package:// from a package.xml above, ROS_PACKAGE_PATH, then the given folders", "[urdf]") {
  TempDir dir;
  dir.write("ws/src/bot/package.xml", "<package><name> bot </name></package>");
  dir.write("ws/src/bot/meshes/a.stl", "solid a\nendsolid a\n");
  dir.write("elsewhere/other/package.xml", "<package><name>other</name></package>");
  dir.write("elsewhere/other/b.stl", "solid b\nendsolid b\n");
  dir.write("given/c.stl", "solid c\nendsolid c\n");
  const std::string urdf = (dir.path() / "ws/src/bot/urdf/bot.urdf").string();
  auto meshPath = [&](const std::string& filename, const UrdfPackages& packages, std::string* error) {
    Diagnostics d;
    auto r = read("<robot name=\"x\">\n<link name=\"a\">\n<visual><geometry>\n<mesh filename=\"" + filename +
                      "\"/></geometry></visual></link></robot>",
                  d, urdf, packages);
    *error = d.errors().empty() ? "" : d.errors()[0].str();
    return r ? r->links[0].visuals[0].path : std::string();
  };
  std::string err;
  CHECK(meshPath("package://bot/meshes/a.stl", {}, &err) == (dir.path() / "ws/src/bot/meshes/a.stl").string());
  CHECK(meshPath("../meshes/a.stl", {}, &err) == (dir.path() / "ws/src/bot/meshes/a.stl").string());
  CHECK(meshPath("package://other/b.stl", {}, &err).empty());
  CHECK(err == urdf +
                   ":4: mesh 'package://other/b.stl': no package 'other': no package.xml naming it in the URDF's "
                   "folder or above, none in ROS_PACKAGE_PATH, and no --package other=DIR or Packages entry");
  ::setenv("ROS_PACKAGE_PATH", (dir.path() / "elsewhere").c_str(), 1);
  CHECK(meshPath("package://other/b.stl", {}, &err) == (dir.path() / "elsewhere/other/b.stl").string());
  ::unsetenv("ROS_PACKAGE_PATH");
  CHECK(meshPath("package://given/c.stl", {{"given", (dir.path() / "given").string()}}, &err) ==
        (dir.path() / "given/c.stl").string());
  CHECK(meshPath("package://given/nothing.stl", {{"given", (dir.path() / "given").string()}}, &err).empty());
  CHECK(err == urdf + ":4: mesh 'package://given/nothing.stl' not found (looked for '" +
                   (dir.path() / "given/nothing.stl").string() + "')");
}

// --- every URDF of Debian's dart-doc (scripts/deps.sh test installs it) ------------------------

TEST_CASE("urdf dart-doc: test/invalid.urdf is refused at line 1", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("test/invalid.urdf", &m, d));
  CHECK(firstError(d) == kDart + "/test/invalid.urdf:1: not a URDF file: no <robot> element");
  CHECK(d.errors().size() == 1);
}

TEST_CASE("urdf dart-doc: test/testWorld.urdf (a <world>) is refused at line 1", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("test/testWorld.urdf", &m, d));
  CHECK(firstError(d) == kDart +
                             "/test/testWorld.urdf:1: root element is <world>, expected <robot> (a URDF <world> is "
                             "not read: import each robot with an RCImportURDF)");
  CHECK(d.errors().size() == 1);
}

TEST_CASE("urdf dart-doc: test/missing_mesh.urdf is refused (66) at its mesh's line", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("test/missing_mesh.urdf", &m, d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].kind == ErrorKind::MissingInput);
  CHECK(firstError(d) == kDart + "/test/missing_mesh.urdf:6: mesh 'this_file_does_not_exist.stl' not found " +
                             "(looked for '" + kDart + "/test/this_file_does_not_exist.stl')");
}

TEST_CASE("urdf dart-doc: test/missing_package.urdf is refused (66) at its mesh's line", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("test/missing_package.urdf", &m, d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].kind == ErrorKind::MissingInput);
  CHECK(firstError(d) == kDart +
                             "/test/missing_package.urdf:6: mesh 'package://missing_package/foo.stl': no package "
                             "'missing_package': no package.xml naming it in the URDF's folder or above, none in "
                             "ROS_PACKAGE_PATH, and no --package missing_package=DIR or Packages entry");
}

TEST_CASE("urdf dart-doc: test/primitive_geometry.urdf is refused at its massless floating link", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("test/primitive_geometry.urdf", &m, d));
  CHECK(d.errors().size() == 1);
  CHECK(firstError(d) == kDart +
                             "/test/primitive_geometry.urdf:3: link 'base_link' moves but has no mass (no <inertial> "
                             "on it or the links fixed to it): ODE cannot step a body without mass; give it an "
                             "<inertial> or import it with FixedBase");
}

TEST_CASE("urdf dart-doc: test/joint_properties.urdf is refused at its first massless link", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("test/joint_properties.urdf", &m, d));
  CHECK(d.errors().size() == 1);
  CHECK(firstError(d) == kDart +
                             "/test/joint_properties.urdf:3: link 'link_0' moves but has no mass (no <inertial> on it "
                             "or the links fixed to it): ODE cannot step a body without mass; give it an <inertial> "
                             "or import it with FixedBase (so do 'link_1', 'link_2')");
}

TEST_CASE("urdf dart-doc: test/joint_properties.urdf with masses keeps damping, friction and limits", "[urdf][dart]") {
  // The same file with an <inertial> in every link (the original has none; see above).
  std::string text = scenetest::readText(kDart + "/test/joint_properties.urdf");
  const std::string inertial =
      "<inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/>"
      "</inertial>";
  for (size_t at = 0; (at = text.find("<visual>", at)) != std::string::npos; at = text.find("</link>", at))
    text.insert(at, inertial);
  Model m = mustCompile(text, "joint_properties.urdf");
  REQUIRE(m.joints.size() == 2);
  CHECK(m.joints[0].damping == 1.2);
  CHECK(m.joints[0].friction == 2.3);
  CHECK(m.joints[0].lo_stop == -3.14159265359);
  CHECK(m.joints[1].damping == 1.2);
  CHECK(std::isinf(m.joints[1].hi_stop));  // continuous: no stops
}

TEST_CASE("urdf dart-doc: test/issue838.urdf loads: a fixed link lumped, colours as skins", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(loadDart("test/issue838.urdf", &m, d));
  REQUIRE(m.bodies.size() == 2);
  CHECK(m.bodies[0].key == "issue838.link_0");
  CHECK(m.bodies[0].mass == 10.0);
  CHECK(m.bodies[1].key == "issue838.link_2");
  REQUIRE(m.frames.size() == 1);
  CHECK(m.frames[0].key == "issue838.link_1");
  CHECK(m.frames[0].body == 0);
  REQUIRE(m.joints.size() == 1);
  CHECK(m.joints[0].key == "issue838.1_to_2");
  CHECK(m.visuals.size() >= 6);
  bool red = false;
  for (const SkinDef& s : m.skins) red = red || (s.color == Rgba{1, 0, 0, 1} && s.key == "issue838.material.Red");
  CHECK(red);
  CHECK(hasNote(m, 36, "link 'link_1' is fixed to 'link_0' (joint '0_to_1'): lumped into body 'issue838.link_0'"));
}

TEST_CASE("urdf dart-doc: test/invalid_mesh.urdf is refused (65) at its mesh's line", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("test/invalid_mesh.urdf", &m, d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].kind == ErrorKind::InvalidInput);
  CHECK(firstError(d).rfind(kDart + "/test/invalid_mesh.urdf:6: mesh 'invalid_mesh.stl': ", 0) == 0);
}

TEST_CASE("urdf dart-doc: wam's package://herb_description is refused at its line unless given", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  CHECK(!loadDart("wam/wam.urdf", &m, d));
  REQUIRE(!d.errors().empty());
  CHECK(firstError(d) == kDart +
                             "/wam/wam.urdf:17: mesh 'package://herb_description/meshes/wam/wam_base.dae': no package "
                             "'herb_description': no package.xml naming it in the URDF's folder or above, none in "
                             "ROS_PACKAGE_PATH, and no --package herb_description=DIR or Packages entry (16 names in "
                             "this package)");
  CHECK(d.errors().size() == 1);  // the package once, not each of its 16 names
  CHECK(d.errors()[0].kind == ErrorKind::MissingInput);
  Registry reg;
  registerBuiltins(reg);
  reg.addPackage("herb_description", kDart + "/wam");
  Scene s;
  Diagnostics d2;
  INFO(errorText(d2));
  REQUIRE(loadScene(kDart + "/wam/wam.urdf", reg, &s, d2));
  REQUIRE(compileScene(s, &m, d2));
  CHECK(m.joints.size() == 7);
}

TEST_CASE("urdf dart-doc: KR5 bare is refused at its deepest link's line: its arm lies in the ground", "[urdf][dart]") {
  // The file lays the arm along URDF +Y; a robot fixed to the world is not raised.
  Model m;
  Diagnostics d;
  CHECK(!loadDart("KR5/KR5 sixx R650.urdf", &m, d));
  CHECK(firstError(d) == kDart +
                             "/KR5/KR5 sixx R650.urdf:107: link 'bicep' of a robot fixed to the world starts 0.169 m "
                             "inside the ground: a robot fixed to the world is not raised; place it with "
                             "RCImportURDF's Pose in a scene (is the file's up axis +Z?)");
  CHECK(d.errors().size() == 1);
}

TEST_CASE("urdf dart-doc: KR5 (a space in its name, root link 'world') imported stood up loads fixed to the world",
          "[urdf][dart]") {
  const std::string scene = std::string("<Simulation><ComponentList><RCGround Key=\"Ground\"/>") +
                            "<RCImportURDF Key=\"kr5\"><File Value=\"" + kDart + "/KR5/KR5 sixx R650.urdf\"/>" +
                            "<Pose><RCGlobalCoordinates><Pose Value=\"0 0.5 0 90 0 0\"/></RCGlobalCoordinates></Pose>" +
                            "</RCImportURDF></ComponentList></Simulation>";
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileText(scene, "kr5.xml", &m, d));
  CHECK(m.bodies.size() == 6);  // base_link is fixed to 'world'
  CHECK(m.joints.size() == 6);
  REQUIRE(m.frames.size() == 1);
  CHECK(m.frames[0].key == "kr5.base_link");
  CHECK(m.frames[0].body == -1);
}

TEST_CASE("urdf dart-doc: drchubo (51 joints, package.xml) loads", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(loadDart("drchubo/drchubo.urdf", &m, d));
  CHECK(m.bodies.size() == 52);
  CHECK(m.joints.size() == 51);
}

TEST_CASE("urdf dart-doc: KR5/ground.urdf loads", "[urdf][dart]") {
  Model m;
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(loadDart("KR5/ground.urdf", &m, d));
  CHECK(m.bodies.empty());  // the ground link is fixed to 'world'
}

TEST_CASE("urdf read: an <origin rpy> becomes urdfdom's quaternion, with correctly rounded sin and cos", "[urdf]") {
  // quatFromRpy is urdfdom's Rotation::setFromRPY and normalize (urdf_model/pose.h) term for
  // term; only its sin and cos are correctly rounded (crSin, crCos) instead of libm's. Against
  // that formula with libm's, as urdfdom computes it, over random angles: every component within
  // 4 ulps of 1 (a last-bit difference in one factor moves a product of three by about that),
  // and equal bits for all but the few angles where libm is not correctly rounded.
  struct Libm {
    double w, x, y, z;
  };
  auto urdfdom = [](double roll, double pitch, double yaw) {
    const double phi = roll / 2.0, the = pitch / 2.0, psi = yaw / 2.0;
    Libm q{std::cos(phi) * std::cos(the) * std::cos(psi) + std::sin(phi) * std::sin(the) * std::sin(psi),
           std::sin(phi) * std::cos(the) * std::cos(psi) - std::cos(phi) * std::sin(the) * std::sin(psi),
           std::cos(phi) * std::sin(the) * std::cos(psi) + std::sin(phi) * std::cos(the) * std::sin(psi),
           std::cos(phi) * std::cos(the) * std::sin(psi) - std::sin(phi) * std::sin(the) * std::cos(psi)};
    const double s = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return Libm{q.w / s, q.x / s, q.y / s, q.z / s};
  };
  std::mt19937_64 rng(28);
  std::uniform_real_distribution<double> a(-4.0, 4.0);
  int equal = 0;
  constexpr int kCases = 20000;
  for (int i = 0; i < kCases; ++i) {
    const double r = a(rng), p = a(rng), y = a(rng);
    const Libm u = urdfdom(r, p, y);
    const simbob::Quat q = simbob::quatFromRpy(r, p, y);
    const double theirs[4] = {u.w, u.x, u.y, u.z};
    bool same = true;
    for (int k = 0; k < 4; ++k) {
      REQUIRE(std::fabs(q[static_cast<size_t>(k)] - theirs[k]) <= 4 * 0x1p-53);
      same = same && q[static_cast<size_t>(k)] == theirs[k];
    }
    equal += same;
  }
  CHECK(equal >= kCases * 99 / 100);
  // A quarter turn about Z: w = cos(pi/4) and z = sin(pi/4), both 0x1.6a09e667f3bcdp-1 rounded.
  const simbob::Quat q = simbob::quatFromRpy(0, 0, 1.5707963267948966);
  CHECK(q[0] == Approx(std::sqrt(0.5)).epsilon(1e-15));
  CHECK(q[3] == Approx(std::sqrt(0.5)).epsilon(1e-15));
}

TEST_CASE("urdf read: a chain 40,000 links deep loads (no recursion over the tree); deeper than 50,000 is refused",
          "[urdf]") {
  // Issue 43 point 11: planUrdf walked the tree recursively (SIGSEGV near 40,000), and urdfdom,
  // which read the values then, freed its links recursively (near 120,000 on an 8 MB stack):
  // simbob plans with a stack of its own and refuses what is deeper than kMaxUrdfDepth.
  auto chain = [](int n) {
    std::string t =
        "<robot name=\"chain\">\n<link name=\"l0\"><inertial><mass value=\"1\"/>"
        "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>\n";
    for (int i = 1; i <= n; ++i)
      t += "<joint name=\"j" + std::to_string(i) + "\" type=\"fixed\"><parent link=\"l" + std::to_string(i - 1) +
           "\"/><child link=\"l" + std::to_string(i) + "\"/><origin xyz=\"0 0 0.001\"/></joint><link name=\"l" +
           std::to_string(i) + "\"/>\n";
    return t + "</robot>\n";
  };
  Diagnostics d;
  auto r = read(chain(40000), d);
  INFO(errorText(d));
  REQUIRE(r);
  REQUIRE(r->links.size() == 40001);
  const UrdfPlan plan = planUrdf(*r, false);
  REQUIRE(plan.bodies.size() == 1);  // every link fixed to l0
  CHECK(plan.bodies[0].links.size() == 40001);
  CHECK(plan.link_global[40000].p[2] == Approx(40.0));  // 40,000 steps of 1 mm up
  Diagnostics deep;
  CHECK(!read(chain(kMaxUrdfDepth + 1), deep));
  CHECK(firstError(deep) == "r.urdf:" + std::to_string(kMaxUrdfDepth + 3) + ": joint 'j" +
                                std::to_string(kMaxUrdfDepth + 1) + "': its child link is more than " +
                                std::to_string(kMaxUrdfDepth) +
                                " joints below the root: simbob reads URDF trees at most that deep (docs/urdf.md)");
}

TEST_CASE("urdf read: 200,000 different unknown elements are each named once, in one pass", "[urdf]") {
  // Issue 43 point 12: the notes were searched one by one for each element (about 70 s); now by
  // a map. The elements are named once each, in the file's order.
  std::string t = "<robot name=\"wide\"><link name=\"a\"/>\n";
  for (int i = 0; i < 200000; ++i) t += "<x" + std::to_string(i) + "/><x" + std::to_string(i) + "/>\n";
  t += "</robot>\n";
  Diagnostics d;
  auto r = read(t, d);
  INFO(errorText(d));
  REQUIRE(r);
  REQUIRE(r->ignored.size() == 200000);
  CHECK(r->ignored[0].text == "<x0> ignored: not an element of URDF inside <robot>");
  CHECK(r->ignored[0].count == 2);
  CHECK(r->ignored[199999].line == 200001);
  CHECK(r->ignored[199999].text == "<x199999> ignored: not an element of URDF inside <robot>");
}

TEST_CASE("urdf read: every number passes the checks a scene file's parameters get (magnitude 1e9, signs)", "[urdf]") {
  // Round five (issue 43): a mass of 1e200 reached ODE and ended in its assertion (exit 70).
  // A scene file refuses any number beyond kMaxValueMagnitude; a URDF now refuses the same.
  auto errors = [](const std::string& link_body, const std::string& joint_body, const std::string& extra = "") {
    Diagnostics d;
    const std::string text = "<robot name=\"x\">\n<link name=\"world\"/>\n<link name=\"arm\">\n" + link_body +
                             "\n</link>\n<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/>"
                             "<child link=\"arm\"/>\n" +
                             joint_body + "\n</joint>\n" + extra + "\n</robot>";
    auto r = readUrdf(text, "r.urdf", {}, d);
    CHECK(!r);
    std::vector<std::string> out;
    for (const Error& e : d.errors()) out.push_back(e.str());
    return out;
  };
  const std::string inertial =
      "<inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>";
  const std::string limit = "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>";
  CHECK(errors("<inertial><mass value=\"1e200\"/><inertia ixx=\"1e200\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" "
               "iyz=\"0\"/></inertial>",
               limit) ==
        std::vector<std::string>{
            "r.urdf:4: link 'arm': <mass> 1e+200 is beyond the supported magnitude 1e+09 (the limit of every number "
            "of a scene)",
            "r.urdf:4: link 'arm': <inertia> 1e+200 is beyond the supported magnitude 1e+09 (the limit of every "
            "number of a scene)"});
  CHECK(errors(inertial + "<collision><origin xyz=\"0 2e9 0\"/><geometry><box size=\"0.1 1e10 0.1\"/></geometry>"
                          "</collision>",
               limit) ==
        std::vector<std::string>{"r.urdf:4: link 'arm': <collision>: <origin> xyz 2e+09 is beyond the supported "
                                 "magnitude 1e+09 (the limit of every number of a scene)",
                                 "r.urdf:4: link 'arm': <collision> size 1e+10 is beyond the supported magnitude "
                                 "1e+09 (the limit of every number of a scene)"});
  CHECK(errors(inertial,
               "<limit lower=\"-1e16\" upper=\"1\" effort=\"-1\" velocity=\"1e300\"/>\n<dynamics damping=\"-0.5\" "
               "friction=\"1e12\"/>") ==
        std::vector<std::string>{
            "r.urdf:7: joint 'j': <limit> lower -1e+16 is beyond the supported magnitude 1e+09 (the limit of every "
            "number of a scene)",
            "r.urdf:7: joint 'j': <limit> effort -1 must be >= 0",
            "r.urdf:7: joint 'j': <limit> velocity 1e+300 is beyond the supported magnitude 1e+09 (the limit of "
            "every number of a scene)",
            "r.urdf:8: joint 'j': <dynamics> damping -0.5 must be >= 0",
            "r.urdf:8: joint 'j': <dynamics> friction 1e+12 is beyond the supported magnitude 1e+09 (the limit of "
            "every number of a scene)"});
  CHECK(errors(inertial, limit, "<gazebo reference=\"arm\"><kp>1e13</kp></gazebo>") ==
        std::vector<std::string>{"r.urdf:9: link 'arm': <kp> 1e+13 is beyond the supported magnitude 1e+09 (the "
                                 "limit of every number of a scene)"});
  // The limit itself is accepted, as in a scene file.
  Diagnostics d;
  CHECK(
      readUrdf("<robot name=\"x\">\n<link name=\"world\"/>\n<link name=\"arm\"><inertial><mass value=\"1e9\"/>"
               "<inertia ixx=\"1e9\" iyy=\"1e9\" izz=\"1e9\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n"
               "<joint name=\"j\" type=\"revolute\"><parent link=\"world\"/><child link=\"arm\"/>"
               "<limit lower=\"-1e9\" upper=\"1e9\" effort=\"1e9\" velocity=\"1e9\"/></joint>\n</robot>",
               "r.urdf", {}, d));
  CHECK(d.errors().empty());
}

TEST_CASE("urdf read: a joint that mimics itself, or joints that mimic each other, are refused at the <mimic>",
          "[urdf]") {
  // Round five (issue 43, item 16): both were accepted and run, with no leader that moves.
  auto errors = [](const std::string& joints) {
    Diagnostics d;
    const std::string text =
        "<robot name=\"x\">\n<link name=\"world\"/>\n"
        "<link name=\"a\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" "
        "iyz=\"0\"/></inertial></link>\n"
        "<link name=\"b\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" "
        "iyz=\"0\"/></inertial></link>\n" +
        joints + "\n</robot>";
    CHECK(!readUrdf(text, "r.urdf", {}, d));
    std::vector<std::string> out;
    for (const Error& e : d.errors()) out.push_back(e.str());
    return out;
  };
  CHECK(errors("<joint name=\"j1\" type=\"continuous\"><parent link=\"world\"/><child link=\"a\"/>\n"
               "<mimic joint=\"j1\"/></joint>\n"
               "<joint name=\"j2\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint>") ==
        std::vector<std::string>{"r.urdf:6: joint 'j1': <mimic> follows the joint itself: a mimic joint needs a "
                                 "leader that moves of its own"});
  CHECK(errors("<joint name=\"j1\" type=\"continuous\"><parent link=\"world\"/><child link=\"a\"/>\n"
               "<mimic joint=\"j2\"/></joint>\n"
               "<joint name=\"j2\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>\n"
               "<mimic joint=\"j1\"/></joint>") ==
        std::vector<std::string>{"r.urdf:6: joint 'j1': <mimic> joints follow each other round a loop ('j1' -> "
                                 "'j2' -> 'j1'): a mimic joint needs a leader that moves of its own"});
  CHECK(errors("<joint name=\"j1\" type=\"continuous\"><parent link=\"world\"/><child link=\"a\"/>\n"
               "<axis xyz=\"1e308 1e308 1e308\"/></joint>\n"
               "<joint name=\"j2\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/></joint>") ==
        std::vector<std::string>{"r.urdf:6: joint 'j1': <axis> xyz 1e+308 is beyond the supported magnitude 1e+09 "
                                 "(the limit of every number of a scene)"});
}

TEST_CASE("urdf read: a link or joint with an empty name is refused at its line", "[urdf]") {
  // Round five (issue 43): a link named "" took the robot's own key ("duplicate key 'robot'").
  Diagnostics d;
  CHECK(!readUrdf("<robot name=\"\">\n<link name=\"\"/>\n</robot>", "r.urdf", {}, d));
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].str() == "r.urdf:2: robot '': a <link> with an empty name (name=\"\"): give it one");
}
