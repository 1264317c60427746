#include "dist/frame_report.hpp"

#include "core/binary_io.hpp"

namespace vdc {

std::string encode(const ProcessReport& r) {
  BinaryWriter out;
  out.value<uint64_t>(r.parts.size());
  for (const PartFrame& p : r.parts) {
    out.value<int32_t>(p.group);
    out.value(p.stats);
    out.value(p.seconds);
  }
  out.nested(r.sizes);
  out.value<uint64_t>(r.checkpoint_parts.size());
  for (const std::string& part : r.checkpoint_parts) out.string(part);
  out.value(r.busy_seconds);
  out.value(r.output_seconds);
  out.value(r.waiting_seconds);
  out.value(r.moving_seconds);
  out.value(r.rebuild_seconds_per_face);
  out.string(r.failed_as);
  out.string(r.failure);
  return out.bytes();
}

ProcessReport decode_report(const std::string& bytes) {
  BinaryReader in(bytes.data(), bytes.size());
  ProcessReport r;
  r.parts.resize(in.value<uint64_t>());
  for (PartFrame& p : r.parts) {
    p.group = in.value<int32_t>();
    p.stats = in.value<FrameStats>();
    p.seconds = in.value<double>();
  }
  r.sizes = in.nested<GarmentSize>();
  r.checkpoint_parts.resize(in.value<uint64_t>());
  for (std::string& part : r.checkpoint_parts) part = in.string();
  r.busy_seconds = in.value<double>();
  r.output_seconds = in.value<double>();
  r.waiting_seconds = in.value<double>();
  r.moving_seconds = in.value<double>();
  r.rebuild_seconds_per_face = in.value<double>();
  r.failed_as = in.string();
  r.failure = in.string();
  return r;
}

std::string encode(const FramePlan& plan) {
  BinaryWriter out;
  out.value<uint8_t>(plan.stop ? 1 : 0);
  out.array(plan.moves);
  return out.bytes();
}

FramePlan decode_plan(const std::string& bytes) {
  BinaryReader in(bytes.data(), bytes.size());
  FramePlan plan;
  plan.stop = in.value<uint8_t>() != 0;
  plan.moves = in.array<GroupMove>();
  return plan;
}

}  // namespace vdc
