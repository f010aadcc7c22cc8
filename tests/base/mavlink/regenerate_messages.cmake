# Runs tools/gen_messages.py on the official XML and compares its output with the committed
# base/mavlink/messages.h: the header is what the generator makes, byte for byte, never edited by
# hand. Skipped (saying so) without the XML or python3.
#   cmake -DHITL_SOURCE_DIR=... -DXML_DIR=... -DPYTHON=... -DWORK_DIR=... -P regenerate_messages.cmake
if(NOT EXISTS "${XML_DIR}/development.xml")
  message("skipped: official MAVLink XML not found at ${XML_DIR} (set HITL_MAVLINK_XML_DIR)")
  return()
endif()
if(NOT PYTHON)
  message("skipped: python3 not found")
  return()
endif()
file(MAKE_DIRECTORY "${WORK_DIR}")
set(generated "${WORK_DIR}/messages.h")
execute_process(
  COMMAND "${PYTHON}" "${HITL_SOURCE_DIR}/tools/gen_messages.py" "${XML_DIR}/development.xml"
  OUTPUT_FILE "${generated}" ERROR_VARIABLE errors RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "tools/gen_messages.py failed (${result}): ${errors}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${generated}" "${HITL_SOURCE_DIR}/base/mavlink/messages.h"
  RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  execute_process(COMMAND diff -u "${HITL_SOURCE_DIR}/base/mavlink/messages.h" "${generated}" OUTPUT_VARIABLE diff_text)
  string(SUBSTRING "${diff_text}" 0 4000 diff_text)
  message(FATAL_ERROR "base/mavlink/messages.h is not what tools/gen_messages.py generates from ${XML_DIR}; "
    "regenerate it (tools/gen_messages.py ${XML_DIR}/development.xml > base/mavlink/messages.h):\n${diff_text}")
endif()
message("base/mavlink/messages.h matches tools/gen_messages.py's output")
