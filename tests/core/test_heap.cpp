// release_library_pages (core/heap.h): the named library's clean pages leave
// the resident set, and its code runs again afterwards.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "core/heap.h"

namespace pt {
namespace {

// The process's resident file-backed bytes (/proc/self/status, RssFile).
long resident_file_kib() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("RssFile:", 0) == 0) return std::stol(line.substr(8));
  }
  return -1;
}

TEST(Heap, ReleaseLibraryPagesDropsTheNamedLibrarysCleanPages) {
  EXPECT_EQ(release_library_pages({"no-such-library-anywhere"}), 0u);
  const long before = resident_file_kib();
  ASSERT_GT(before, 0) << "no RssFile in /proc/self/status";
  // libstdc++ is mapped and its code has run (this test's streams): its
  // read-only segments are advised away...
  const std::size_t bytes = release_library_pages({"libstdc++.so"});
  EXPECT_GT(bytes, std::size_t{100} << 10);
  const long after = resident_file_kib();
  EXPECT_LT(after, before) << "released " << bytes << " bytes";
  // ... and its code runs again afterwards (the pages come back from the file).
  std::ostringstream s;
  s << 12345 << ' ' << 0.5;
  EXPECT_EQ(s.str(), "12345 0.5");
}

}  // namespace
}  // namespace pt
