// Showing a run to people and their tools: `vdcloth report`'s page opened in a real browser
// (Debian's headless Chromium) loads without an error, draws the cloth as the project's own
// renderer does, changes frame through its timeline and plots the runs' own numbers; bad inputs
// exit 2 with nothing written; a run's log.txt; the Blender add-on in Debian's Blender.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"
#include "app/report_command.hpp"
#include "app/report_data.hpp"
#include "app/run_frames.hpp"
#include "core/error.hpp"
#include "io/ply.hpp"
#include "scene/scene.hpp"
#include "support/process_output.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A sheet hanging above a ball, seen by a camera that cuts at 0.08 s (frame 2), with depth of
// field (focused on its target) and motion blur.
const char* kScene =
    R"({"frames": 4, "substeps": 2, "remeshing": {"size": [0.06, 0.5]},)"
    R"( "camera": {"fov": 40, "width": 320, "height": 240, "focus_distance": "target", "f_stop": 4, "shutter": 0.5, "keys": [)"
    R"({"time": 0, "position": [0.5, 0.6, 1.6], "target": [0.5, 0.0, -0.5]},)"
    R"({"time": 0.08, "position": [0.6, 0.9, 1.4], "target": [0.5, 0.0, -0.5], "cut": true}]},)"
    R"( "obstacles": [{"name": "ball", "mesh": {"sphere": {"radius": 0.2, "subdivisions": 2}}, "transform": {"translate": [0.5, -0.5, -0.5]}}],)"
    R"( "garments": [{"name": "s", "mesh": {"grid": {"size": [1, 1], "cells": [6, 6]}}, "material": "cotton.json",)"
    R"( "handles": [{"uv": [[0, 1], [1, 1]]}]}]})";

using test::capture;
using test::Output;

// Debian's headless Chromium (chromium-headless-shell), or the full browser.
std::string browser() {
  for (const char* name : {"chromium-headless-shell", "chromium"})
    if (capture(std::string("command -v ") + name + " 2>/dev/null").status == 0) return name;
  return "";
}

std::string unescape_html(std::string s) {
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&amp;", "&"}}) {
    for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
  }
  return s;
}

class ReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdcloth_report_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    write("cotton.json", R"({"name": "c", "density": 0.13, "stretch": {"warp": 5000, "weft": 3500, "shear": 300}, "bending": 1e-5})");
    scene_ = write("scene.json", kScene);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  int cli(std::vector<std::string> args) {
    out_.str("");
    err_.str("");
    return run_cli(args, out_, err_, false);
  }
  // A run of the scene in `mode` into dir_/name.
  std::string run(const std::string& mode, const std::string& name) {
    const std::string out = (dir_ / name).string();
    EXPECT_EQ(cli({"run", scene_, "--mode", mode, "--out", out, "--threads", "1"}), kExitOk) << err_.str();
    return out;
  }

  // What the report's page found when it checked itself (index.html#selftest) in the browser
  // `name`; the browser's log in dir_/browser.log. Null (and a failure) when it did not finish.
  // Root in a container: no sandbox, and shared memory in /tmp rather than a small /dev/shm.
  json open_page(const std::string& name, const fs::path& page) {
    const std::string command = name + " --no-sandbox --disable-dev-shm-usage --enable-unsafe-swiftshader --enable-logging=stderr --v=0 --user-data-dir='" +
                                (dir_ / "browser").string() + "' --virtual-time-budget=30000 --dump-dom 'file://" +
                                fs::absolute(page).string() + "#selftest' 2>'" + (dir_ / "browser.log").string() + "'";
    const Output dom = capture(command);
    EXPECT_EQ(dom.status, 0) << command;
    const std::string open = "<pre id=\"selftest-result\">";
    const std::size_t start = dom.text.find(open), end = dom.text.find("</pre>", start);
    if (start == std::string::npos || end == std::string::npos) {
      ADD_FAILURE() << "the page's check did not finish:\n" << dom.text.substr(0, 2000);
      return nullptr;
    }
    return json::parse(unescape_html(dom.text.substr(start + open.size(), end - start - open.size())));
  }

  fs::path dir_;
  std::string scene_;
  std::ostringstream out_, err_;
};

// The vertices of each mesh of a written frame, from its OBJ ("v" lines).
std::map<std::string, int> obj_vertices(const FrameFiles& files) {
  std::map<std::string, int> counts;
  for (const auto& [name, path] : files) {
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) counts[name] += line.rfind("v ", 0) == 0;
  }
  return counts;
}

// The cells of one CSV line.
std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
  return cells;
}

// A run's stats.csv: its header's cells and its rows' cells.
struct StatsTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  }
};

StatsTable read_stats(const std::string& run_dir) {
  std::ifstream in(run_dir + "/stats.csv");
  StatsTable t;
  std::string line;
  std::getline(in, line);
  t.header = csv_cells(line);
  while (std::getline(in, line)) t.rows.push_back(csv_cells(line));
  return t;
}

// A stats.csv column.
std::vector<double> stats_column(const std::string& run_dir, const std::string& column) {
  const StatsTable t = read_stats(run_dir);
  std::vector<double> values;
  for (const auto& row : t.rows) values.push_back(std::stod(row.at(t.column(column))));
  return values;
}

// Sets a stats.csv column to `values`, a row each.
void set_stats_column(const std::string& run_dir, const std::string& column, const std::vector<int>& values) {
  StatsTable t = read_stats(run_dir);
  ASSERT_EQ(t.rows.size(), values.size());
  std::string text;
  auto add = [&](const std::vector<std::string>& cells) {
    for (std::size_t k = 0; k < cells.size(); ++k) text += (k ? "," : "") + cells[k];
    text += "\n";
  };
  add(t.header);
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    t.rows[r].at(t.column(column)) = std::to_string(values[r]);
    add(t.rows[r]);
  }
  std::ofstream(run_dir + "/stats.csv") << text;
}

TEST_F(ReportTest, TheReportOpensInABrowserAndShowsTheRuns) {
  const std::string name = browser();
  ASSERT_FALSE(name.empty()) << "no headless Chromium: scripts/install-deps.sh installs chromium-headless-shell";
  const std::string view = run("view", "view"), fixed = run("fixed", "fixed");
  // The view run's group at the far level of detail on frames 2 and 3 (its camera is too near
  // for it: the column is set by hand), for the page's plot of it.
  set_stats_column(view, "far_groups", {0, 1, 1, 0});
  ASSERT_EQ(cli({"report", view, "--compare", fixed}), kExitOk) << err_.str();
  const fs::path page = fs::path(view) / "report" / "index.html";
  ASSERT_TRUE(fs::exists(page));
  for (const char* lib : {"three.min.js", "OrbitControls.js", "chart.min.js"}) EXPECT_TRUE(fs::exists(fs::path(view) / "report" / "lib" / lib)) << lib;

  const json result = open_page(name, page);
  ASSERT_TRUE(result.is_object());

  // No error in the page, nothing on the browser's console but its WebGL performance notes (the
  // check reads pixels back).
  EXPECT_TRUE(result["errors"].empty()) << result["errors"].dump();
  std::ifstream log(dir_ / "browser.log");
  for (std::string line; std::getline(log, line);) {
    if (line.find(":CONSOLE") != std::string::npos) {
      EXPECT_NE(line.find("GL Driver Message"), std::string::npos) << line;
    }
  }

  // The first frame drawn, with each run's meshes as written, its cloth covering the pixels the
  // project's renderer gives it through the same camera (antialiased edges aside).
  const std::map<int, FrameFiles> view_frames = read_frame_files(view), fixed_frames = read_frame_files(fixed);
  ASSERT_EQ(result["frames"], json({0, 1, 2, 3, 4}));
  const json& first = result["shown"][0];
  EXPECT_EQ(first["frames"], json({0, 0}));
  EXPECT_EQ(first["vertices"][0], json(obj_vertices(view_frames.at(0))));
  EXPECT_EQ(first["vertices"][1], json(obj_vertices(fixed_frames.at(0))));
  const Scene scene = load_scene(scene_);
  auto cloth_pixels = [&](int frame) {
    FrameFiles cloth{{"cloth_s", view_frames.at(frame).at("cloth_s")}};
    const DrawnFrame drawn = draw_frame(scene.cameras.front().path.at(frame * scene.frame_time), cloth, 1.0);
    return static_cast<double>(std::count(drawn.pixels.mesh.begin(), drawn.pixels.mesh.end(), 0));
  };
  const double expected_first = cloth_pixels(0);
  ASSERT_GT(expected_first, 2000);  // the sheet fills a good part of the 320 x 240 picture
  EXPECT_NEAR(first["cloth_pixels"].get<double>(), expected_first, 0.06 * expected_first);
  EXPECT_GT(first["pixels"].get<double>(), first["cloth_pixels"].get<double>() + 200);  // the ball too

  // The timeline dragged to the last frame: the label, the meshes and the picture follow.
  const json& last = result["shown"][1];
  EXPECT_EQ(last["frames"], json({4, 4}));
  EXPECT_NE(last["label"].get<std::string>().find("frame 4 "), std::string::npos) << last["label"];
  EXPECT_NE(last["label"].get<std::string>().find("shot 1"), std::string::npos) << last["label"];
  EXPECT_EQ(last["vertices"][0], json(obj_vertices(view_frames.at(4))));
  EXPECT_NE(last["vertices"][0], first["vertices"][0]);  // remeshed as it fell
  EXPECT_NEAR(last["cloth_pixels"].get<double>(), cloth_pixels(4), 0.06 * cloth_pixels(4));
  EXPECT_GT(result["shown"][2]["cloth_pixels"].get<double>(), 0.9 * last["cloth_pixels"].get<double>());  // view colours, wireframe
  // Coloured by what set each face's resolution: the page holds the PLY's reasons.
  const json& by_reason = result["shown"][3];
  EXPECT_GT(by_reason["cloth_pixels"].get<double>(), 0.9 * last["cloth_pixels"].get<double>());
  std::map<std::string, int> reasons;
  const PlyFaceValues ply = read_ply_with_face_values(fs::path(view_frames.at(4).at("cloth_s")).replace_extension(".ply").string());
  for (const double r : ply.more.at("reason")) ++reasons[std::to_string(static_cast<int>(r))];
  EXPECT_EQ(by_reason["reasons"]["cloth_s"], json(reasons));

  // The plots hold the runs' stats.csv; the time breakdown, its timed parts and the rest of the
  // frame's wall time (none where the parts, timed across threads, add up to more).
  EXPECT_EQ(result["plots"]["faces"], json({stats_column(view, "faces"), stats_column(fixed, "faces")}));
  EXPECT_EQ(result["plots"]["seconds"], json({stats_column(view, "seconds"), stats_column(fixed, "seconds")}));
  const std::vector<double> seconds = stats_column(view, "seconds");
  const json& parts = result["plots"]["breakdown"][0];
  const char* timed[] = {"assemble_seconds", "solve_seconds", "remesh_seconds", "collision_seconds", "view_seconds"};
  ASSERT_EQ(parts.size(), std::size(timed) + 1);
  std::vector<double> sum(seconds.size(), 0.0);
  for (std::size_t k = 0; k < std::size(timed); ++k) {
    const std::vector<double> column = stats_column(view, timed[k]);
    EXPECT_EQ(parts[k], json(column)) << timed[k];
    for (std::size_t f = 0; f < sum.size(); ++f) sum[f] += column[f];
  }
  for (std::size_t f = 0; f < seconds.size(); ++f) EXPECT_NEAR(parts.back()[f].get<double>(), std::max(0.0, seconds[f] - sum[f]), 1e-9) << "frame " << f + 1;
  EXPECT_EQ(result["plots"]["cuts"], json({2}));
  EXPECT_EQ(result["plots"]["far"], json({std::vector<double>{0, 1, 1, 0}, stats_column(fixed, "far_groups")}));
  const std::string summary = result["tables"]["summary"];
  for (const char* says : {"view", "fixed", "done", "cores"}) EXPECT_NE(summary.find(says), std::string::npos) << says << " in\n" << summary;
  EXPECT_NE(result["tables"]["log"].get<std::string>().find("0 message(s)"), std::string::npos) << result["tables"]["log"];

  // A frame script gone: the page says it could not show that frame.
  fs::remove(fs::path(view) / "report" / "data" / "run0" / "0004.js");
  const json broken = open_page(name, page);
  ASSERT_FALSE(broken["errors"].empty());
  EXPECT_NE(broken["errors"][0].get<std::string>().find("cannot load"), std::string::npos) << broken["errors"];
  EXPECT_NE(broken["errors"][0].get<std::string>().find("data/run0/0004.js"), std::string::npos) << broken["errors"];
}

TEST_F(ReportTest, BadInputsExitTwoWithNothingWritten) {
  EXPECT_EQ(cli({"report"}), kExitBadInput);
  EXPECT_EQ(cli({"report", (dir_ / "nowhere").string()}), kExitBadInput);
  EXPECT_NE(err_.str().find("nowhere/summary.json"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(dir_ / "nowhere"));
  EXPECT_EQ(cli({"report", "--help"}), kExitOk);
  EXPECT_NE(out_.str().find("--compare"), std::string::npos);

  const std::string view = run("view", "view");
  EXPECT_EQ(cli({"report", view, "--every", "0"}), kExitBadInput);
  // Something else where the report would go is left alone.
  fs::create_directories(dir_ / "notes");
  write("notes/keep.txt", "mine");
  EXPECT_EQ(cli({"report", view, "--out", (dir_ / "notes").string()}), kExitBadInput);
  EXPECT_NE(err_.str().find("not a vdcloth report"), std::string::npos) << err_.str();
  EXPECT_TRUE(fs::exists(dir_ / "notes" / "keep.txt"));
  // A damaged stats.csv is named with its line; no report is left.
  std::ofstream(fs::path(view) / "stats.csv", std::ios::app) << "5,12,abc\n";
  EXPECT_EQ(cli({"report", view}), kExitBadInput);
  EXPECT_NE(err_.str().find("stats.csv"), std::string::npos) << err_.str();
  EXPECT_NE(err_.str().find("line 6"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(fs::path(view) / "report"));
  EXPECT_FALSE(fs::exists(fs::path(view) / "report.partial"));
  // Without Debian's libraries: the package to install.
  EXPECT_THROW(
      {
        try {
          report_command({view}, out_, (dir_ / "no-javascript").string());
        } catch (const UsageError& e) {
          EXPECT_NE(std::string(e.what()).find("libjs-three"), std::string::npos) << e.what();
          throw;
        }
      },
      UsageError);
}

// A run without frame meshes or without a camera still has its report, which says what it lacks.
TEST_F(ReportTest, ThinRunsGetAReportThatSaysWhatItLacks) {
  const std::string bare = (dir_ / "bare").string();
  ASSERT_EQ(cli({"run", scene_, "--out", bare, "--threads", "1", "--frames", "2", "--mesh-every", "0"}), kExitOk) << err_.str();
  ASSERT_EQ(cli({"report", bare}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find("no frame meshes (runs made with --mesh-every 0)"), std::string::npos) << out_.str();
  EXPECT_TRUE(fs::exists(fs::path(bare) / "report" / "data" / "runs.js"));
  EXPECT_FALSE(fs::exists(fs::path(bare) / "report" / "data" / "run0" / "0001.js"));

  std::string no_camera = kScene;
  const std::size_t camera = no_camera.find(R"( "camera")"), obstacles = no_camera.find(R"( "obstacles")");
  no_camera.erase(camera, obstacles - camera);
  const std::string path = write("no-camera.json", no_camera), out = (dir_ / "no-camera").string();
  ASSERT_EQ(cli({"run", path, "--out", out, "--threads", "1", "--frames", "1"}), kExitOk) << err_.str();
  ASSERT_EQ(cli({"report", out}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find("has no camera.json (its scene has no camera): the 3D view has the orbit camera only"), std::string::npos)
      << out_.str();
  EXPECT_TRUE(fs::exists(fs::path(out) / "report" / "data" / "run0" / "0001.js"));
}

// A run's warnings go to its log.txt as to the error stream, those of its setup (before the
// output directory is made ready) too; a new run in the same directory starts it afresh.
TEST_F(ReportTest, ARunKeepsItsWarningsInLogTxt) {
  std::string crossing = kScene;
  const std::string ball_below = R"("translate": [0.5, -0.5, -0.5])", ball_through = R"("translate": [0.5, 0.0, -0.5])";
  crossing.replace(crossing.find(ball_below), ball_below.size(), ball_through);
  const std::string path = write("crossing.json", crossing);
  const std::string out = (dir_ / "run").string();
  ASSERT_EQ(cli({"run", path, "--out", out, "--frames", "1", "--threads", "1"}), kExitOk) << err_.str();
  const std::string warning = "frame 0: untangling 0 cloth-cloth and ";
  ASSERT_NE(err_.str().find(warning), std::string::npos) << err_.str();
  std::ifstream log(fs::path(out) / "log.txt");
  const std::string logged((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(logged.find(warning), std::string::npos) << logged;
  const std::string errors = err_.str();
  EXPECT_EQ(std::count(logged.begin(), logged.end(), '\n'), std::count(errors.begin(), errors.end(), '\n')) << "every line once:\n" << logged;
  ASSERT_EQ(cli({"run", scene_, "--out", out, "--frames", "1", "--threads", "1"}), kExitOk) << err_.str();
  EXPECT_EQ(err_.str(), "");
  EXPECT_EQ(fs::file_size(fs::path(out) / "log.txt"), 0u);
}

// The Blender add-on (tools/blender/vdcloth_import.py) loads a run into Debian's Blender, run
// headless: tools/blender/check_import.py finds every object's vertex and face counts at every
// frame (counted from the OBJ's lines), the pattern UVs, the view factors and the camera (with
// its cut, its focus and its lens) as the run wrote them.
TEST_F(ReportTest, BlenderLoadsTheRunAsItWasWritten) {
  ASSERT_EQ(capture("command -v blender >/dev/null 2>&1").status, 0) << "no blender: scripts/install-deps.sh installs it";
  const std::string view = run("view", "view");
  const std::string command = "blender -b --factory-startup --python '" + std::string(VDCLOTH_SOURCE_DIR) +
                              "/tools/blender/check_import.py' -- '" + view + "' 2>&1";
  const Output good = capture(command);
  EXPECT_EQ(good.status, 0) << good.text;
  // Five frames (0 to 4) of the sheet and the ball; the camera at each.
  EXPECT_NE(good.text.find("check_import: 10 object frames and 5 camera frames checked, 0 failure(s)"), std::string::npos) << good.text;

}

// A run with two cameras, one looking at the sheet and one away from it: the page offers each
// (the one --camera names first), and switching shows the sheet through the first and nothing
// through the second; Blender gets both cameras, each keyed as its file says.
TEST_F(ReportTest, ARunWithSeveralCamerasShowsEachInThePageAndInBlender) {
  std::string two = kScene;
  const std::string one_camera = two.substr(two.find(R"( "camera": {)"), two.find(R"( "obstacles")") - two.find(R"( "camera": {)"));
  two.replace(two.find(one_camera), one_camera.size(),
              R"( "cameras": [{"name": "sheet", "fov": 40, "width": 320, "height": 240, "keys": [{"time": 0, "position": [0.5, 0.6, 1.6], "target": [0.5, 0.0, -0.5]}]},)"
              R"( {"name": "away", "fov": 40, "width": 320, "height": 240, "keys": [{"time": 0, "position": [0.5, 0.6, 1.6], "target": [0.5, 0.6, 3.0]}]}],)");
  scene_ = write("two.json", two);
  const std::string view = run("view", "view");
  ASSERT_EQ(cli({"report", view, "--camera", "away"}), kExitOk) << err_.str();
  const std::string name = browser();
  ASSERT_FALSE(name.empty()) << "no headless Chromium: scripts/install-deps.sh installs chromium-headless-shell";
  const json result = open_page(name, fs::path(view) / "report" / "index.html");
  ASSERT_TRUE(result.is_object());
  EXPECT_TRUE(result["errors"].empty()) << result["errors"].dump();
  EXPECT_EQ(result["cameras"], json::parse(R"([["shot", "camera sheet"], ["shot:1", "camera away"], ["orbit", "orbit"]])"));
  EXPECT_EQ(result["shown"][0]["cloth_pixels"], 0) << "the page starts with the camera --camera names, which looks away";
  const json& shown = result["shown"];
  ASSERT_EQ(shown.size(), 6u);
  EXPECT_EQ(shown[4]["style"], "shot");
  EXPECT_GT(shown[4]["cloth_pixels"].get<double>(), 1000);
  EXPECT_EQ(shown[5]["style"], "shot:1");
  EXPECT_EQ(shown[5]["cloth_pixels"], 0);

  ASSERT_EQ(capture("command -v blender >/dev/null 2>&1").status, 0) << "no blender: scripts/install-deps.sh installs it";
  const Output blender = capture("blender -b --factory-startup --python '" + std::string(VDCLOTH_SOURCE_DIR) + "/tools/blender/check_import.py' -- '" +
                                 view + "' 2>&1");
  EXPECT_EQ(blender.status, 0) << blender.text;
  EXPECT_NE(blender.text.find("check_import: 10 object frames and 10 camera frames checked, 0 failure(s)"), std::string::npos) << blender.text;
}

// A run's record: stats.csv's columns as numbers (nan and inf, which a failed run's last row
// may hold, as null), its log's lines, no check or camera when the run has none.
TEST(ReportData, ARunsRecordHoldsItsTables) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_record_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << R"({"name": "s", "mode": "view"})";
  std::ofstream(dir / "stats.csv") << "frame,faces,kinetic_energy\n1,12,0.5\n2,14,nan\n3,16,-inf\n";
  std::ofstream(dir / "log.txt") << "frame 2: something\nframe 3: more\n";
  const json record = read_run_record(dir.string());
  EXPECT_EQ(record["stats"]["frame"], json({1, 2, 3}));
  EXPECT_EQ(record["stats"]["faces"], json({12, 14, 16}));
  EXPECT_EQ(record["stats"]["kinetic_energy"], json({0.5, nullptr, nullptr}));
  EXPECT_EQ(record["log"], json({"frame 2: something", "frame 3: more"}));
  EXPECT_TRUE(record["check"].is_null());
  EXPECT_TRUE(record["camera"].is_null());
  EXPECT_EQ(record["summary"]["mode"], "view");
  fs::remove_all(dir);
}

TEST(ReportData, Base64IsRfc4648) {
  // RFC 4648, section 10.
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

}  // namespace
}  // namespace vdc
