// Compiled only by hitl_target_core_cxx17 (C++17): every header of target/core, so that the
// header-only parts are checked too, with the base/ headers they use (base/contract is built as
// C++17 itself).
#include "base/common/expected.h"
#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "base/contract/device_ids.h"
#include "base/contract/dsp_hitl_status.h"
#include "base/contract/session_status.h"
#include "base/mavlink/hil_sensor_fields.h"
#include "target/core/dsp_hitl.h"
#include "target/core/hil_gps.h"
#include "target/core/hil_inputs.h"
#include "target/core/hil_split.h"
#include "target/core/hil_uorb_messages.h"
#include "target/core/periodic_schedule.h"
#include "target/core/px4_topics.h"
#include "target/core/simulated_battery.h"

static_assert(__cplusplus == 201703L, "hitl_target_core_cxx17 must build as C++17");
