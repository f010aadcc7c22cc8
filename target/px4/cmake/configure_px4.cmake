# Configures PX4 with target/px4 as its external modules: the second step of px4_hitl
# (px4_hitl_target.cmake), and what tests/target/px4/px4_standin_check.cmake runs against a stand-in.
#
#   cmake -DPX4_DIR=DIR -DPX4_BUILD_DIR=DIR -DPX4_CONFIG=NAME -DEXTERNAL_MODULES_LOCATION=<hitl>/target/px4
#         [-DHIL_SPLIT_ANY_BOARD=ON] [-DPX4_PYTHON_EXECUTABLE=P] [-DGENERATOR=G]
#         [-DEXTRA_CMAKE_ARGS=a|b|...] -P configure_px4.cmake
#
# The python is PX4_PYTHON_EXECUTABLE or the one px4_python.cmake finds; it reaches PX4 as its
# PYTHON_EXECUTABLE. The generator is the existing build directory's, else Ninja when installed,
# else Unix Makefiles.
cmake_minimum_required(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/px4_python.cmake)

foreach(var PX4_DIR PX4_BUILD_DIR PX4_CONFIG EXTERNAL_MODULES_LOCATION)
	if(NOT ${var})
		message(FATAL_ERROR "configure_px4: ${var} is not set")
	endif()
endforeach()

hitl_find_px4_python(python)
message(STATUS "PX4's python: ${python}")

if(NOT GENERATOR AND EXISTS "${PX4_BUILD_DIR}/CMakeCache.txt")
	file(STRINGS "${PX4_BUILD_DIR}/CMakeCache.txt" cached REGEX "^CMAKE_GENERATOR:INTERNAL=")
	string(REGEX REPLACE "^CMAKE_GENERATOR:INTERNAL=" "" GENERATOR "${cached}")
endif()
if(NOT GENERATOR)
	find_program(ninja ninja)
	if(ninja)
		set(GENERATOR Ninja)
	else()
		set(GENERATOR "Unix Makefiles")
	endif()
endif()
if(HIL_SPLIT_ANY_BOARD)
	set(split ON)
else()
	set(split OFF)
endif()
set(extra)
if(EXTRA_CMAKE_ARGS)
	string(REPLACE "|" ";" extra "${EXTRA_CMAKE_ARGS}")
endif()

execute_process(
	COMMAND ${CMAKE_COMMAND} -S ${PX4_DIR} -B ${PX4_BUILD_DIR} -G ${GENERATOR}
		-DCONFIG=${PX4_CONFIG}
		-DEXTERNAL_MODULES_LOCATION=${EXTERNAL_MODULES_LOCATION}
		-DHITL_HIL_SPLIT_ANY_BOARD=${split}
		-DPYTHON_EXECUTABLE=${python}
		${extra}
	RESULT_VARIABLE result)
if(NOT result EQUAL 0)
	message(FATAL_ERROR "configure_px4: configuring PX4 (${PX4_CONFIG}) in ${PX4_BUILD_DIR} failed (above)")
endif()
