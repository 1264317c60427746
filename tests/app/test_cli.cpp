// The command line: usage errors, a short good run's frames, stats and summary, results that
// cannot be written, resumption, check, render, fidelity and table1. Bad inputs of every kind
// are the corpus's (tests/corpus, test_corpus.cpp).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"
#include "app/table1.hpp"
#include "core/binary_io.hpp"
#include "core/error.hpp"
#include "core/mesh.hpp"
#include "io/ply.hpp"
#include "output/checkpoint.hpp"
#include "physics/cloth_model.hpp"
#include "physics/membrane.hpp"
#include "remesh/sizing.hpp"
#include "view/camera.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

// A CSV file's lines split at every comma (a trailing empty cell kept).
std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells(1);
    for (const char c : line) {
      if (c == ',') cells.emplace_back();
      else cells.back() += c;
    }
    rows.push_back(cells);
  }
  return rows;
}

// A CSV file's rows as cells named by its header; a row of another width is a failure.
std::vector<std::map<std::string, std::string>> csv_rows(const fs::path& path) {
  const std::vector<std::vector<std::string>> lines = read_csv(path);
  std::vector<std::map<std::string, std::string>> rows;
  if (lines.empty()) return rows;
  const std::vector<std::string>& names = lines[0];
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const std::vector<std::string>& cells = lines[k];
    if (cells.size() != names.size()) ADD_FAILURE() << path << " row " << k << ": " << cells.size() << " cells where the header names " << names.size();
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < std::min(cells.size(), names.size()); ++c) row[names[c]] = cells[c];
    rows.push_back(std::move(row));
  }
  return rows;
}

// The value in a named column of stats.csv at a frame.
double stats_column(const fs::path& path, const std::string& column, int frame) {
  std::ifstream in(path);
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    std::stringstream cells(line);
    std::vector<std::string> row;
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(cell);
    if (names.empty()) {
      names = row;
      continue;
    }
    const auto c = static_cast<std::size_t>(std::find(names.begin(), names.end(), column) - names.begin());
    if (c < row.size() && std::stoi(row[0]) == frame) return std::stod(row[c]);
  }
  ADD_FAILURE() << path << " has no " << column << " at frame " << frame;
  return 0;
}

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
  // Runs a hanging sheet six frames in `mode`, whole and in pieces resumed from checkpoints.
  void resumed_run_matches(const std::string& mode, bool with_ball);

  fs::path dir_;
  std::ostringstream out_, err_;
};

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
  // Resident memory at each frame's end: this test program's, a few MiB at least.
  for (int f = 1; f <= 3; ++f) EXPECT_GT(stats_column(dir_ / "out" / "stats.csv", "resident_mib", f), 1.0) << f;
}

TEST_F(CliTest, RunWritesMeshesEveryNthFrameOnly) {
  ASSERT_EQ(run({"run", scene(), "--out", out_dir(), "--frames", "4", "--threads", "1", "--mesh-every", "2"}), kExitOk) << err_.str();
  for (int f = 0; f <= 4; ++f)
    EXPECT_EQ(fs::exists(dir_ / "out" / "frames" / ("cloth_s.000" + std::to_string(f) + ".obj")), f % 2 == 0) << f;
  ASSERT_EQ(run({"run", scene(), "--out", out_dir(), "--frames", "2", "--threads", "1", "--mesh-every", "0"}), kExitOk) << err_.str();
  EXPECT_TRUE(fs::is_empty(dir_ / "out" / "frames"));
}

// An earlier run's frame that cannot be cleared away is refused before anything runs (status 2);
// results that stop being writable part-way (a full disk: /dev/full under stats.csv) stop the
// run with status 3 and a summary saying why and how far it got.
TEST_F(CliTest, ResultsThatCannotBeWrittenStopTheRunSayingWhy) {
  const fs::path frames = dir_ / "out" / "frames";
  fs::create_directories(frames / "cloth_s.0002.obj" / "inside");
  EXPECT_EQ(run({"run", scene(), "--out", out_dir(), "--frames", "3", "--threads", "1"}), kExitBadInput);
  EXPECT_NE(err_.str().find("cloth_s.0002.obj: cannot remove this frame of an earlier run"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(dir_ / "out" / "summary.json"));

  if (!fs::exists("/dev/full")) GTEST_SKIP() << "this system has no /dev/full";
  fs::remove_all(dir_ / "out");
  fs::create_directories(dir_ / "out");
  fs::create_symlink("/dev/full", dir_ / "out" / "stats.csv");
  EXPECT_EQ(run({"run", scene(), "--out", out_dir(), "--frames", "3", "--threads", "1", "--mesh-every", "1"}), kExitSimulationFailed);
  EXPECT_NE(err_.str().find("writing the results failed: "), std::string::npos) << err_.str();
  EXPECT_NE(err_.str().find("stats.csv: cannot write"), std::string::npos) << err_.str();
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir_ / "out" / "summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_EQ(summary["frames"], 0);
  EXPECT_NE(summary["error"].get<std::string>().find("stats.csv: cannot write"), std::string::npos) << summary.dump();
  EXPECT_FALSE(fs::exists(frames / "cloth_s.0002.obj"));  // stopped at the first frame
}

// A stream buffer that takes `lines` lines and then refuses every character.
class BreaksAfterLines : public std::streambuf {
 public:
  explicit BreaksAfterLines(int lines) : lines_left_(lines) {}

 protected:
  int_type overflow(int_type c) override {
    if (lines_left_ <= 0) return traits_type::eof();
    if (c == '\n') --lines_left_;
    return c;
  }

 private:
  int lines_left_;
};

// An error that is neither the input's nor the simulation's (here the progress stream failing
// after the run's first line and its first frame's) still ends the run with status 3, the
// frames done kept and a `failed` summary naming the error, instead of escaping to terminate.
TEST_F(CliTest, AnUnexpectedErrorPartWayStopsTheRunSayingWhy) {
  BreaksAfterLines broken(2);
  std::ostream out(&broken);
  out.exceptions(std::ios::badbit);
  std::ostringstream err;
  const int status = run_cli({"run", scene(), "--out", out_dir(), "--frames", "4", "--threads", "1", "--mesh-every", "1"}, out, err, false);
  EXPECT_EQ(status, kExitSimulationFailed) << err.str();
  EXPECT_NE(err.str().find("vdcloth: unexpected error: "), std::string::npos) << err.str();
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir_ / "out" / "summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_EQ(summary["error"].get<std::string>().rfind("unexpected error: ", 0), 0u) << summary.dump();
  // Frame 2 was done and written before its progress line broke the stream.
  EXPECT_EQ(summary["frames"], 2);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "frames" / "cloth_s.0002.obj"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "frames" / "cloth_s.0003.obj"));
}

TEST_F(CliTest, RenderDrawsEachFrameAndARunComparedWithItselfMatchesExactly) {
  const std::string camera =
      R"("camera": {"fov": 40, "width": 160, "height": 120, "keys": [{"time": 0, "position": [0.5, 1.5, 1.5], "target": [0.5, 0, -0.5]}]}, )";
  const std::string path = scene("", camera);
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--frames", "2", "--threads", "1"}), kExitOk) << err_.str();
  ASSERT_EQ(run({"render", path, out_dir(), "--scale", "1"}), kExitOk) << err_.str();
  for (int f = 0; f <= 2; ++f) EXPECT_TRUE(fs::exists(dir_ / "out" / "render" / ("frame_000" + std::to_string(f) + ".png"))) << f;
  ASSERT_EQ(run({"render", path, out_dir(), "--compare", out_dir(), "--every", "2", "--scale", "0.5"}), kExitOk) << err_.str();
  EXPECT_TRUE(fs::exists(dir_ / "out" / "compare" / "compare_0000.png"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "compare" / "compare_0001.png"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "compare" / "compare.csv.partial"));
  std::ifstream csv(dir_ / "out" / "compare" / "compare.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "frame,time,cloth_pixels_a,cloth_pixels_b,cloth_iou,mean_abs_diff");
  const auto rows = csv_rows(dir_ / "out" / "compare" / "compare.csv");
  for (const auto& row : rows) {
    EXPECT_GT(std::stoi(row.at("cloth_pixels_a")), 100) << "the sheet is in the picture at frame " << row.at("frame");
    EXPECT_EQ(row.at("cloth_pixels_a"), row.at("cloth_pixels_b")) << row.at("frame");
    EXPECT_EQ(row.at("cloth_iou"), "1") << row.at("frame");
    EXPECT_EQ(row.at("mean_abs_diff"), "0") << row.at("frame");
  }
  EXPECT_EQ(rows.size(), 2u);  // frames 0 and 2
}

// Cloth coloured by its view factors (the frames' PLY files) with its edges drawn: the pictures
// of every frame; a damaged PLY stops the command naming it and its line, nothing left written.
TEST_F(CliTest, RenderColoursByViewFactorFromThePlyFiles) {
  const std::string camera =
      R"("camera": {"fov": 40, "width": 160, "height": 120, "keys": [{"time": 0, "position": [0.5, 1.5, 1.5], "target": [0.5, 0, -0.5]}]}, )";
  const std::string path = scene("", camera);
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--frames", "2", "--threads", "1", "--mode", "view"}), kExitOk) << err_.str();
  ASSERT_TRUE(fs::exists(dir_ / "out" / "frames" / "cloth_s.0002.ply"));
  ASSERT_EQ(run({"render", path, out_dir(), "--colour", "view", "--wireframe", "--scale", "1"}), kExitOk) << err_.str();
  for (int f = 0; f <= 2; ++f) EXPECT_TRUE(fs::exists(dir_ / "out" / "render" / ("frame_000" + std::to_string(f) + ".png"))) << f;
  fs::remove_all(dir_ / "out" / "render");
  std::ofstream(dir_ / "out" / "frames" / "cloth_s.0002.ply") << "ply\nformat ascii 1.0\nelement vertex x\n";
  EXPECT_EQ(run({"render", path, out_dir(), "--colour", "view"}), kExitBadInput);
  EXPECT_NE(err_.str().find("cloth_s.0002.ply"), std::string::npos) << err_.str();
  EXPECT_NE(err_.str().find("line 3"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(dir_ / "out" / "render"));
  EXPECT_EQ(run({"render", path, out_dir(), "--colour", "purple"}), kExitBadInput);
  EXPECT_NE(err_.str().find("--colour expects garment or view"), std::string::npos) << err_.str();
}

// What ffprobe (installed with ffmpeg) says of a video's first stream: "codec,width,height,
// frame rate,frames read".
std::string probe_video(const fs::path& video) {
  const std::string command = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                              "stream=codec_name,width,height,r_frame_rate,nb_read_frames -of csv=p=0 '" + video.string() + "'";
  std::string text;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (fgets(buffer, sizeof buffer, pipe) != nullptr) text += buffer;
    pclose(pipe);
  }
  return text;
}

// The pictures as an MP4 at the shot's speed (frames 0 to 4 drawn every second one: 0, 2, 4 at
// 25 / 2 frames a second), side by side with --compare; without ffmpeg on the PATH, exit 2 and
// nothing written.
TEST_F(CliTest, RenderVideoHoldsEveryPictureAtTheShotsSpeed) {
  const std::string camera =
      R"("camera": {"fov": 40, "width": 160, "height": 120, "keys": [{"time": 0, "position": [0.5, 1.5, 1.5], "target": [0.5, 0, -0.5]}]}, )";
  const std::string path = scene("", camera);
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--frames", "4", "--threads", "1"}), kExitOk) << err_.str();
  ASSERT_EQ(run({"render", path, out_dir(), "--video", "--every", "2", "--scale", "1"}), kExitOk) << err_.str();
  EXPECT_EQ(probe_video(dir_ / "out" / "render" / "render.mp4"), "h264,160,120,25/2,3\n");
  ASSERT_EQ(run({"render", path, out_dir(), "--compare", out_dir(), "--video", "--scale", "0.5"}), kExitOk) << err_.str();
  EXPECT_EQ(probe_video(dir_ / "out" / "compare" / "compare.mp4"), "h264,248,60,25/1,5\n");  // three pictures 80 wide, two gaps of 4

  const std::string path_before = std::getenv("PATH");
  setenv("PATH", (dir_ / "no-programs-here").c_str(), 1);
  const int status = run({"render", path, out_dir(), "--video", "--out", (dir_ / "pictures").string()});
  setenv("PATH", path_before.c_str(), 1);
  EXPECT_EQ(status, kExitBadInput);
  EXPECT_NE(err_.str().find("--video needs ffmpeg"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(dir_ / "pictures"));
}

// The spin counts libgomp reports at start-up (OMP_DISPLAY_ENV), in order: one a program image.
std::vector<std::string> spin_counts_reported(const std::string& environment) {
  const std::string command = "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT " + environment + " OMP_DISPLAY_ENV=verbose " +
                              std::string(VDCLOTH_BINARY) + " --version 2>&1";
  std::vector<std::string> counts;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[256];
    while (fgets(buffer, sizeof buffer, pipe) != nullptr) {
      const std::string line = buffer, key = "GOMP_SPINCOUNT = '";
      if (const auto at = line.find(key); at != std::string::npos) counts.push_back(line.substr(at + key.size(), line.find('\'', at + key.size()) - at - key.size()));
    }
    pclose(pipe);
  }
  return counts;
}

// Idle OpenMP threads sleep by default (the program starts itself again with the passive wait
// policy, libgomp's spin count 0); a policy or spin count the environment sets is kept as it is,
// and a run under valgrind is not started again.
TEST_F(CliTest, IdleThreadsSleepUnlessTheEnvironmentChooses) {
  EXPECT_EQ(spin_counts_reported(""), (std::vector<std::string>{"300000", "0"}));
  EXPECT_EQ(spin_counts_reported("OMP_WAIT_POLICY=active"), (std::vector<std::string>{"30000000000"}));
  EXPECT_EQ(spin_counts_reported("GOMP_SPINCOUNT=1000"), (std::vector<std::string>{"1000"}));
  // Under valgrind (seen by its preloaded library) /proc/self/exe is valgrind's tool: no restart.
  EXPECT_EQ(spin_counts_reported("LD_PRELOAD=/nowhere/vgpreload_core-amd64-linux.so"), (std::vector<std::string>{"300000"}));
}

TEST_F(CliTest, RenderBadInputsExitTwoNamingTheProblem) {
  const std::string no_camera = scene();
  ASSERT_EQ(run({"run", no_camera, "--out", out_dir(), "--frames", "1", "--threads", "1"}), kExitOk) << err_.str();
  EXPECT_EQ(run({"render", no_camera, out_dir()}), kExitBadInput);
  EXPECT_NE(err_.str().find("no camera"), std::string::npos) << err_.str();
  const std::string with_camera =
      scene("", R"("camera": {"keys": [{"time": 0, "position": [0, 1, 2], "target": [0, 0, 0]}]}, )");
  EXPECT_EQ(run({"render", with_camera, (dir_ / "nowhere").string()}), kExitBadInput);
  EXPECT_NE(err_.str().find("nowhere/frames"), std::string::npos) << err_.str();
  EXPECT_EQ(run({"render", with_camera, out_dir(), "--scale", "0"}), kExitBadInput);
  EXPECT_NE(err_.str().find("--scale"), std::string::npos) << err_.str();
  EXPECT_EQ(run({"render", with_camera}), kExitBadInput);
  EXPECT_EQ(run({"render", with_camera, out_dir(), "--frobnicate"}), kExitBadInput);
  ASSERT_EQ(run({"run", no_camera, "--out", (dir_ / "bare").string(), "--frames", "1", "--threads", "1", "--mesh-every", "0"}), kExitOk);
  EXPECT_EQ(run({"render", with_camera, (dir_ / "bare").string()}), kExitBadInput);
  EXPECT_NE(err_.str().find("no frame meshes"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(dir_ / "bare" / "render"));
  EXPECT_EQ(run({"render", "--help"}), kExitOk);
  EXPECT_NE(out_.str().find("--compare"), std::string::npos);
}

TEST_F(CliTest, CheckPassesACleanRunAndListsPlantedCrossings) {
  ASSERT_EQ(run({"run", scene(), "--out", out_dir(), "--frames", "2", "--threads", "1"}), kExitOk) << err_.str();
  ASSERT_EQ(run({"check", out_dir()}), kExitOk) << out_.str();
  EXPECT_NE(out_.str().find("3 frame(s)"), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("0 with crossings"), std::string::npos) << out_.str();
  std::ifstream clean_status(fs::path(out_dir()) / "check_status.txt");
  int checked = -1, crossing = -1, every = -1;
  clean_status >> checked >> crossing >> every;
  EXPECT_EQ(checked, 3);
  EXPECT_EQ(crossing, 0);
  EXPECT_EQ(every, 1);
  // A planted run: at frame 0 a body stands clear of the sheet, at frame 1 a wall cuts
  // through it.
  const fs::path frames = dir_ / "planted" / "frames";
  fs::create_directories(frames);
  const std::string sheet = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";
  const std::string wall = "v 0.5 -1 -1\nv 0.5 1 -1\nv 0.5 1 2\nv 0.5 -1 2\nf 1 2 3\nf 1 3 4\n";
  const std::string apart = "v 5 -1 -1\nv 5 1 -1\nv 5 1 2\nv 5 -1 2\nf 1 2 3\nf 1 3 4\n";
  std::ofstream(frames / "cloth_s.0000.obj") << sheet;
  std::ofstream(frames / "obstacle_w.0000.obj") << apart;
  std::ofstream(frames / "cloth_s.0001.obj") << sheet;
  std::ofstream(frames / "obstacle_w.0001.obj") << wall;
  EXPECT_EQ(run({"check", (dir_ / "planted").string()}), kExitSimulationFailed) << out_.str() << err_.str();
  EXPECT_NE(out_.str().find("frame 1: cloth_s crosses obstacle_w"), std::string::npos) << out_.str();
  std::ifstream csv(dir_ / "planted" / "check.csv");
  std::string header, row, extra;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header, "frame,mesh,other,face_pairs");
  EXPECT_EQ(row.rfind("1,cloth_s,obstacle_w,", 0), 0u) << row;
  EXPECT_FALSE(std::getline(csv, extra)) << "only frame 1 crosses: " << extra;
  std::ifstream planted_status(dir_ / "planted" / "check_status.txt");
  planted_status >> checked >> crossing >> every;
  EXPECT_EQ(checked, 2);
  EXPECT_EQ(crossing, 1);
  // Bad inputs.
  EXPECT_EQ(run({"check"}), kExitBadInput);
  EXPECT_EQ(run({"check", (dir_ / "nowhere").string()}), kExitBadInput);
  EXPECT_NE(err_.str().find("nowhere/frames"), std::string::npos) << err_.str();
  EXPECT_EQ(run({"check", out_dir(), "--every", "0"}), kExitBadInput);
  EXPECT_EQ(run({"check", "--help"}), kExitOk);
  EXPECT_NE(out_.str().find("--every"), std::string::npos);
}

// A sheet hanging from two corners, remeshed every frame: enough motion and topology change for
// a resumed run to have something to get wrong.
std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}


// stats.csv without the columns that measure the process (times, named *seconds, and the
// resident memory), which differ run to run.
std::vector<std::string> stats_without_timings(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> rows;
  std::vector<bool> timing;
  for (std::string line; std::getline(in, line);) {
    std::stringstream cells(line);
    std::string row, cell;
    for (std::size_t c = 0; std::getline(cells, cell, ','); ++c) {
      if (rows.empty()) timing.push_back((cell.size() >= 7 && cell.compare(cell.size() - 7, 7, "seconds") == 0) || cell == "resident_mib");
      if (c < timing.size() && !timing[c]) row += cell + ",";
    }
    rows.push_back(row);
  }
  return rows;
}

const char* kHangingSheet =
    R"({"frames": 6, "substeps": 2, "remeshing": {"size": [0.06, 0.5]}, "garments": [{"name": "s", )"
    R"("mesh": {"grid": {"size": [1, 1], "cells": [4, 4]}}, "material": "cotton.json", "handles": [{"uv": [[0, 1], [1, 1]]}]}]})";

// A ball rising into the falling sheet from frame 3 on: collisions against an obstacle whose
// hierarchies the collider keeps across remeshing (they must restart at the checkpoint too).
const char* kRisingBall =
    R"("obstacles": [{"name": "ball", "mesh": {"sphere": {"radius": 0.2, "subdivisions": 2}}, )"
    R"("transform": {"translate": [0.5, -0.4, -0.35]}, )"
    R"("motion": {"translate": [{"time": 0, "offset": [0, 0, 0]}, {"time": 0.24, "offset": [0, 0.25, 0]}]}}], )";

// Remeshed every frame (meshes and attributes must come back exactly), with and without an
// obstacle, and fixed with a linear solver that carries a preconditioner and a first guess from
// step to step (they must restart at the checkpoint, in the run as in its resumption).
TEST_F(CliTest, AResumedRunIsTheRunThatNeverStopped) {
  for (const std::string mode : {"adaptive", "fixed"}) {
    SCOPED_TRACE(mode);
    resumed_run_matches(mode, false);
  }
  SCOPED_TRACE("adaptive, with a ball");
  resumed_run_matches("adaptive", true);
  // Seen from 10 m, the sheet's faces soften towards the folds too fine for the image over
  // view.fold_time, from the factors the checkpoint holds, and the coarse faces the rising ball
  // gathers keep the gathering they were made with (view.gathering), as the checkpoint holds it.
  SCOPED_TRACE("view, far, with a ball");
  resumed_run_matches("view", true);
}

void CliTest::resumed_run_matches(const std::string& mode, bool with_ball) {
  std::string scene = kHangingSheet;
  if (mode == "fixed") scene.replace(1, 0, R"("solver": {"linear": "cholmod-pcg"}, )");
  if (with_ball) scene.replace(1, 0, kRisingBall);
  if (mode == "view")
    scene.replace(1, 0, R"("view": {"gathering": 0.3}, "camera": {"fov": 40, "width": 160, "height": 120, "keys": [{"time": 0, "position": [0.5, -0.5, 10], "target": [0.5, -0.5, 0]}]}, )");
  const std::string name = mode + (with_ball ? "_ball" : "");
  const std::string scene_path = write(name + ".json", scene);
  const fs::path whole = dir_ / (name + "_whole"), pieces = dir_ / (name + "_pieces");
  auto run_to = [&](const fs::path& out, std::vector<std::string> extra) {
    std::vector<std::string> args{"run", scene_path, "--mode", mode, "--out", out.string(), "--threads", "1", "--checkpoint-every", "2"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  };
  ASSERT_EQ(run_to(whole, {}), kExitOk) << err_.str();
  // In pieces: to frame 2 (a checkpoint), on to frame 3 (another), then back to the checkpoint
  // of frame 2, as if the process had died at frame 3 before writing its own.
  ASSERT_EQ(run_to(pieces, {"--frames", "2"}), kExitOk) << err_.str();
  const fs::path at2 = dir_ / (name + "_at2.bin");
  fs::copy_file(pieces / "checkpoint.bin", at2);
  ASSERT_EQ(run_to(pieces, {"--frames", "3", "--resume"}), kExitOk) << err_.str();
  ASSERT_TRUE(fs::exists(pieces / "frames" / "cloth_s.0003.obj"));
  fs::copy_file(at2, pieces / "checkpoint.bin", fs::copy_options::overwrite_existing);
  ASSERT_EQ(run_to(pieces, {"--resume"}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find("resumed at frame 2"), std::string::npos) << out_.str();

  for (int f = 0; f <= 6; ++f) {
    const std::string file = "cloth_s.000" + std::to_string(f) + ".obj";
    EXPECT_EQ(read_file(pieces / "frames" / file), read_file(whole / "frames" / file)) << file;
  }
  // The frames are rounded to the micrometre; the last checkpoints hold the state exactly.
  const Checkpoint whole_end = read_checkpoint((whole / "checkpoint.bin").string());
  const Checkpoint pieces_end = read_checkpoint((pieces / "checkpoint.bin").string());
  ASSERT_EQ(whole_end.frame, 6);
  ASSERT_EQ(pieces_end.frame, 6);
  const Mesh& a = whole_end.parts.at(0).garments.at(0);
  const Mesh& b = pieces_end.parts.at(0).garments.at(0);
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  for (NodeId n : a.nodes()) {
    EXPECT_EQ(a.x(n), b.x(n)) << "node " << n.idx;
    EXPECT_EQ(a.v(n), b.v(n)) << "node " << n.idx;
  }
  if (mode == "view") {
    // The compression factors are state: the same in both, and on faces the folds lead still
    // on their way to the law's factor after six frames (0.2 s of a 0.4 s fold_time).
    const auto& compression = a.face_attrs().get<double>(kCompressionAttr);
    const auto& coarsening = a.face_attrs().get<double>(kCoarseningAttr);
    const auto& fold_led = a.face_attrs().get<double>(kFoldLedAttr);
    // So are the gatherings the coarse faces were made with (view.gathering).
    const auto& gathered = a.face_attrs().get<Vec2>(kGatheredAttr);
    int easing = 0, gathering = 0;
    for (FaceId f : a.faces()) {
      EXPECT_EQ(compression[f], b.face_attrs().get<double>(kCompressionAttr)[f]) << "face " << f.idx;
      if (fold_led[f] > 0 && compression[f] > coarse_compression_factor(coarsening[f])) ++easing;
      EXPECT_EQ(gathered[f], b.face_attrs().get<Vec2>(kGatheredAttr)[f]) << "face " << f.idx;
      gathering += gathered[f].minCoeff() < 0;
    }
    EXPECT_GT(easing, 0);
    EXPECT_GT(gathering, 0);
  }
  const std::vector<std::string> rows = stats_without_timings(whole / "stats.csv");
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(stats_without_timings(pieces / "stats.csv"), rows);
  // The adaptive run remeshed: the sheet's face count changed over the six frames.
  auto faces = [](const std::string& row) { return std::stoi(row.substr(row.find(',') + 1)); };
  if (mode == "adaptive") {
    EXPECT_NE(faces(rows[1]), faces(rows[6])) << rows[1] << " / " << rows[6];
  }
  // The ball met the sheet after the checkpoint of frame 2.
  if (with_ball) {
    EXPECT_GT(stats_column(whole / "stats.csv", "impacts", 5), 0);
  }
  nlohmann::json summary = nlohmann::json::parse(std::ifstream(pieces / "summary.json"));
  EXPECT_EQ(summary["status"], "done");
  EXPECT_EQ(summary["frames"], 6);
  EXPECT_EQ(summary["segments"], 2);
  EXPECT_GT(summary["cpu_seconds"].get<double>(), 0);
  EXPECT_GT(summary["peak_memory_kib"].get<long>(), 0);
}

// A checkpoint restarts the linear solver and keeps the collision hierarchies, whose shape
// changes no result: the sheet falling on the rising ball (remeshed every frame, collisions
// with a body whose hierarchies are refit and rebuilt), small enough for the restart to change
// nothing here, is the same run with a checkpoint every frame as without any.
TEST_F(CliTest, CheckpointsLeaveTheRunAsItIs) {
  // Finer than kHangingSheet, a finer ball and twice the frames: enough contact for a restart
  // that rebuilt the hierarchies, with candidates taken in the order met, to change the run
  // from frame 4 on.
  const std::string scene_path = write("checkpointed.json",
      R"({"obstacles": [{"name": "ball", "mesh": {"sphere": {"radius": 0.2, "subdivisions": 3}}, )"
      R"("transform": {"translate": [0.5, -0.4, -0.35]}, )"
      R"("motion": {"translate": [{"time": 0, "offset": [0, 0, 0]}, {"time": 0.24, "offset": [0, 0.25, 0]}]}}], )"
      R"("frames": 12, "substeps": 2, "remeshing": {"size": [0.03, 0.5]}, "garments": [{"name": "s", )"
      R"("mesh": {"grid": {"size": [1, 1], "cells": [4, 4]}}, "material": "cotton.json", "handles": [{"uv": [[0, 1], [1, 1]]}]}]})");
  const fs::path none = dir_ / "no_checkpoints", every = dir_ / "every_frame";
  for (const auto& [out, interval] : {std::pair{none, "0"}, std::pair{every, "1"}})
    ASSERT_EQ(run({"run", scene_path, "--mode", "adaptive", "--out", out.string(), "--threads", "2", "--checkpoint-every", interval}), kExitOk)
        << err_.str();
  for (int f = 0; f <= 12; ++f) {
    char file[32];
    std::snprintf(file, sizeof file, "cloth_s.%04d.obj", f);
    EXPECT_EQ(read_file(every / "frames" / file), read_file(none / "frames" / file)) << file;
  }
  EXPECT_EQ(stats_without_timings(every / "stats.csv"), stats_without_timings(none / "stats.csv"));
  EXPECT_GT(stats_column(none / "stats.csv", "impacts", 5), 0);
}

TEST_F(CliTest, ResumeRefusesWhatItCannotGoOnFromAndLeavesTheRunAlone) {
  const std::string scene_path = write("hang.json", kHangingSheet);
  const fs::path out = dir_ / "out";
  auto resume = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"run", scene_path, "--mode", "adaptive", "--out", out.string(), "--threads", "1", "--resume"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run(args);
  };
  EXPECT_EQ(resume({}), kExitBadInput);
  EXPECT_NE(err_.str().find("no checkpoint to resume from"), std::string::npos) << err_.str();
  ASSERT_EQ(run({"run", scene_path, "--mode", "adaptive", "--out", out.string(), "--threads", "1", "--frames", "2"}), kExitOk) << err_.str();
  const fs::path checkpoint = out / "checkpoint.bin";
  ASSERT_TRUE(fs::exists(checkpoint));  // the default interval still checkpoints the last frame
  const std::string stats = read_file(out / "stats.csv"), summary = read_file(out / "summary.json"), good = read_file(checkpoint);

  struct Case {
    const char* what;
    std::function<void()> spoil;
    std::vector<std::string> extra;
    std::vector<std::string> expect;
  };
  const std::vector<Case> cases{
      {"another mode", [] {}, {"--mode", "fixed"}, {"adaptive mode, not fixed"}},
      {"frames before the checkpoint", [] {}, {"--frames", "1"}, {"at frame 2, past the 1 frames"}},
      {"a flipped byte", [&] { std::string b = good; b[b.size() / 2] ^= 0x10; std::ofstream(checkpoint, std::ios::binary) << b; }, {},
       {"checkpoint.bin", "checksum"}},
      {"a cut-off file", [&] { std::ofstream(checkpoint, std::ios::binary) << good.substr(0, good.size() / 3); }, {}, {"checkpoint.bin"}},
      {"not a checkpoint", [&] { std::ofstream(checkpoint, std::ios::binary) << "frame,faces\n1,2\n"; }, {}, {"checkpoint.bin", "not a vdcloth checkpoint"}},
      {"an edited scene", [&] { write("hang.json", std::string(kHangingSheet).replace(1, 11, "\"frames\": 9")); }, {}, {"another version of"}},
      {"another build",
       [&] {
         // The executable's hash follows the magic (8 + 18 bytes), the format (4) and the scene's
         // hash (8); the checksum over everything before it is made again.
         std::string b = good;
         b[8 + 18 + 4 + 8 + 2] ^= 0x01;
         const uint64_t sum = fnv1a64(b.data(), b.size() - 8);
         std::memcpy(b.data() + b.size() - 8, &sum, 8);
         std::ofstream(checkpoint, std::ios::binary) << b;
       },
       {},
       {"checkpoint.bin", "another build of vdcloth"}},
      {"another interval", [] {}, {"--checkpoint-every", "5"}, {"checkpointed every 10 frames", "--checkpoint-every 10"}},
      {"another perturbation", [] {}, {"--perturb", "1e-6"}, {"made with --perturb 0, not 1e-06"}},
  };
  for (const Case& c : cases) {
    std::ofstream(checkpoint, std::ios::binary) << good;
    write("hang.json", kHangingSheet);
    c.spoil();
    EXPECT_EQ(resume(c.extra), kExitBadInput) << c.what;
    for (const auto& text : c.expect) EXPECT_NE(err_.str().find(text), std::string::npos) << c.what << ": " << err_.str();
    const std::string message = err_.str();
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << c.what << ": " << message;
    EXPECT_EQ(read_file(out / "stats.csv"), stats) << c.what;
    EXPECT_EQ(read_file(out / "summary.json"), summary) << c.what;
  }
  // A run that is done has nothing to resume: it says so and leaves its files as they are (its
  // summary was rewritten as a second segment).
  std::ofstream(checkpoint, std::ios::binary) << good;
  write("hang.json", kHangingSheet);
  EXPECT_EQ(resume({"--frames", "2"}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find("is done (2 frames); nothing to resume"), std::string::npos) << out_.str();
  EXPECT_EQ(read_file(out / "stats.csv"), stats);
  EXPECT_EQ(read_file(out / "summary.json"), summary);
}

TEST_F(CliTest, Table1ReadsARunsStatistics) {
  const std::string csv = write("stats.csv", "frame,faces,vertices,seconds,substeps\n1,100,60,0.5,8\n2,300,170,1.5,8\n3,200,120,1.0,8\n");
  const RunTable t = read_run_table(csv);
  EXPECT_EQ(t.frames, 3);
  EXPECT_EQ(t.faces_min, 100);
  EXPECT_EQ(t.faces_max, 300);
  EXPECT_DOUBLE_EQ(t.faces_mean, 200);
  EXPECT_EQ(t.vertices_min, 60);
  EXPECT_EQ(t.vertices_max, 170);
  EXPECT_DOUBLE_EQ(t.vertices_mean, 350.0 / 3);
  EXPECT_DOUBLE_EQ(t.seconds_min, 0.5);
  EXPECT_DOUBLE_EQ(t.seconds_max, 1.5);
  EXPECT_DOUBLE_EQ(t.seconds_mean, 1.0);
  // A baseline of 3 frames against a run of 2: over the first 2, (0.5 + 1.5) / (0.25 + 0.25).
  const RunTable two = read_run_table(write("two.csv", "frame,faces,vertices,seconds\n1,50,30,0.25\n2,60,35,0.25\n"));
  int shared = 0;
  EXPECT_DOUBLE_EQ(speedup_over_shared_frames(t, two, &shared), 4.0);
  EXPECT_EQ(shared, 2);
  EXPECT_DOUBLE_EQ(speedup_over_shared_frames(two, t), 0.25);
  EXPECT_DOUBLE_EQ(speedup_over_shared_frames(RunTable{}, t), 0.0);
  EXPECT_THROW(read_run_table(write("bad.csv", "frame,faces,vertices,seconds\n1,x,3,0.5\n")), InputError);
  EXPECT_THROW(read_run_table(write("other.csv", "a,b\n")), InputError);
}

TEST_F(CliTest, Table1UsageErrors) {
  EXPECT_EQ(run({"bench"}), kExitBadInput);
  EXPECT_EQ(run({"bench", "table2"}), kExitBadInput);
  EXPECT_EQ(run({"bench", "table1", "--scene", "judo"}), kExitBadInput);
  EXPECT_NE(err_.str().find("judo"), std::string::npos);
  EXPECT_EQ(run({"bench", "table1", "--scenes", (dir_ / "none").string(), "--out", out_dir()}), kExitBadInput);
  EXPECT_NE(err_.str().find("scene not found"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(out_dir()));
  EXPECT_EQ(run({"bench", "table1", "--help"}), kExitOk);
  EXPECT_NE(out_.str().find("table1.md"), std::string::npos);
  EXPECT_EQ(run({"bench", "--help"}), kExitOk);
  EXPECT_NE(out_.str().find("vdcloth bench table1"), std::string::npos) << out_.str();
  // Every command's help: exit 0 and its usage line.
  for (const char* command : {"run", "render", "check", "fidelity"}) {
    EXPECT_EQ(run({command, "--help"}), kExitOk) << command;
    EXPECT_NE(out_.str().find(std::string("usage: vdcloth ") + command), std::string::npos) << command << ": " << out_.str();
  }
}

// The whole command on three tiny stand-in scenes (one of them with two groups), through the
// real executable: nine child runs of two frames, and the tables they make.
TEST_F(CliTest, Table1RunsEverySceneInEveryModeAndWritesTheTables) {
  fs::create_directories(dir_ / "scenes");
  const std::string camera = R"("camera": {"fov": 40, "width": 320, "height": 240, "keys": [{"time": 0, "position": [0.5, 2, 1], "target": [0.5, 0, -0.5]}]}, )";
  const std::string garment = R"({"name": "NAME", GROUP "mesh": {"grid": {"size": [1, 1], "cells": [4, 4]}}, "material": "../cotton.json"})";
  auto sheet = [&](const std::string& name, const std::string& group) {
    std::string g = garment;
    g.replace(g.find("NAME"), 4, name);
    g.replace(g.find("GROUP"), 5, group.empty() ? "" : "\"group\": \"" + group + "\",");
    return g;
  };
  for (const std::string name : {"karate", "solo-dancer"})
    write("scenes/" + name + ".json", R"({"substeps": 2, "remeshing": {"size": [0.2, 0.5]}, )" + camera + R"("garments": [)" + sheet("s", "") + "]}");
  write("scenes/dancers-10.json", R"({"substeps": 2, "remeshing": {"size": [0.2, 0.5]}, )" + camera + R"("garments": [)" + sheet("a", "one") + ", " +
                                      sheet("b", "two") + "]}");
  const std::string out = (dir_ / "table").string();
  const std::string command = std::string(VDCLOTH_BINARY) + " bench table1 --scenes " + (dir_ / "scenes").string() + " --frames 2 --threads 1 --mesh-every 1 --out " +
                              out + " > " + (dir_ / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << std::ifstream(dir_ / "log.txt").rdbuf();
  std::ifstream csv(out + "/table1.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("scene,mode,status,frames,faces_min", 0), 0u);
  const auto rows = csv_rows(out + "/table1.csv");
  for (const auto& row : rows) {
    const std::string run = row.at("scene") + " " + row.at("mode");
    EXPECT_EQ(row.at("speedup_vs_fixed_frames"), "2") << "every run compared with its fixed run over both frames: " << run;
    EXPECT_EQ(row.at("frames_checked"), "3") << "frames 0, 1 and 2 checked: " << run;
    EXPECT_EQ(row.at("frames_with_crossings"), "0") << "no crossings: " << run;
    EXPECT_GT(std::stod(row.at("cpu_seconds_per_frame")), 0) << run;
    // Empty (unknown) when the machine's CPU counters did not advance during the run: these
    // runs take a few hundredths of a second, about the kernel's clock tick.
    if (!row.at("steal_percent").empty()) {
      EXPECT_GE(std::stod(row.at("steal_percent")), 0) << run;
      EXPECT_LE(std::stod(row.at("steal_percent")), 100) << run;
    }
    EXPECT_EQ(row.at("status"), "done") << run;
    EXPECT_EQ(row.at("frames"), "2") << run;
    if (row.at("mode") == "adaptive") {
      EXPECT_EQ(row.at("speedup_vs_adaptive"), "1.00") << run;
    }
    if (row.at("scene") == "dancers-10") {
      EXPECT_EQ(std::stoi(row.at("faces_min")) % 2, 0) << "two identical sheets: " << run;
    }
  }
  EXPECT_EQ(rows.size(), 9u);
  std::ifstream md(out + "/table1.md");
  int clean_rows = 0;
  for (std::string l; std::getline(md, l);) clean_rows += l.find("| 0 of 3 |") != std::string::npos;
  EXPECT_EQ(clean_rows, 9) << "every run checked, none crossing";
  for (const std::string name : {"karate", "solo-dancer", "dancers-10"}) {
    std::ifstream frames(out + "/table1_" + name + "_frames.csv");
    int n = 0;
    for (std::string l; std::getline(frames, l);) ++n;
    EXPECT_EQ(n, 3) << name;  // header and two frames
    EXPECT_TRUE(fs::exists(out + "/" + name + "/view/stats.csv")) << name;
  }
}

// Rows of a CSV file cut into cells, empty cells kept (the header first).
std::string first_line(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

const std::string kFidelityFramesHeader =
    "frame,time,shot,cloth_pixels_run,cloth_pixels_reference,overlap,floor_overlap,detail_run,detail_reference,detail_floor,"
    "popping_run,popping_reference,popping_floor,floor_overlaps,sample_overlaps";
const std::string kFidelityGarmentsHeader = "frame,shot,garment,pixels_run,pixels_reference,overlap,floor_overlap";
const std::string kFidelityShotsHeader =
    "shot,first_frame,last_frame,frames,overlap_mean,overlap_min,floor_overlap_mean,floor_overlap_min,detail_run,detail_reference,"
    "detail_ratio,popping_pairs,popping_run,popping_reference,popping_ratio,verdict,failed,detail_floor_ratio,popping_floor_ratio,"
    "floors,floor_overlap_means,floor_overlap_mins,samples,sample_overlap_means,sample_overlap_mins";

// A hanging sheet seen from above and in front, with a cut to another view at 0.07 s: frames 0
// and 1 are shot 0, frames 2 to 4 shot 1.
const char* kCutCamera =
    R"("camera": {"fov": 40, "width": 96, "height": 72, "keys": [{"time": 0, "position": [0.5, 1.5, 1.5], "target": [0.5, 0, -0.5]}, )"
    R"({"time": 0.07, "position": [0.5, 1.2, 1.8], "target": [0.5, -0.2, -0.5], "cut": true}]}, )";

// A run with a camera writes it frame by frame (the cut at 0.07 s falls in frame 2, at 0.08 s);
// a run of a scene without one into the same directory leaves no camera of the earlier run.
TEST_F(CliTest, RunWritesTheCameraOfEveryFrame) {
  const std::string path = scene("", kCutCamera);
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--frames", "4", "--threads", "1", "--mode", "view"}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find("to look at it: vdcloth render " + path + " " + out_dir() + " draws it"), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("vdcloth report " + out_dir() + " writes " + out_dir() + "/report/index.html"), std::string::npos) << out_.str();
  const nlohmann::json camera = nlohmann::json::parse(std::ifstream(dir_ / "out" / "camera.json"));
  ASSERT_EQ(camera["frames"].size(), 5u);
  for (int f = 0; f <= 4; ++f) {
    EXPECT_EQ(camera["frames"][f]["cut"], f == 2) << f;
    EXPECT_EQ(camera["frames"][f]["shot"], f < 2 ? 0 : 1) << f;
  }
  EXPECT_EQ(camera["frames"][3]["position"], nlohmann::json({0.5, 1.2, 1.8}));
  EXPECT_EQ(camera["width"], 96);
  std::istringstream chan(read_file(dir_ / "out" / "camera.chan"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(chan, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[3].rfind("3 0.5 1.2 1.8 ", 0), 0u) << lines[3];
  EXPECT_EQ(lines[3].substr(lines[3].rfind(' ')), " 40") << lines[3];
  // Obstacle-free sheet frames are rounded to the micrometre: no coordinate longer than 6 decimals.
  const std::string obj = read_file(dir_ / "out" / "frames" / "cloth_s.0004.obj");
  EXPECT_EQ(obj.find("0000000"), std::string::npos);
  std::istringstream lines_of_obj(obj);
  for (std::string line; std::getline(lines_of_obj, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    for (std::string number; in >> number;) {
      const auto point = number.find('.');
      EXPECT_TRUE(point == std::string::npos || number.size() - point - 1 <= 6) << line;
    }
  }

  ASSERT_EQ(run({"run", write("bare.json", read_file(scene())), "--out", out_dir(), "--frames", "1", "--threads", "1"}), kExitOk)
      << err_.str();
  EXPECT_FALSE(fs::exists(dir_ / "out" / "camera.json"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "camera.chan"));
  EXPECT_EQ(out_.str().find("to look at it"), std::string::npos) << "no camera, nothing to draw through";
}

// A shot with two named cameras, one over the sheet and one looking away from it, writes each
// camera's files (and no camera.json), says in its PLY files which camera decided each face (the
// one over the sheet, as the other sees none of it), and render and fidelity look through the
// camera --camera names; a stereo camera's eyes are written as left and right.
TEST_F(CliTest, AShotWithSeveralCamerasWritesEachAndLooksThroughTheOneNamed) {
  const std::string lens = R"("fov": 40, "width": 96, "height": 72, )";
  const std::string path = scene("", R"("cameras": [{"name": "over", )" + lens +
                                         R"("keys": [{"time": 0, "position": [0.5, 1.5, 1.5], "target": [0.5, 0, -0.5]}]},
      {"name": "away", )" + lens + R"("keys": [{"time": 0, "position": [0.5, 1.5, 1.5], "target": [0.5, 3, 3]}]}], )");
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--frames", "2", "--threads", "1", "--mode", "view"}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find(out_dir() + "/camera_over.chan the camera"), std::string::npos) << out_.str();
  EXPECT_FALSE(fs::exists(dir_ / "out" / "camera.json"));
  for (const std::string name : {"over", "away"}) {
    ASSERT_TRUE(fs::exists(dir_ / "out" / ("camera_" + name + ".chan"))) << name;
    const nlohmann::json camera = nlohmann::json::parse(std::ifstream(dir_ / "out" / ("camera_" + name + ".json")));
    EXPECT_EQ(camera["name"], name);
    EXPECT_EQ(camera["index"], name == "over" ? 0 : 1);
    EXPECT_EQ(camera["frames"].size(), 3u);
  }
  const PlyFaceValues ply = read_ply_with_face_values((dir_ / "out" / "frames" / "cloth_s.0002.ply").string());
  ASSERT_EQ(ply.more.count("camera"), 1u);
  ASSERT_FALSE(ply.more.at("camera").empty());
  for (const double decider : ply.more.at("camera")) EXPECT_EQ(decider, 0.0);

  ASSERT_EQ(run({"render", path, out_dir(), "--camera", "away", "--scale", "1"}), kExitOk) << err_.str();
  EXPECT_TRUE(fs::exists(dir_ / "out" / "render_away" / "frame_0002.png"));
  ASSERT_EQ(run({"fidelity", path, out_dir(), out_dir(), "--camera", "over", "--scale", "1"}), kExitOk) << out_.str() << err_.str();
  const auto frames = csv_rows(dir_ / "out" / "fidelity_over" / "fidelity.csv");
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_GT(std::stoi(frames[2].at("cloth_pixels_run")), 300) << "the camera over the sheet sees it";

  const std::string stereo = write("stereo.json", read_file(scene("", R"("camera": {)" + lens + R"("stereo": {"interaxial": 0.1},
      "keys": [{"time": 0, "position": [0.5, 1.5, 1.5], "target": [0.5, 0, -0.5]}]}, )")));
  ASSERT_EQ(run({"run", stereo, "--out", out_dir(), "--frames", "1", "--threads", "1", "--mode", "view"}), kExitOk) << err_.str();
  EXPECT_FALSE(fs::exists(dir_ / "out" / "camera_over.json")) << "an earlier run's cameras removed";
  const nlohmann::json left = nlohmann::json::parse(std::ifstream(dir_ / "out" / "camera_left.json"));
  const nlohmann::json right = nlohmann::json::parse(std::ifstream(dir_ / "out" / "camera_right.json"));
  EXPECT_EQ(left["eye_offset"], -0.05);
  EXPECT_EQ(right["eye_offset"], 0.05);
  EXPECT_NEAR(right["frames"][0]["position"][0].get<double>() - left["frames"][0]["position"][0].get<double>(), 0.1, 1e-12);
}

// A view run whose scene settles says which frames it sizes as the adaptive run does: with
// settle 0.1 s and 0.04 s frames, frames 1 to 3 (starting at 0, 0.04 and 0.08 s); an adaptive
// run, or a view run without settle, says nothing of it.
TEST_F(CliTest, AViewRunSaysWhichFramesItLeavesToTheAdaptiveSizing) {
  const std::string settles = scene("", kCutCamera + std::string(R"("view": {"settle": 0.1}, )"));
  const std::string said = "sized as in adaptive mode up to frame 3 (view.settle";
  ASSERT_EQ(run({"run", settles, "--out", out_dir(), "--frames", "1", "--threads", "1", "--mode", "view"}), kExitOk) << err_.str();
  EXPECT_NE((out_.str() + err_.str()).find(said), std::string::npos) << out_.str() << err_.str();
  ASSERT_EQ(run({"run", settles, "--out", out_dir(), "--frames", "1", "--threads", "1", "--mode", "adaptive"}), kExitOk) << err_.str();
  EXPECT_EQ((out_.str() + err_.str()).find("sized as in adaptive mode"), std::string::npos) << out_.str() << err_.str();
  ASSERT_EQ(run({"run", scene("", kCutCamera), "--out", out_dir(), "--frames", "1", "--threads", "1", "--mode", "view"}), kExitOk) << err_.str();
  EXPECT_EQ((out_.str() + err_.str()).find("sized as in adaptive mode"), std::string::npos) << out_.str() << err_.str();
}

TEST_F(CliTest, FidelityOfARunAgainstItselfIsPerfectInEveryShot) {
  const std::string path = scene(", \"handles\": [{\"uv\": [[0, 1], [1, 1]]}]", kCutCamera);
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--frames", "4", "--threads", "1"}), kExitOk) << err_.str();
  ASSERT_EQ(run({"fidelity", path, out_dir(), out_dir(), "--floor", out_dir(), "--scale", "1"}), kExitOk) << out_.str() << err_.str();
  EXPECT_NE(out_.str().find("shot 0 (frames 0-1): overlap 1.000 mean / 1.000 min (floor 1.000 / 1.000), detail 100% of reference "
                            "(floor 100%), popping 1.00x (floor 1.00x): pass"),
            std::string::npos)
      << out_.str();
  EXPECT_NE(out_.str().find("shot 1 (frames 2-4): "), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("all (frames 0-4): "), std::string::npos) << out_.str();
  const fs::path dir = dir_ / "out" / "fidelity";
  EXPECT_FALSE(fs::exists(dir / "fidelity.csv.partial"));
  EXPECT_FALSE(fs::exists(dir / "fidelity_shots.csv.partial"));
  const auto frames = csv_rows(dir / "fidelity.csv");
  ASSERT_EQ(frames.size(), 5u);
  double most_popping = 0;
  for (int k = 0; k <= 4; ++k) {
    const auto& row = frames[static_cast<std::size_t>(k)];
    EXPECT_EQ(row.at("frame"), std::to_string(k));
    EXPECT_EQ(row.at("shot"), k < 2 ? "0" : "1") << "shot of frame " << k;
    EXPECT_GT(std::stoi(row.at("cloth_pixels_run")), 300) << "the sheet is in the picture at frame " << k;
    EXPECT_EQ(row.at("cloth_pixels_run"), row.at("cloth_pixels_reference")) << k;
    EXPECT_EQ(row.at("overlap"), "1") << k;
    EXPECT_EQ(row.at("floor_overlap"), "1") << k;
    EXPECT_EQ(row.at("detail_run"), row.at("detail_reference")) << k;
    EXPECT_EQ(row.at("detail_run"), row.at("detail_floor")) << k;
    const bool first_of_shot = k == 0 || k == 2;
    EXPECT_EQ(row.at("popping_run").empty(), first_of_shot) << k;
    EXPECT_EQ(row.at("popping_run"), row.at("popping_reference")) << k;
    EXPECT_EQ(row.at("popping_run"), row.at("popping_floor")) << k;
    if (!first_of_shot) most_popping = std::max(most_popping, std::stod(row.at("popping_run")));
  }
  EXPECT_GT(most_popping, 0) << "the sheet falls";
  EXPECT_GT(std::stod(frames[4].at("detail_run")), 0) << "the hanging sheet curves";
  EXPECT_EQ(first_line(dir / "fidelity.csv"), kFidelityFramesHeader);
  EXPECT_EQ(first_line(dir / "fidelity_garments.csv"), kFidelityGarmentsHeader);
  EXPECT_EQ(first_line(dir / "fidelity_shots.csv"), kFidelityShotsHeader);
  EXPECT_FALSE(fs::exists(dir / "fidelity_garments.csv.partial"));
  const auto garment_rows = csv_rows(dir / "fidelity_garments.csv");
  ASSERT_EQ(garment_rows.size(), 5u) << "one garment, five frames";
  for (const auto& row : garment_rows) {
    EXPECT_EQ(row.at("pixels_run"), frames[static_cast<std::size_t>(std::stoi(row.at("frame")))].at("cloth_pixels_run"));
    EXPECT_EQ(row.at("overlap"), "1") << row.at("frame");
    EXPECT_EQ(row.at("floor_overlap"), "1") << row.at("frame");
  }
  const auto shots = csv_rows(dir / "fidelity_shots.csv");
  ASSERT_EQ(shots.size(), 3u);
  const std::vector<std::string> expect_shot{"0", "1", "all"}, expect_frames{"2", "3", "5"}, expect_pairs{"1", "2", "3"};
  for (std::size_t k = 0; k < shots.size(); ++k) {
    const auto& row = shots[k];
    EXPECT_EQ(row.at("shot"), expect_shot[k]);
    EXPECT_EQ(row.at("frames"), expect_frames[k]) << row.at("shot");
    EXPECT_EQ(row.at("overlap_mean"), "1") << row.at("shot");
    EXPECT_EQ(row.at("floor_overlap_mean"), "1") << row.at("shot");
    EXPECT_EQ(row.at("detail_ratio"), "1") << row.at("shot");
    EXPECT_EQ(row.at("popping_pairs"), expect_pairs[k]) << row.at("shot");
    EXPECT_EQ(row.at("popping_ratio"), "1") << row.at("shot");
    EXPECT_EQ(row.at("verdict"), "pass") << row.at("shot");
    EXPECT_EQ(row.at("failed"), "") << row.at("shot");
    EXPECT_EQ(row.at("detail_floor_ratio"), "1") << row.at("shot");
    EXPECT_EQ(row.at("popping_floor_ratio"), "1") << row.at("shot");
  }
  // Every other frame: frame 4's popping is measured from frame 3, drawn for it, as above.
  const fs::path every = dir_ / "every2";
  ASSERT_EQ(run({"fidelity", path, out_dir(), out_dir(), "--every", "2", "--scale", "1", "--out", every.string()}), kExitOk) << err_.str();
  const auto sparse = csv_rows(every / "fidelity.csv");
  ASSERT_EQ(sparse.size(), 3u);
  EXPECT_EQ(sparse[1].at("frame"), "2");
  EXPECT_EQ(sparse[1].at("popping_run"), "") << "frame 2 starts shot 1";
  EXPECT_EQ(sparse[2].at("frame"), "4");
  EXPECT_EQ(sparse[2].at("popping_run"), frames[4].at("popping_run"));
  EXPECT_EQ(sparse[2].at("floor_overlap"), "") << "no floor";
}

// Two flat rectangles facing a still camera, in a scene without gravity (the run keeps them
// where they are), their edges a quarter pixel off the pixel centres: 20 x 24 and 16 x 24 pixels.
// A copy of the run with the first moved 5 pixels sideways overlaps the run by
// (15 x 24 + 16 x 24) / (25 x 24 + 16 x 24) = 31/41 at every frame.
TEST_F(CliTest, FidelityOfAGarmentMovedByWholePixelsGivesTheOverlapComputedByHand) {
  const Camera lens{.position = Vec3(0, 0, 2), .target = Vec3::Zero(), .fov_y_degrees = 40, .width = 64, .height = 48};
  const double metres_per_pixel = 2 / lens.focal_pixels();  // at the rectangles' depth
  // The rectangle that covers screen x from x0 to x1 and y from y0 to y1 (y down).
  auto rectangle = [&](double x0, double x1, double y0, double y1) {
    const double left = (x0 - 32) * metres_per_pixel, right = (x1 - 32) * metres_per_pixel;
    const double top = (24 - y0) * metres_per_pixel, bottom = (24 - y1) * metres_per_pixel;
    std::ostringstream obj;
    obj << std::setprecision(17) << "v " << left << " " << bottom << " 0\nv " << right << " " << bottom << " 0\nv " << right << " " << top
        << " 0\nv " << left << " " << top << " 0\nvt 0 0\nvt " << right - left << " 0\nvt " << right - left << " " << top - bottom << "\nvt 0 "
        << top - bottom << "\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    return obj.str();
  };
  write("a.obj", rectangle(10.25, 30.25, 12.25, 36.25));  // columns 10 to 29, rows 12 to 35
  write("b.obj", rectangle(40.25, 56.25, 12.25, 36.25));  // columns 40 to 55
  const std::string path = write(
      "still.json",
      R"({"frames": 2, "substeps": 2, "gravity": [0, 0, 0], "remeshing": {"fixed_size": 2}, )"
      R"("camera": {"fov": 40, "width": 64, "height": 48, "keys": [{"time": 0, "position": [0, 0, 2], "target": [0, 0, 0]}]}, )"
      R"("garments": [{"name": "a", "mesh": "a.obj", "material": "cotton.json"}, {"name": "b", "mesh": "b.obj", "material": "cotton.json"}]})");
  ASSERT_EQ(run({"run", path, "--out", out_dir(), "--threads", "1"}), kExitOk) << err_.str();
  const fs::path moved = dir_ / "moved";
  fs::copy(out_dir(), moved, fs::copy_options::recursive);
  int moved_files = 0;
  for (const auto& entry : fs::directory_iterator(moved / "frames")) {
    if (entry.path().filename().string().rfind("cloth_a.", 0) != 0 || entry.path().extension() != ".obj") continue;
    std::ifstream in(entry.path());
    std::ostringstream text;
    text << std::setprecision(17);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("v ", 0) == 0) {
        std::istringstream v(line.substr(2));
        double x = 0, y = 0, z = 0;
        v >> x >> y >> z;
        text << "v " << x + 5 * metres_per_pixel << " " << y << " " << z << "\n";
      } else {
        text << line << "\n";
      }
    }
    in.close();
    std::ofstream(entry.path()) << text.str();
    ++moved_files;
  }
  ASSERT_EQ(moved_files, 3);
  // Without a floor the overlap is not judged; nothing moves in either run (popping 0 / 0).
  const fs::path plain = dir_ / "plain", floored = dir_ / "floored";
  ASSERT_EQ(run({"fidelity", path, moved.string(), out_dir(), "--scale", "1", "--out", plain.string()}), kExitOk) << out_.str() << err_.str();
  const auto rows = csv_rows(plain / "fidelity.csv");
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("cloth_pixels_run"), "864") << row.at("frame");
    EXPECT_EQ(row.at("cloth_pixels_reference"), "864") << row.at("frame");
    EXPECT_NEAR(std::stod(row.at("overlap")), 31.0 / 41.0, 1e-6) << row.at("frame");
  }
  // Garment by garment: a overlaps its place in the reference by 15 x 24 over 25 x 24 pixels, b
  // by all of its own; a first, the lower.
  const auto garment_rows = csv_rows(plain / "fidelity_garments.csv");
  ASSERT_EQ(garment_rows.size(), 6u) << "two garments, three frames";
  for (const auto& row : garment_rows) {
    const bool a = row.at("garment") == "a";
    EXPECT_EQ(row.at("pixels_run"), a ? "480" : "384") << row.at("frame");
    EXPECT_EQ(row.at("pixels_reference"), row.at("pixels_run")) << row.at("frame");
    EXPECT_NEAR(std::stod(row.at("overlap")), a ? 0.6 : 1.0, 1e-12) << row.at("garment") << " " << row.at("frame");
    EXPECT_EQ(row.at("floor_overlap"), "") << "no floor";
  }
  EXPECT_NE(out_.str().find("garments by overlap over the run, lowest first: a 0.600, b 1.000\n"), std::string::npos) << out_.str();
  EXPECT_EQ(out_.str().find("pixels lost beyond the floor"), std::string::npos) << "no floor, no departure";
  // Against the unmoved run as the floor (overlap 1), both overlap targets fail: exit status 3.
  EXPECT_EQ(run({"fidelity", path, moved.string(), out_dir(), "--floor", out_dir(), "--scale", "1", "--out", floored.string()}),
            kExitSimulationFailed)
      << out_.str() << err_.str();
  EXPECT_NE(out_.str().find("overlap 0.756 mean / 0.756 min (floor 1.000 / 1.000)"), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find(": fail (overlap mean, overlap min)"), std::string::npos) << out_.str();
  EXPECT_NE(out_.str().find("lowest first: a 0.600 (floor 1.000), b 1.000 (floor 1.000)\n"), std::string::npos) << out_.str();
  // Only a loses pixels beyond the floor (240 of its 600 a frame): all of the departure.
  EXPECT_NE(out_.str().find("garments by their part of the pixels lost beyond the floor, largest first: a 100%\n"), std::string::npos)
      << out_.str();
  const auto shots = csv_rows(floored / "fidelity_shots.csv");
  ASSERT_EQ(shots.size(), 2u);
  EXPECT_EQ(shots[1].at("shot"), "all");
  EXPECT_EQ(shots[1].at("verdict"), "fail");
  EXPECT_EQ(shots[1].at("failed"), "overlap mean;overlap min");
  EXPECT_EQ(shots[1].at("floors"), "1");
  EXPECT_EQ(shots[1].at("floor_overlap_means"), "1");
  // Two floor runs, the unmoved run (overlap 1) and the moved one (31 / 41): the floor is their
  // mean, (1 + 31 / 41) / 2 = 0.878049, at every frame and over the run, its minimum the mean of
  // theirs; a's floor pooled over both, (480 + 15 x 24) / (480 + 25 x 24) = 0.778. With margins
  // of 0.125 the run's 0.756 passes.
  const fs::path two = dir_ / "two";
  EXPECT_EQ(run({"fidelity", path, moved.string(), out_dir(), "--floor", out_dir(), "--floor", moved.string(), "--scale", "1",
                 "--overlap-margin", "0.125", "--min-margin", "0.125", "--out", two.string()}),
            kExitOk)
      << out_.str() << err_.str();
  EXPECT_NE(out_.str().find("overlap 0.756 mean / 0.756 min (floor 0.878 / 0.878, mean of 2 floor runs, their means 0.756 to 1.000)"),
            std::string::npos)
      << out_.str();
  EXPECT_NE(out_.str().find("lowest first: a 0.600 (floor 0.778), b 1.000 (floor 1.000)\n"), std::string::npos) << out_.str();
  for (const auto& row : csv_rows(two / "fidelity.csv")) {
    EXPECT_NEAR(std::stod(row.at("floor_overlap")), (1 + 31.0 / 41.0) / 2, 1e-6) << row.at("frame");
    EXPECT_EQ(row.at("floor_overlaps"), "1;0.756098") << row.at("frame");
  }
  const auto two_shots = csv_rows(two / "fidelity_shots.csv");
  ASSERT_EQ(two_shots.size(), 2u);
  EXPECT_EQ(two_shots[1].at("verdict"), "pass");
  EXPECT_EQ(two_shots[1].at("floors"), "2");
  EXPECT_EQ(two_shots[1].at("floor_overlap_means"), "1;0.756098");
  EXPECT_EQ(two_shots[1].at("floor_overlap_mins"), "1;0.756098");
  EXPECT_NEAR(std::stod(two_shots[1].at("floor_overlap_min")), (1 + 31.0 / 41.0) / 2, 1e-6);
  EXPECT_EQ(two_shots[1].at("samples"), "1");
  EXPECT_EQ(two_shots[1].at("sample_overlap_means"), "");
  // The moved run judged with the unmoved one as a second sample of its method: the judged
  // overlap is their mean, (31 / 41 + 1) / 2 = 0.878 at every frame, its minimum the mean of
  // theirs, which passes against the one floor run (the moved one, 0.756) by default margins;
  // the garments are the run's own.
  const fs::path sampled = dir_ / "sampled";
  EXPECT_EQ(run({"fidelity", path, moved.string(), out_dir(), "--floor", moved.string(), "--sample", out_dir(), "--scale", "1", "--out",
                 sampled.string()}),
            kExitOk)
      << out_.str() << err_.str();
  EXPECT_NE(out_.str().find("overlap 0.878 mean / 0.878 min (mean of 2 runs, their means 0.756 to 1.000) (floor 0.756 / 0.756)"),
            std::string::npos)
      << out_.str();
  EXPECT_NE(out_.str().find("lowest first: a 0.600 (floor 0.600), b 1.000 (floor 1.000)\n"), std::string::npos) << out_.str();
  for (const auto& row : csv_rows(sampled / "fidelity.csv")) {
    EXPECT_NEAR(std::stod(row.at("overlap")), 31.0 / 41.0, 1e-6) << row.at("frame");
    EXPECT_EQ(row.at("sample_overlaps"), "1") << row.at("frame");
  }
  const auto sampled_shots = csv_rows(sampled / "fidelity_shots.csv");
  ASSERT_EQ(sampled_shots.size(), 2u);
  EXPECT_EQ(sampled_shots[1].at("verdict"), "pass");
  EXPECT_NEAR(std::stod(sampled_shots[1].at("overlap_mean")), (1 + 31.0 / 41.0) / 2, 1e-6);
  EXPECT_NEAR(std::stod(sampled_shots[1].at("overlap_min")), (1 + 31.0 / 41.0) / 2, 1e-6);
  EXPECT_EQ(sampled_shots[1].at("samples"), "2");
  EXPECT_EQ(sampled_shots[1].at("sample_overlap_means"), "0.756098;1");
  EXPECT_EQ(sampled_shots[1].at("sample_overlap_mins"), "0.756098;1");
}

TEST_F(CliTest, FidelityBadInputsExitTwoAndWriteNothing) {
  const std::string no_camera = write("bare.json", read_file(scene()));
  const std::string with_camera = scene("", kCutCamera);
  ASSERT_EQ(run({"run", with_camera, "--out", out_dir(), "--frames", "2", "--threads", "1"}), kExitOk) << err_.str();
  const fs::path lonely = dir_ / "lonely" / "frames";  // a run with only a frame the other lacks
  fs::create_directories(lonely);
  fs::copy_file(dir_ / "out" / "frames" / "cloth_s.0001.obj", lonely / "cloth_s.0007.obj");
  const fs::path damaged = dir_ / "damaged";  // a mesh the command meets part-way
  fs::copy(out_dir(), damaged, fs::copy_options::recursive);
  std::ofstream(damaged / "frames" / "cloth_s.0002.obj") << "v 0 0 0\nf 1 2 3\n";
  const std::string fid = (dir_ / "fid").string();
  struct Case {
    const char* what;
    std::vector<std::string> args;
    std::vector<std::string> expect;
  };
  const std::string run_dir = out_dir(), nowhere = (dir_ / "nowhere").string();
  const std::vector<Case> cases{
      {"missing run", {with_camera, nowhere, run_dir}, {"nowhere/frames", "no such directory"}},
      {"missing reference", {with_camera, run_dir, nowhere}, {"nowhere/frames"}},
      {"missing floor", {with_camera, run_dir, run_dir, "--floor", nowhere}, {"nowhere/frames"}},
      {"missing sample", {with_camera, run_dir, run_dir, "--sample", nowhere}, {"nowhere/frames"}},
      {"a sample without a frame in common", {with_camera, run_dir, run_dir, "--sample", (dir_ / "lonely").string()},
       {"no frame in common with", "lonely"}},
      {"no frame in common", {with_camera, run_dir, (dir_ / "lonely").string()}, {"no frame in common with", "lonely"}},
      {"no camera", {no_camera, run_dir, run_dir}, {"bare.json", "camera", "no camera"}},
      {"missing scene", {(dir_ / "none.json").string(), run_dir, run_dir}, {"none.json"}},
      {"a damaged mesh", {with_camera, damaged.string(), run_dir}, {"cloth_s.0002.obj"}},
      {"two directories only", {with_camera, run_dir}, {"fidelity expects SCENE.json, RUN_DIR and REFERENCE_DIR"}},
      {"every 0", {with_camera, run_dir, run_dir, "--every", "0"}, {"--every", "'0'"}},
      {"scale 9", {with_camera, run_dir, run_dir, "--scale", "9"}, {"--scale", "0.05 to 4", "'9'"}},
      {"negative detail", {with_camera, run_dir, run_dir, "--detail", "-1"}, {"--detail", "0 to 10"}},
      {"popping not a number", {with_camera, run_dir, run_dir, "--popping", "x"}, {"--popping", "'x'"}},
      {"margin above 1", {with_camera, run_dir, run_dir, "--overlap-margin", "2"}, {"--overlap-margin", "0 to 1"}},
      {"margin not a number", {with_camera, run_dir, run_dir, "--min-margin", "nan"}, {"--min-margin", "'nan'"}},
      {"floor without a value", {with_camera, run_dir, run_dir, "--floor"}, {"--floor needs a value"}},
      {"sample without a value", {with_camera, run_dir, run_dir, "--sample"}, {"--sample needs a value"}},
      {"unknown option", {with_camera, run_dir, run_dir, "--frobnicate"}, {"unknown option '--frobnicate'"}},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"fidelity"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.insert(args.begin() + 1, {"--out", fid});
    EXPECT_EQ(run(args), kExitBadInput) << c.what << ": " << out_.str();
    const std::string message = err_.str();
    for (const auto& text : c.expect) EXPECT_NE(message.find(text), std::string::npos) << c.what << ": '" << text << "' not in: " << message;
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << c.what << ": " << message;
    EXPECT_FALSE(fs::exists(fid)) << c.what << " left output behind";
    EXPECT_FALSE(fs::exists(dir_ / "out" / "fidelity")) << c.what;
    EXPECT_FALSE(fs::exists(damaged / "fidelity")) << c.what;
  }
  EXPECT_EQ(run({"fidelity", "--help"}), kExitOk);
  for (const char* option : {"--floor", "--sample", "--every", "--scale", "--out", "--overlap-margin", "--min-margin", "--detail", "--popping", "--perturb 1e-6"})
    EXPECT_NE(out_.str().find(option), std::string::npos) << option;
  EXPECT_EQ(run({"--help"}), kExitOk);
  EXPECT_NE(out_.str().find("vdcloth fidelity"), std::string::npos);
}

// Gravity one part in a million stronger: the same first state, another second frame. The
// perturbation is in summary.json and the checkpoint, and a resumption must keep it.
TEST_F(CliTest, PerturbChangesTheRunAndAResumptionMustKeepIt) {
  const std::string path = scene(", \"handles\": [{\"uv\": [[0, 1], [1, 1]]}]");
  const fs::path plain = dir_ / "plain", perturbed = dir_ / "perturbed";
  ASSERT_EQ(run({"run", path, "--out", plain.string(), "--frames", "2", "--threads", "1"}), kExitOk) << err_.str();
  ASSERT_EQ(run({"run", path, "--out", perturbed.string(), "--frames", "1", "--threads", "1", "--perturb", "1e-6"}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find("gravity perturbed by 1e-06"), std::string::npos) << out_.str();
  EXPECT_EQ(run({"run", path, "--out", perturbed.string(), "--frames", "2", "--threads", "1", "--resume"}), kExitBadInput);
  EXPECT_NE(err_.str().find("made with --perturb 1e-06, not 0; resume it with --perturb 1e-06"), std::string::npos) << err_.str();
  EXPECT_FALSE(fs::exists(perturbed / "frames" / "cloth_s.0002.obj"));
  ASSERT_EQ(run({"run", path, "--out", perturbed.string(), "--frames", "2", "--threads", "1", "--resume", "--perturb", "1e-6"}), kExitOk)
      << err_.str();
  EXPECT_EQ(read_file(perturbed / "frames" / "cloth_s.0000.obj"), read_file(plain / "frames" / "cloth_s.0000.obj"));
  // The sheet has fallen about 3 cm by frame 2, a millionth of it below the frames' micrometre:
  // the energies (nine digits) tell the runs apart. Gravity's pull grew by 1e-6, so the
  // gravitational energy (m g h, h < 0 from the start) moves by one part in a million at least.
  const double u_plain = stats_column(plain / "stats.csv", "gravitational_energy", 2);
  const double u_perturbed = stats_column(perturbed / "stats.csv", "gravitational_energy", 2);
  EXPECT_GT(std::abs(u_perturbed - u_plain), 0.5e-6 * std::abs(u_plain)) << u_plain << " " << u_perturbed;
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(perturbed / "summary.json"))["perturbation"].get<double>(), 1e-6);
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(plain / "summary.json"))["perturbation"].get<double>(), 0.0);
  // And the other way: an unperturbed run resumed with a perturbation.
  EXPECT_EQ(run({"run", path, "--out", plain.string(), "--frames", "3", "--threads", "1", "--resume", "--perturb", "-1e-6"}), kExitBadInput);
  EXPECT_NE(err_.str().find("made with --perturb 0, not -1e-06"), std::string::npos) << err_.str();
  EXPECT_EQ(run({"run", "--help"}), kExitOk);
  EXPECT_NE(out_.str().find("--perturb E"), std::string::npos) << out_.str();
}

// Every edge allowed 5% longer: the same start, another remeshed first frame. Sizes fixed at
// 24 cm refine the unit sheet to a grid of 12.5 cm (128 faces: 25 cm edges are too long); 5%
// longer, 25.2 cm, keeps the grid of 25 cm (64 faces). Like --perturb, in summary.json and the
// checkpoint, and a resumption must keep it.
TEST_F(CliTest, PerturbResolutionChangesTheMeshAndAResumptionMustKeepIt) {
  const std::string path = write("scene.json", R"({"frames": 2, "substeps": 2, "remeshing": {"size": [0.24, 0.24]},
    "garments": [{"name": "s", "mesh": "sheet.obj", "material": "cotton.json", "handles": [{"uv": [[0, 1], [1, 1]]}]}]})");
  const fs::path plain = dir_ / "plain", coarser = dir_ / "coarser";
  const std::vector<std::string> adaptive{"--mode", "adaptive", "--threads", "1"};
  auto with = [&](std::vector<std::string> args) {
    args.insert(args.end(), adaptive.begin(), adaptive.end());
    return run(args);
  };
  ASSERT_EQ(with({"run", path, "--out", plain.string(), "--frames", "2"}), kExitOk) << err_.str();
  ASSERT_EQ(with({"run", path, "--out", coarser.string(), "--frames", "1", "--perturb-resolution", "0.05"}), kExitOk) << err_.str();
  EXPECT_NE(out_.str().find("resolution perturbed by 0.05"), std::string::npos) << out_.str();
  EXPECT_EQ(with({"run", path, "--out", coarser.string(), "--frames", "2", "--resume"}), kExitBadInput);
  EXPECT_NE(err_.str().find("made with --perturb-resolution 0.05, not 0; resume it with --perturb-resolution 0.05"), std::string::npos)
      << err_.str();
  ASSERT_EQ(with({"run", path, "--out", coarser.string(), "--frames", "2", "--resume", "--perturb-resolution", "0.05"}), kExitOk)
      << err_.str();
  EXPECT_EQ(read_file(coarser / "frames" / "cloth_s.0000.obj"), read_file(plain / "frames" / "cloth_s.0000.obj"));
  for (int frame = 1; frame <= 2; ++frame) {
    EXPECT_EQ(stats_column(plain / "stats.csv", "faces", frame), 128) << frame;
    EXPECT_EQ(stats_column(coarser / "stats.csv", "faces", frame), 64) << frame;
  }
  const auto summary = nlohmann::json::parse(std::ifstream(coarser / "summary.json"));
  EXPECT_EQ(summary["resolution_perturbation"].get<double>(), 0.05);
  EXPECT_EQ(summary["perturbation"].get<double>(), 0.0);
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(plain / "summary.json"))["resolution_perturbation"].get<double>(), 0.0);
  EXPECT_EQ(run({"run", "--help"}), kExitOk);
  EXPECT_NE(out_.str().find("--perturb-resolution E"), std::string::npos) << out_.str();
}

}  // namespace
}  // namespace vdc
