#include "render/reuse_switch.h"

namespace tuneray {

void ReuseSwitch::after_reuse_pass(const ReuseMoments& pass, double film_spp, double cost_ratio) {
  moments_.add(pass);
  if (moments_.samples < kMinSamples || cost_ratio <= 0) {
    on_ = false;  // undecided: the next pass probes again
    next_probe_spp_ = 0;
    return;
  }
  const double own = moments_.own_variance();
  on_ = own > 0 && cost_ratio * moments_.reused_variance() < (1 - kMinGain) * own;
  next_probe_spp_ = on_ ? 0 : 2 * film_spp;
}

}  // namespace tuneray
