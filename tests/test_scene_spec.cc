// The <Visualization> block (docs/input-reference.md): every tag read into the scene, defaults,
// and each malformed value an error naming the file and line of its tag.
#include <gtest/gtest.h>

#include <cmath>

#include "vis/SceneSpec.h"

namespace anode {
namespace {

// Reads the scenes of `<Visualization>` + body, as the driver would for a run of `materials`
// materials from 0 to maxTime 10, where p.stress (9), p.velocity (3) and p.volume (1) exist and
// p.concentration needs diffusion.
std::vector<Scene> read(const std::string& body) {
  const std::string text = "<Uintah_specification>\n<Visualization>\n" + body +
                           "\n</Visualization>\n</Uintah_specification>\n";
  auto spec = ProblemSpec::fromText(text, "scene.ups");
  SceneContext context;
  context.initTime = 0;
  context.maxTime = 10;
  context.materials = 2;
  context.lookup = [](const std::string& label) -> SceneContext::LabelInfo {
    if (label == "p.stress") return {9, ""};
    if (label == "p.velocity") return {3, ""};
    if (label == "p.volume") return {1, ""};
    if (label == "p.concentration") return {0, "p.concentration is a diffusion quantity"};
    return {0, label + " is not a particle quantity this code computes"};
  };
  std::vector<Scene> scenes = readScenes(spec->root().child("Visualization"), context);
  spec->checkAllUsed();
  return scenes;
}

// The message of the InputError that reading `body` throws ("" when none).
std::string errorOf(const std::string& body) {
  try {
    read(body);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneSpec, ReadsEveryTag) {
  const auto scenes = read(R"(<scene name="cut">
  <times>[5, 1, 2.5]</times>
  <field>p.stress:zy</field>
  <scale>1e-6</scale>
  <range>[-1, 3]</range>
  <colormap>blue_red</colormap>
  <materials>[1]</materials>
  <clip><point>[0, 0.5, 0]</point><normal>[0, -1, 0]</normal></clip>
  <camera><position>[1, -2, 3]</position><focal_point>[0, 0, 0.5]</focal_point><up>[0, 0, 1]</up>
          <view_angle>20</view_angle></camera>
  <size>[640, 480]</size>
  <background>[0, 0, 0.2]</background>
  <title>Cut-away</title>
  <units>kPa</units>
  <field_name>sigma_zy</field_name>
  <time_unit>s</time_unit>
  <time_scale>1e-6</time_scale>
</scene>)");
  ASSERT_EQ(scenes.size(), 1u);
  const Scene& s = scenes[0];
  EXPECT_EQ(s.name, "cut");
  EXPECT_EQ(s.times, (std::vector<double>{1, 2.5, 5}));
  EXPECT_EQ(s.field.label, "p.stress");
  EXPECT_EQ(s.field.reduce, FieldSpec::Reduce::Component);
  EXPECT_EQ(s.field.component, 7);  // row z, column y, row-major as saved
  EXPECT_EQ(s.field.components, 9);
  EXPECT_EQ(s.scale, 1e-6);
  ASSERT_TRUE(s.range);
  EXPECT_EQ(s.range->first, -1);
  EXPECT_EQ(s.range->second, 3);
  EXPECT_EQ(s.colourMap, ColourMapKind::BlueRed);
  EXPECT_EQ(s.materials, std::vector<int>{1});
  EXPECT_FALSE(s.drawsMaterial(0));
  ASSERT_TRUE(s.clip);
  EXPECT_EQ(s.clip->normal, Vec3(0, -1, 0));
  const double kept[3] = {0, 0.6, 0}, cut[3] = {0, 0.4, 0};
  EXPECT_TRUE(s.keeps(kept));
  EXPECT_FALSE(s.keeps(cut));
  EXPECT_EQ(s.camera.preset, CameraPreset::Custom);
  EXPECT_EQ(*s.camera.position, Vec3(1, -2, 3));
  EXPECT_EQ(*s.camera.focalPoint, Vec3(0, 0, 0.5));
  EXPECT_EQ(s.camera.viewAngle, 20);
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 480);
  EXPECT_EQ(s.background, Vec3(0, 0, 0.2));
  EXPECT_EQ(s.title, "Cut-away");
  EXPECT_EQ(s.units, "kPa");
  EXPECT_EQ(s.barName(), "sigma_zy");  // else the field as written
  EXPECT_EQ(s.timeUnit, "s");
  EXPECT_EQ(s.timeScale, 1e-6);
  EXPECT_EQ(s.imageFile(2.5), "images/cut_2.5.png");    // the file keeps the simulation time
  EXPECT_EQ(s.titleAt(2.8e7), "Cut-away    t = 28 s");  // 2.8e7 us
}

// A section: the particles within thickness/2 of the plane, on both sides (an array's row of
// pillars seen face-on, whatever side of the plane each particle lies).
TEST(SceneSpec, SectionKeepsASlabAboutThePlane) {
  const auto scenes = read(R"(<scene name="row">
  <times>[0]</times>
  <field>p.volume</field>
  <clip><point>[0, 0.1, 0]</point><normal>[0, 2, 0]</normal><thickness>0.02</thickness></clip>
  <camera>front</camera>
</scene>)");
  ASSERT_EQ(scenes.size(), 1u);
  const Scene& s = scenes[0];
  for (const double y : {0.091, 0.1, 0.109}) {
    const double x[3] = {5, y, -3};
    EXPECT_TRUE(s.keeps(x)) << y;
  }
  for (const double y : {0.085, 0.115, 0.3, -0.1}) {
    const double x[3] = {5, y, -3};
    EXPECT_FALSE(s.keeps(x)) << y;
  }
}

TEST(SceneSpec, Defaults) {
  const auto scenes =
      read(R"(<scene name="a"><interval>2.5</interval><field>p.volume</field></scene>
<scene name="b"><times>[0]</times><field>p.velocity:magnitude</field><camera>top</camera></scene>)");
  ASSERT_EQ(scenes.size(), 2u);
  const Scene& a = scenes[0];
  EXPECT_FALSE(a.range);
  EXPECT_EQ(a.scale, 1);
  EXPECT_EQ(a.colourMap, ColourMapKind::Viridis);
  EXPECT_TRUE(a.materials.empty());
  EXPECT_TRUE(a.drawsMaterial(1));
  EXPECT_FALSE(a.clip);
  EXPECT_EQ(a.camera.preset, CameraPreset::Iso);
  EXPECT_EQ(a.width, 1024);
  EXPECT_EQ(a.height, 768);
  EXPECT_EQ(a.background, Vec3(1, 1, 1));
  EXPECT_EQ(a.timeScale, 1);
  EXPECT_EQ(a.titleAt(2.5), "a    t = 2.5");
  EXPECT_EQ(a.renderTimes(0, 10), (std::vector<double>{0, 2.5, 5, 7.5, 10}));
  EXPECT_EQ(scenes[1].camera.preset, CameraPreset::Top);
  EXPECT_EQ(scenes[1].field.reduce, FieldSpec::Reduce::Magnitude);
}

TEST(SceneSpec, FieldSyntax) {
  EXPECT_EQ(parseField("p.concentration").reduce, FieldSpec::Reduce::Scalar);
  EXPECT_EQ(parseField("p.velocity:z").component, 2);
  EXPECT_EQ(parseField("p.stress:xx").component, 0);
  EXPECT_EQ(parseField("p.stress:von_mises").reduce, FieldSpec::Reduce::VonMises);
  EXPECT_THROW(parseField("concentration"), std::invalid_argument);
  EXPECT_THROW(parseField("p.stress:qq"), std::invalid_argument);
}

TEST(SceneSpec, FieldValues) {
  // Uniaxial stress s_zz = 3: von Mises 3; pure shear s_xy = s_yx = 1: von Mises sqrt(3).
  const double uniaxial[9] = {0, 0, 0, 0, 0, 0, 0, 0, 3}, shear[9] = {0, 1, 0, 1, 0, 0, 0, 0, 0};
  EXPECT_NEAR(parseField("p.stress:von_mises").evaluate(uniaxial), 3, 1e-14);
  EXPECT_NEAR(parseField("p.stress:von_mises").evaluate(shear), std::sqrt(3.0), 1e-14);
  EXPECT_EQ(parseField("p.stress:zz").evaluate(uniaxial), 3);
  const double v[3] = {3, 0, 4};
  EXPECT_EQ(parseField("p.velocity:magnitude").evaluate(v), 5);
  EXPECT_EQ(parseField("p.velocity:x").evaluate(v), 3);
}

TEST(SceneSpec, ErrorsNameFileAndLine) {
  const std::string head = "<scene name=\"s\">\n<times>[0]</times>\n<field>p.volume</field>\n";
  // The scene opens on line 3 of the text; its fourth line is the tag under test.
  auto expect = [&](const std::string& tag, const std::string& message) {
    const std::string error = errorOf(head + tag + "\n</scene>");
    EXPECT_NE(error.find("scene.ups:6: "), std::string::npos) << tag << " -> " << error;
    EXPECT_NE(error.find(message), std::string::npos) << tag << " -> " << error;
  };
  expect("<colormap>jet</colormap>", "unknown colour map 'jet'; accepted: viridis, blue_red, grey");
  expect("<range>[2, 1]</range>", "min < max");
  expect("<range>[0, x]</range>", "expected a number");
  expect("<materials>[-1]</materials>", "material indices are >= 0");
  expect("<camera>oblique</camera>", "unknown camera 'oblique'");
  expect("<camera><view_angle>200</view_angle></camera>", "between 0 and 180");
  expect("<size>[10, 10]</size>", "each 64 to 8192");
  expect("<background>[2, 0, 0]</background>", "each in [0, 1]");
  expect("<interval>-1</interval>", "positive");
  expect("<scale>0</scale>", "<scale> multiplies the field's values: a finite number, not 0");
  expect("<time_scale>-1</time_scale>", "<time_scale> multiplies the simulation time");
  expect("<colour>grey</colour>", "unknown tag <colour> in <scene>");
  expect("<scale_bar>furlong</scale_bar>", "<scale_bar> names the positions' length unit");
  expect("<clip/>", "<clip> needs <point> and <normal>");
  expect("<clip><point>[0,0,0]</point><normal>[0,0,1]</normal><thickness>0</thickness></clip>",
         "<thickness> is the section's width about the plane");
  expect("<title><b>x</b></title>", "takes a value, not tags");
  expect("<field>p.volume</field>", "given twice");
  expect("<clip><point>[0,0,0]</point><plane>[0,0,1]</plane></clip>", "unknown tag <clip/plane>");
}

TEST(SceneSpec, SceneErrorsNameTheSceneLine) {
  auto expect = [&](const std::string& body, const std::string& message) {
    const std::string error = errorOf(body);
    EXPECT_NE(error.find("scene.ups:3: "), std::string::npos) << body << " -> " << error;
    EXPECT_NE(error.find(message), std::string::npos) << body << " -> " << error;
  };
  expect("<scene name=\"s\"><field>p.volume</field></scene>", "give <times> or <interval>");
  expect(
      "<scene name=\"s\"><times>[1]</times><interval>1</interval><field>p.volume</field></scene>",
      "give <times> or <interval>");
  expect("<scene name=\"s\"><times>[11]</times><field>p.volume</field></scene>", "after maxTime");
  expect("<scene name=\"s\"><times>[-1]</times><field>p.volume</field></scene>", "before initTime");
  expect("<scene name=\"s\"><times>[1]</times></scene>", "p.concentration is a diffusion quantity");
  expect("<scene name=\"s\"><times>[1]</times><field>p.mass2</field></scene>",
         "not a particle quantity");
  expect("<scene name=\"s\"><times>[1]</times><field>p.stress</field></scene>",
         "p.stress is a tensor");
  expect("<scene name=\"s\"><times>[1]</times><field>p.velocity:xx</field></scene>",
         "p.velocity is a vector");
  expect(
      "<scene "
      "name=\"s\"><times>[1]</times><field>p.volume</field><materials>[2]</materials></scene>",
      "material 2 does not exist");
  expect(
      "<scene "
      "name=\"s\"><times>[1]</times><field>p.volume</field><clip><normal>[0,0,0]</normal></clip></"
      "scene>",
      "non-zero <normal>");
  expect(
      "<scene "
      "name=\"s\"><times>[1]</times><field>p.volume</field><camera><position>[1,0,0]</position></"
      "camera></scene>",
      "needs both <position> and <focal_point>");
  expect(
      "<scene "
      "name=\"s\"><times>[1]</times><field>p.volume</field><camera><position>[0,0,1]</position>"
      "<focal_point>[0,0,0]</focal_point></camera></scene>",
      "parallel to the view direction");
  expect("<scene name=\"a/b\"><times>[1]</times><field>p.volume</field></scene>",
         "must be letters, digits");
  expect("<scene><times>[1]</times></scene>", "requires the attribute name");
  expect("<view/>", "unknown tag <view> in <Visualization>");
}

TEST(SceneSpec, DuplicateSceneNames) {
  const std::string error = errorOf(
      "<scene name=\"s\"><times>[1]</times><field>p.volume</field></scene>\n"
      "<scene name=\"s\"><times>[2]</times><field>p.volume</field></scene>");
  EXPECT_NE(error.find("scene.ups:4: a second scene named \"s\""), std::string::npos) << error;
}

}  // namespace
}  // namespace anode
