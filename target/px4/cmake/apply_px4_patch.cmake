# Applies target/px4's MavlinkReceiver patch to a PX4 tree, once:
#   cmake -DPX4_DIR=DIR -DPATCH=FILE [-DCHECK_ONLY=ON] -P apply_px4_patch.cmake
# Already applied: says so and changes nothing. Applies cleanly: applies it (CHECK_ONLY: only says
# so). Otherwise fails naming the tree, its version and git's reason. With CHECK_ONLY and no PX4_DIR
# it prints "skipped: ..." (the CTest check, skipped in CI where there is no PX4).
cmake_minimum_required(VERSION 3.22)

if(NOT PATCH OR NOT EXISTS "${PATCH}")
	message(FATAL_ERROR "apply_px4_patch: the patch file '${PATCH}' does not exist")
endif()
if(NOT PX4_DIR)
	if(CHECK_ONLY)
		message(STATUS "skipped: PX4_DIR is not set (configure hitl with -DPX4_DIR=/path/to/PX4-Autopilot to check the patch)")
		return()
	endif()
	message(FATAL_ERROR "apply_px4_patch: PX4_DIR is not set")
endif()
set(receiver "${PX4_DIR}/src/modules/mavlink/mavlink_receiver.cpp")
if(NOT EXISTS "${receiver}")
	message(FATAL_ERROR "apply_px4_patch: PX4_DIR=${PX4_DIR} is not a PX4-Autopilot tree (no src/modules/mavlink/mavlink_receiver.cpp)")
endif()
find_program(GIT_EXECUTABLE git)
if(NOT GIT_EXECUTABLE)
	message(FATAL_ERROR "apply_px4_patch: git is needed to apply ${PATCH}")
endif()

execute_process(COMMAND "${GIT_EXECUTABLE}" describe --tags --always WORKING_DIRECTORY "${PX4_DIR}"
	OUTPUT_VARIABLE px4_version OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT px4_version)
	set(px4_version "unknown version (not a git checkout)")
endif()
get_filename_component(patch_name "${PATCH}" NAME)

execute_process(COMMAND "${GIT_EXECUTABLE}" apply --reverse --check "${PATCH}" WORKING_DIRECTORY "${PX4_DIR}"
	RESULT_VARIABLE reverse_result OUTPUT_QUIET ERROR_QUIET)
if(reverse_result EQUAL 0)
	message(STATUS "PX4 ${px4_version} in ${PX4_DIR}: ${patch_name} is applied")
	return()
endif()

execute_process(COMMAND "${GIT_EXECUTABLE}" apply --check "${PATCH}" WORKING_DIRECTORY "${PX4_DIR}"
	RESULT_VARIABLE check_result ERROR_VARIABLE check_error OUTPUT_QUIET)
if(NOT check_result EQUAL 0)
	message(FATAL_ERROR "apply_px4_patch: ${patch_name} does not apply to PX4 ${px4_version} in ${PX4_DIR} "
		"(it is made against PX4 v1.16.0):\n${check_error}")
endif()
if(CHECK_ONLY)
	message(STATUS "PX4 ${px4_version} in ${PX4_DIR}: ${patch_name} applies cleanly")
	return()
endif()

execute_process(COMMAND "${GIT_EXECUTABLE}" apply "${PATCH}" WORKING_DIRECTORY "${PX4_DIR}"
	RESULT_VARIABLE apply_result ERROR_VARIABLE apply_error)
if(NOT apply_result EQUAL 0)
	message(FATAL_ERROR "apply_px4_patch: applying ${patch_name} to ${PX4_DIR} failed:\n${apply_error}")
endif()
message(STATUS "PX4 ${px4_version} in ${PX4_DIR}: applied ${patch_name} (git -C ${PX4_DIR} apply -R ${PATCH} undoes it)")
