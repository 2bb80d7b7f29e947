#include "tuner/hardware_signature.h"

#include <fstream>
#include <thread>

namespace tuneray::tuner {

std::string hardware_signature() {
  std::string model = "unknown-cpu";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) {
        model = line.substr(line.find_first_not_of(" \t", colon + 1));
        break;
      }
    }
  }
  return model + " x" + std::to_string(std::thread::hardware_concurrency());
}

}  // namespace tuneray::tuner
