// TextFile: numbers come back exactly, precision matches printf, failures are reported.
#include "io/text_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using vdc::TextFile;

namespace {

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() / ("vdcloth_test_text_file_" + name + "_" + std::to_string(::getpid()))).string();
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

// Doubles of every magnitude, written one per line (more than the buffer holds, so it is flushed
// many times), read back bit for bit.
TEST(TextFile, DoublesComeBackExactly) {
  std::vector<double> values = {0.0, -0.0, 0.1, -1.0 / 3.0, 1e-300, 5e-324, std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::min(), 123456789012345678.0, 2.5};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < 20000; ++i) values.push_back(std::ldexp(mantissa(rng), exponent(rng)));
  const std::string path = temp_path("doubles");
  TextFile out(path);
  ASSERT_TRUE(out.ok());
  for (double v : values) out.text("v ").number(v).text("\n");
  ASSERT_TRUE(out.close());

  std::istringstream in(contents(path));
  std::string tag, token;
  std::size_t i = 0;
  while (in >> tag >> token) {
    ASSERT_EQ(tag, "v");
    ASSERT_LT(i, values.size());
    double back = 0;
    const auto res = std::from_chars(token.data(), token.data() + token.size(), back);
    ASSERT_EQ(res.ec, std::errc());
    ASSERT_EQ(res.ptr, token.data() + token.size());
    EXPECT_EQ(back, values[i]) << token;
    EXPECT_EQ(std::signbit(back), std::signbit(values[i])) << token;
    ++i;
  }
  EXPECT_EQ(i, values.size());
  fs::remove(path);
}

// number(v, p) and integer(n) print what printf's %.<p>g and %lld print.
TEST(TextFile, PrecisionAndIntegersMatchPrintf) {
  const std::vector<double> values = {0.0, 1.0, 0.123456789, 1234567.0, 1e-7, 0.01, 0.2, 99999.95, -3.14159265};
  const std::vector<long long> integers = {0, 1, -1, 42, 2147483647, -9223372036854775807LL};
  const std::string path = temp_path("precision");
  TextFile out(path);
  std::string expected;
  char buf[64];
  for (double v : values) {
    out.number(v, 6).text(" ");
    std::snprintf(buf, sizeof buf, "%.6g ", v);
    expected += buf;
  }
  for (long long n : integers) {
    out.integer(n).text(" ");
    std::snprintf(buf, sizeof buf, "%lld ", n);
    expected += buf;
  }
  ASSERT_TRUE(out.close());
  EXPECT_EQ(contents(path), expected);
  fs::remove(path);
}

TEST(TextFile, UnwritablePathIsReported) {
  TextFile out(temp_path("missing") + "/sub/file.txt");
  EXPECT_FALSE(out.ok());
  out.text("x").number(1.5).integer(3);  // harmless
  EXPECT_FALSE(out.close());
}

// Rounded to a number of decimals: hand-written expectations, no trailing zeros, no "-0", and
// what cannot be written in fixed form (huge, infinite, NaN) in its shortest form.
TEST(TextFile, FixedRoundsAndDropsTrailingZeros) {
  const std::string path = temp_path("fixed");
  TextFile out(path);
  ASSERT_TRUE(out.ok());
  out.fixed(0.5, 6).text(" ").fixed(1.0, 6).text(" ").fixed(123.4567894, 6).text(" ").fixed(-0.0000004, 6).text(" ");
  out.fixed(-0.0000006, 6).text(" ").fixed(-0.0, 6).text(" ").fixed(1.7, 0).text(" ").fixed(-0.3, 0).text(" ");
  out.fixed(100.0, 3).text(" ").fixed(1e20, 6).text(" ").fixed(std::numeric_limits<double>::infinity(), 6).text(" ");
  out.fixed(999999999999999.0, 17).text("\n");
  ASSERT_TRUE(out.close());
  EXPECT_EQ(contents(path), "0.5 1 123.456789 0 -0.000001 0 2 0 100 1e+20 inf 999999999999999\n");
  std::filesystem::remove(path);
}
