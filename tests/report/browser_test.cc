// The report in a real browser: Debian's headless Chromium opens the page of a small result
// folder, its scripts run (three.js, Chart.js, the page's own), and the test reads what the page
// wrote: a status line without errors, and the tree's most moving node at two times.

#include <cstdlib>
#include <regex>

#include <gtest/gtest.h>

#include "report/report_fixtures.h"
#include "simtree/io/image_io.h"
#include "simtree/report/report.h"
#include "test_util.h"

namespace simtree::report {
namespace {

namespace fs = std::filesystem;

std::string FindChromium() {
  if (const char* given = std::getenv("SIMTREE_CHROMIUM")) return given;
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (fs::exists(p)) return p;
  }
  return "";
}

class ReportBrowser : public ::testing::Test {
 protected:
  void SetUp() override {
    chromium_ = FindChromium();
    if (chromium_.empty()) {
      GTEST_SKIP() << "chromium is not installed (Debian package chromium; "
                      "scripts/install-deps.sh installs it): the report is not opened in a browser";
    }
    dir_ = test::TempDir();
    test::WriteResultFolder(dir_ / "result");
    page_ = WriteReport(dir_ / "result").path;
  }

  // Runs headless Chromium on the page (with `hash`); returns its stdout.
  std::string Run(const std::string& hash, const std::string& mode, int budget_ms) {
    static int run = 0;
    const fs::path profile = dir_ / ("profile-" + std::to_string(++run));
    const fs::path out = dir_ / ("out-" + std::to_string(run) + ".txt");
    const std::string command = fmt::format(
        "timeout 90 \"{}\" --headless --no-sandbox --disable-gpu --enable-unsafe-swiftshader "
        "--disable-background-networking --disable-component-update --disable-sync "
        "--no-first-run --user-data-dir=\"{}\" --window-size=1280,800 "
        "--virtual-time-budget={} {} \"file://{}{}\" > \"{}\" 2> \"{}.err\"",
        chromium_, profile.string(), budget_ms, mode, fs::absolute(page_).string(), hash,
        out.string(), out.string());
    const int status = std::system(command.c_str());
    EXPECT_EQ(status, 0) << command << "\n" << test::ReadText(out.string() + ".err");
    return test::ReadText(out);
  }

  struct PageState {
    std::string status, state, viewer, charts;
    nlohmann::json probe;
  };
  PageState DumpDom(const std::string& hash, int budget_ms) {
    const std::string dom = Run(hash, "--dump-dom", budget_ms);
    PageState s;
    std::smatch m;
    const std::regex status_element(R"re(<div id="report-status"([^>]*)>([^<]*)</div>)re");
    if (std::regex_search(dom, m, status_element)) {
      const std::string attributes = m[1];
      s.status = m[2];
      std::smatch a;
      if (std::regex_search(attributes, a, std::regex(R"re(data-state="([^"]*)")re")))
        s.state = a[1];
      if (std::regex_search(attributes, a, std::regex(R"re(data-viewer="([^"]*)")re")))
        s.viewer = a[1];
      if (std::regex_search(attributes, a, std::regex(R"re(data-charts="([^"]*)")re")))
        s.charts = a[1];
    }
    if (std::regex_search(dom, m, std::regex(R"re(<pre id="viewer-probe"[^>]*>([^<]*)</pre>)re"))) {
      s.probe = nlohmann::json::parse(std::string(m[1]), nullptr, false);
    }
    return s;
  }

  std::string chromium_;
  fs::path dir_, page_;
};

Eigen::Vector3d Position(const nlohmann::json& probe) {
  return {probe["position"][0].get<double>(), probe["position"][1].get<double>(),
          probe["position"][2].get<double>()};
}

TEST_F(ReportBrowser, ThePageRendersWithoutErrors) {
  const PageState s = DumpDom("", 1500);
  EXPECT_EQ(s.state, "ok") << s.status;
  EXPECT_EQ(s.status.rfind("ok: ", 0), 0u) << s.status;
  EXPECT_EQ(s.viewer, "WebGL") << s.status;
  // The trajectories and one chart per link.
  EXPECT_GE(std::atoi(s.charts.c_str()), 3) << s.status;
  ASSERT_TRUE(s.probe.is_object()) << "no probe written";
}

TEST_F(ReportBrowser, TheAnimationMovesTheTree) {
  // Opened paused at two times: before the pull and while the rope holds the branch.
  const PageState rest = DumpDom("#t=0", 500);
  const PageState held = DumpDom("#t=0.9", 500);
  ASSERT_EQ(rest.state, "ok") << rest.status;
  ASSERT_EQ(held.state, "ok") << held.status;
  ASSERT_TRUE(rest.probe.is_object() && held.probe.is_object());
  EXPECT_EQ(rest.probe["node"], held.probe["node"]);
  EXPECT_GT((Position(held.probe) - Position(rest.probe)).norm(), 0.02)
      << rest.probe.dump() << " vs " << held.probe.dump();
  // Playing: the clock runs on the page's timers, and the node moves with it. Loading the page
  // (three.js, software WebGL) spends virtual time too, about 2 s of a 2.5 s budget on a loaded
  // 2-core machine: a budget of 6 s leaves the clock seconds to run.
  const PageState playing = DumpDom("", 6000);
  ASSERT_EQ(playing.state, "ok") << playing.status;
  EXPECT_GT(playing.probe["t"].get<double>(), 0.5) << playing.probe.dump();
}

TEST_F(ReportBrowser, TwoScreenshotsOfTheViewDiffer) {
  const auto shot = [&](const std::string& hash, const std::string& name) {
    const fs::path png = dir_ / name;
    Run(hash, "--screenshot=\"" + png.string() + "\"", 800);
    return ReadColorImage(png);
  };
  const RgbImage a = shot("#view&t=0", "rest.png");
  const RgbImage b = shot("#view&t=0.9", "held.png");
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  // "#view" shows the 3D view alone: the tree covers part of it (pixels far from the background,
  // 0xe9eef2), and the pull moves it.
  const int background[3] = {0xe9, 0xee, 0xf2};
  long changed = 0, tree = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      int d = 0, e = 0;
      for (int c = 0; c < 3; ++c) {
        d = std::max(d, std::abs(a.at(x, y, c) - b.at(x, y, c)));
        e = std::max(e, std::abs(a.at(x, y, c) - background[c]));
      }
      if (d > 40) ++changed;
      if (e > 60) ++tree;
    }
  }
  EXPECT_GT(tree, 500) << "no tree in the screenshot of the view";
  EXPECT_GT(changed, 100) << "the tree did not move between the screenshots";
}

}  // namespace
}  // namespace simtree::report
