// vdcloth command-line entry point.
#include <malloc.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <iostream>

#include "app/cli.hpp"

int main(int argc, char** argv) {
  // OpenMP threads with nothing to do sleep rather than spin, unless the environment chooses.
  // libgomp's default spins up to 300,000 rounds at every barrier and between parallel regions,
  // and the factorization's team of one working thread (physics/cholmod_use.hpp) keeps a
  // second thread spinning through every factorization: free on an idle machine, but two runs
  // sharing two cores (two jobs, `--group` shares, ctest -j2) then go at half speed
  // (bench/RESULTS.md "Idle OpenMP threads"). libgomp reads its environment once, when it is
  // loaded (before main; the C library's start-up also resets the environment after any
  // pre-initialisation), so the program starts itself again with the policy set. If that
  // fails it goes on as it is; so it does under valgrind (its preloaded libraries in
  // LD_PRELOAD), where /proc/self/exe is valgrind's tool and starting it again would leave
  // valgrind.
  const char* preload = std::getenv("LD_PRELOAD");
  const bool under_valgrind = preload != nullptr && std::strstr(preload, "vgpreload") != nullptr;
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr && !under_valgrind &&
      setenv("OMP_WAIT_POLICY", "passive", 0) == 0)
    execv("/proc/self/exe", argv);
  // Freed memory stays with the process: a run rebuilds its systems and hierarchies every frame
  // with buffers of the same sizes, and memory handed back to the kernel comes back as page
  // faults, which cost microseconds each in a virtual machine (three times fewer faults in a
  // solo-dancer run, bench/RESULTS.md). Blocks over 32 MB still come from and go back to mmap.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  std::vector<std::string> args(argv + 1, argv + argc);
  return vdc::run_cli(args, std::cout, std::cerr, isatty(STDOUT_FILENO) != 0);
}
