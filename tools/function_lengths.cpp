// Lists the functions of C++ sources longer than a limit: vdcloth_function_lengths [--max N]
// [--top K] DIR_OR_FILE... Prints `file:line: name: N lines` for each function over N lines
// (default 120), longest first, and exits 1 when there is one; with --top K it lists the K
// longest whatever their length and exits 0. make test runs it over src/ (tests/CMakeLists.txt).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "function_lengths.hpp"

namespace {

struct Found {
  std::string file;
  vdc::tools::FunctionSpan span;
};

bool is_source(const std::filesystem::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".cpp" || ext == ".hpp" || ext == ".h" || ext == ".cc";
}

int usage() {
  std::fprintf(stderr, "usage: vdcloth_function_lengths [--max N] [--top K] DIR_OR_FILE...\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int max_lines = 120;
  int top = 0;
  std::vector<std::filesystem::path> files;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if ((arg == "--max" || arg == "--top") && a + 1 < argc) {
      char* end = nullptr;
      const long value = std::strtol(argv[++a], &end, 10);
      if (*end != '\0' || value < 1) return usage();
      (arg == "--max" ? max_lines : top) = static_cast<int>(value);
    } else if (std::filesystem::is_directory(arg)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(arg))
        if (entry.is_regular_file() && is_source(entry.path())) files.push_back(entry.path());
    } else if (std::filesystem::is_regular_file(arg)) {
      files.emplace_back(arg);
    } else {
      std::fprintf(stderr, "vdcloth_function_lengths: %s: no such file or directory\n", arg.c_str());
      return 2;
    }
  }
  if (files.empty()) return usage();
  std::sort(files.begin(), files.end());
  std::vector<Found> all;
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    for (const auto& span : vdc::tools::find_functions(text.str())) all.push_back({file.string(), span});
  }
  std::stable_sort(all.begin(), all.end(), [](const Found& a, const Found& b) { return a.span.lines() > b.span.lines(); });
  int over = 0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const bool listed = top > 0 ? static_cast<int>(k) < top : all[k].span.lines() > max_lines;
    if (!listed) continue;
    over += all[k].span.lines() > max_lines;
    std::printf("%s:%d: %s: %d lines\n", all[k].file.c_str(), all[k].span.first_line, all[k].span.name.c_str(),
                all[k].span.lines());
  }
  if (top > 0) return 0;
  if (over > 0) std::printf("%d function(s) over %d lines in %zu files\n", over, max_lines, files.size());
  return over > 0 ? 1 : 0;
}
