// A short text naming the machine, so that samples measured on one CPU are not used on another
// ("AMD Ryzen 9 5950X 16-Core Processor x32").
#pragma once

#include <string>

namespace tuneray::tuner {

// CPU model name from /proc/cpuinfo (or "unknown-cpu") and the number of hardware threads.
std::string hardware_signature();

}  // namespace tuneray::tuner
