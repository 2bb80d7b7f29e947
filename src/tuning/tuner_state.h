// The scene/camera indicators as the tuner's state.
#pragma once

#include "scene/indicators.h"
#include "tuner/indicators.h"

namespace tuneray {

// One entry per indicator of scene/indicators.h, with its fixed range.
tuner::IndicatorSchema make_indicator_schema();
tuner::State to_tuner_state(const Indicators& indicators);

}  // namespace tuneray
