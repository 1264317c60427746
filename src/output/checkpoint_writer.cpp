// Checkpoints written on a thread of their own, one at a time.
#include "output/checkpoint_writer.hpp"

#include <utility>

#include "core/error.hpp"

namespace vdc {

CheckpointWriter::~CheckpointWriter() {
  try {
    finish();
  } catch (...) {  // a destructor cannot say more
  }
}

std::string CheckpointWriter::start(std::string path, Checkpoint c, SimMode mode, int frame, std::vector<std::string> parts) {
  std::string failed = finish();
  pending_frame_ = frame;
  pending_ = std::async(std::launch::async, [path = std::move(path), c = std::move(c), mode, frame, parts = std::move(parts)] {
    write_checkpoint(path, c, mode, frame, parts);
  });
  return failed;
}

std::string CheckpointWriter::finish() {
  if (!pending_.valid()) return "";
  try {
    pending_.get();
  } catch (const OutputError& e) {
    return "the checkpoint of frame " + std::to_string(pending_frame_) + ": " + e.what();
  }
  return "";
}

}  // namespace vdc
