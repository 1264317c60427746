// A file in the temp directory with a name no other test (or test process) uses; removed at the end.
#pragma once
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

namespace vdc::test {

class TempFile {
 public:
  explicit TempFile(const std::string& suffix = ".obj") {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "vdcloth_test_" + std::string(info ? info->name() : "x") + "_" +
                       std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + "_" +
                       std::to_string(counter++) + suffix;
    path_ = (std::filesystem::temp_directory_path() / name).string();
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  const std::string& path() const { return path_; }
  void write(const std::string& text) const {
    std::ofstream out(path_, std::ios::binary);
    out << text;
  }

 private:
  std::string path_;
};

}  // namespace vdc::test
