#include "simtree/report/detail/html.h"

#include <gtest/gtest.h>

#include "simtree/report/detail/json_tables.h"

namespace simtree::report {
namespace {

TEST(Html, EscapesText) {
  EXPECT_EQ(EscapeHtml("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
}

TEST(Html, ScriptTextCannotCloseItsElement) {
  EXPECT_EQ(EscapeScriptText("x = '</script>'; y = '</SCRIPT'; z = '<!--';"),
            "x = '<\\/script>'; y = '<\\/SCRIPT'; z = '<\\!--';");
  EXPECT_EQ(EscapeScriptText("a < b && c </div>"), "a < b && c </div>");
  EXPECT_EQ(EscapeJsonForScript(R"({"a":"</script><!--"})"), R"({"a":"\u003c/script>\u003c!--"})");
  const nlohmann::json back =
      nlohmann::json::parse(EscapeJsonForScript(R"({"a":"</script><!--"})"));
  EXPECT_EQ(back["a"], "</script><!--");
}

TEST(Html, FormatsNumbersAndBytes) {
  EXPECT_EQ(FormatNumber(1.23456, 2), "1.23");
  EXPECT_EQ(FormatNumber(std::nan(""), 2), "\xE2\x80\x93");
  EXPECT_EQ(FormatBytes(12), "12 B");
  EXPECT_EQ(FormatBytes(34'400), "34 kB");
  EXPECT_EQ(FormatBytes(12'345'678), "12.3 MB");
}

TEST(Html, TablesEscapeTheirCells) {
  HtmlTable table({"name", "value"});
  table.AddRow({"<b>", "1 & 2"});
  table.AddHtmlRow({"<i>x</i>", "y"});
  const std::string html = table.Html();
  EXPECT_NE(html.find("<td>&lt;b&gt;</td><td>1 &amp; 2</td>"), std::string::npos);
  EXPECT_NE(html.find("<td><i>x</i></td>"), std::string::npos);
  EXPECT_EQ(table.rows(), 2);
}

TEST(JsonTables, NestedObjectsBecomeHeadedTables) {
  const nlohmann::ordered_json doc = {
      {"version", 1},
      {"registration",
       {{"rotation_deg", 0.1234567},
        {"views", {{{"name", "a"}, {"err", 1.5}}, {{"name", "b"}, {"ok", true}}}}}},
      {"ranges", {1.07, 1.5}},
      {"note", nullptr}};
  const std::string html = JsonToHtmlTables(doc);
  EXPECT_NE(html.find("<td>version</td><td>1</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>ranges</td><td>[1.070, 1.500]</td>"), std::string::npos);
  EXPECT_NE(html.find("registration</h3>"), std::string::npos);
  EXPECT_NE(html.find("<td>rotation_deg</td><td>0.1235</td>"), std::string::npos);
  // An array of objects: one column per member, in the order met.
  EXPECT_NE(html.find("<th>name</th><th>err</th><th>ok</th>"), std::string::npos);
  EXPECT_NE(html.find("<td>b</td><td></td><td>true</td>"), std::string::npos);
  EXPECT_EQ(JsonValueText(nullptr), "\xE2\x80\x93");
  EXPECT_EQ(JsonValueText(15744.0), "15744");
  EXPECT_EQ(JsonValueText(123.456), "123.5");
}

}  // namespace
}  // namespace simtree::report
