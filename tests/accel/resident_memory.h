// The process's resident memory, for the tests that check that freed trees are returned.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <fstream>

namespace tuneray::test {

inline size_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<size_t>(sysconf(_SC_PAGESIZE));
}

}  // namespace tuneray::test
