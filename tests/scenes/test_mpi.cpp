// A run made by several processes under mpirun (Open MPI) writes what one process writes:
// every frame file, stats.csv but its timings, the checkpoint's meshes, byte for byte, for 2
// and 3 processes, with groups moved at every checkpoint, after a process was killed and the
// run resumed on another number of processes, and with more processes than groups.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

namespace vdc {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Four groups of hanging sheets of unequal sizes, apart from each other.
std::string four_groups(const fs::path& dir, int frames, const std::string& linear_solver = "cholmod") {
  fs::create_directories(dir);
  std::string garments;
  const std::pair<const char*, double> sheets[] = {{"a", 0.3}, {"b", 0.5}, {"c", 0.8}, {"d", 0.4}};
  int i = 0;
  for (const auto& [name, width] : sheets) {
    if (!garments.empty()) garments += ", ";
    const std::string w = std::to_string(width), x = std::to_string(i++);
    garments += std::string(R"({"name": ")") + name + R"(", "group": ")" + name + R"(", "mesh": {"grid": {"size": [)" + w + ", " + w +
                R"(], "cells": [16, 16]}}, "transform": {"translate": [)" + x + R"(, 0, 0]}, "material": ")" + VDCLOTH_SOURCE_DIR +
                R"(/materials/cotton.json", "handles": [{"box": [[)" + std::to_string(i - 2) + ", -1, -1], [" + x + R"(.05, 1, 1]]}]})";
  }
  const fs::path path = dir / "four.json";
  std::ofstream(path) << R"({"solver": {"linear": ")" << linear_solver << R"("}, "frame_time": 0.04, "substeps": 2, "frames": )" << frames
                      << R"(, "remeshing": {"size": [0.01, 0.1]}, "garments": [)" << garments << "]}";
  return path.string();
}

// mpirun as CI runs it: as root, oversubscribed on two cores, shared memory without the
// single-copy mechanism containers forbid.
std::string mpirun(int processes) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none "
         "OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -np " + std::to_string(processes) + " ";
}

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string run_command(const std::string& scene, const fs::path& out, const std::string& options) {
  return std::string(VDCLOTH_BINARY) + " run " + scene + " --mode adaptive --threads 1 --out " + out.string() + " " + options + " > " +
         out.string() + ".log 2>&1";
}

// stats.csv without the columns of time and memory.
std::vector<std::string> stats_without_timings(const fs::path& dir) {
  std::ifstream in(dir / "stats.csv");
  std::string header;
  std::getline(in, header);
  std::vector<std::string> names;
  for (std::stringstream h(header); std::getline(h, header, ',');) names.push_back(header);
  static const std::set<std::string> timings{"seconds", "assemble_seconds", "solve_seconds", "remesh_seconds", "collision_seconds",
                                             "view_seconds", "resident_mib"};
  std::vector<std::string> rows;
  for (std::string line; std::getline(in, line);) {
    std::string kept, cell;
    std::size_t c = 0;
    for (std::stringstream l(line); std::getline(l, cell, ','); ++c)
      if (c < names.size() && !timings.count(names[c])) kept += cell + ",";
    rows.push_back(kept);
  }
  return rows;
}

// The checkpoint's mode, frame and meshes: all but the costs so far and the checksum over them.
std::string checkpoint_meshes(const fs::path& dir) {
  const std::string b = contents(dir / "checkpoint.bin");
  std::size_t o = 0;
  auto skip_string = [&] {
    uint64_t n = 0;
    std::memcpy(&n, b.data() + o, 8);
    o += 8 + n;
  };
  skip_string();
  o += 4 + 8 + 8 + 4 + 16;
  const std::size_t mode = o;
  skip_string();
  o += 8;  // frame, segments
  const std::string head = b.substr(mode, o - mode - 4);
  o += 40;  // wall and CPU seconds, peak memory, the machine's ticks
  return head + b.substr(o, b.size() - 8 - o);
}

// `run` wrote the same frames, statistics and checkpoint meshes as `reference`.
void expect_same_run(const fs::path& run, const fs::path& reference) {
  EXPECT_EQ(stats_without_timings(run), stats_without_timings(reference)) << run;
  std::vector<std::string> files, reference_files;
  for (const auto& e : fs::directory_iterator(reference / "frames")) reference_files.push_back(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(run / "frames")) files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  std::sort(reference_files.begin(), reference_files.end());
  ASSERT_EQ(files, reference_files) << run;
  ASSERT_FALSE(files.empty());
  for (const std::string& f : files) ASSERT_TRUE(contents(run / "frames" / f) == contents(reference / "frames" / f)) << run / "frames" / f;
  EXPECT_TRUE(checkpoint_meshes(run) == checkpoint_meshes(reference)) << run;
}

nlohmann::json summary(const fs::path& dir) { return nlohmann::json::parse(contents(dir / "summary.json")); }

class Mpi : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdcloth-mpi-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "-" +
                                        std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_F(Mpi, TwoAndThreeProcessesWriteWhatOneWrites) {
  const std::string scene = four_groups(dir_, 12);
  ASSERT_EQ(shell(run_command(scene, dir_ / "one", "--checkpoint-every 4")), 0) << contents(dir_ / "one.log");
  for (int n : {2, 3}) {
    const fs::path out = dir_ / ("np" + std::to_string(n));
    ASSERT_EQ(shell(mpirun(n) + run_command(scene, out, "--checkpoint-every 4")), 0) << contents(out.string() + ".log");
    expect_same_run(out, dir_ / "one");
    const nlohmann::json s = summary(out);
    EXPECT_EQ(s["status"], "done");
    EXPECT_EQ(s["groups"], 4);
    EXPECT_EQ(s["distribution"]["processes"], n);
    EXPECT_EQ(s["garments"], summary(dir_ / "one")["garments"]);  // every group's sizes, not only rank 0's
    // ranks.csv: a row for each process at each frame; the groups add up to four.
    std::ifstream ranks(out / "ranks.csv");
    std::string line;
    std::getline(ranks, line);
    EXPECT_EQ(line, "frame,process,groups,faces,busy_seconds,waiting_seconds,moving_seconds");
    std::map<int, int> groups;
    int rows = 0;
    while (std::getline(ranks, line)) {
      int frame = 0, process = 0, count = 0;
      ASSERT_EQ(std::sscanf(line.c_str(), "%d,%d,%d", &frame, &process, &count), 3) << line;
      groups[frame] += count;
      ++rows;
    }
    EXPECT_EQ(rows, 12 * n);
    for (const auto& [frame, count] : groups) EXPECT_EQ(count, 4) << "frame " << frame;
    // groups.csv: each group at each frame, its faces those of its garment in stats.csv's sum.
    std::ifstream group_rows(out / "groups.csv");
    std::getline(group_rows, line);
    EXPECT_EQ(line, "frame,group,process,faces,seconds,far");
    std::map<int, int> faces;
    std::set<std::string> named;
    for (rows = 0; std::getline(group_rows, line); ++rows) {
      int frame = 0, process = 0, count = 0;
      char group[8] = {};
      ASSERT_EQ(std::sscanf(line.c_str(), "%d,%7[^,],%d,%d", &frame, group, &process, &count), 4) << line;
      EXPECT_LT(process, n);
      faces[frame] += count;
      named.insert(group);
    }
    EXPECT_EQ(rows, 12 * 4);
    EXPECT_EQ(named, (std::set<std::string>{"a", "b", "c", "d"}));
    const std::vector<std::string> stats = stats_without_timings(out);
    for (const auto& [frame, count] : faces) EXPECT_EQ(std::to_string(frame) + "," + std::to_string(count) + ",", stats[static_cast<std::size_t>(frame - 1)].substr(0, std::to_string(frame).size() + std::to_string(count).size() + 2));
  }
  EXPECT_FALSE(fs::exists(dir_ / "one" / "ranks.csv"));
  // One process of four groups writes groups.csv too, every group on process 0 at full level.
  std::ifstream one(dir_ / "one" / "groups.csv");
  std::string line;
  std::getline(one, line);
  EXPECT_EQ(line, "frame,group,process,faces,seconds,far");
  int rows = 0;
  for (; std::getline(one, line); ++rows) {
    int frame = 0, process = -1, count = 0, far = -1;
    char group[8] = {};
    double seconds = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%7[^,],%d,%d,%lf,%d", &frame, group, &process, &count, &seconds, &far), 6) << line;
    EXPECT_EQ(process, 0);
    EXPECT_EQ(far, 0);
  }
  EXPECT_EQ(rows, 12 * 4);
}

// With the direct solver groups move after every frame, between checkpoints too (every three
// frames here); with cholmod-pcg, whose first guess and preconditioner change its results, only
// where every process restarts its solvers: at the checkpoints.
TEST_F(Mpi, GroupsMovedAfterEveryFrameOrCheckpointChangeNothing) {
  for (const auto& [solver, moving_frames] : {std::pair{"cholmod", std::vector<int>{1, 2, 3, 4, 5, 6, 7}}, std::pair{"cholmod-pcg", std::vector<int>{3, 6}}}) {
    SCOPED_TRACE(solver);
    const fs::path dir = dir_ / solver;
    const std::string scene = four_groups(dir, 8, solver);
    ASSERT_EQ(shell(run_command(scene, dir / "one", "--checkpoint-every 3")), 0) << contents(dir / "one.log");
    for (int n : {2, 3}) {
      const fs::path out = dir / ("moved" + std::to_string(n));
      ASSERT_EQ(shell(mpirun(n) + run_command(scene, out, "--checkpoint-every 3 --force-moves")), 0) << contents(out.string() + ".log");
      expect_same_run(out, dir / "one");
      // Every group to the next process at each of those frames (none after the last).
      const nlohmann::json moves = summary(out)["distribution"]["moves"];
      ASSERT_EQ(moves.size(), 4u * moving_frames.size());
      for (std::size_t k = 0; k < moves.size(); ++k) EXPECT_EQ(moves[k]["frame"], moving_frames[k / 4]);
      for (const auto& m : moves) EXPECT_EQ(m["to"], (m["from"].get<int>() + 1) % n);
      EXPECT_NE(contents(out / "log.txt").find("moves from process"), std::string::npos);
    }
  }
}

// The process of `rank` among those running into `out`, found by its command line and the
// rank mpirun gave it; 0 when there is none yet.
pid_t process_of_rank(const fs::path& out, int rank) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = contents(e.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.rfind(VDCLOTH_BINARY, 0) != 0 || cmdline.find(out.string() + " ") == std::string::npos) continue;
    std::string environ = contents(e.path() / "environ");
    if (environ.find(std::string("OMPI_COMM_WORLD_RANK=") + std::to_string(rank) + '\0') != std::string::npos) return std::stoi(name);
  }
  return 0;
}

TEST_F(Mpi, AKilledProcessFailsTheRunAndAResumeOnThreeFinishesItAsOneWould) {
  const int frames = 150;
  const std::string scene = four_groups(dir_, frames);
  const fs::path out = dir_ / "killed";
  const pid_t launcher = ::fork();
  if (launcher == 0) {
    const std::string command = mpirun(2) + run_command(scene, out, "--checkpoint-every 5");
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ASSERT_GT(launcher, 0);
  // Rank 1 killed once the run has written ten frames (not at a frame boundary).
  pid_t victim = 0;
  for (int i = 0; i < 6000 && !victim; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::ifstream stats(out / "stats.csv");
    int rows = 0;
    for (std::string line; std::getline(stats, line);) ++rows;
    if (rows > 11) victim = process_of_rank(out, 1);
  }
  ASSERT_GT(victim, 0) << "no rank 1 found while the run went on";
  ::kill(victim, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(launcher, &status, 0), launcher);
  // mpirun reports the killed process's status; the run says it failed.
  EXPECT_NE(WEXITSTATUS(status), 0);
  const nlohmann::json failed = summary(out);
  EXPECT_EQ(failed["status"], "failed");
  EXPECT_NE(failed["error"].get<std::string>().find("signal 15"), std::string::npos) << failed["error"];
  EXPECT_LT(failed["frames"].get<int>(), frames);
  EXPECT_NE(contents(out / "log.txt").find("another process of the run ended"), std::string::npos);

  ASSERT_EQ(shell(mpirun(3) + run_command(scene, out, "--checkpoint-every 5 --resume")), 0) << contents(out.string() + ".log");
  EXPECT_NE(contents(out.string() + ".log").find("resumed at frame"), std::string::npos);
  ASSERT_EQ(shell(run_command(scene, dir_ / "one", "--checkpoint-every 5")), 0) << contents(dir_ / "one.log");
  expect_same_run(out, dir_ / "one");
  EXPECT_EQ(summary(out)["segments"], 2);
  EXPECT_EQ(summary(out)["distribution"]["processes"], 3);
}

TEST_F(Mpi, SpareProcessesIdleWithOneWarning) {
  const std::string scene = four_groups(dir_, 4);
  ASSERT_EQ(shell(run_command(scene, dir_ / "one", "")), 0) << contents(dir_ / "one.log");
  const fs::path out = dir_ / "five";
  ASSERT_EQ(shell(mpirun(5) + run_command(scene, out, "")), 0) << contents(out.string() + ".log");
  expect_same_run(out, dir_ / "one");
  const std::string log = contents(out / "log.txt");
  const std::string warning = "5 processes for 4 garment groups: processes 4 to 4 have nothing to do";
  ASSERT_NE(log.find(warning), std::string::npos) << log;
  EXPECT_EQ(log.find(warning, log.find(warning) + 1), std::string::npos) << log;
}

TEST_F(Mpi, BadInputEndsEveryProcessWithStatusTwoSaidOnce) {
  fs::create_directories(dir_);
  const fs::path out = dir_ / "bad";
  EXPECT_EQ(shell(mpirun(2) + run_command((dir_ / "missing.json").string(), out, "")), 2);
  const std::string said = contents(out.string() + ".log");
  const std::string message = (dir_ / "missing.json").string();
  ASSERT_NE(said.find(message), std::string::npos) << said;
  EXPECT_EQ(said.find(message, said.find(message) + 1), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(out));
  const std::string scene = four_groups(dir_, 4);
  EXPECT_EQ(shell(mpirun(2) + run_command(scene, out, "--frames 0")), 2);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace vdc
