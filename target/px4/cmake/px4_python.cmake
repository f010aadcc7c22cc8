# The python PX4's build runs (its PYTHON_EXECUTABLE): one that has the modules PX4 v1.16 imports
# while it configures and generates (kconfiglib's menuconfig, empy, genmsg, jinja2, yaml).
#
#   cmake -P px4_python.cmake                 prints the python to use, or fails saying what each lacks
#   cmake -DPX4_PYTHON_EXECUTABLE=P -P ...    checks P only
#
# For PX4's Makefile: make px4_sitl_nolockstep PYTHON_EXECUTABLE=$(cmake -P <this file>) ...
# Included (configure_px4.cmake), it defines hitl_find_px4_python(OUT) and runs nothing.
if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
	cmake_minimum_required(VERSION 3.22)
endif()

# Module PX4's build imports -> what provides it (pip name / Debian package).
set(HITL_PX4_PYTHON_PROVIDERS
	"menuconfig=kconfiglib (python3-kconfiglib)"
	"em=empy 3.x (python3-empy)"
	"genmsg=pyros-genmsg (python3-genmsg)"
	"jinja2=jinja2 (python3-jinja2)"
	"yaml=pyyaml (python3-yaml)")

# The modules P lacks among MODULES (empty when none), into OUT.
function(hitl_python_lacks python modules out)
	execute_process(
		COMMAND "${python}" -c "import importlib.util, sys; print(' '.join(m for m in sys.argv[1:] if importlib.util.find_spec(m) is None))" ${modules}
		RESULT_VARIABLE result OUTPUT_VARIABLE missing OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_VARIABLE error)
	if(NOT result EQUAL 0)
		set(missing "(it does not run: ${result} ${error})")
	endif()
	set(${out} "${missing}" PARENT_SCOPE)
endfunction()

# OUT: PX4_PYTHON_EXECUTABLE when it has every module, else the first of /usr/bin/python3 and
# python3 on PATH that has them. Stops with a message naming PX4_PYTHON_EXECUTABLE otherwise.
# PX4_PYTHON_MODULES (a list) replaces the modules checked (the tests' stand-in PX4 needs none).
function(hitl_find_px4_python out)
	if(DEFINED PX4_PYTHON_MODULES)
		set(modules ${PX4_PYTHON_MODULES})
	else()
		set(modules)
		foreach(entry ${HITL_PX4_PYTHON_PROVIDERS})
			string(REGEX REPLACE "=.*" "" module "${entry}")
			list(APPEND modules ${module})
		endforeach()
	endif()
	set(provides "")
	foreach(entry ${HITL_PX4_PYTHON_PROVIDERS})
		string(REPLACE "=" " from " entry "${entry}")
		string(APPEND provides "\n  ${entry}")
	endforeach()
	string(CONCAT how "Install them (docs/px4-module.md) or name a python that has them: "
		"PX4_PYTHON_EXECUTABLE=/path/to/python3 (cmake -DPX4_PYTHON_EXECUTABLE=... for px4_hitl; "
		"PX4's Makefile takes PYTHON_EXECUTABLE=... instead). The modules:${provides}")

	if(PX4_PYTHON_EXECUTABLE)
		if(NOT EXISTS "${PX4_PYTHON_EXECUTABLE}")
			message(FATAL_ERROR "PX4_PYTHON_EXECUTABLE=${PX4_PYTHON_EXECUTABLE} does not exist")
		endif()
		hitl_python_lacks("${PX4_PYTHON_EXECUTABLE}" "${modules}" missing)
		if(missing)
			message(FATAL_ERROR "PX4_PYTHON_EXECUTABLE=${PX4_PYTHON_EXECUTABLE} lacks what PX4's build imports: ${missing}. ${how}")
		endif()
		set(${out} "${PX4_PYTHON_EXECUTABLE}" PARENT_SCOPE)
		return()
	endif()

	set(candidates)
	if(EXISTS /usr/bin/python3)
		list(APPEND candidates /usr/bin/python3)
	endif()
	find_program(path_python3 python3)
	if(path_python3 AND NOT path_python3 IN_LIST candidates)
		list(APPEND candidates "${path_python3}")
	endif()
	set(tried "")
	foreach(python ${candidates})
		hitl_python_lacks("${python}" "${modules}" missing)
		if(NOT missing)
			set(${out} "${python}" PARENT_SCOPE)
			return()
		endif()
		string(APPEND tried "\n  ${python} lacks ${missing}")
	endforeach()
	if(NOT candidates)
		set(tried "\n  no python3 found (/usr/bin/python3, PATH)")
	endif()
	message(FATAL_ERROR "no python3 with what PX4's build imports (set PX4_PYTHON_EXECUTABLE):${tried}\n${how}")
endfunction()

if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
	hitl_find_px4_python(python)
	execute_process(COMMAND ${CMAKE_COMMAND} -E echo "${python}")
endif()
