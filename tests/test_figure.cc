// Figures (vis/Figure): the <figure> file read with file:line errors, the panels laid out row by
// row with their letters, one colour bar for all.
#include <gtest/gtest.h>

#include <string>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"
#include "vis/Figure.h"

namespace anode {
namespace {

Figure readText(const std::string& text) {
  auto spec = ProblemSpec::fromText("<Uintah_specification>\n" + text + "\n</Uintah_specification>",
                                    "fig.xml");
  return readFigure(spec->root().requireChild("figure"));
}

std::string errorOf(const std::string& text) {
  try {
    readText(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kScene = "<scene><field>p.volume</field><size>[100, 80]</size></scene>";

TEST(Figure, ReadsItsTagsAndPanels) {
  const Figure f = readText(std::string("<figure><title>T</title><columns>2</columns>"
                                        "<time_scale>1e-6</time_scale><time_unit>s</time_unit>") +
                            kScene +
                            "<panel><data>a/particles.pvd</data><time>4e6</time><label>A</label>"
                            "</panel><panel><data>b.pvd</data><time>0</time></panel></figure>");
  EXPECT_EQ(f.title, "T");
  EXPECT_EQ(f.columns, 2);
  EXPECT_EQ(f.timeScale, 1e-6);
  EXPECT_EQ(f.timeUnit, "s");
  EXPECT_EQ(f.scene.field.label, "p.volume");
  EXPECT_EQ(f.scene.width, 100);
  ASSERT_EQ(f.panels.size(), 2u);
  EXPECT_EQ(f.panels[0].data, "a/particles.pvd");
  EXPECT_EQ(f.panels[0].time, 4e6);
  EXPECT_EQ(f.panels[0].label, "A");
  EXPECT_EQ(f.panels[1].label, "");
  EXPECT_FALSE(f.panels[0].box);
}

TEST(Figure, APanelMayGiveTheBoxItsCameraIsMadeFrom) {
  const Figure f = readText(std::string("<figure>") + kScene +
                            "<panel><data>a.pvd</data><time>0</time><box_min>[-1, -2, -3]</box_min>"
                            "<box_max>[1, 2, 3.5]</box_max></panel></figure>");
  ASSERT_TRUE(f.panels[0].box);
  EXPECT_EQ(f.panels[0].box->first, Vec3(-1, -2, -3));
  EXPECT_EQ(f.panels[0].box->second, Vec3(1, 2, 3.5));
  EXPECT_NE(errorOf(std::string("<figure>") + kScene +
                    "\n<panel><data>a</data><time>0</time><box_min>[0, 0, 0]</box_min></panel>"
                    "</figure>")
                .find("fig.xml:3: a <panel> gives both <box_min> and <box_max> or neither"),
            std::string::npos);
  EXPECT_NE(errorOf(std::string("<figure>") + kScene +
                    "<panel><data>a</data><time>0</time>\n<box_min>[0, 2, 0]</box_min>"
                    "<box_max>[1, 1, 1]</box_max></panel></figure>")
                .find("fig.xml:3: <box_min> must not exceed <box_max>"),
            std::string::npos);
}

TEST(Figure, ErrorsNameFileAndLine) {
  EXPECT_NE(errorOf(std::string("<figure>") + kScene + "</figure>")
                .find("fig.xml:2: a <figure> needs at least one <panel>"),
            std::string::npos);
  EXPECT_NE(
      errorOf("<figure>\n<panel><data>a</data><time>0</time></panel></figure>").find("fig.xml:2: "),
      std::string::npos);
  EXPECT_NE(errorOf(std::string("<figure>") + kScene + "\n<columns>0</columns>" +
                    "<panel><data>a</data><time>0</time></panel></figure>")
                .find("fig.xml:3: <columns> must be at least 1"),
            std::string::npos);
  EXPECT_NE(errorOf(std::string("<figure>") + kScene + "\n<panel><data>a</data></panel></figure>")
                .find("fig.xml:3: "),
            std::string::npos);
  EXPECT_NE(errorOf("<figure><scene><field>p.volume</field>\n<times>[1]</times></scene>"
                    "<panel><data>a</data><time>0</time></panel></figure>")
                .find("fig.xml:3: <times> has no place in a figure's scene"),
            std::string::npos);
  EXPECT_NE(errorOf("<figure><scene><field>p.volume</field>\n<colormap>jet</colormap></scene>"
                    "<panel><data>a</data><time>0</time></panel></figure>")
                .find("fig.xml:3: <colormap>: unknown colour map"),
            std::string::npos);
}

TEST(Figure, PanelLetters) {
  EXPECT_EQ(panelLetter(0), "(a)");
  EXPECT_EQ(panelLetter(7), "(h)");
  EXPECT_EQ(panelLetter(25), "(z)");
  EXPECT_EQ(panelLetter(26), "(aa)");
}

TEST(Figure, PanelsRowByRowWithOneColourBar) {
  Figure f = readText(std::string("<figure><columns>2</columns>") + kScene +
                      "<panel><data>a</data><time>0</time></panel>"
                      "<panel><data>a</data><time>1</time></panel>"
                      "<panel><data>a</data><time>2</time></panel></figure>");
  const RGB colours[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<Canvas> panels;
  for (const RGB& c : colours) panels.emplace_back(100, 80, c);
  const Canvas out = composeFigure(f, panels, {0, 1, 2}, {0, 1});
  ASSERT_EQ(out.height(), 160);  // two rows, no title
  ASSERT_GT(out.width(), 200);   // two columns and the colour bar
  auto colourAt = [&](int x, int y) {
    const unsigned char* p = out.pixel(x, y);
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  // Row 0 of a canvas is its bottom: the first row of panels is on top. Away from the labels.
  EXPECT_EQ(colourAt(50, 100), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(colourAt(150, 100), (std::array<int, 3>{0, 255, 0}));
  EXPECT_EQ(colourAt(50, 20), (std::array<int, 3>{0, 0, 255}));
  EXPECT_EQ(colourAt(150, 20), (std::array<int, 3>{255, 255, 255}));  // no fourth panel
  // Each panel's letter is written on it (dark text in its top left corner).
  for (int k = 0; k < 3; ++k) {
    const int x0 = (k % 2) * 100, y1 = k < 2 ? 160 : 80;
    int dark = 0;
    for (int y = y1 - 16; y < y1; ++y)
      for (int x = x0; x < x0 + 40; ++x) dark += out.pixel(x, y)[0] + out.pixel(x, y)[1] < 100;
    EXPECT_GT(dark, 10) << panelLetter(k);
  }
  // The colour bar: viridis' dark purple at its bottom, yellow at its top, right of the panels.
  int purple = 0, yellow = 0;
  for (int x = 200; x < out.width(); ++x)
    for (int y = 0; y < 160; ++y) {
      const unsigned char* p = out.pixel(x, y);
      purple += p[0] > 50 && p[0] < 90 && p[1] < 20 && p[2] > 70;
      yellow += p[0] > 230 && p[1] > 200 && p[2] < 60;
    }
  EXPECT_GT(purple, 5);
  EXPECT_GT(yellow, 5);
}

}  // namespace
}  // namespace anode
