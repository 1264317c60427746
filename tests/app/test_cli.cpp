// The command line: bad inputs give exit status 2 with a message naming the problem and leave
// no output behind; a short good run writes frames, stats and summary.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdcloth_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    write("cotton.json", R"({"name": "c", "density": 0.13, "stretch": {"warp": 5000, "weft": 3500, "shear": 300}, "bending": 1e-5})");
    write("sheet.obj", "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  std::string scene(const std::string& garment_extra = "", const std::string& top_extra = "",
                    const std::string& material = "\"cotton.json\"", const std::string& mesh = "\"sheet.obj\"") {
    return write("scene.json", "{\"frames\": 2, \"substeps\": 2, \"remeshing\": {\"fixed_size\": 0.5}, " + top_extra + "\"garments\": [{\"name\": \"s\", \"mesh\": " + mesh +
                                   ", \"material\": " + material + garment_extra + "}]}");
  }
  int run(std::vector<std::string> args) {
    out_.str("");
    err_.str("");
    return run_cli(args, out_, err_, false);
  }
  std::string out_dir() const { return (dir_ / "out").string(); }

  fs::path dir_;
  std::ostringstream out_, err_;
};

TEST_F(CliTest, BadInputsExitTwoWithAClearMessageAndNoOutput) {
  auto run_scene = [](const std::string& path, const std::string& out) { return std::vector<std::string>{"run", path, "--out", out}; };
  struct Row {
    std::string label;
    std::function<std::string()> make_scene;  // returns the scene path
    std::vector<std::string> extra_args;
    std::vector<std::string> expect;  // substrings of the error
  };
  std::vector<Row> rows = {
      {"malformed JSON", [&] { return write("scene.json", "{\"frames\": 2,\n  \"garments\": [}\n"); }, {}, {"scene.json", "line 2, column 16", "syntax error"}},
      {"missing mesh file", [&] { return scene("", "", "\"cotton.json\"", "\"nowhere.obj\""); }, {}, {"garments[0].mesh", "file not found", "nowhere.obj"}},
      {"missing material file", [&] { return scene("", "", "\"silk.json\""); }, {}, {"garments[0].material", "file not found"}},
      {"unknown key", [&] { return scene(", \"colour\": 3"); }, {}, {"garments[0].colour", "unknown key"}},
      {"unknown top-level key", [&] { return scene("", "\"fps\": 25, "); }, {}, {"fps", "unknown key"}},
      {"wrong type", [&] { return scene("", "\"substeps\": \"eight\", "); }, {}, {"substeps", "expected an integer"}},
      {"non-manifold OBJ",
       [&] {
         write("nm.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 0 1 0\nv 0 -1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2/1 1/2 4/3\nf 1/1 2/2 5/3\n");
         return scene("", "", "\"cotton.json\"", "\"nm.obj\"");
       },
       {},
       {"garments[0].mesh", "nm.obj", "line 11", "non-manifold"}},
      {"zero-area face",
       [&] {
         write("za.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n");
         return scene("", "", "\"cotton.json\"", "\"za.obj\"");
       },
       {},
       {"za.obj", "line 7", "zero area in world space"}},
      {"negative density",
       [&] { return scene("", "", R"({"density": -1, "stretch": {"warp": 1, "weft": 1, "shear": 1}, "bending": 0})"); },
       {},
       {"garments[0].material.density", "greater than 0"}},
      {"zero frame time", [&] { return scene("", "\"frame_time\": 0, "); }, {}, {"frame_time", "greater than 0"}},
      {"frames -1", [&] { return scene(); }, {"--frames", "-1"}, {"--frames", "-1"}},
      {"unknown mode", [&] { return scene(); }, {"--mode", "fast"}, {"--mode", "fast"}},
      {"unknown option", [&] { return scene(); }, {"--speed", "2"}, {"unknown option", "--speed"}},
      {"missing frame of an obstacle sequence",
       [&] {
         write("body.01.obj", "v 0 -1 0\nv 1 -1 0\nv 0 -1 1\nf 1 3 2\n");
         write("body.02.obj", "v 0 -1 0\nv 1 -1 0\nv 0 -1 1\nf 1 3 2\n");
         return scene("", R"("obstacles": [{"name": "b", "mesh": {"sequence": {"files": "body.%02d.obj", "count": 3}}}], )");
       },
       {},
       {"obstacles[0].mesh.sequence.files", "body.03.obj", "file not found", "frame 3"}},
      {"obstacle sequence that changes topology",
       [&] {
         write("body.01.obj", "v 0 -1 0\nv 1 -1 0\nv 0 -1 1\nv 1 -1 1\nf 1 3 2\nf 2 3 4\n");
         write("body.02.obj", "v 0 -1 0\nv 1 -1 0\nv 0 -1 1\nv 1 -1 1\nf 1 3 2\nf 2 4 3\n");
         return scene("", R"("obstacles": [{"name": "b", "mesh": {"sequence": {"files": "body.%02d.obj", "count": 2}}}], )");
       },
       {},
       {"body.02.obj", "face 2", "other vertices"}},
      {"view mode without a camera", [&] { return scene(); }, {"--mode", "view"}, {"scene.json", "camera", "--mode view needs a camera"}},
      {"missing scene", [&] { return (dir_ / "nothing.json").string(); }, {}, {"nothing.json", "cannot open"}},
  };
  for (const Row& row : rows) {
    std::string path = row.make_scene();
    auto args = run_scene(path, out_dir());
    args.insert(args.end(), row.extra_args.begin(), row.extra_args.end());
    EXPECT_EQ(run(args), kExitBadInput) << row.label;
    const std::string msg = err_.str();
    for (const auto& part : row.expect) EXPECT_NE(msg.find(part), std::string::npos) << row.label << ": '" << part << "' not in: " << msg;
    EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 1) << row.label << ": one line expected: " << msg;
    EXPECT_FALSE(fs::exists(out_dir())) << row.label << " left output behind";
  }
}

TEST_F(CliTest, UsageErrors) {
  EXPECT_EQ(run({}), kExitBadInput);
  EXPECT_EQ(run({"fly"}), kExitBadInput);
  EXPECT_EQ(run({"run"}), kExitBadInput);
  EXPECT_EQ(run({"--help"}), kExitOk);
  EXPECT_NE(out_.str().find("vdcloth run"), std::string::npos);
  EXPECT_EQ(run({"run", "--help"}), kExitOk);
  for (const char* option : {"--mode", "--frames", "--out", "--threads"}) EXPECT_NE(out_.str().find(option), std::string::npos) << option;
}

TEST_F(CliTest, ShortRunWritesFramesStatsAndSummary) {
  std::string path = scene(", \"handles\": [{\"uv\": [[0, 1], [1, 1]]}]");
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--frames", "3", "--threads", "1"}), kExitOk) << err_.str();
  for (int f = 0; f <= 3; ++f) EXPECT_TRUE(fs::exists(dir_ / "out" / "frames" / ("cloth_s.000" + std::to_string(f) + ".obj")));
  std::ifstream stats(dir_ / "out" / "stats.csv");
  std::string header;
  std::getline(stats, header);
  EXPECT_EQ(header.rfind("frame,faces,vertices,seconds", 0), 0u);
  int rows = 0;
  for (std::string line; std::getline(stats, line);) ++rows;
  EXPECT_EQ(rows, 3);
  nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir_ / "out" / "summary.json"));
  EXPECT_EQ(summary["status"], "done");
  EXPECT_EQ(summary["frames"], 3);
  EXPECT_EQ(summary["mode"], "fixed");
}

}  // namespace
}  // namespace vdc
