// The work of `tuneray compare A B [--json]` (app/cmd_compare_cli.cpp registers the command):
// error metrics of image A against the reference B.
#pragma once

#include <ostream>
#include <string>

namespace tuneray {

// Both images must be linear float files (EXR, PFM, HDR) or both 8-bit files (PNG, ...); the
// latter are compared in their stored display encoding (byte / 255, no sRGB decoding), so their
// PSNR is the usual 8-bit PSNR. Prints RMSE, PSNR and relMSE one per line, or with `json` one
// object {"rmse","psnr","relmse","max_abs","width","height"} (psnr is null for identical
// images). Returns 0 on success, 1 with a message on `err` for any error.
int run_compare(const std::string& path_a, const std::string& path_b, bool json, std::ostream& out,
                std::ostream& err);

}  // namespace tuneray
