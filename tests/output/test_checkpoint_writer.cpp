// Checkpoints written in the background: what is read back is what was given, a write waits
// for the one before it, and a failed write is reported by the next call, with its frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "output/checkpoint_writer.hpp"
#include "scene/scene.hpp"
#include "sim/ensemble.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

TEST(CheckpointWriter, WritesInTurnAndReportsAFailedWriteWithItsFrame) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-writer-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  const fs::path scene = dir / "sheet.json";
  std::ofstream(scene) << R"({"frame_time": 0.04, "substeps": 2, "remeshing": {"fixed_size": 0.2}, "garments": [{"name": "s", "mesh": {"grid": {"size": [0.5, 0.5], "cells": [4, 4]}}, )"
                       << R"("material": ")" << VDCLOTH_SOURCE_DIR << R"(/materials/cotton.json", "handles": [{"box": [[-1, -1, -1], [0.05, 1, 1]]}]}]})";
  Ensemble run(load_scene(scene.string()), SimOptions{SimMode::Fixed, 1});
  auto parts = [&] {
    std::vector<std::string> p;
    for (const auto& part : run.parts()) p.push_back(checkpoint_part(*part));
    return p;
  };
  Checkpoint c;
  c.mode = "fixed";
  c.checkpoint_every = 1;
  const std::string path = (dir / "checkpoint.bin").string();
  {
    CheckpointWriter writer;
    run.step_frame();
    EXPECT_EQ(writer.start(path, c, SimMode::Fixed, 1, parts()), "");
    run.step_frame();
    const double y2 = run.parts()[0]->garment_mesh(0).x(NodeId(24)).y();
    EXPECT_EQ(writer.start(path, c, SimMode::Fixed, 2, parts()), "");  // waits for frame 1's
    EXPECT_EQ(writer.finish(), "");
    const Checkpoint back = read_checkpoint(path);
    EXPECT_EQ(back.frame, 2);
    ASSERT_EQ(back.parts.size(), 1u);
    EXPECT_EQ(back.parts[0].garments.at(0).x(NodeId(24)).y(), y2);
    EXPECT_NE(y2, 0.0);  // the sheet fell: frame 2's state, not the start
    // Into a directory that does not exist: the failure comes with the next call.
    EXPECT_EQ(writer.start((dir / "missing" / "checkpoint.bin").string(), c, SimMode::Fixed, 3, parts()), "");
    const std::string failed = writer.finish();
    EXPECT_NE(failed.find("the checkpoint of frame 3: "), std::string::npos) << failed;
    EXPECT_NE(failed.find("missing"), std::string::npos) << failed;
    EXPECT_EQ(writer.finish(), "");  // reported once
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vdc
