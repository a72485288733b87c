#include "simtree/report/report.h"

#include <unistd.h>

#include <regex>

#include <gtest/gtest.h>

#include "report/report_fixtures.h"
#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree::report {
namespace {

namespace fs = std::filesystem;

// The folder made once per test process (a simulation and an identification: about a second).
// CTest runs each test in its own process, several at once: the folder is the process's own, so
// one test never reads it while another rewrites it.
const fs::path& FullResult() {
  static const fs::path root = [] {
    const fs::path dir =
        fs::path(SIMTREE_TEST_TMP_DIR) / ("process_" + std::to_string(::getpid())) / "full_result";
    fs::remove_all(dir);
    fs::create_directories(dir);
    test::WriteResultFolder(dir);
    return dir;
  }();
  return root;
}

bool SectionPresent(const std::string& html, const std::string& id) {
  return html.find("<section id=\"" + id + "\" data-present=\"yes\">") != std::string::npos;
}

TEST(Report, ShowsEverySectionWhoseFilesAreThere) {
  ReportResult result;
  const std::string html = BuildReportHtml(FullResult(), {}, &result);
  for (const char* id : {"stages", "animation", "registration", "reconstruction", "tracking",
                         "identification", "branches", "render", "paper", "eval"}) {
    const SectionReport* s = result.Find(id);
    ASSERT_NE(s, nullptr) << id;
    EXPECT_TRUE(s->present) << id;
    EXPECT_TRUE(SectionPresent(html, id)) << id;
  }
  // The views need preprocess/, which the fixture does not have: said on the page.
  ASSERT_NE(result.Find("views"), nullptr);
  EXPECT_FALSE(result.Find("views")->present);
  EXPECT_NE(html.find("preprocess/preprocess.json is not in the result"), std::string::npos);
  // What each section shows.
  EXPECT_NE(html.find("no markers &lt;found&gt;"), std::string::npos);  // run.json, escaped
  EXPECT_NE(html.find("status-failed"), std::string::npos);
  EXPECT_EQ(html.find("run.json could not be read"), std::string::npos);  // "wall_s": null is fine
  EXPECT_NE(html.find("id=\"viewer-canvas\""), std::string::npos);
  EXPECT_NE(html.find("id=\"chart-trajectories\""), std::string::npos);
  EXPECT_NE(html.find("id=\"chart-spectrum-0\""), std::string::npos);
  EXPECT_NE(html.find("<th>f bend u (Hz)</th>"), std::string::npos);
  EXPECT_NE(html.find("source-measured"), std::string::npos);
  EXPECT_NE(html.find("paper Table IV: Acer rubrum"), std::string::npos);
  EXPECT_NE(html.find("this run (eval.json, against the truth)"), std::string::npos);
  EXPECT_NE(html.find("normalised_rmse"), std::string::npos);
  // 4 overlay frames of 8, 6 render frames of 20, 2 pictures: 12 images.
  EXPECT_EQ(std::count(html.begin(), html.end(), '\0'), 0);
  size_t images = 0;
  for (size_t p = html.find("<img "); p != std::string::npos; p = html.find("<img ", p + 1)) {
    ++images;
  }
  EXPECT_EQ(images, 12u);
  EXPECT_TRUE(result.animation.present);
  EXPECT_EQ(result.animation.frames, 121);
  EXPECT_EQ(result.animation.sent_frames, 121);
  EXPECT_GT(result.library_bytes, 1'000'000);
  EXPECT_EQ(result.bytes, static_cast<int64_t>(html.size()));
  EXPECT_NE(html.find("<title>simtree report: full_result</title>"), std::string::npos);
  const std::string slash = BuildReportHtml(FullResult().string() + "/", {});
  EXPECT_NE(slash.find("<title>simtree report: full_result</title>"), std::string::npos);
}

TEST(Report, TheDataBlockHasWhatTheChartsAndTheViewerRead) {
  const std::string html = BuildReportHtml(FullResult(), {});
  const std::string open = "<script type=\"application/json\" id=\"simtree-data\">";
  const size_t begin = html.find(open) + open.size();
  const size_t end = html.find("</script>", begin);
  const nlohmann::json data = nlohmann::json::parse(html.substr(begin, end - begin));
  ASSERT_TRUE(data.contains("trajectories"));
  EXPECT_EQ(data["trajectories"]["times"].size(), 121u);
  ASSERT_TRUE(data.contains("spectra"));
  const nlohmann::json& links = data["spectra"]["links"];
  ASSERT_FALSE(links.empty());
  int with_values = 0;
  for (const auto& l : links) {
    if (!l["frequency_hz"].is_null()) ++with_values;
    if (l["channels"].empty()) continue;
    EXPECT_EQ(l["channels"].size(), 2u);
    EXPECT_GT(l["bin_hz"].get<double>(), 0.0);
  }
  EXPECT_GT(with_values, 0);
  ASSERT_TRUE(data.contains("animation"));
  EXPECT_EQ(data["animation"]["nodes"], 65);  // ThreeLevelTree: 31 + 16 + 7 + 11 nodes
  EXPECT_TRUE(data["animation"].contains("rope"));
}

TEST(Report, AnEmptyFolderGivesNotesNotErrors) {
  const fs::path dir = test::TempDir();
  const ReportResult result = WriteReport(dir, {});
  EXPECT_TRUE(fs::exists(dir / "report.html"));
  EXPECT_EQ(result.path, dir / "report.html");
  for (const SectionReport& s : result.sections) {
    if (s.id == "paper") continue;  // the paper's own numbers are always there
    EXPECT_FALSE(s.present) << s.id;
    EXPECT_FALSE(s.notes.empty()) << s.id;
  }
  const std::string html = test::ReadText(dir / "report.html");
  EXPECT_NE(html.find("run.json is not in this result folder"), std::string::npos);
  EXPECT_NE(html.find("simulate/nodes.bin is not in the result"), std::string::npos);
  EXPECT_NE(html.find("eval/eval.json is not in the result"), std::string::npos);
  EXPECT_NE(html.find("Missing or left out"), std::string::npos);
}

TEST(Report, AFileThatDoesNotReadBecomesANote) {
  const fs::path dir = test::TempDir();
  test::WriteJson(dir / "run.json", {{"format", "simtree.run"}, {"version", 7}});
  fs::create_directories(dir / "identify");
  test::WriteText(dir / "identify/materials.json", "{ not json");
  fs::create_directories(dir / "render");
  test::WriteText(dir / "render/000000.png", "not a png");
  ReportResult result;
  const std::string html = BuildReportHtml(dir, {}, &result);
  EXPECT_NE(html.find("run.json could not be read"), std::string::npos);
  EXPECT_NE(html.find("version: expected 1"), std::string::npos);
  EXPECT_NE(html.find("identify/materials.json could not be read"), std::string::npos);
  EXPECT_NE(html.find("render/000000.png could not be read"), std::string::npos);
}

TEST(Report, NothingInThePageReachesTheNetwork) {
  const std::string html = BuildReportHtml(FullResult(), {});
  // Every src and href is inline data or an anchor in the page.
  const std::regex attribute(R"re((src|href)\s*=\s*"([^"]*)")re");
  int attributes = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), attribute);
       it != std::sregex_iterator(); ++it) {
    const std::string value = (*it)[2];
    EXPECT_TRUE(value.rfind("data:", 0) == 0 || value.rfind("#", 0) == 0) << value.substr(0, 80);
    ++attributes;
  }
  EXPECT_GT(attributes, 10);
  // No "http" outside the inlined libraries (whose licence headers and XML namespaces name URLs
  // but load nothing), and no import, fetch or XMLHttpRequest in the page's own code.
  std::string own = html;
  for (size_t p = own.find("<script data-library="); p != std::string::npos;
       p = own.find("<script data-library=")) {
    own.erase(p, own.find("</script>", p) + 9 - p);
  }
  EXPECT_EQ(own.find("http"), std::string::npos);
  EXPECT_EQ(own.find("fetch("), std::string::npos);
  EXPECT_EQ(own.find("XMLHttpRequest"), std::string::npos);
  EXPECT_EQ(own.find("@import"), std::string::npos);
  EXPECT_EQ(own.find("url("), std::string::npos);
}

TEST(Report, StaysWithinItsSizeBudget) {
  const fs::path dir = test::TempDir();
  test::WriteSimulatedStages(dir, 12.0);  // 361 frames
  ReportOptions options;
  options.max_bytes = 2'000'000;  // the libraries alone are 1.1 MB
  options.animation_max_bytes = 120'000;
  ReportResult result;
  const std::string html = BuildReportHtml(dir, options, &result);
  EXPECT_LE(static_cast<int64_t>(html.size()), options.max_bytes);
  EXPECT_TRUE(result.animation.present);
  EXPECT_LE(result.animation.bytes, options.animation_max_bytes);
  EXPECT_GT(result.animation.frame_stride * result.animation.node_stride, 1);
  EXPECT_GE(result.animation.sent_fps, options.min_animation_fps);
  EXPECT_FALSE(result.Find("animation")->notes.empty());  // says it was thinned
  // Images past their budget are left out with a note, not an error.
  options.image_max_bytes = 0;
  fs::create_directories(dir / "render");
  WritePng(test::TestPicture(64, 64, 1), dir / "render/000000.png");
  const std::string without = BuildReportHtml(dir, options, &result);
  EXPECT_EQ(without.find("<img "), std::string::npos);
  EXPECT_NE(without.find("reached their budget"), std::string::npos);
}

TEST(Report, AMissingLibraryIsAClearErrorUnlessAllowed) {
  const fs::path empty = test::TempDir();
  ReportOptions options;
  options.javascript_dir = empty;
  try {
    BuildReportHtml(FullResult(), options);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("libjs-three"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("libjs-chart.js"), std::string::npos) << e.what();
  }
  options.allow_missing_javascript = true;
  ReportResult result;
  const std::string html = BuildReportHtml(FullResult(), options, &result);
  EXPECT_EQ(html.find("data-library="), std::string::npos);
  EXPECT_NE(html.find("The 3D view needs the JavaScript libraries"), std::string::npos);
  EXPECT_EQ(result.library_bytes, 0);
}

TEST(Report, OptionsAreValidated) {
  EXPECT_NO_THROW(ReportOptions{}.Validate());
  ReportOptions o;
  o.max_bytes = 1000;
  EXPECT_THROW(o.Validate(), Error);
  o = {};
  o.min_animation_fps = 0;
  EXPECT_THROW(o.Validate(), Error);
  o = {};
  o.max_image_width = 10;
  EXPECT_THROW(o.Validate(), Error);
  EXPECT_THROW(WriteReport(test::TempDir() / "no-such-folder"), InputError);
}

TEST(Report, IsDeterministicAndWrittenWhole) {
  const fs::path out = test::TempDir() / "r.html";
  ReportOptions options;
  options.output = out;
  const ReportResult a = WriteReport(FullResult(), options);
  const std::string first = test::ReadText(out);
  WriteReport(FullResult(), options);
  EXPECT_EQ(test::ReadText(out), first);
  EXPECT_EQ(a.bytes, static_cast<int64_t>(first.size()));
  EXPECT_EQ(std::distance(fs::directory_iterator(out.parent_path()), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace simtree::report
