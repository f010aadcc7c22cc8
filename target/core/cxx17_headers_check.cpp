// Compiled only by hitl_target_core_cxx17 (C++17): every header of target/core, so that the
// header-only parts are checked too.
#include "target/core/device_ids.h"
#include "target/core/dsp_hitl.h"
#include "target/core/dsp_hitl_status.h"
#include "target/core/hil_gps.h"
#include "target/core/hil_inputs.h"
#include "target/core/hil_spec.h"
#include "target/core/hil_sensor_fields.h"
#include "target/core/hil_split.h"
#include "target/core/hil_uorb_messages.h"
#include "target/core/periodic_schedule.h"
#include "target/core/px4_topics.h"
#include "target/core/simulated_battery.h"

static_assert(__cplusplus == 201703L, "hitl_target_core_cxx17 must build as C++17");
