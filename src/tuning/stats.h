// Robust summaries of noisy measurements.
#pragma once

#include <vector>

namespace tuneray {

double median(std::vector<double> values);                 // 0 for an empty list
double geometric_mean(const std::vector<double>& values);  // of positive values; 0 if empty
double quantile(std::vector<double> values, double q);     // linear interpolation, q in [0,1]

}  // namespace tuneray
