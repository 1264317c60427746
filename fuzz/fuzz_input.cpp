#include "fuzz/fuzz_input.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

namespace vdc::fuzz {

namespace fs = std::filesystem;

namespace {

// scratch/common/ and scratch/case/ each hold the common files; inputs go to scratch/case/.
class Scratch {
 public:
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "vdcloth_fuzz_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot make a scratch directory");
    root_ = pattern;
    for (const char* part : {"common", "case"}) fs::copy(VDCLOTH_CORPUS_COMMON, root_ / part, fs::copy_options::recursive);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  fs::path case_dir() const { return root_ / "case"; }

 private:
  fs::path root_;
};

}  // namespace

std::string write_input(const uint8_t* data, std::size_t size, const std::string& name) {
  static const Scratch scratch;
  const std::string path = (scratch.case_dir() / name).string();
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr || (size > 0 && std::fwrite(data, 1, size, file) != size) || std::fclose(file) != 0)
    throw std::runtime_error("cannot write the input to " + path);
  return path;
}

}  // namespace vdc::fuzz
