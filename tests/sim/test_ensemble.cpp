// A crowd's parts are independent: whatever order and threads they are stepped in (the ensemble
// starts the part that took longest last frame first), each part's result is the one it makes
// alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "output/checkpoint.hpp"
#include "scene/scene.hpp"
#include "sim/ensemble.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

// Three groups of hanging sheets of unequal cost (the largest one last in part order, so that
// the longest-first order differs from it after the first frame).
std::string crowd_scene(const fs::path& dir) {
  fs::create_directories(dir);
  std::string garments;
  const std::pair<const char*, double> sheets[] = {{"a", 0.3}, {"b", 0.5}, {"c", 1.0}};
  for (const auto& [name, width] : sheets) {
    if (!garments.empty()) garments += ", ";
    const std::string w = std::to_string(width);
    garments += std::string(R"({"name": ")") + name + R"(", "group": ")" + name + R"(", "mesh": {"grid": {"size": [)" + w + ", " + w +
                R"(], "cells": [4, 4]}}, "material": ")" + VDCLOTH_SOURCE_DIR + R"(/materials/cotton.json", "handles": [{"box": [[-1, -1, -1], [0.05, 1, 1]]}]})";
  }
  const fs::path path = dir / "crowd.json";
  std::ofstream(path) << R"({"frame_time": 0.04, "substeps": 2, "remeshing": {"size": [0.05, 0.2]}, "garments": [)" << garments << "]}";
  return path.string();
}

TEST(Ensemble, PartsGiveTheSameResultsInAnyOrderOnAnyThreads) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-ensemble-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  const std::string path = crowd_scene(dir);
  Ensemble one(load_scene(path), SimOptions{SimMode::Fixed, 1});
  Ensemble two(load_scene(path), SimOptions{SimMode::Fixed, 2});
  ASSERT_EQ(two.parts().size(), 3u);
  for (int f = 0; f < 4; ++f) {
    const FrameStats a = one.step_frame(), b = two.step_frame();
    EXPECT_EQ(a.substeps, b.substeps);
    for (std::size_t k = 0; k < 3; ++k) {
      const Mesh& ma = one.parts()[k]->garment_mesh(0);
      const Mesh& mb = two.parts()[k]->garment_mesh(0);
      ASSERT_EQ(ma.num_nodes(), mb.num_nodes());
      for (NodeId n : ma.nodes()) ASSERT_EQ(ma.x(n), mb.x(n)) << "part " << k << ", frame " << f + 1;
    }
  }
  // The sheets did fall: the test compares moving states, not the initial ones.
  const Mesh& finest = one.parts()[2]->garment_mesh(0);
  double lowest = 0;
  for (NodeId n : finest.nodes()) lowest = std::min(lowest, finest.x(n).y());
  EXPECT_LT(lowest, -0.01);
  fs::remove_all(dir);
}

// A crowd run in shares: the groups kept by keep_groups step exactly as their parts of the
// whole scene do, and a group the scene does not have is named in the error with the ones it has.
TEST(Ensemble, GroupsKeptAloneStepAsInTheWholeScene) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-groups-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  const std::string path = crowd_scene(dir);
  Ensemble whole(load_scene(path), SimOptions{SimMode::Adaptive, 2});
  Ensemble share(keep_groups(load_scene(path), {"c", "a"}), SimOptions{SimMode::Adaptive, 1});
  ASSERT_EQ(share.parts().size(), 2u);
  const std::pair<std::size_t, std::size_t> same[] = {{0, 0}, {1, 2}};  // share's part, whole's part
  for (int f = 0; f < 3; ++f) {
    whole.step_frame();
    share.step_frame();
    for (const auto& [k, w] : same) {
      const Mesh& ms = share.parts()[k]->garment_mesh(0);
      const Mesh& mw = whole.parts()[w]->garment_mesh(0);
      ASSERT_EQ(ms.num_nodes(), mw.num_nodes()) << "part " << w << ", frame " << f + 1;
      ASSERT_EQ(ms.num_faces(), mw.num_faces()) << "part " << w << ", frame " << f + 1;
      for (NodeId n : ms.nodes()) ASSERT_EQ(ms.x(n), mw.x(n)) << "part " << w << ", frame " << f + 1;
    }
  }
  EXPECT_EQ(share.parts()[1]->scene().garments[0].name, "c");
  try {
    keep_groups(load_scene(path), {"a", "d"});
    ADD_FAILURE() << "group d was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "no garment group 'd' (its groups: a, b, c)");
  }
  fs::remove_all(dir);
}

// A group handed from one share of the groups to another at a restart of the solvers (as the
// processes of an MPI run do at a checkpoint) goes on exactly as in an ensemble of every group
// restarted at the same frame; the group's count and frame stay with each share.
TEST(Ensemble, AGroupHandedOverAtARestartGoesOnAsIfItHadStayed) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-handover-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  const std::string path = crowd_scene(dir);
  Ensemble whole(load_scene(path), SimOptions{SimMode::Adaptive, 1});
  Ensemble first(load_scene(path), SimOptions{SimMode::Adaptive, 1}, {}, std::vector<int>{0, 1});
  Ensemble second(load_scene(path), SimOptions{SimMode::Adaptive, 1}, {}, std::vector<int>{2});
  EXPECT_EQ(first.groups(), 3);
  EXPECT_EQ(second.here(), std::vector<int>{2});
  EXPECT_EQ(second.group_scene(1).garments[0].name, "b");  // waiting there
  for (int f = 0; f < 2; ++f) {
    whole.step_frame();
    first.step_parts();
    second.step_parts();
  }
  whole.restart_solvers();
  first.restart_solvers();
  second.restart_solvers();
  const std::string bytes = checkpoint_part(*first.parts()[1]);
  first.drop(1);
  second.adopt(1, read_checkpoint_part(bytes, first.frame(), "test"), "test");
  EXPECT_EQ(first.here(), std::vector<int>{0});
  EXPECT_EQ(second.here(), (std::vector<int>{1, 2}));
  EXPECT_EQ(first.group_scene(1).garments[0].name, "b");  // waiting here now
  for (int f = 2; f < 5; ++f) {
    whole.step_frame();
    first.step_parts();
    const std::vector<PartFrame> frames = second.step_parts();
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].group, 1);
    EXPECT_EQ(frames[0].stats.frame, f + 1);
    for (std::size_t k = 0; k < 2; ++k) {
      const Mesh& moved = second.parts()[k]->garment_mesh(0);
      const Mesh& stayed = whole.parts()[k + 1]->garment_mesh(0);
      ASSERT_EQ(moved.num_faces(), stayed.num_faces()) << "group " << k + 1 << ", frame " << f + 1;
      for (NodeId n : moved.nodes()) ASSERT_EQ(moved.x(n), stayed.x(n)) << "group " << k + 1 << ", frame " << f + 1;
    }
  }
  EXPECT_EQ(second.frame(), 5);
  EXPECT_EQ(first.frame(), 5);
  fs::remove_all(dir);
}

// A scene of grouped and ungrouped garments: each garment lands in its own group's part once,
// the ungrouped ones in one part of their own, and an obstacle of no group in every part.
TEST(Ensemble, SplitGivesEachGarmentToItsGroupOnce) {
  Scene scene;
  for (const auto& [name, group] : {std::pair<std::string, std::string>{"a", "x"}, {"b", ""}, {"c", "x"}, {"d", "y"}}) {
    GarmentSpec g;
    g.name = name;
    g.group = group;
    scene.garments.push_back(g);
  }
  ObstacleSpec floor, body;
  floor.name = "floor";
  body.name = "body";
  body.group = "y";
  scene.obstacles = {floor, body};
  const std::vector<Scene> parts = split_groups(scene);
  ASSERT_EQ(parts.size(), 3u);
  auto names = [](const Scene& s) {
    std::string n;
    for (const auto& g : s.garments) n += "[" + g.name + "]";
    n += " |";
    for (const auto& o : s.obstacles) n += " " + o.name;
    return n;
  };
  EXPECT_EQ(names(parts[0]), "[a][c] | floor");
  EXPECT_EQ(names(parts[1]), "[b] | floor");
  EXPECT_EQ(names(parts[2]), "[d] | floor body");
}

}  // namespace
}  // namespace vdc
