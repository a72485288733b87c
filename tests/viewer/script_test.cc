// Scripted input: every action parses with its numbers, and mistakes name the line.

#include "simtree/viewer/detail/script.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::viewer {
namespace {

using ::testing::HasSubstr;

std::string Error(const std::string& text) {
  try {
    ParseScript(text, "actions.txt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Script, ParsesEveryAction) {
  const auto actions = ParseScript(
      "# a pull and release\n"
      "pick 640 300\n"
      "pick-branch 12@0.5\n"
      "pick-branch 3\n"
      "drag 700 500 20   # over 20 frames\n"
      "drag 10 10\n"
      "drag-by -5 7 3\n"
      "wait 30\n\n"
      "screenshot out/a.png\n"
      "release\n"
      "hover 5 6\n"
      "key space\n"
      "play\npause\nstep\nreset\n"
      "wind on\nwind 7.5\n"
      "leaves off\n"
      "material level 2 damping 0.05\n"
      "orbit 30 -10\n"
      "zoom 0.8\n"
      "quit\n",
      "actions.txt");
  ASSERT_EQ(actions.size(), 22u);
  EXPECT_EQ(actions[0].verb, ScriptVerb::kPick);
  EXPECT_EQ(actions[0].line, 2);
  EXPECT_EQ(actions[0].numbers, (std::vector<double>{640, 300}));
  EXPECT_EQ(actions[1].branch, 12);
  EXPECT_DOUBLE_EQ(actions[1].arc_length, 0.5);
  EXPECT_EQ(actions[2].branch, 3);
  EXPECT_LT(actions[2].arc_length, 0);
  EXPECT_EQ(actions[3].numbers, (std::vector<double>{700, 500, 20}));
  EXPECT_EQ(actions[4].numbers[2], 1);
  EXPECT_EQ(actions[5].verb, ScriptVerb::kDragBy);
  EXPECT_EQ(actions[5].numbers, (std::vector<double>{-5, 7, 3}));
  EXPECT_EQ(actions[7].text, "out/a.png");
  EXPECT_TRUE(actions[15].on);
  EXPECT_EQ(actions[16].numbers, (std::vector<double>{7.5}));
  EXPECT_EQ(actions[18].verb, ScriptVerb::kMaterial);
  EXPECT_FALSE(actions[17].on);
  EXPECT_EQ(actions[18].scope, MaterialScope::kLevel);
  EXPECT_EQ(actions[18].property, MaterialProperty::kDamping);
  EXPECT_EQ(actions[18].branch, 2);
  EXPECT_EQ(actions[21].verb, ScriptVerb::kQuit);
}

TEST(Script, MistakesNameTheLine) {
  EXPECT_THAT(Error("wait 1\njump 3\n"), HasSubstr("actions.txt: line 2: unknown action \"jump\""));
  EXPECT_THAT(Error("pick 1\n"), HasSubstr("line 1: pick: expected \"pick X Y\""));
  EXPECT_THAT(Error("pick 1 nan\n"), HasSubstr("expected a finite number for Y"));
  EXPECT_THAT(Error("wait -2\n"), HasSubstr("expected FRAMES >= 0"));
  EXPECT_THAT(Error("drag 1 2 0\n"), HasSubstr("expected FRAMES >= 1"));
  EXPECT_THAT(Error("pick-branch x@1\n"), HasSubstr("expected an integer"));
  EXPECT_THAT(Error("pick-branch 3@-1\n"), HasSubstr("expected BRANCH >= 0 and S >= 0"));
  EXPECT_THAT(Error("leaves maybe\n"), HasSubstr("expected on or off"));
  EXPECT_THAT(Error("wind -3\n"), HasSubstr("expected a speed >= 0"));
  EXPECT_THAT(Error("material tree 1 damping 3\n"), HasSubstr("expected branch or level"));
  EXPECT_THAT(Error("material branch 1 colour 3\n"), HasSubstr("frequency, damping or stiffness"));
  EXPECT_THAT(Error("zoom 0\n"), HasSubstr("expected a factor > 0"));
  EXPECT_THAT(Error("quit now\n"), HasSubstr("expected \"quit\""));
  EXPECT_TRUE(ParseScript("", "empty.txt").empty());
}

}  // namespace
}  // namespace simtree::viewer
