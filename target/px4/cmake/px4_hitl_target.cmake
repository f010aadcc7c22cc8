# The px4_hitl target of the hitl build: PX4 built against a PX4 tree with target/px4 in it.
#
#   cmake -S . -B build -DPX4_DIR=/path/to/PX4-Autopilot     # v1.16.0, submodules checked out
#   cmake --build build --target px4_hitl
#
# 1. applies patches/v1.16.0-mavlink-receiver-hil-split.patch to PX4_DIR (once; apply_px4_patch.cmake),
# 2. configures PX4 (PX4_CONFIG) in PX4_DIR/build/PX4_CONFIG with target/px4 as
#    EXTERNAL_MODULES_LOCATION (msg/: the two uORB messages; src/: target/core, the receiver side of
#    the split, the dsp_hitl module), for px4_sitl_* configurations with HITL_HIL_SPLIT_ANY_BOARD=ON,
#    and a python that has PX4's modules (configure_px4.cmake, px4_python.cmake),
# 3. builds it with PX4_BUILD_JOBS jobs.
# Without PX4_DIR the target only says it was skipped (CI has no PX4). docs/px4-module.md.
# Included from target/CMakeLists.txt: no return() here, it would end the includer too.
set(PX4_DIR "" CACHE PATH "PX4-Autopilot v1.16.0 tree (with submodules) that the px4_hitl target builds")
set(PX4_CONFIG "px4_sitl_nolockstep" CACHE STRING
	"PX4 configuration px4_hitl builds (px4_sitl_nolockstep: SITL flights with hitl sim; modalai_voxl2: the board)")
set(PX4_BUILD_JOBS "2" CACHE STRING "Parallel jobs of the PX4 build")

set(HITL_PX4_DIR "${CMAKE_CURRENT_LIST_DIR}/..")
get_filename_component(HITL_PX4_DIR "${HITL_PX4_DIR}" ABSOLUTE)
set(HITL_PX4_PATCH "${HITL_PX4_DIR}/patches/v1.16.0-mavlink-receiver-hil-split.patch")
set(HITL_PX4_APPLY "${CMAKE_CURRENT_LIST_DIR}/apply_px4_patch.cmake")

if(NOT PX4_DIR)
	message(STATUS "target/px4: PX4_DIR not set, px4_hitl (PX4 with dsp_hitl and the receiver patch) is skipped")
	add_custom_target(px4_hitl
		COMMAND ${CMAKE_COMMAND} -E echo "px4_hitl skipped: no PX4 tree. Configure with -DPX4_DIR=/path/to/PX4-Autopilot (v1.16.0); see docs/px4-module.md"
		VERBATIM)
else()
	get_filename_component(PX4_DIR "${PX4_DIR}" ABSOLUTE)
	if(NOT EXISTS "${PX4_DIR}/src/modules/mavlink/mavlink_receiver.cpp" OR NOT EXISTS "${PX4_DIR}/msg/CMakeLists.txt")
		message(FATAL_ERROR "PX4_DIR=${PX4_DIR} is not a PX4-Autopilot source tree (no src/modules/mavlink/mavlink_receiver.cpp or msg/CMakeLists.txt)")
	endif()
	if(NOT PX4_BUILD_JOBS MATCHES "^[1-9][0-9]*$")
		message(FATAL_ERROR "PX4_BUILD_JOBS must be a positive number, not '${PX4_BUILD_JOBS}'")
	endif()
	if(NOT PX4_CONFIG MATCHES "^[a-z0-9]+_[a-z0-9_]+$")
		message(FATAL_ERROR "PX4_CONFIG '${PX4_CONFIG}' is not a PX4 configuration name (vendor_model[_label], e.g. px4_sitl_nolockstep)")
	endif()
	# PX4's python: PX4_PYTHON_EXECUTABLE, or found when px4_hitl runs (px4_python.cmake says what a
	# python lacks). Empty by default: the system python3 first, then python3 on PATH.
	set(PX4_PYTHON_EXECUTABLE "" CACHE FILEPATH "Python 3 with PX4's build modules (kconfiglib, empy, genmsg, jinja2, yaml); empty: found")
	set(PX4_BUILD_DIR "${PX4_DIR}/build/${PX4_CONFIG}")
	if(PX4_CONFIG MATCHES "^px4_sitl")
		set(px4_split_any_board ON)
	else()
		set(px4_split_any_board OFF)
	endif()

	add_custom_target(px4_hitl
		COMMAND ${CMAKE_COMMAND} -DPX4_DIR=${PX4_DIR} -DPATCH=${HITL_PX4_PATCH} -P ${HITL_PX4_APPLY}
		COMMAND ${CMAKE_COMMAND} -DPX4_DIR=${PX4_DIR} -DPX4_BUILD_DIR=${PX4_BUILD_DIR} -DPX4_CONFIG=${PX4_CONFIG}
			-DEXTERNAL_MODULES_LOCATION=${HITL_PX4_DIR} -DHIL_SPLIT_ANY_BOARD=${px4_split_any_board}
			-DPX4_PYTHON_EXECUTABLE=${PX4_PYTHON_EXECUTABLE}
			-P ${CMAKE_CURRENT_LIST_DIR}/configure_px4.cmake
		COMMAND ${CMAKE_COMMAND} --build ${PX4_BUILD_DIR} -j ${PX4_BUILD_JOBS}
		COMMENT "PX4 ${PX4_CONFIG} with dsp_hitl and the MavlinkReceiver patch (${PX4_BUILD_DIR})"
		USES_TERMINAL
		VERBATIM)
	message(STATUS "target/px4: px4_hitl builds PX4 ${PX4_CONFIG} in ${PX4_BUILD_DIR}")
endif()
