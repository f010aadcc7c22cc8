// Parameters of the HITL set a firmware lacks (param_notes.h), how check rows count them
// (params_check.h), and the firmware version text (firmware_version.h).
#include <gtest/gtest.h>

#include "engine/vehicle/firmware_version.h"
#include "engine/vehicle/param_notes.h"
#include "engine/vehicle/params_check.h"

namespace hitl::vehicle {
namespace {

TEST(ParamNotes, ParsesAbsentLinesAndSkipsMalformedOnes) {
  const auto notes = parse_absent_notes(
      "# comment\n#absent A_B | PX4 v1.16 | gone: use C\n1\t1\tA_B\t1\t6\n#absent BROKEN | only two\n#absent  X | FW |  y \n");
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(notes[0].name, "A_B");
  EXPECT_EQ(notes[0].firmware, "PX4 v1.16");
  EXPECT_EQ(notes[0].replacement, "gone: use C");
  EXPECT_EQ(notes[1].name, "X");
  EXPECT_EQ(notes[1].replacement, "y");
}

TEST(ParamNotes, TheHitlSetNamesWhatPx4V116Lacks) {
  for (const char* name : {"COM_ARM_EKF_POS", "COM_ARM_EKF_VEL"}) {
    const AbsentParamNote* note = find_absent_note(name);
    ASSERT_NE(note, nullptr) << name;
    EXPECT_EQ(note->firmware, "PX4 v1.16");
    EXPECT_NE(note->replacement.find("#23411"), std::string::npos);
    // Every note is about a parameter of the set.
  }
  for (const auto& note : hitl_absent_notes()) {
    bool in_set = false;
    for (const auto& p : hitl_default_params()) in_set = in_set || p.name == note.name;
    EXPECT_TRUE(in_set) << note.name;
  }
  EXPECT_EQ(find_absent_note("SYS_HITL"), nullptr);
}

TEST(ParamNotes, AbsentIsNotWrongUnlessStrict) {
  std::vector<Param> board = hitl_default_params();
  std::erase_if(board, [](const Param& p) { return p.name == "COM_ARM_EKF_POS"; });
  board.front().value = ParamValue::int32(board.front().value.i + 1);
  const auto rows = check_params(board, hitl_default_params());
  for (const auto& r : rows) {
    if (r.name == "COM_ARM_EKF_POS") {
      EXPECT_TRUE(r.absent);
      EXPECT_FALSE(r.ok);
      EXPECT_FALSE(row_fails(r, false));
      EXPECT_TRUE(row_fails(r, true));
      EXPECT_EQ(r.note.rfind("not in PX4 v1.16: ", 0), 0u) << r.note;
    } else if (r.name == board.front().name) {
      EXPECT_FALSE(r.absent);
      EXPECT_TRUE(row_fails(r, false));
    } else {
      EXPECT_TRUE(r.ok) << r.name;
    }
  }
}

TEST(FirmwareVersion, PackedAsPx4Does) {
  EXPECT_EQ(format_flight_sw_version((1u << 24) | (16u << 16) | (0u << 8) | 255u), "v1.16.0");
  EXPECT_EQ(format_flight_sw_version((1u << 24) | (16u << 16) | (0u << 8) | 0u), "v1.16.0-dev");
  EXPECT_EQ(format_flight_sw_version((1u << 24) | (15u << 16) | (2u << 8) | 192u), "v1.15.2-rc");
  EXPECT_EQ(format_flight_sw_version((1u << 24) | (14u << 16) | (3u << 8) | 7u), "v1.14.3-7");
}

}  // namespace
}  // namespace hitl::vehicle
