#include "dist/process_tables.hpp"

#include <cstdlib>
#include <iomanip>
#include <vector>

#include "core/error.hpp"

namespace vdc {

FrameTable::FrameTable(const std::string& path, const std::string& header, int resume_at) : path_(path) {
  std::vector<std::string> kept;
  if (resume_at > 0) {
    std::ifstream in(path_);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line))
      if (std::atoi(line.c_str()) <= resume_at) kept.push_back(line);
  }
  table_.open(path_, std::ios::trunc);
  table_ << header << "\n";
  for (const auto& line : kept) table_ << line << "\n";
  if (!table_) throw OutputError(path_, "cannot write");
}

void FrameTable::process_row(int frame, int process, const ProcessReport& r, double waiting, double moving) {
  int faces = 0;
  for (const PartFrame& p : r.parts) faces += p.stats.faces;
  table_ << frame << "," << process << "," << r.parts.size() << "," << faces << "," << std::fixed << std::setprecision(6) << r.busy_seconds
         << "," << waiting << "," << moving << "\n";
  finish_row();
}

void FrameTable::group_row(const std::string& group, int process, const PartFrame& p) {
  table_ << p.stats.frame << "," << group << "," << process << "," << p.stats.faces << "," << std::fixed << std::setprecision(6) << p.seconds
         << "," << p.stats.far_groups << "\n";
  finish_row();
}

void FrameTable::finish_row() {
  table_.unsetf(std::ios::fixed);
  if (!table_.flush()) throw OutputError(path_, "cannot write");
}

}  // namespace vdc
