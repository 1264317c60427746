// The function-length scanner on hand-written sources: each function's name, first and last
// line counted by hand, through what a lexer must not take for code (comments, strings, raw
// strings, directives) and what a brace-counter must not take for a function (aggregates,
// classes, namespaces, initializer lists, lambdas).
#include <gtest/gtest.h>

#include "tools/function_lengths.hpp"

namespace vdc::tools {
namespace {

struct Expected {
  std::string name;
  int first, last;
};

void expect_functions(const std::string& source, const std::vector<Expected>& expected) {
  const std::vector<FunctionSpan> found = find_functions(source);
  ASSERT_EQ(found.size(), expected.size()) << source;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(found[k].name, expected[k].name) << k;
    EXPECT_EQ(found[k].first_line, expected[k].first) << expected[k].name;
    EXPECT_EQ(found[k].last_line, expected[k].last) << expected[k].name;
    EXPECT_EQ(found[k].lines(), expected[k].last - expected[k].first + 1) << expected[k].name;
  }
}

TEST(FunctionLengths, PlainFunctionsInNamespacesAndTheirSignaturesOverLines) {
  expect_functions(R"(#include <vector>
namespace a {
namespace {
int f(int x) {
  if (x) { return 1; }
  return 0;
}
}  // namespace
std::vector<int> Scene::load(const std::string& path,
                             int n) {
  return {n};
}
}  // namespace a
)",
                   {{"f", 4, 7}, {"Scene::load", 9, 12}});
}

TEST(FunctionLengths, BracesInCommentsStringsAndRawStringsAreNotCode) {
  expect_functions(R"SRC(void g() {
  // a comment with a brace {
  const char* s = "a string with } and \" and {";
  const char c = '{';
  /* a block comment { {
     } */
  const char* raw = R"X(a raw string with "}" and { )X";
}
#define BRACE {
int h() { return 2; }
)SRC",
                   {{"g", 1, 8}, {"h", 10, 10}});
}

TEST(FunctionLengths, LambdasBelongToTheirFunctionAndInitializersAreNotFunctions) {
  expect_functions(R"(const int table[] = {1, 2, 3};
struct Point {
  double x = 0, y{0};
  bool operator==(const Point& o) const { return x == o.x && y == o.y; }
  Point() = default;
};
Worker::Worker(int n)
    : count_{n}, values_(n, 0.0) {
  auto square = [](int v) {
    return v * v;
  };
  total_ = square(n);
}
enum class Mode { fixed, adaptive };
class Holder {
 public:
  int size() const {
    return 3;
  }
};
)",
                   {{"operator==", 4, 4}, {"Worker::Worker", 7, 13}, {"size", 17, 19}});
}

}  // namespace
}  // namespace vdc::tools
