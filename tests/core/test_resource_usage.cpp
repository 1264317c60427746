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
  // Ordinary pages only: a huge-page fault could also make untouched memory next to the block
  // resident, and the block would not merge with a neighbouring mapping.
  ::madvise(block, kBytes, MADV_NOHUGEPAGE);
  std::memset(block, 1, kBytes);  // every page made resident
  const long touched = resident_kib();
  ASSERT_EQ(::munmap(block, kBytes), 0);
  const long after = resident_kib();
  // 65536 KiB touched. Page tables are not resident memory, but the kernel may fault in a few
  // library pages meanwhile, so the rise may exceed the block by a little, never fall short.
  EXPECT_GE(touched - before, 65536 - 256);
  EXPECT_LE(touched - before, 65536 + 16384);
  EXPECT_GE(touched - after, 65536 - 256);
  EXPECT_LE(touched - after, 65536 + 4096);
}

}  // namespace
}  // namespace vdc
