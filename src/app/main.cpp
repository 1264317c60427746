// vdcloth command-line entry point.
#include <malloc.h>
#include <unistd.h>

#include <iostream>

#include "app/cli.hpp"

int main(int argc, char** argv) {
  // Freed memory stays with the process: a run rebuilds its systems and hierarchies every frame
  // with buffers of the same sizes, and memory handed back to the kernel comes back as page
  // faults, which cost microseconds each in a virtual machine (three times fewer faults in a
  // solo-dancer run, bench/RESULTS.md). Blocks over 32 MB still come from and go back to mmap.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  std::vector<std::string> args(argv + 1, argv + argc);
  return vdc::run_cli(args, std::cout, std::cerr, isatty(STDOUT_FILENO) != 0);
}
