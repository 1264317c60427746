// Running a shell command in a test: everything it prints and its exit status.
#pragma once
#include <cstdio>
#include <string>

namespace vdc::test {

struct Output {
  std::string text;
  int status = -1;
};

inline Output capture(const std::string& command) {
  Output o;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    for (std::size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) o.text.append(buffer, n);
    o.status = pclose(pipe);
  }
  return o;
}

}  // namespace vdc::test
