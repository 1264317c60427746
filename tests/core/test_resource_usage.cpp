// resident_kib: the process's resident memory follows memory touched and given back, which the
// peak does not.
#include "core/resource_usage.hpp"

#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cstring>

namespace vdc {
namespace {

TEST(ResidentMemory, RisesByWhatIsTouchedAndFallsWhenItIsGivenBack) {
  constexpr std::size_t kBytes = std::size_t{64} << 20;
  const long before = resident_kib();
  ASSERT_GT(before, 0);
  void* block = ::mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(block, MAP_FAILED);
  std::memset(block, 1, kBytes);  // every page made resident
  const long touched = resident_kib();
  ASSERT_EQ(::munmap(block, kBytes), 0);
  const long after = resident_kib();
  // 65536 KiB touched; other threads of the test program may move a few hundred KiB meanwhile.
  EXPECT_NEAR(static_cast<double>(touched - before), 65536.0, 4096.0);
  EXPECT_NEAR(static_cast<double>(touched - after), 65536.0, 4096.0);
}

}  // namespace
}  // namespace vdc
