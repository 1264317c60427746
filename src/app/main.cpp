// vdcloth command-line entry point.
#include <unistd.h>

#include <iostream>

#include "app/cli.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  return vdc::run_cli(args, std::cout, std::cerr, isatty(STDOUT_FILENO) != 0);
}
