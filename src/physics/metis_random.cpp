// libc's rand and srand with a generator per thread, for METIS's orderings (cholmod_use.hpp).
// Debian's METIS draws its random numbers from rand() and reseeds with srand() at the start of
// every ordering; glibc keeps one generator for the whole process, so two orderings at once
// would draw from each other's sequence. These definitions, exported by the programs that link
// them (CMakeLists.txt), are the ones METIS calls: each thread then draws glibc's own sequence
// (random_r's additive feedback generator with glibc's 128-byte state) from its own state, and
// an ordering is what it would be alone. Where the loader did not take them (dlsym says so),
// metis_draws_per_thread() is false and the orderings run one at a time as before.
#include <dlfcn.h>

#include <cstdint>
#include <cstdlib>

#include "physics/cholmod_use.hpp"

namespace {

// A thread's generator: unseeded, glibc's as if seeded with 1 (as rand() is before srand()).
struct ThreadGenerator {
  random_data data{};
  int32_t state[32]{};  // 128 bytes: glibc's default degree (TYPE_3)
  ThreadGenerator() { initstate_r(1, reinterpret_cast<char*>(state), sizeof state, &data); }
};

ThreadGenerator& thread_generator() {
  thread_local ThreadGenerator generator;
  return generator;
}

}  // namespace

extern "C" int rand() noexcept {
  int32_t value = 0;
  random_r(&thread_generator().data, &value);
  return value;
}

extern "C" void srand(unsigned int seed) noexcept { srandom_r(seed, &thread_generator().data); }

namespace vdc {

bool metis_draws_per_thread() {
  static const bool ours = dlsym(RTLD_DEFAULT, "rand") == reinterpret_cast<void*>(&rand) &&
                           dlsym(RTLD_DEFAULT, "srand") == reinterpret_cast<void*>(&srand);
  return ours;
}

}  // namespace vdc
