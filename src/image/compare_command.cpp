#include "image/compare_command.h"

#include <cmath>
#include <exception>
#include <iomanip>
#include <nlohmann/json.hpp>

#include "image/io.h"
#include "image/metrics.h"

namespace tuneray {

namespace {

const char* kind_name(ImageFormat format) {
  return is_linear_float_format(format) ? "linear float (EXR/PFM/HDR)" : "8-bit display (PNG...)";
}

}  // namespace

int run_compare(const std::string& path_a, const std::string& path_b, bool json, std::ostream& out,
                std::ostream& err) {
  const ImageFormat format_a = image_format_from_path(path_a);
  const ImageFormat format_b = image_format_from_path(path_b);
  if (format_a != ImageFormat::kUnknown && format_b != ImageFormat::kUnknown &&
      is_linear_float_format(format_a) != is_linear_float_format(format_b)) {
    err << "compare: " << path_a << " is " << kind_name(format_a) << " but " << path_b << " is "
        << kind_name(format_b)
        << "; their values are not on the same scale, so compare two linear files or two "
           "8-bit files\n";
    return 1;
  }
  try {
    // 8-bit files keep their stored encoding so that their errors are display-space errors.
    const ReadOptions options{.srgb_to_linear = false};
    const Image a = read_image(path_a, options);
    const Image b = read_image(path_b, options);
    ErrorMetrics m;
    try {
      m = compare_images(a, b);
    } catch (const std::invalid_argument& e) {
      err << "compare: " << path_a << " vs " << path_b << ": " << e.what() << "\n";
      return 1;
    }
    if (json) {
      nlohmann::json j = {{"rmse", m.rmse},
                          {"relmse", m.relmse},
                          {"max_abs", m.max_abs},
                          {"width", a.width()},
                          {"height", a.height()}};
      j["psnr"] = std::isfinite(m.psnr) ? nlohmann::json(m.psnr) : nlohmann::json(nullptr);
      out << j.dump() << "\n";
    } else {
      out << std::setprecision(8) << "RMSE " << m.rmse << "\n"
          << "PSNR " << m.psnr << " dB\n"
          << "relMSE " << m.relmse << "\n";
    }
    return 0;
  } catch (const std::exception& e) {  // ImageError names the file itself
    err << "compare: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace tuneray
