#include "run_command.h"

namespace tuneray::testing {

CommandResult run_tuneray(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {tuneray_binary()};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_program(argv);
}

}  // namespace tuneray::testing
