# Stand-in for PX4's px4_add_module(MODULE name MAIN cmd SRCS ... DEPENDS ... [EXTERNAL]): a static
# library named MODULE of SRCS, linked to DEPENDS. The other keywords are accepted and ignored.
include(px4_add_library)
function(px4_add_module)
	cmake_parse_arguments(IN "EXTERNAL;UNITY_BUILD;DYNAMIC;NO_DAEMON" "MODULE;MAIN;STACK_MAIN;STACK_MAX;PRIORITY"
		"SRCS;DEPENDS;COMPILE_FLAGS;INCLUDES;MODULE_CONFIG;LINK_FLAGS" ${ARGN})
	if(NOT IN_MODULE OR NOT IN_SRCS)
		message(FATAL_ERROR "px4_add_module: MODULE and SRCS are required")
	endif()
	add_library(${IN_MODULE} STATIC ${IN_SRCS})
	target_compile_definitions(${IN_MODULE} PRIVATE MODULE_NAME="${IN_MAIN}")
	if(IN_DEPENDS)
		target_link_libraries(${IN_MODULE} PRIVATE ${IN_DEPENDS})
	endif()
endfunction()
