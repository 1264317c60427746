// read_input_text: a text file comes back byte for byte; a file too large for its kind, a NUL
// byte and a directory are refused, naming the file, the byte and the problem.
#include "io/input_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"

namespace fs = std::filesystem;

namespace vdc {
namespace {

class InputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (fs::temp_directory_path() / ("vdcloth_input_file_" + std::to_string(::getpid()))).string();
  }
  void TearDown() override { fs::remove(path_); }
  void write(const std::string& bytes) { std::ofstream(path_, std::ios::binary) << bytes; }
  // The message of the InputError reading the file with a limit of `max_bytes`.
  std::string refusal(std::uintmax_t max_bytes) {
    try {
      read_input_text(path_, max_bytes, "OBJ");
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "read without complaint";
    return "";
  }
  std::string path_;
};

TEST_F(InputFileTest, TextComesBackByteForByte) {
  const std::string text = "v 0 0 0\r\nv 1 0 0\n\xc3\xa9\n";
  write(text);
  EXPECT_EQ(read_input_text(path_, text.size(), "OBJ"), text);
}

TEST_F(InputFileTest, AFileLargerThanItsKindAllowsIsRefusedUnread) {
  write(std::string((3u << 20) + 1, 'v'));
  EXPECT_EQ(refusal(3u << 20), path_ + ": OBJ files are read up to 3 MiB: this one is larger");
}

TEST_F(InputFileTest, ANulByteIsRefusedAtItsPlace) {
  write(std::string("v 0 0 0\nv 1") + '\0' + "0 0\n");
  EXPECT_EQ(refusal(1000), path_ + ":byte 12: a NUL byte: OBJ files are text");
}

TEST_F(InputFileTest, ADirectoryOrNothingIsRefused) {
  EXPECT_EQ(refusal(1000), path_ + ": file not found");
  fs::create_directory(path_);
  EXPECT_EQ(refusal(1000), path_ + ": not a regular file");
}

}  // namespace
}  // namespace vdc
