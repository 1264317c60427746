#include "app/run_log.hpp"

namespace vdc {

void RunLog::warn(const std::string& msg) {
  end_line();
  err_ << "vdcloth: " << msg << std::endl;
  if (output_) output_->append_log(msg);
  else early_.push_back(msg);
}

void RunLog::attach(RunOutput& output, const std::string& first) {
  output_ = &output;
  if (!first.empty()) output.append_log(first);
  for (const std::string& msg : early_) output.append_log(msg);
  early_.clear();
}

void RunLog::progress(const std::string& line) {
  if (interactive_) {
    say() << "\r" << line << "   " << std::flush;
    line_open_ = root_;
  } else {
    say() << line << "\n" << std::flush;
  }
}

void RunLog::end_line() {
  if (line_open_) out_ << "\n";
  line_open_ = false;
}

}  // namespace vdc
