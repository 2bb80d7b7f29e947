// Registers `tuneray compare A B [--json]` (the work is in image/compare_command.cpp).
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "image/compare_command.h"

namespace tuneray {

CommandAction add_compare_command(CLI::App& app) {
  struct Args {
    std::string a, b;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "RMSE (r, g, b as separate values), PSNR and relative MSE of A against B");
  cmd->add_option("image", args->a, "Image to judge (.exr/.pfm, or .png with another .png)")
      ->required();
  cmd->add_option("reference", args->b, "Reference image (e.g. a converged ground truth)")
      ->required();
  cmd->add_flag("--json", args->json, "Print JSON");
  return [args] { return run_compare(args->a, args->b, args->json, std::cout, std::cerr); };
}

}  // namespace tuneray
