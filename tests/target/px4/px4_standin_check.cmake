# target/px4's CMake glue on a PX4 tree that was never built, without PX4: the stand-in in
# px4_standin/ (the shape of PX4 v1.16's build as the glue meets it) configured and built through
# px4_hitl's own configure step (target/px4/cmake/configure_px4.cmake).
#
#   cmake -DHITL_SOURCE_DIR=DIR -DWORK_DIR=DIR -DPYTHON=P [-DGENERATOR=G] -P px4_standin_check.cmake
#
# 1. configure_px4.cmake refuses a python that lacks what PX4 imports, naming PX4_PYTHON_EXECUTABLE;
# 2. from an empty build directory (no generated MAVLink headers) PX4's configure and generate pass;
# 3. the build runs to the end, and hil_split_receiver.cpp is compiled after the MAVLink headers were
#    generated, with their include directory (compile_probe.sh records each compile).
cmake_minimum_required(VERSION 3.22)
foreach(var HITL_SOURCE_DIR WORK_DIR PYTHON)
	if(NOT ${var})
		message(FATAL_ERROR "px4_standin_check: ${var} is not set")
	endif()
endforeach()
if(NOT GENERATOR)
	set(GENERATOR "Unix Makefiles")
endif()
set(standin ${HITL_SOURCE_DIR}/tests/target/px4/px4_standin)
set(configure ${HITL_SOURCE_DIR}/target/px4/cmake/configure_px4.cmake)
set(build ${WORK_DIR}/build)
set(log ${WORK_DIR}/compiles.log)
set(header ${build}/mavlink/development/development.h)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# check("CONDITION" "what"): stops with "FAIL: what" unless the if() condition holds.
macro(check condition what)
	cmake_language(EVAL CODE "if(NOT (${condition}))\n message(FATAL_ERROR \"FAIL: ${what}\")\nendif()")
	message(STATUS "ok: ${what}")
endmacro()

# 1. a python without PX4's modules
execute_process(
	COMMAND ${CMAKE_COMMAND} -DPX4_DIR=${standin} -DPX4_BUILD_DIR=${WORK_DIR}/refused -DPX4_CONFIG=px4_sitl_nolockstep
		-DEXTERNAL_MODULES_LOCATION=${HITL_SOURCE_DIR}/target/px4 -DPX4_PYTHON_EXECUTABLE=${PYTHON}
		-DPX4_PYTHON_MODULES=hitl_no_such_module -P ${configure}
	RESULT_VARIABLE refused OUTPUT_VARIABLE refused_out ERROR_VARIABLE refused_err)
string(REGEX REPLACE "[ \n]+" " " refused_text "${refused_out}${refused_err}")
check("NOT refused EQUAL 0" "configure_px4 refuses a python that lacks a module (exit ${refused})")
check("refused_text MATCHES \"PX4_PYTHON_EXECUTABLE=.* lacks what PX4's build imports: hitl_no_such_module\""
	"the refusal names PX4_PYTHON_EXECUTABLE and the missing module")
check("NOT EXISTS ${WORK_DIR}/refused/CMakeCache.txt" "nothing was configured with the refused python")

# 2. configure and generate from nothing
check("NOT EXISTS ${header}" "no generated MAVLink header before the build")
execute_process(
	COMMAND ${CMAKE_COMMAND} -DPX4_DIR=${standin} -DPX4_BUILD_DIR=${build} -DPX4_CONFIG=px4_sitl_nolockstep
		-DEXTERNAL_MODULES_LOCATION=${HITL_SOURCE_DIR}/target/px4 -DHIL_SPLIT_ANY_BOARD=ON
		-DPX4_PYTHON_EXECUTABLE=${PYTHON} -DPX4_PYTHON_MODULES=json -DGENERATOR=${GENERATOR}
		"-DEXTRA_CMAKE_ARGS=-DCMAKE_CXX_COMPILER_LAUNCHER=${standin}/compile_probe.sh|-DCMAKE_C_COMPILER_LAUNCHER=${standin}/compile_probe.sh"
		-P ${configure}
	RESULT_VARIABLE configured)
check("configured EQUAL 0" "PX4 stand-in configured and generated with target/px4 (${GENERATOR})")
check("NOT EXISTS ${header}" "still no generated MAVLink header after configuring")

# 3. build
execute_process(COMMAND ${CMAKE_COMMAND} -E env HITL_PROBE_LOG=${log} HITL_PROBE_HEADER=${header}
	${CMAKE_COMMAND} --build ${build} RESULT_VARIABLE built)
check("built EQUAL 0" "PX4 stand-in built")
check("EXISTS ${header}" "the build generated the MAVLink header")
file(STRINGS ${log} compiles)
set(receiver_line "")
set(dsp_hitl_line "")
set(mavlink_line "")
foreach(line ${compiles})
	if(line MATCHES "hil_split_receiver/hil_split_receiver\\.cpp\t")
		set(receiver_line "${line}")
	elseif(line MATCHES "dsp_hitl/dsp_hitl\\.cpp\t")
		set(dsp_hitl_line "${line}")
	elseif(line MATCHES "mavlink/mavlink_receiver\\.cpp\t")
		set(mavlink_line "${line}")
	endif()
endforeach()
check("receiver_line" "hil_split_receiver.cpp was compiled")
check("receiver_line MATCHES \"\tpresent\t\"" "hil_split_receiver.cpp was compiled after the MAVLink generation")
string(REPLACE "+" "\\+" build_re "${build}")
check("receiver_line MATCHES \"-I${build_re}/mavlink/development( |$)\"" "hil_split_receiver.cpp has mavlink_c's include directories")
check("dsp_hitl_line" "dsp_hitl.cpp was compiled")
string(REPLACE "+" "\\+" hitl_re "${HITL_SOURCE_DIR}")
check("mavlink_line MATCHES \"HITL_HIL_SPLIT_AVAILABLE.*-I${hitl_re}/target/px4/src/lib\"" "the mavlink module gets the split's define and include directory")
message(STATUS "PASS: target/px4 on a never-built PX4 stand-in (${GENERATOR})")
