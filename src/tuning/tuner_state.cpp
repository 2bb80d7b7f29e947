#include "tuning/tuner_state.h"

namespace tuneray {

tuner::IndicatorSchema make_indicator_schema() {
  tuner::IndicatorSchema schema;
  for (const IndicatorInfo& info : indicator_infos()) schema.add(info.name, info.lo, info.hi);
  return schema;
}

tuner::State to_tuner_state(const Indicators& indicators) {
  return tuner::State(indicators.values.begin(), indicators.values.end());
}

}  // namespace tuneray
