// Checkpoints written in the background, one at a time, so that the run's next frames need not
// wait for the file (rank 0 writes every group's parts while the others would wait for it).
#pragma once
#include <future>
#include <string>
#include <vector>

#include "output/checkpoint.hpp"

namespace vdc {

class CheckpointWriter {
 public:
  CheckpointWriter() = default;
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;
  ~CheckpointWriter();  // waits for the write in progress; its failure is then lost

  // Waits for the write before this one, then writes `parts` at `frame` to `path` on a thread
  // of its own (write_checkpoint). Returns why the write before failed, "" if it did not.
  std::string start(std::string path, Checkpoint c, SimMode mode, int frame, std::vector<std::string> parts);
  // Waits for the write in progress; returns why it failed, "" if it did not (or there is none).
  std::string finish();

 private:
  std::future<void> pending_;
  int pending_frame_ = 0;
};

}  // namespace vdc
