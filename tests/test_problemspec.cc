// Pins the .ups reader: typed values, FILE:LINE: errors, defaults, comments, unread tags,
// unsupported.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {
namespace {

// Line numbers below count from the line holding <Uintah_specification> (line 1).
const char* kValues = R"(<Uintah_specification>
  <d>1e-6</d>
  <i> -42 </i>
  <t>true</t>
  <f>false</f>
  <v>[1, 2.5, -3e2]</v>
  <vi>[1, -2, 3]</vi>
  <list>[4, 5, 6, 7]</list>
  <s>  linear  </s>
  <c> 1.0 <!-- a comment --> </c>
  <vc>[1, <!-- y follows --> 2, 3]</vc>
  <Time>
    <initTime>0</initTime>
  </Time>
</Uintah_specification>
)";

// Runs `body` and returns the InputError it throws (failing the test if it throws none).
template <class F>
InputError expectInputError(F body) {
  try {
    body();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", 0, "");
}

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}
bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST(ProblemSpec, ReadsTypedValues) {
  auto spec = ProblemSpec::fromText(kValues, "values.ups");
  const PSNode root = spec->root();
  EXPECT_DOUBLE_EQ(root.require<double>("d"), 1e-6);
  EXPECT_EQ(root.require<int>("i"), -42);
  EXPECT_TRUE(root.require<bool>("t"));
  EXPECT_FALSE(root.require<bool>("f"));
  const Vec3 v = root.require<Vec3>("v");
  EXPECT_DOUBLE_EQ(v.x(), 1.0);
  EXPECT_DOUBLE_EQ(v.y(), 2.5);
  EXPECT_DOUBLE_EQ(v.z(), -300.0);
  EXPECT_EQ(root.require<Vec3i>("vi"), Vec3i(1, -2, 3));
  EXPECT_EQ(root.require<std::vector<int>>("list"), (std::vector<int>{4, 5, 6, 7}));
  EXPECT_EQ(root.require<std::string>("s"), "linear");
}

TEST(ProblemSpec, ParseValueRejectsMalformedText) {
  EXPECT_THROW(parseValue<double>("1e-6x"), std::invalid_argument);
  EXPECT_THROW(parseValue<double>(""), std::invalid_argument);
  EXPECT_THROW(parseValue<int>("2.5"), std::invalid_argument);
  EXPECT_THROW(parseValue<bool>("yes"), std::invalid_argument);
  EXPECT_THROW(parseValue<Vec3>("[1, 2]"), std::invalid_argument);
  EXPECT_THROW(parseValue<Vec3>("[1, 2, 3, 4]"), std::invalid_argument);
  EXPECT_THROW(parseValue<Vec3>("1, 2, 3"), std::invalid_argument);
  EXPECT_THROW(parseValue<Vec3i>("[1, 2.5, 3]"), std::invalid_argument);
  EXPECT_THROW(parseValue<std::vector<int>>("[1, x]"), std::invalid_argument);
  EXPECT_TRUE(parseValue<bool>(" TRUE "));
}

TEST(ProblemSpec, ParseValueRejectsNonFiniteNumbers) {
  // strtod reads these; no input quantity may be NaN or infinite (1e400 overflows to infinity).
  for (const char* text : {"nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e400", "-1e400"}) {
    EXPECT_THROW(parseValue<double>(text), std::invalid_argument) << text;
    EXPECT_THROW(parseValue<Vec3>(std::string("[0, ") + text + ", 0]"), std::invalid_argument)
        << text;
  }
  EXPECT_EQ(parseValue<double>("-0"), 0.0);
  EXPECT_EQ(parseValue<double>("1e308"), 1e308);
}

TEST(ProblemSpec, EmptyInputIsAnInputErrorOnLine1) {
  for (const char* text : {"", "  \n", "<?xml version='1.0'?>"}) {
    const InputError e = expectInputError([&] { ProblemSpec::fromText(text, "empty.ups"); });
    EXPECT_EQ(e.line(), 1) << e.what();
    EXPECT_TRUE(startsWith(e.what(), "empty.ups:1: ")) << e.what();
  }
}

TEST(ProblemSpec, MalformedValueNamesTheTagLine) {
  auto spec = ProblemSpec::fromText(kValues, "values.ups");
  const PSNode root = spec->root();
  const InputError e = expectInputError([&] { root.require<Vec3>("list"); });
  EXPECT_EQ(e.line(), 8);
  EXPECT_TRUE(startsWith(e.what(), "values.ups:8: <list>:")) << e.what();
  EXPECT_TRUE(contains(e.what(), "expected a vector of 3 components")) << e.what();
  const InputError i = expectInputError([&] { root.require<int>("d"); });
  EXPECT_TRUE(startsWith(i.what(), "values.ups:2:")) << i.what();
}

TEST(ProblemSpec, RequireMissingNamesTheParentLine) {
  auto spec = ProblemSpec::fromText(kValues, "values.ups");
  const PSNode time = spec->root().requireChild("Time");
  const InputError e = expectInputError([&] { time.require<double>("maxTime"); });
  EXPECT_EQ(e.file(), "values.ups");
  EXPECT_EQ(e.line(), 12);
  EXPECT_TRUE(startsWith(e.what(), "values.ups:12:")) << e.what();
  EXPECT_TRUE(contains(e.what(), "<Time> requires a <maxTime> tag")) << e.what();
}

TEST(ProblemSpec, GetFallsBackOnlyWhenAbsent) {
  auto spec = ProblemSpec::fromText(kValues, "values.ups");
  const PSNode root = spec->root();
  EXPECT_DOUBLE_EQ(root.get<double>("absent", 3.0), 3.0);
  EXPECT_DOUBLE_EQ(root.get<double>("d", 3.0), 1e-6);
  EXPECT_EQ(root.get<std::string>("absent", "linear"), "linear");
  EXPECT_FALSE(root.find<int>("absent").has_value());
  EXPECT_FALSE(root.child("absent"));
}

TEST(ProblemSpec, CommentsInsideAValueAreSkipped) {
  auto spec = ProblemSpec::fromText(kValues, "values.ups");
  const PSNode root = spec->root();
  EXPECT_DOUBLE_EQ(root.require<double>("c"), 1.0);
  EXPECT_EQ(root.require<Vec3>("vc"), Vec3(1, 2, 3));
}

TEST(ProblemSpec, CheckAllUsedNamesTheUnreadTagWithItsLine) {
  const std::string text =
      "<Uintah_specification>\n"
      "  <Time>\n"
      "    <maxTime>1</maxTime>\n"
      "    <maxTiem>2</maxTiem>\n"
      "  </Time>\n"
      "  <Unread><inside/></Unread>\n"
      "</Uintah_specification>\n";
  auto spec = ProblemSpec::fromText(text, "unused.ups");
  EXPECT_DOUBLE_EQ(spec->root().requireChild("Time").require<double>("maxTime"), 1.0);
  const InputError e = expectInputError([&] { spec->checkAllUsed(); });
  EXPECT_EQ(e.line(), 4);
  EXPECT_TRUE(startsWith(e.what(), "unused.ups:4: unknown tag <maxTiem> in <Time>")) << e.what();
  // Every unread tag is listed; the children of an unread tag are not listed again.
  EXPECT_TRUE(contains(e.what(), "\nunused.ups:6: unknown tag <Unread> in <Uintah_specification>"))
      << e.what();
  EXPECT_FALSE(contains(e.what(), "<inside>")) << e.what();
}

TEST(ProblemSpec, CheckAllUsedPassesWhenEverythingWasRead) {
  auto spec = ProblemSpec::fromText(
      "<Uintah_specification><a>1</a><inert><deep><deeper/></deep></inert></Uintah_specification>",
      "used.ups");
  const PSNode root = spec->root();
  EXPECT_EQ(root.require<int>("a"), 1);
  root.acceptInert("inert");
  EXPECT_NO_THROW(spec->checkAllUsed());
}

TEST(ProblemSpec, ChildrenWhereMarksOnlyTheSelectedTags) {
  auto spec = ProblemSpec::fromText(
      "<Uintah_specification>\n"
      "  <geom_object>\n"
      "    <box/>\n"
      "    <colour>red</colour>\n"
      "    <box/>\n"
      "  </geom_object>\n"
      "</Uintah_specification>\n",
      "where.ups");
  const PSNode geom = spec->root().requireChild("geom_object");
  EXPECT_TRUE(geom.hasChildren());
  const auto boxes = geom.childrenWhere([](const std::string& tag) { return tag == "box"; });
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].line(), 3);
  EXPECT_EQ(boxes[1].line(), 5);
  EXPECT_FALSE(boxes[0].hasChildren());
  const InputError e = expectInputError([&] { spec->checkAllUsed(); });
  EXPECT_TRUE(startsWith(e.what(), "where.ups:4: unknown tag <colour> in <geom_object>"))
      << e.what();
}

const char* kUnsupported = R"(<Uintah_specification>
  <MPM>
    <do_scalar_diffusion>true</do_scalar_diffusion>
  </MPM>
</Uintah_specification>
)";

TEST(ProblemSpec, UnsupportedIsAnErrorByDefault) {
  auto spec = ProblemSpec::fromText(kUnsupported, "feature.ups");
  const PSNode flag = spec->root().requireChild("MPM").requireChild("do_scalar_diffusion");
  const InputError e = expectInputError([&] { flag.unsupported("scalar diffusion"); });
  EXPECT_EQ(e.line(), 3);
  EXPECT_TRUE(startsWith(e.what(), "feature.ups:3: scalar diffusion")) << e.what();
  EXPECT_TRUE(contains(e.what(), "--ignore-unsupported")) << e.what();
  EXPECT_TRUE(spec->warnings().empty());
}

TEST(ProblemSpec, UnsupportedIsAWarningWithIgnoreUnsupported) {
  auto spec = ProblemSpec::fromText(kUnsupported, "feature.ups", /*ignoreUnsupported=*/true);
  EXPECT_TRUE(spec->ignoreUnsupported());
  const PSNode flag = spec->root().requireChild("MPM").requireChild("do_scalar_diffusion");
  EXPECT_NO_THROW(flag.unsupported("scalar diffusion"));
  ASSERT_EQ(spec->warnings().size(), 1u);
  EXPECT_TRUE(startsWith(spec->warnings()[0], "feature.ups:3: scalar diffusion"))
      << spec->warnings()[0];
}

TEST(ProblemSpec, BrokenXmlIsAnInputErrorWithALine) {
  const InputError e = expectInputError([] {
    ProblemSpec::fromText(
        "<Uintah_specification>\n  <Time>\n    <maxTime>1\n  </Time>\n</Uintah_specification>\n",
        "broken.ups");
  });
  // The unclosed element's own line, not the line where the mismatch was noticed.
  EXPECT_EQ(e.line(), 3);
  EXPECT_TRUE(startsWith(e.what(), "broken.ups:3: malformed XML")) << e.what();
}

TEST(ProblemSpec, RootMustBeUintahSpecification) {
  const InputError e =
      expectInputError([] { ProblemSpec::fromText("<!-- c -->\n<Uintah_spec/>\n", "root.ups"); });
  EXPECT_EQ(e.line(), 2);
  EXPECT_TRUE(contains(e.what(), "the root element must be <Uintah_specification>")) << e.what();
}

TEST(ProblemSpec, AttributesAreTrimmedAndRequired) {
  auto spec = ProblemSpec::fromText(
      "<Uintah_specification>\n  <box label=\" a \"/>\n</Uintah_specification>", "attr.ups");
  const PSNode box = spec->root().requireChild("box");
  EXPECT_EQ(box.attribute("label").value_or(""), "a");
  EXPECT_FALSE(box.attribute("name").has_value());
  const InputError e = expectInputError([&] { box.requireAttribute("type"); });
  EXPECT_TRUE(startsWith(e.what(), "attr.ups:2:")) << e.what();
}

TEST(ProblemSpec, MissingFileIsAnInputError) {
  const InputError e = expectInputError([] { ProblemSpec("/nonexistent/dir/x.ups", false); });
  EXPECT_TRUE(contains(e.what(), "cannot open the input file")) << e.what();
}

}  // namespace
}  // namespace anode
