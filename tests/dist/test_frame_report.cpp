// What the processes of a run send each other comes back as it was sent.
#include <gtest/gtest.h>

#include "dist/frame_report.hpp"

namespace vdc {
namespace {

TEST(FrameReport, AReportAndAPlanComeBackAsSent) {
  ProcessReport r;
  PartFrame p;
  p.group = 7;
  p.stats.frame = 12;
  p.stats.faces = 345;
  p.stats.energy.kinetic = 0.125;
  p.stats.collision_candidates = 1LL << 40;
  p.seconds = 0.5;
  r.parts = {p};
  r.sizes = {{{300, 170}, {45, 30}}};
  r.checkpoint_parts = {std::string("\0bytes\xff", 7)};
  r.busy_seconds = 1.5;
  r.output_seconds = 0.25;
  r.waiting_seconds = 0.75;
  r.moving_seconds = 2;
  r.rebuild_seconds_per_face = 1e-5;
  r.failed_as = "simulation failed";
  r.failure = "a step failed";
  const ProcessReport back = decode_report(encode(r));
  ASSERT_EQ(back.parts.size(), 1u);
  EXPECT_EQ(back.parts[0].group, 7);
  EXPECT_EQ(back.parts[0].stats.frame, 12);
  EXPECT_EQ(back.parts[0].stats.faces, 345);
  EXPECT_EQ(back.parts[0].stats.energy.kinetic, 0.125);
  EXPECT_EQ(back.parts[0].stats.collision_candidates, 1LL << 40);
  EXPECT_EQ(back.parts[0].seconds, 0.5);
  ASSERT_EQ(back.sizes.size(), 1u);
  ASSERT_EQ(back.sizes[0].size(), 2u);
  EXPECT_EQ(back.sizes[0][1].faces, 45);
  EXPECT_EQ(back.sizes[0][1].vertices, 30);
  EXPECT_EQ(back.checkpoint_parts, r.checkpoint_parts);
  EXPECT_EQ(back.busy_seconds, 1.5);
  EXPECT_EQ(back.output_seconds, 0.25);
  EXPECT_EQ(back.waiting_seconds, 0.75);
  EXPECT_EQ(back.moving_seconds, 2);
  EXPECT_EQ(back.rebuild_seconds_per_face, 1e-5);
  EXPECT_EQ(back.failed_as, "simulation failed");
  EXPECT_EQ(back.failure, "a step failed");

  FramePlan plan;
  plan.stop = true;
  plan.moves = {{3, 0, 2}, {1, 2, 0}};
  const FramePlan plan_back = decode_plan(encode(plan));
  EXPECT_TRUE(plan_back.stop);
  ASSERT_EQ(plan_back.moves.size(), 2u);
  EXPECT_EQ(plan_back.moves[1].group, 1);
  EXPECT_EQ(plan_back.moves[1].from, 2);
  EXPECT_EQ(plan_back.moves[1].to, 0);
}

}  // namespace
}  // namespace vdc
