// The build uses AVX2 and FMA; on a CPU without them the program would die of SIGILL somewhere
// deep inside. This file is compiled without AVX (see CMakeLists.txt) and checks in a
// constructor that runs before the other static initialisers, so the error is plain.
#include <cstdio>
#include <cstdlib>

namespace {

__attribute__((constructor(101))) void require_avx2() {
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    std::fputs(
        "tuneray: error: this CPU lacks AVX2/FMA, which this build requires "
        "(x86-64 with AVX2: Intel Haswell / AMD Excavator or newer)\n",
        stderr);
    std::exit(3);
  }
}

}  // namespace
